// What is known of a rotation E beyond its coefficients: that it is the rotation about a coordinate
// axis by an angle of known sine and cosine. Such a rotation's products (packed3.hpp's
// AxisRotation) mix two lanes of a vector where a product with E's coefficients takes all nine.
#pragma once

namespace spatial_dynamics {

/// E is the rotation about coordinate axis `axis` (0–2; RBDA Table 2.2's rx, ry, rz) by the angle
/// of sine s and cosine c, or nothing is known (axis −1). ^iX_λ of a revolute joint about a
/// coordinate axis whose tree transform does not rotate is such a rotation (Data::up_rotation_axis).
template <class S>
struct RotationAboutAxis {
  int axis = -1;
  S s = S(0), c = S(1);
};

/// Eᵀ's structure from E's: the rotation about the same axis by the opposite angle.
template <class S>
RotationAboutAxis<S> transposed(const RotationAboutAxis<S>& E) {
  return {E.axis, -E.s, E.c};
}

}  // namespace spatial_dynamics
