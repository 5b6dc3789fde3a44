// The ABA's gravity split: q̈ = FD(q, q̇, τ) under gravity equals FD(q, q̇, τ − τ_g(q)) without it,
// τ_g(q) = ID(q, 0, 0) the generalised gravity force (RBDA eq. 5.1: M q̈ + C q̇ + τ_g = τ).
//
// With gravity as the base acceleration a_0 = −a_g (RBDA §5.3), every joint of a robot holding
// itself up against gravity solves q̈ = D⁻¹(u − Uᵀ a') from u and Uᵀ a', both of the size of its
// gravity torque, while D q̈ is often far smaller: the roundings of each pass, a few ε of the
// gravity torque, are divided by D. Forming τ − τ_g once in a type about twice as precise
// (WiderScalar) leaves the three passes only the motion's own forces to round.
//
// τ_g is the RNEA's with q̇ = q̈ = 0 (a_0 = −a_g): body i's acceleration is the pure linear
// (0 ; −g_i), g_i gravity in its coordinates (g_i = E_i g_λ), its force I_i (0 ; −g_i) =
// (g_i × h_i ; −m_i g_i) (h_i = m_i c_i), the forces summed inwards by Xᵀ and projected by Sᵀ.
// The sums are the RNEA's to the letter, not the shorter form with subtree masses and first
// moments: that one takes the transforms' rotations for exactly orthogonal, which they are only to
// double's precision, and on a long chain with general axes the difference outgrows the rounding.
#pragma once

#include <type_traits>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {
namespace detail {

/// Whether the ABA splits gravity off: for float and double, whose wider type is cheap, when
/// the model has gravity. Other scalars (the float128 reference, long double, double-double) have
/// no wider type to gain from and keep gravity in the passes as the base acceleration.
template <class S>
SD_INLINE bool splits_gravity(const Model<S>& model) {
  if constexpr (std::is_same<WiderScalar<S>, S>::value) {
    return false;
  } else {
    return !(model.gravity[0] == S(0) && model.gravity[1] == S(0) && model.gravity[2] == S(0));
  }
}

/// Starts the split: the base's gravity a_g.
template <class S>
SD_INLINE void gravity_split_start(const Model<S>& model, Data<S>& data) {
  for (int k = 0; k < 3; ++k) data.gravity_split[0].gravity[k] = WiderScalar<S>(model.gravity[k]);
}

/// Body i on the way out (after data.X_up[i]): g_i = E_i g_λ and its own gravity force
/// (g_i × h_i ; −m_i g_i), where the sum over its subtree starts.
template <class S>
SD_INLINE void gravity_split_outward(const Model<S>& model, Data<S>& data, int i) {
  using W = WiderScalar<S>;
  const Matrix3<S>& E = data.X_up[i].E;
  const W* g_parent = data.gravity_split[model.parent[i]].gravity;
  auto& b = data.gravity_split[i];
  W* g = b.gravity;
  for (int r = 0; r < 3; ++r) g[r] = E(r, 0) * g_parent[0] + E(r, 1) * g_parent[1] + E(r, 2) * g_parent[2];
  const Vector3<S>& h = model.inertia[i].first_moment;
  const S m = model.inertia[i].mass;
  b.moment[0] = g[1] * h[2] - g[2] * h[1];
  b.moment[1] = g[2] * h[0] - g[0] * h[2];
  b.moment[2] = g[0] * h[1] - g[1] * h[0];
  for (int k = 0; k < 3; ++k) b.force[k] = -(g[k] * m);
}

/// Body i on the way in, its subtree's force complete: τ − Sᵀ f for its joint into
/// data.tau_less_gravity (rounded once), then f_λ += Xᵀ f = (Eᵀ n + r × Eᵀ f ; Eᵀ f).
template <class S>
SD_INLINE void gravity_split_inward(const Model<S>& model, Data<S>& data, int i, const ConstVectorRef<S>& tau) {
  using W = WiderScalar<S>;
  const Joint<S>& j = model.joints[i];
  const auto& b = data.gravity_split[i];
  const W* n = b.moment;
  const W* f = b.force;
  const int v = j.idx_v;
  S* out = data.tau_less_gravity.data();
  W projected[6];
  joint_project(j, data.joint_sin[i], data.joint_cos[i], n, f, projected);  // Sᵀ f, in W
  for (int k = 0; k < j.nv; ++k) out[v + k] = S(W(tau[v + k]) - projected[k]);
  const int lambda = model.parent[i];
  if (lambda == 0) return;
  const Matrix3<S>& E = data.X_up[i].E;
  const Vector3<S>& r = data.X_up[i].r;
  W Etf[3];
  for (int c = 0; c < 3; ++c) Etf[c] = E(0, c) * f[0] + E(1, c) * f[1] + E(2, c) * f[2];
  auto& p = data.gravity_split[lambda];
  for (int c = 0; c < 3; ++c) p.moment[c] += E(0, c) * n[0] + E(1, c) * n[1] + E(2, c) * n[2];
  p.moment[0] += r[1] * Etf[2] - r[2] * Etf[1];
  p.moment[1] += r[2] * Etf[0] - r[0] * Etf[2];
  p.moment[2] += r[0] * Etf[1] - r[1] * Etf[0];
  for (int c = 0; c < 3; ++c) p.force[c] += Etf[c];
}

}  // namespace detail
}  // namespace spatial_dynamics
