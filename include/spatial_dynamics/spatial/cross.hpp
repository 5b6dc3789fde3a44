// Spatial cross products: v×m for motions (eq. 17) and v×*f for forces (eq. 18), with
// v×* = -(v×)^T. Also their 6×6 matrix forms, used by tests and the inertia derivative (eq. 27).
#pragma once

#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"

namespace spatial_dynamics {

/// v × m = (ω×ω_m ; ω×v_m + v×ω_m)   (eq. 17)
template <class S>
SD_INLINE MotionVector<S> cross(const MotionVector<S>& v, const MotionVector<S>& m) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) {
    using namespace packed3;
    const Packed3 w = load3(v.angular), u = load3(v.linear), mw = load3(m.angular), mv = load3(m.linear);
    return {to_vector3(cross(w, mw)), to_vector3(cross(w, mv) + cross(u, mw))};
  }
#endif
  return {cross_3d(v.angular, m.angular), Vector3<S>(cross_3d(v.angular, m.linear) + cross_3d(v.linear, m.angular))};
}

/// v ×* f = (ω×n + v×f ; ω×f)   (eq. 18)
template <class S>
SD_INLINE ForceVector<S> cross(const MotionVector<S>& v, const ForceVector<S>& f) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) {
    using namespace packed3;
    const Packed3 w = load3(v.angular), u = load3(v.linear), n = load3(f.angular), l = load3(f.linear);
    return {to_vector3(cross(w, n) + cross(u, l)), to_vector3(cross(w, l))};
  }
#endif
  return {Vector3<S>(cross_3d(v.angular, f.angular) + cross_3d(v.linear, f.linear)), cross_3d(v.angular, f.linear)};
}

/// The 6×6 matrix of v× (eq. 17): [ω× 0; v× ω×].
template <class S>
Matrix6<S> motion_cross_matrix(const MotionVector<S>& v) {
  Matrix6<S> m = Matrix6<S>::Zero();
  m.template topLeftCorner<3, 3>() = skew(v.angular);
  m.template bottomLeftCorner<3, 3>() = skew(v.linear);
  m.template bottomRightCorner<3, 3>() = skew(v.angular);
  return m;
}

/// The 6×6 matrix of v×* (eq. 18): [ω× v×; 0 ω×] = -(v×)^T.
template <class S>
Matrix6<S> force_cross_matrix(const MotionVector<S>& v) {
  Matrix6<S> m = Matrix6<S>::Zero();
  m.template topLeftCorner<3, 3>() = skew(v.angular);
  m.template topRightCorner<3, 3>() = skew(v.linear);
  m.template bottomRightCorner<3, 3>() = skew(v.angular);
  return m;
}

}  // namespace spatial_dynamics
