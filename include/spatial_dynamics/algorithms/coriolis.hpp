// The Coriolis matrix C(q, q̇) of M q̈ + C q̇ + g = τ, in the factorisation with Ṁ = C + Cᵀ, and
// the generalized momentum p = M q̇ with Cᵀ q̇ (the momentum observer's inputs, momentum_observer.hpp).
// With M = Σ_k J_kᵀ I_k J_k over the bodies (J_k: body k's Jacobian, I_k its inertia, both in base
// coordinates), C = Σ_k J_kᵀ (I_k J̇_k + B_k J_k) with B(I, v) = ½ (İ + (I v)×̄), İ = v×* I − I v×
// and (f×̄) m = m ×* f: B + Bᵀ = İ gives Ṁ = C + Cᵀ and B v = v ×* I v gives C q̇ = h − g
// (Echeandia and Wensing, "Numerical Methods to Compute the Coriolis Matrix and Christoffel
// Symbols for Rigid-Body Systems", JCND 2021, whose B makes C the Christoffel-symbol one).
#pragma once

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

/// C(row, col) = value, or C(row, col) += k value where coupled mimic joints share coordinates
/// (C = Gᵀ C_free G with G constant; C zeroed first), k the product of the two multipliers.
template <class S>
SD_INLINE void set_coriolis_entry(const Model<S>& model, MatrixX<S>& C, Eigen::Index row, Eigen::Index col,
                                  const S& k, const S& value) {
  if (model.has_coupled_joints)
    C(row, col) += k * value;
  else
    C(row, col) = value;
}

/// C(q, q̇) into data.C, in base coordinates about the base origin, where a subtree's quantities
/// are plain sums. Forward: ^iX_0, v_i = v_λ + S_i q̇_i, S_i, Ṡ_i = v_i × S_i + ^0X_i S̊_i, and body
/// i's I_i, İ_i = v_i×* I_i − I_i v_i× and h_i = I_i v_i. Backward: Iᶜ, İᶜ and hᶜ summed over each
/// subtree. Then for each column s of S_i, with Bᶜ s = ½ (İᶜ s + s ×* hᶜ) and Bᶜᵀ s = ½ (İᶜ s − s ×* hᶜ):
///   C_ji = S_jᵀ (Iᶜ_i Ṡ_i + Bᶜ_i S_i)    for j = i and every ancestor j of i,
///   C_ij = Ṡ_jᵀ Iᶜ_i S_i + S_jᵀ Bᶜ_iᵀ S_i  for every ancestor j of i.
/// Entries between bodies on different branches are zero: Data creates C zeroed and they are
/// never written. Armature adds a constant to M and nothing to C.
template <class S>
void coriolis_matrix_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                          const ConstVectorRef<S>& qd) {
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  joint_sines_and_cosines(model, data, q.data());
  data.X_base[0] = PluckerTransform<S>::Identity();
  data.v_base[0] = MotionVector<S>::Zero();
  for (int i = 1; i < model.nbodies(); ++i) {
    const int lambda = model.parent[i];
    const BodyJoint<S> J(model, data, i, q.data(), qd.data());
    J.visit([&](const auto& joint) SD_INLINE_LAMBDA {
      data.X_up[i] = joint.transform(J.X_tree, J.q, J.s, J.c, J.label);
      const PluckerTransform<S>& X = data.X_base[i] = data.X_up[i] * data.X_base[lambda];  // ^iX_0
      MotionVector<S> v = data.v_base[lambda];
      for (int k = 0; k < joint.nv; ++k) {
        const MotionVector<S>& s = data.S_base[i][k] = X.applyInverse(joint.column(k, J.s, J.c));
        v += s * J.qd[k];  // v_i = v_λ + S_i q̇_i
      }
      data.v_base[i] = v;
      for (int k = 0; k < joint.nv; ++k)  // Ṡ_i = v_i × S_i + ^0X_i S̊_i
        data.S_rate_base[i][k] = cross(v, data.S_base[i][k]) + X.applyInverse(joint.column_rate(k, J.qd, J.s, J.c));
    });
    const RigidInertia<S> I = data.X_base[i].applyInverse(model.inertia[i]);  // ^0X_i* I_i ^iX_0
    data.Ic[i] = I;
    data.Ic_rate[i] = I.rate(data.v_base[i]);  // İ_i (eq. 27)
    data.hc_base[i] = I * data.v_base[i];      // h_i = I_i v_i (eq. 23)
  }
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    const int lambda = model.parent[i];
    if (lambda == 0) continue;
    data.Ic[lambda] += data.Ic[i];
    data.Ic_rate[lambda] += data.Ic_rate[i];
    data.hc_base[lambda] += data.hc_base[i];
  }
  if (model.has_coupled_joints) data.C.setZero();
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& joint_i = model.joints[i];
    const S k_i = coupling_multiplier(joint_i);
    for (int k = 0; k < joint_i.nv; ++k) {
      const Eigen::Index col = joint_i.idx_v + k;
      const MotionVector<S>& s = data.S_base[i][k];
      const ForceVector<S> half_rate = data.Ic_rate[i] * s * S(0.5), half_cross = cross(s, data.hc_base[i]) * S(0.5);
      const ForceVector<S> F = data.Ic[i] * data.S_rate_base[i][k] + half_rate + half_cross;  // Iᶜ Ṡ + Bᶜ S
      const ForceVector<S> IS = data.Ic[i] * s;                                          // Iᶜ S
      const ForceVector<S> BtS = half_rate - half_cross;                                // Bᶜᵀ S
      for (int l = 0; l < joint_i.nv; ++l)  // C_ii
        set_coriolis_entry(model, data.C, joint_i.idx_v + l, col, k_i * k_i, dot(data.S_base[i][l], F));
      for (int j = model.parent[i]; j > 0; j = model.parent[j]) {
        const Joint<S>& joint_j = model.joints[j];
        const S k_ij = k_i * coupling_multiplier(joint_j);
        for (int l = 0; l < joint_j.nv; ++l) {
          const Eigen::Index row = joint_j.idx_v + l;
          set_coriolis_entry(model, data.C, row, col, k_ij, dot(data.S_base[j][l], F));  // C_ji
          set_coriolis_entry(model, data.C, col, row, k_ij,
                             dot(data.S_rate_base[j][l], IS) + dot(data.S_base[j][l], BtS));  // C_ij
        }
      }
    }
  }
}

/// p = M q̇ and Cᵀ q̇ into data.momentum and data.coriolis_transpose_velocity, and with `gravity`
/// g(q) into data.tau as well, in one pass in body coordinates without M or C: forward
/// v_i = ^iX_λ v_λ + S_i q̇_i and h_i = I_i v_i (eq. 23); backward hᶜ_λ += ^iX_λᵀ hᶜ_i; then
/// p_i = S_iᵀ hᶜ_i (+ armature ⊙ q̇) and, since Bᵀ v = 0, Cᵀ q̇ = Σ_k J̇_kᵀ I_k v_k, whose entry for
/// a column s of S_i is (v_i × s + s̊)ᵀ hᶜ_i = sᵀ (−v_i ×* hᶜ_i) + s̊ᵀ hᶜ_i. g is the RNEA's at
/// q̇ = q̈ = 0 (Table 5.1: a_i = ^iX_λ a_λ from a_0 = −a_g, f_i = I_i a_i, τ_i = S_iᵀ f_i,
/// f_λ += ^iX_λᵀ f_i) riding on the same transforms: the momentum observer's one pass.
template <class S>
void momentum_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd,
                   bool gravity) {
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  joint_sines_and_cosines(model, data, q.data());
  data.v[0] = MotionVector<S>::Zero();
  data.a[0] = MotionVector<S>(Vector3<S>::Zero(), -model.gravity);  // a_0 = −a_g
  for (int i = 1; i < model.nbodies(); ++i) {
    const int lambda = model.parent[i];
    const BodyJoint<S> J(model, data, i, q.data(), qd.data());
    J.visit([&](const auto& joint) SD_INLINE_LAMBDA {
      const PluckerTransform<S>& X = data.X_up[i] = joint.transform(J.X_tree, J.q, J.s, J.c, J.label);
      data.v[i] = X.apply(data.v[lambda]) + joint.motion(J.qd, J.s, J.c);
      if (gravity) data.a[i] = X.apply(data.a[lambda]);
    });
    data.h[i] = model.inertia[i] * data.v[i];
    if (gravity) data.f[i] = model.inertia[i] * data.a[i];
  }
  const bool coupled = model.has_coupled_joints;
  if (coupled) {
    data.momentum.setZero();
    data.coriolis_transpose_velocity.setZero();
    if (gravity) data.tau.setZero();
  }
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    const ForceVector<S>& h = data.h[i];
    write_joint_torque(model, data, i, h, data.momentum.data(), coupled);  // p_i = S_iᵀ hᶜ_i
    write_joint_torque(model, data, i, -cross(data.v[i], h), data.coriolis_transpose_velocity.data(), coupled);
    const BodyJoint<S> J(model, data, i, nullptr, qd.data());
    J.visit([&](const auto& joint) SD_INLINE_LAMBDA {  // + s̊ᵀ hᶜ_i
      for (int k = 0; k < joint.nv; ++k)
        data.coriolis_transpose_velocity[J.joint.idx_v + k] +=
            coupling_multiplier(J.joint) * dot(joint.column_rate(k, J.qd, J.s, J.c), h);
    });
    if (gravity) write_joint_torque(model, data, i, data.f[i], data.tau.data(), coupled);  // g_i = S_iᵀ f_i
    const int lambda = model.parent[i];
    if (lambda == 0) continue;
    data.h[lambda] += data.X_up[i].applyInverse(h);
    if (gravity) data.f[lambda] += data.X_up[i].applyInverse(data.f[i]);
  }
  if (model.has_armature)  // + armature ⊙ q̇
    for (int k = 0; k < model.nv; ++k) data.momentum[k] += model.armature[k] * qd[k];
}

}  // namespace detail

/// C(q, q̇) (nv × nv) in data.C, with Ṁ = C + Cᵀ and C q̇ = h(q, q̇) − g(q) (the Christoffel-symbol
/// factorisation); every joint type, fixed or floating base, coupled mimic joints. A non-finite
/// entry throws std::domain_error naming its column.
template <class S>
const MatrixX<S>& coriolis_matrix(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                  const ConstVectorRef<S>& qd) {
  detail::coriolis_matrix_impl(model, data, q, qd);
  detail::check_finite_result(model, "Coriolis matrix: the column", data.C);
  return data.C;
}

/// The generalized momentum p = M(q) q̇ (armature included) in data.momentum, without forming M;
/// the same pass leaves Cᵀ q̇ in data.coriolis_transpose_velocity.
template <class S>
const VectorX<S>& generalized_momentum(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                       const ConstVectorRef<S>& qd) {
  detail::momentum_impl(model, data, q, qd, false);
  detail::check_finite_result(model, "generalized momentum: the coordinate", data.momentum);
  return data.momentum;
}

/// C(q, q̇)ᵀ q̇ in data.coriolis_transpose_velocity, without forming C (= Ṁ q̇ − C q̇); the same
/// pass leaves p = M q̇ in data.momentum.
template <class S>
const VectorX<S>& coriolis_transpose_times_velocity(const Model<S>& model, Data<S>& data,
                                                    const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd) {
  detail::momentum_impl(model, data, q, qd, false);
  detail::check_finite_result(model, "Cᵀ q̇: the coordinate", data.coriolis_transpose_velocity);
  return data.coriolis_transpose_velocity;
}

/// What the momentum observer needs at (q, q̇), in one pass: p = M q̇ in data.momentum, Cᵀ q̇ in
/// data.coriolis_transpose_velocity and g(q) in data.tau. A non-finite result throws as above.
template <class S>
void momentum_observer_terms(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                             const ConstVectorRef<S>& qd) {
  detail::momentum_impl(model, data, q, qd, true);
  detail::check_finite_result(model, "generalized momentum: the coordinate", data.momentum);
  detail::check_finite_result(model, "Cᵀ q̇: the coordinate", data.coriolis_transpose_velocity);
  detail::check_finite_result(model, "gravity torques: the joint force", data.tau);
}

}  // namespace spatial_dynamics
