// Coordinate rotations of a rotation matrix E by an angle of known sine and cosine: about a
// coordinate axis (two rows mixed) or about a general unit axis (RBDA eq. 2.24, transposed), in
// place or into a new matrix (packed where the CPU has AVX2 and FMA).
#pragma once

#include <type_traits>

#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"

namespace spatial_dynamics {
namespace detail {

/// Rows (m, n) of E become (c·row_m + s·row_n, −s·row_m + c·row_n): E ← rot_axis(θ) E
/// for a coordinate rotation about the remaining axis.
template <class S>
SD_INLINE void rotate_rows(Matrix3<S>& E, int m, int n, const S& c, const S& s) {
  for (int k = 0; k < 3; ++k) {
    const S em = E(m, k), en = E(n, k);
    E(m, k) = c * em + s * en;
    E(n, k) = c * en - s * em;
  }
}

/// E ← rot(a, θ)ᵀ E column by column, from c = cos θ and s = sin θ (RBDA eq. 2.24, transposed):
/// each column e becomes c e − s a×e + (1 − c)(a·e) a, without forming the rotation matrix.
template <class S>
SD_INLINE void rotate_about_axis(Matrix3<S>& E, const Vector3<S>& a, const S& c, const S& s) {
  for (int k = 0; k < 3; ++k) {
    const Vector3<S> e = E.col(k);
    E.col(k) = c * e - s * cross_3d(a, e) + ((S(1) - c) * a.dot(e)) * a;
  }
}

/// rot(a, θ)ᵀ E for a general unit axis a, from c = cos θ and s = sin θ (RBDA eq. 2.24,
/// transposed): packed where the CPU has AVX2 and FMA.
template <class S>
SD_INLINE Matrix3<S> rotated_about_axis(const Matrix3<S>& E_tree, const Vector3<S>& a, const S& c, const S& s) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) {
    using namespace packed3;
    Packed3 c0, c1, c2;
    load_columns(E_tree, c0, c1, c2);
    // rot(a, θ)ᵀ = c 1 − s a× + (1 − c) a aᵀ, by its rows r0..r2.
    const Packed3 axis = make(a.x(), a.y(), a.z());
    const double k = 1 - c;
    const Packed3 r0 = (k * a.x()) * axis + make(c, -s * a.z(), s * a.y());
    const Packed3 r1 = (k * a.y()) * axis + make(s * a.z(), c, -s * a.x());
    const Packed3 r2 = (k * a.z()) * axis + make(-s * a.y(), s * a.x(), c);
    Matrix3<S> E;
    store3(mat_vec(r0, r1, r2, c0), E.data());
    store3(mat_vec(r0, r1, r2, c1), E.data() + 3);
    store3(mat_vec(r0, r1, r2, c2), E.data() + 6);
    return E;
  }
#endif
  Matrix3<S> E = E_tree;
  rotate_about_axis(E, a, c, s);
  return E;
}

}  // namespace detail
}  // namespace spatial_dynamics
