// What the joint types share: products with a coordinate axis e_k that read one component or
// two (the coordinate rotations about an axis are spatial/rotations.hpp's).
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
#include "spatial_dynamics/spatial/rotations.hpp"

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
