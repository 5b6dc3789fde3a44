// The ABA's gravity split: q̈ = FD(q, q̇, τ) under gravity equals FD(q, q̇, τ − τ_g(q)) without it,
// τ_g(q) = ID(q, 0, 0) the generalised gravity force (RBDA eq. 5.1: M q̈ + C q̇ + τ_g = τ).
//
// With gravity as the base acceleration a_0 = −a_g (RBDA §5.3), every joint of a robot holding
// itself up against gravity solves q̈ = D⁻¹(u − Uᵀ a') from u and Uᵀ a', both of the size of its
// gravity torque, while D q̈ is often far smaller: the roundings of each pass, a few ε of the
// gravity torque, are divided by D. Forming τ − τ_g once in a type about twice as precise
// (WiderScalar) leaves the three passes only the motion's own forces to round.
//
// τ_g comes from the subtrees' masses and first moments, which gravity's uniform field reduces
// to: subtree i pulled by g_i (gravity in body i's coordinates) exerts about body i's origin the
// wrench (h_i × g_i ; M_i g_i), so τ_g,i = Sᵢᵀ (g_i × h_i ; −M_i g_i) (the RNEA's f_i = I a_i
// with a_i = (0 ; −g_i), summed over the subtree).
#pragma once

#include <type_traits>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {
namespace detail {

/// Whether the ABA splits gravity off: for float and double, whose wider type is cheap, when
/// the model has gravity. Other scalars (the float128 reference, long double, double-double) keep
/// gravity in the passes: the split's identity Eᵀ(h × g) = (Eᵀh) × (Eᵀg) holds for orthogonal E
/// only, and a model's rotations (rpy angles, a general axis) are orthogonal to double's
/// precision, not to theirs. There the ABA stays the exact inverse of the RNEA on the model as
/// given, as a reference must.
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

/// Body i on the way out (after data.X_up[i]): g_i = E_i g_λ; its subtree's sums start from its
/// own mass and first moment.
template <class S>
SD_INLINE void gravity_split_outward(const Model<S>& model, Data<S>& data, int i) {
  using W = WiderScalar<S>;
  const Matrix3<S>& E = data.X_up[i].E;
  const W* g = data.gravity_split[model.parent[i]].gravity;
  auto& b = data.gravity_split[i];
  for (int r = 0; r < 3; ++r) b.gravity[r] = E(r, 0) * g[0] + E(r, 1) * g[1] + E(r, 2) * g[2];
  b.mass = W(model.inertia[i].mass);
  for (int k = 0; k < 3; ++k) b.first_moment[k] = W(model.inertia[i].first_moment[k]);
}

/// Body i on the way in, its subtree's sums complete: τ − τ_g for its joint into
/// data.tau_less_gravity (rounded once), then h_λ += Eᵢᵀ h_i + M_i r_i and M_λ += M_i.
/// A free joint's six components are (g × h ; −M g) of the whole robot.
template <class S>
SD_INLINE void gravity_split_inward(const Model<S>& model, Data<S>& data, int i, const ConstVectorRef<S>& tau) {
  using W = WiderScalar<S>;
  const Joint<S>& j = model.joints[i];
  const auto& b = data.gravity_split[i];
  const W* g = b.gravity;
  const W* h = b.first_moment;
  const int v = j.idx_v;
  S* out = data.tau_less_gravity.data();
  if (j.type == JointType::Revolute) {  // aᵀ (g × h)
    W torque;
    switch (j.axis_kind) {
      case AxisKind::X: torque = g[1] * h[2] - g[2] * h[1]; break;
      case AxisKind::Y: torque = g[2] * h[0] - g[0] * h[2]; break;
      case AxisKind::Z: torque = g[0] * h[1] - g[1] * h[0]; break;
      default:
        torque = j.axis[0] * (g[1] * h[2] - g[2] * h[1]) + j.axis[1] * (g[2] * h[0] - g[0] * h[2]) +
                 j.axis[2] * (g[0] * h[1] - g[1] * h[0]);
    }
    out[v] = S(W(tau[v]) - torque);
  } else if (j.type == JointType::Prismatic) {  // aᵀ (−M g)
    out[v] = S(W(tau[v]) + b.mass * (j.axis[0] * g[0] + j.axis[1] * g[1] + j.axis[2] * g[2]));
  } else {  // free joint, S = 1
    out[v + 0] = S(W(tau[v + 0]) - (g[1] * h[2] - g[2] * h[1]));
    out[v + 1] = S(W(tau[v + 1]) - (g[2] * h[0] - g[0] * h[2]));
    out[v + 2] = S(W(tau[v + 2]) - (g[0] * h[1] - g[1] * h[0]));
    for (int k = 0; k < 3; ++k) out[v + 3 + k] = S(W(tau[v + 3 + k]) + b.mass * g[k]);
  }
  const int lambda = model.parent[i];
  if (lambda == 0) return;
  const Matrix3<S>& E = data.X_up[i].E;
  const Vector3<S>& r = data.X_up[i].r;
  auto& p = data.gravity_split[lambda];
  for (int c = 0; c < 3; ++c) p.first_moment[c] += E(0, c) * h[0] + E(1, c) * h[1] + E(2, c) * h[2] + r[c] * b.mass;
  p.mass += b.mass;
}

}  // namespace detail
}  // namespace spatial_dynamics
