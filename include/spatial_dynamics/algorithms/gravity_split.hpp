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
// The wide 3-vectors and their operations are spatial/number/wide_vector3.hpp's (packed where the CPU has it).
#pragma once

#include <type_traits>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/wide_vector3.hpp"

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
  using Wide = wide3::Form<S>;
  Wide::store(Wide::from(model.gravity), data.gravity_split[0].gravity);
}

/// Body i on the way out: g_i = E_i g_λ (E_i of data.X_up[i]) and its own gravity force
/// (g_i × h_i ; −m_i g_i), where the sum over its subtree starts.
template <class S>
SD_INLINE void gravity_split_outward(const Model<S>& model, Data<S>& data, int i) {
  using Wide = wide3::Form<S>;
  auto& body = data.gravity_split[i];
  const typename Wide::Vector g =
      Wide::rotation(data.X_up[i].E) * Wide::load(data.gravity_split[model.parent[i]].gravity);
  Wide::store(g, body.gravity);
  Wide::store(wide3::cross(g, model.inertia[i].first_moment), body.moment);
  Wide::store(wide3::scale(S(-model.inertia[i].mass), g), body.force);
}

/// Body i on the way in, its subtree's force complete: τ − Sᵀ f for its joint into
/// data.tau_less_gravity (rounded once), then f_λ += Xᵀ f = (Eᵀ n + r × Eᵀ f ; Eᵀ f) (eq. 12).
template <class S>
SD_INLINE void gravity_split_inward(const Model<S>& model, Data<S>& data, int i, const ConstVectorRef<S>& tau) {
  using W = WiderScalar<S>;
  using Wide = wide3::Form<S>;
  const Joint<S>& j = model.joints[i];
  const auto& body = data.gravity_split[i];
  const typename Wide::Vector n = Wide::load(body.moment), f = Wide::load(body.force);
  W projected[6], n_lanes[3], f_lanes[3];  // Sᵀ f, in W
  Wide::lanes(n, n_lanes);
  Wide::lanes(f, f_lanes);
  joint_project(j, data.joint_sin[i], data.joint_cos[i], n_lanes, f_lanes, projected);
  for (int k = 0; k < j.nv; ++k) data.tau_less_gravity[j.idx_v + k] = S(W(tau[j.idx_v + k]) - projected[k]);
  const int lambda = model.parent[i];
  if (lambda == 0) return;
  const auto Et = Wide::transposed_rotation(data.X_up[i].E);
  const typename Wide::Vector Et_n = Et * n, Et_f = Et * f;
  auto& parent = data.gravity_split[lambda];
  Wide::store(Wide::load(parent.moment) + (Et_n + wide3::cross(data.X_up[i].r, Et_f)), parent.moment);
  Wide::store(Wide::load(parent.force) + Et_f, parent.force);
}

}  // namespace detail
}  // namespace spatial_dynamics
