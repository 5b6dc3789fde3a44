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
// The sums are the RNEA's to the letter, not the shorter sum with subtree masses and first
// moments: that one takes the transforms' rotations for exactly orthogonal, which they are only to
// double's precision, and on a long chain with general axes the difference outgrows the rounding.
// The wide 3-vectors' products with S are spatial/number/wide_vec3.hpp's (packed where the CPU has them).
#pragma once

#include <type_traits>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/wide_vec3.hpp"

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
  using W = WiderScalar<S>;
  data.gravity_split[0].gravity = Vec3<W>(W(model.gravity[0]), W(model.gravity[1]), W(model.gravity[2]));
}

/// Body i on the way out: g_i = E_i g_λ (E_i of data.X_up[i]) and its own gravity force
/// (g_i × h_i ; −m_i g_i), where the sum over its subtree starts.
template <class S>
SD_INLINE void gravity_split_outward(const Model<S>& model, Data<S>& data, int i) {
  auto& body = data.gravity_split[i];
  body.gravity = data.X_up[i].E * data.gravity_split[model.parent[i]].gravity;  // g_i = E_i g_λ
  body.force.angular = cross(body.gravity, model.inertia[i].first_moment);      // g_i × h_i
  body.force.linear = S(-model.inertia[i].mass) * body.gravity;                 // −m_i g_i
}

/// Body i on the way in, its subtree's force complete: τ − Sᵀ f for its joint into
/// data.tau_less_gravity (rounded once), then f_λ += Xᵀ f (eq. 12).
template <class S>
SD_INLINE void gravity_split_inward(const Model<S>& model, Data<S>& data, int i, const ConstVectorRef<S>& tau) {
  using W = WiderScalar<S>;
  const Joint<S>& j = model.joints[i];
  const auto& body = data.gravity_split[i];
  W projected[6];  // Sᵀ f, in W
  joint_project(j, data.joint_sin[i], data.joint_cos[i], body.force.angular, body.force.linear, projected);
  for (int k = 0; k < j.nv; ++k) data.tau_less_gravity[j.idx_v + k] = S(W(tau[j.idx_v + k]) - projected[k]);
  const int lambda = model.parent[i];
  if (lambda == 0) return;
  data.gravity_split[lambda].force += data.X_up[i].applyInverse(body.force);
}

}  // namespace detail
}  // namespace spatial_dynamics
