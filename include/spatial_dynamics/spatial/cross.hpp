// Spatial cross products: v×m for motions (eq. 17) and v×*f for forces (eq. 18), with
// v×* = -(v×)^T. Also their 6×6 matrix forms, used by tests and the inertia derivative (eq. 27).
#pragma once

#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/mat3.hpp"

namespace spatial_dynamics {

/// v × m = (ω×ω_m ; ω×v_m + v×ω_m)   (eq. 17)
template <class S>
SD_INLINE MotionVector<S> cross(const MotionVector<S>& v, const MotionVector<S>& m) {
  return {cross(v.angular, m.angular), cross(v.angular, m.linear) + cross(v.linear, m.angular)};
}

/// v ×* f = (ω×n + v×f ; ω×f)   (eq. 18)
template <class S>
SD_INLINE ForceVector<S> cross(const MotionVector<S>& v, const ForceVector<S>& f) {
  return {cross(v.angular, f.angular) + cross(v.linear, f.linear), cross(v.angular, f.linear)};
}

/// The 6×6 matrix of v× (eq. 17): [ω× 0; v× ω×].
template <class S>
Matrix6<S> motion_cross_matrix(const MotionVector<S>& v) {
  Matrix6<S> m = Matrix6<S>::Zero();
  m.template topLeftCorner<3, 3>() = skew(v.angular).eigen();
  m.template bottomLeftCorner<3, 3>() = skew(v.linear).eigen();
  m.template bottomRightCorner<3, 3>() = skew(v.angular).eigen();
  return m;
}

/// The 6×6 matrix of v×* (eq. 18): [ω× v×; 0 ω×] = -(v×)^T.
template <class S>
Matrix6<S> force_cross_matrix(const MotionVector<S>& v) {
  Matrix6<S> m = Matrix6<S>::Zero();
  m.template topLeftCorner<3, 3>() = skew(v.angular).eigen();
  m.template topRightCorner<3, 3>() = skew(v.linear).eigen();
  m.template bottomRightCorner<3, 3>() = skew(v.angular).eigen();
  return m;
}

}  // namespace spatial_dynamics
