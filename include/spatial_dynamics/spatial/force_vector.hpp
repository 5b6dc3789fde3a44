// Spatial force vector f = (n_O; f) in Plücker coordinates, moment about the frame origin
// first (Featherstone 2010, eq. 6). A distinct type from MotionVector.
#pragma once

#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/vec3.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"

namespace spatial_dynamics {

template <class S>
struct ForceVector {
  Vec3<S> angular;  // n_O: moment about the frame origin
  Vec3<S> linear;   // f: resultant force

  ForceVector() = default;
  SD_INLINE ForceVector(const Vec3<S>& angular_part, const Vec3<S>& linear_part)
      : angular(angular_part), linear(linear_part) {}
  explicit ForceVector(const Vector6<S>& f) : angular(f[0], f[1], f[2]), linear(f[3], f[4], f[5]) {}

  static ForceVector Zero() { return {Vec3<S>(), Vec3<S>()}; }

  Vector6<S> toVector() const {
    Vector6<S> f;
    for (int k = 0; k < 3; ++k) {
      f[k] = angular[k];
      f[k + 3] = linear[k];
    }
    return f;
  }

  template <class T>
  ForceVector<T> cast() const {
    return {angular.template cast<T>(), linear.template cast<T>()};
  }

  SD_INLINE ForceVector& operator+=(const ForceVector& o) { angular += o.angular; linear += o.linear; return *this; }
  SD_INLINE ForceVector& operator-=(const ForceVector& o) { angular -= o.angular; linear -= o.linear; return *this; }
  SD_INLINE ForceVector operator+(const ForceVector& o) const { return {angular + o.angular, linear + o.linear}; }
  SD_INLINE ForceVector operator-(const ForceVector& o) const { return {angular - o.angular, linear - o.linear}; }
  SD_INLINE ForceVector operator-() const { return {-angular, -linear}; }
  SD_INLINE ForceVector operator*(const S& k) const { return {angular * k, linear * k}; }

  /// The same force with its moment about the point p (from the frame origin, same axes):
  /// (n − p × f ; f) (eq. 12 with E = 1).
  SD_INLINE ForceVector aboutPoint(const Vec3<S>& p) const { return {angular - cross(p, linear), linear}; }
};

template <class S>
ForceVector<S> operator*(const S& k, const ForceVector<S>& f) { return f * k; }

/// Scalar product m · f = ω·n_O + v_O·f: the power delivered by f on a body moving with m
/// (Featherstone 2010, eq. 7). Defined only between a motion and a force.
template <class S>
SD_INLINE S dot(const MotionVector<S>& m, const ForceVector<S>& f) {
  return dot_sum(m.angular, f.angular, m.linear, f.linear);
}
template <class S>
SD_INLINE S dot(const ForceVector<S>& f, const MotionVector<S>& m) {
  return dot(m, f);
}

}  // namespace spatial_dynamics
