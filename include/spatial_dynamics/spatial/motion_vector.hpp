// Spatial motion vector m = (ω; v_O) in Plücker coordinates, angular part first
// (Featherstone 2010, eq. 5). A distinct type from ForceVector so that adding a force to a
// velocity does not compile.
#pragma once

#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/vec3.hpp"

namespace spatial_dynamics {

template <class S>
struct MotionVector {
  Vec3<S> angular;  // ω
  Vec3<S> linear;   // v_O: velocity of the body-fixed point at the frame origin

  MotionVector() = default;
  SD_INLINE MotionVector(const Vec3<S>& angular_part, const Vec3<S>& linear_part)
      : angular(angular_part), linear(linear_part) {}
  explicit MotionVector(const Vector6<S>& v) : angular(v[0], v[1], v[2]), linear(v[3], v[4], v[5]) {}

  static MotionVector Zero() { return {Vec3<S>(), Vec3<S>()}; }

  Vector6<S> toVector() const {
    Vector6<S> v;
    for (int k = 0; k < 3; ++k) {
      v[k] = angular[k];
      v[k + 3] = linear[k];
    }
    return v;
  }

  template <class T>
  MotionVector<T> cast() const {
    return {angular.template cast<T>(), linear.template cast<T>()};
  }

  SD_INLINE MotionVector& operator+=(const MotionVector& o) { angular += o.angular; linear += o.linear; return *this; }
  SD_INLINE MotionVector& operator-=(const MotionVector& o) { angular -= o.angular; linear -= o.linear; return *this; }
  SD_INLINE MotionVector operator+(const MotionVector& o) const { return {angular + o.angular, linear + o.linear}; }
  SD_INLINE MotionVector operator-(const MotionVector& o) const { return {angular - o.angular, linear - o.linear}; }
  SD_INLINE MotionVector operator-() const { return {-angular, -linear}; }
  SD_INLINE MotionVector operator*(const S& k) const { return {angular * k, linear * k}; }
};

template <class S>
MotionVector<S> operator*(const S& k, const MotionVector<S>& m) { return m * k; }

}  // namespace spatial_dynamics
