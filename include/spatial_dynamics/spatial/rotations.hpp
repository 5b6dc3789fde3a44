// Coordinate rotations of a rotation matrix E by an angle of known sine and cosine: about a
// coordinate axis (two rows mixed) or about a general unit axis (RBDA eq. 2.24, transposed).
#pragma once

#include "spatial_dynamics/spatial/mat3.hpp"

namespace spatial_dynamics {
namespace detail {

/// rot_k(θ) E for the coordinate rotation about axis k (RBDA Table 2.2's rx, ry, rz), from
/// c = cos θ and s = sin θ: rows m = k + 1 and n = k + 2 (mod 3) of E become
/// (c·row_m + s·row_n, c·row_n − s·row_m).
template <int k, class S>
SD_INLINE Mat3<S> rotated_about_coordinate_axis(const Mat3<S>& E, const S& c, const S& s) {
  constexpr int m = (k + 1) % 3, n = (k + 2) % 3;
  const auto column = [](const S& at_m, const S& at_n) SD_INLINE_LAMBDA {  // of rot_k(θ)
    S x[3] = {S(0), S(0), S(0)};
    x[m] = at_m;
    x[n] = at_n;
    return Vec3<S>(x[0], x[1], x[2]);
  };
  Mat3<S> R;
  R.column[k] = Vec3<S>::Unit(k);
  R.column[m] = column(c, -s);
  R.column[n] = column(s, c);
  return R * E;
}

/// rot(a, θ)ᵀ E for a unit axis a, from c = cos θ and s = sin θ (RBDA eq. 2.24, transposed):
/// rot(a, θ)ᵀ = c 1 − s a× + (1 − c) a aᵀ by its columns, times E.
template <class S>
SD_INLINE Mat3<S> rotated_about_axis(const Mat3<S>& E, const Vec3<S>& a, const S& c, const S& s) {
  const S k = S(1) - c;
  const Mat3<S> R(a * (k * a[0]) + Vec3<S>(c, -(s * a[2]), s * a[1]),  // column j: c e_j − s a × e_j + k a_j a
                  a * (k * a[1]) + Vec3<S>(s * a[2], c, -(s * a[0])),
                  a * (k * a[2]) + Vec3<S>(-(s * a[1]), s * a[0], c));
  return R * E;
}

}  // namespace detail
}  // namespace spatial_dynamics
