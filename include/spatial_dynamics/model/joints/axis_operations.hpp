// What the joint types share: products with a coordinate axis e_k that read one component or
// two, and the coordinate rotations about an axis.
#pragma once

#include <string>

#include "spatial_dynamics/spatial/cross.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/number/lane_trigonometry.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

/// Who a joint type's transform works for, for its error messages: the joint's name and its first
/// coordinate in q.
struct JointLabel {
  const std::string& name;
  int idx_q;
};

namespace detail {

/// q e_k.
template <class S, int k>
SD_INLINE Vector3<S> unit_axis(const S& q) {
  Vector3<S> x = Vector3<S>::Zero();
  x[k] = q;
  return x;
}

/// x × (q e_k): (x × e_k)_k = 0, (x × e_k)_{k+1} = x_{k+2}, (x × e_k)_{k+2} = −x_{k+1} (indices mod 3).
template <int k, class S>
SD_INLINE Vector3<S> cross_unit_axis(const Vector3<S>& x, const S& q) {
  constexpr int m = (k + 1) % 3, n = (k + 2) % 3;
  Vector3<S> y;
  y[k] = S(0);
  y[m] = x[n] * q;
  y[n] = -(x[m] * q);
  return y;
}

/// sin θ and cos θ of one angle: the batched routine on one lane (lane_trigonometry.hpp, within
/// 1 ulp for double and |θ| ≤ 1e5); other scalars and larger angles take std::sin and std::cos.
template <class S>
SD_INLINE void joint_sin_cos(const S& angle, S& s, S& c) {
  Lanes<S, 1> sine, cosine;
  sincos_lanes(Lanes<S, 1>::Constant(angle), sine, cosine);
  s = sine[0];
  c = cosine[0];
}

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

/// ^iX_λ's E = E_J(θ) E_tree of a revolute joint as B0 + cos θ B1 + sin θ B2 (Rodrigues' E_J =
/// c 1 − s a× + (1 − c) a aᵀ, RBDA eq. 2.24, times E_tree): B0 = a aᵀ E_tree, B1 = E_tree − B0,
/// B2 = −a× E_tree, constants of the model, so that forming E takes two products per column
/// instead of the rotation of E_tree's columns. In double-double, for the residual RNEA
/// (algorithms/wide_residual_form.hpp), and rounded once for the packed passes (Data).
struct RevoluteRotationTerms {
  DoubleDouble B[3][3][3];  // B[t][k][m]: term t (B0, B1, B2), column k, row m
};
inline RevoluteRotationTerms revolute_rotation_terms(const Vector3<double>& a, const Matrix3<double>& E_tree) {
  using DD = DoubleDouble;
  RevoluteRotationTerms terms;
  for (int k = 0; k < 3; ++k) {  // column k of each, from E_tree's column t
    const Vector3<double> t = E_tree.col(k);
    const DD a_dot_t = (DD(a[0]) * t[0] + DD(a[1]) * t[1]) + DD(a[2]) * t[2];
    for (int m = 0; m < 3; ++m) {
      const int m1 = (m + 1) % 3, m2 = (m + 2) % 3;
      terms.B[0][k][m] = a_dot_t * a[m];                         // a aᵀ t
      terms.B[1][k][m] = DD(t[m]) - terms.B[0][k][m];            // t − a aᵀ t
      terms.B[2][k][m] = DD(a[m2]) * t[m1] - DD(a[m1]) * t[m2];  // −a × t
    }
  }
  return terms;
}

}  // namespace detail
}  // namespace spatial_dynamics
