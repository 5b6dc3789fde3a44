// Articulated-body algorithm, q̈ = FD(q, q̇, τ, f_ext)   (RBDA Table 7.1). For float and double,
// gravity is split off first: the passes solve FD(q, q̇, τ − τ_g(q)) without it (gravity_split.hpp).
// A joint whose subtree has no inertia along its motion (D = Sᵀ Iᴬ S = 0, e.g. a massless leaf)
// makes forward dynamics undefined: the call fails with a message naming that joint.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>
#include <array>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "spatial_dynamics/algorithms/gravity_split.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

template <class S>
[[noreturn]] void throw_singular_joint(const Model<S>& model, int i) {
  throw std::domain_error("joint '" + model.joint_names[i] +
                          "': its subtree has no inertia along the joint's motion (Sᵀ Iᴬ S = 0, e.g. a massless "
                          "leaf link), so forward dynamics is undefined");
}

template <class S>
SD_INLINE void check_aba_inputs(const Model<S>& model, const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd,
                                const ConstVectorRef<S>& tau) {
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  check_length("effort", tau.size(), model.nv);
  if (model.has_coupled_joints)
    throw std::invalid_argument("the model has coupled mimic joints, which the ABA cannot solve; use forward_dynamics()");
}

/// Pass 1 (outward): ^iX_λ, v_i = X v_λ + S q̇, c_i = c_J + v_i × S q̇, Iᴬ_i = I_i and
/// pᴬ_i = v_i ×* I_i v_i − f_ext,i (RBDA Table 7.1); with split_gravity, the wide pass of
/// gravity_split.hpp alongside.
template <class S>
void aba_velocity_pass(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                       const ConstVectorRef<S>& qd, const ForceVector<S>* f_ext, bool split_gravity) {
  joint_sines_and_cosines(model, data, q.data());
  data.v[0] = MotionVector<S>::Zero();
  if (split_gravity) gravity_split_start(model, data);
  for (int i = 1; i < model.nbodies(); ++i) {
    const BodyJoint<S> J(model, data, i, q.data(), qd.data());
    J.visit([&](const auto& joint) SD_INLINE_LAMBDA {
      const PluckerTransform<S>& X = data.X_up[i] = joint.transform(J.X_tree, J.q, J.s, J.c, J.label);
      data.v[i] = X.apply(data.v[model.parent[i]]) + joint.motion(J.qd, J.s, J.c);
      data.c[i] = joint.velocity_product(data.v[i], J.qd, J.s, J.c);
    });
    if (split_gravity) gravity_split_outward(model, data, i);
    const RigidInertia<S>& I = model.inertia[i];
    data.IA[i] = ArticulatedInertia<S>(I);
    data.f[i] = I.biasForce(data.v[i]);
    if (f_ext) data.f[i] -= f_ext[i];
  }
}

/// Pass 2's inertia part at body i: U = Iᴬ S, D = Sᵀ U (+ armature, RBDA §7.3), D⁻¹, and
/// Iᴬ_λ += Xᵀ Iᵃ X with Iᵃ = Iᴬ − U D⁻¹ Uᵀ; returns Iᵃ c_i for the force part (zero at a joint on
/// the base). Compiled once per joint type, with its number of coordinates n.
template <class S>
SD_INLINE ForceVector<S> articulated_inertia_step(const Model<S>& model, Data<S>& data, int i) {
  const S s = data.joint_sin[i], c = data.joint_cos[i];
  return visit_joint(model.joints[i], [&](const auto& joint) SD_INLINE_LAMBDA {
    constexpr int n = std::decay_t<decltype(joint)>::nv;
    const ArticulatedInertia<S>& IA = data.IA[i];
    std::array<ForceVector<S>, 6>& U = data.U[i];
    Eigen::Matrix<S, n, n> D;
    // D is numerically zero where it is below the rounding noise of the blocks of Iᴬ that S's
    // columns reach (kg m² for a rotation, kg for a translation), so that the test does not
    // depend on the units (a millimetre robot is not singular). Those blocks are positive
    // semi-definite, so their largest entries are on their diagonals.
    using std::abs;
    using std::max;
    S scale(0);
    for (int k = 0; k < n; ++k) {
      const MotionVector<S> column = joint.column(k, s, c);
      U[k] = IA * column;                                          // U = Iᴬ S
      D.col(k) = joint.project(U[k], s, c);                        // D = Sᵀ U
      if (model.has_armature) D(k, k) += model.armature[model.joints[i].idx_v + k];
      for (int m = 0; m < 3; ++m) {
        if (!column.angular.isZero()) scale = max(scale, abs(IA.A(m, m)));
        if (!column.linear.isZero()) scale = max(scale, abs(IA.C(m, m)));
      }
    }
    const S tolerance = S(64) * Eigen::NumTraits<S>::epsilon() * scale;
    auto D_inv = data.D_inv[i].template topLeftCorner<n, n>();
    if constexpr (n == 1) {
      if (!(D(0, 0) > tolerance)) throw_singular_joint(model, i);
      D_inv(0, 0) = S(1) / D(0, 0);
    } else {
      const Eigen::LLT<Eigen::Matrix<S, n, n>> llt(D);
      bool singular = llt.info() != Eigen::Success;
      for (int k = 0; k < n && !singular; ++k) singular = !(D(k, k) > tolerance);
      if (singular) throw_singular_joint(model, i);
      D_inv = llt.solve(Eigen::Matrix<S, n, n>::Identity());
    }
    const int lambda = model.parent[i];
    if (lambda == 0) return ForceVector<S>::Zero();
    // Iᴬ_λ += Xᵀ Iᵃ X for Iᵃ = Iᴬ − U D⁻¹ Uᵀ, as Xᵀ Iᴬ X − W D⁻¹ Wᵀ with W = Xᵀ U: the same
    // matrix, whose transform does not wait for D⁻¹; and Iᵃ c = Iᴬ c − U D⁻¹ Uᵀ c.
    const PluckerTransform<S>& X = data.X_up[i];
    ArticulatedInertia<S> XtIaX = X.applyInverse(IA);
    ForceVector<S> Ia_c = IA * data.c[i];
    std::array<ForceVector<S>, n> W;
    std::array<S, n> Ut_c;
    for (int k = 0; k < n; ++k) {
      W[k] = X.applyInverse(U[k]);
      Ut_c[k] = dot(data.c[i], U[k]);
    }
    for (int k = 0; k < n; ++k) {
      ForceVector<S> W_D_inv_k = W[0] * D_inv(0, k);
      S D_inv_Ut_c_k = D_inv(0, k) * Ut_c[0];
      for (int l = 1; l < n; ++l) {
        W_D_inv_k += W[l] * D_inv(l, k);
        D_inv_Ut_c_k += D_inv(l, k) * Ut_c[l];
      }
      XtIaX.subtractOuter(W[k], W_D_inv_k);
      Ia_c -= U[k] * D_inv_Ut_c_k;
    }
    data.IA[lambda] += XtIaX;
    return Ia_c;
  });
}

/// Pass 2's force part at body i, on the factorisation (U, D⁻¹, X_up) in data: u_i = τ_i − Sᵀ p_i,
/// then p_λ += Xᵀ pᵃ with pᵃ = p_i + Iᵃ c_i + U D⁻¹ u_i (Iᵃ c_i: `inertia_times_bias`, none when
/// solving M δ = r with the factorisation, aba_refined.hpp). p_i holds pᴬ_i on entry.
template <class S>
SD_INLINE void articulated_force_step(const Model<S>& model, const Data<S>& data, int i, const S* tau,
                                      ForceVector<S>* p, Vector6<S>* u, const ForceVector<S>* inertia_times_bias) {
  const Joint<S>& joint = model.joints[i];
  S projected[6];
  body_joint_project(model, data, i, p[i], projected);
  for (int k = 0; k < joint.nv; ++k) u[i][k] = tau[joint.idx_v + k] - projected[k];  // u = τ − Sᵀ pᴬ
  const int lambda = model.parent[i];
  if (lambda == 0) return;
  ForceVector<S> pa = p[i];
  for (int k = 0; k < joint.nv; ++k) {  // pᵃ = pᴬ + U D⁻¹ u
    S D_inv_u(0);
    for (int l = 0; l < joint.nv; ++l) D_inv_u += data.D_inv[i](k, l) * u[i][l];
    pa += data.U[i][k] * D_inv_u;
  }
  if (inertia_times_bias) pa += *inertia_times_bias;  // + Iᵃ c
  p[lambda] += data.X_up[i].applyInverse(pa);          // pᴬ_λ += Xᵀ pᵃ (eq. 12)
}

/// Pass 2 (inward): articulated inertias and bias forces, from data.X_up, c, Iᴬ = I and f = pᴬ;
/// with split_gravity, the joint forces τ − τ_g(q) in place of τ.
template <class S>
void aba_inertia_pass(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& tau_in, bool split_gravity) {
  const S* tau = split_gravity ? data.tau_less_gravity.data() : tau_in.data();
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    if (split_gravity) gravity_split_inward(model, data, i, tau_in);  // τ − τ_g at joint i
    const ForceVector<S> Ia_c = articulated_inertia_step(model, data, i);
    articulated_force_step(model, data, i, tau, data.f.data(), data.u.data(), &Ia_c);
  }
}

/// Pass 3 (outward) on the factorisation in data, from a[0]: a'_i = X a_λ + c_i,
/// q̈_i = D⁻¹(u_i − Uᵀ a'_i), a_i = a'_i + S q̈_i. `c` is the ABA's velocity-product
/// accelerations; none (nullptr) when solving M δ = r with the factorisation.
template <class S>
SD_INLINE void articulated_acceleration_pass(const Model<S>& model, const Data<S>& data, const MotionVector<S>* c,
                                             const Vector6<S>* u, MotionVector<S>* a, S* qdd) {
  for (int i = 1; i < model.nbodies(); ++i) {
    MotionVector<S> a_prime = data.X_up[i].apply(a[model.parent[i]]);
    if (c) a_prime += c[i];
    visit_joint(model.joints[i], [&](const auto& joint) SD_INLINE_LAMBDA {
      constexpr int n = std::decay_t<decltype(joint)>::nv;
      Eigen::Matrix<S, n, 1> u_less_Ut_a;  // u − Uᵀ a'
      for (int k = 0; k < n; ++k) u_less_Ut_a[k] = u[i][k] - dot(a_prime, data.U[i][k]);
      const Eigen::Matrix<S, n, 1> qdd_i = data.D_inv[i].template topLeftCorner<n, n>() * u_less_Ut_a;
      for (int k = 0; k < n; ++k) qdd[model.joints[i].idx_v + k] = qdd_i[k];
      a[i] = a_prime + joint.motion(qdd_i.data(), data.joint_sin[i], data.joint_cos[i]);  // a = a' + S q̈
    });
  }
}

/// Pass 3 of the ABA: accelerations into data.qdd; gravity as a_0 = −a_g unless it was split off.
template <class S>
SD_INLINE void aba_acceleration_pass(const Model<S>& model, Data<S>& data, bool split_gravity) {
  data.a[0] = MotionVector<S>(Vector3<S>::Zero(), split_gravity ? Vector3<S>::Zero() : Vector3<S>(-model.gravity));
  articulated_acceleration_pass(model, data, data.c.data(), data.u.data(), data.a.data(), data.qdd.data());
}

template <class S>
const VectorX<S>& aba_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                           const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                           const ForceVector<S>* f_ext) {
  check_aba_inputs(model, q, qd, tau);
  const bool split_gravity = splits_gravity(model);
  aba_velocity_pass(model, data, q, qd, f_ext, split_gravity);
  aba_inertia_pass(model, data, tau, split_gravity);
  aba_acceleration_pass(model, data, split_gravity);
  return data.qdd;
}

}  // namespace detail

/// Joint accelerations q̈ produced by joint forces τ at (q, q̇) under gravity. Result in data.qdd;
/// a non-finite one throws std::domain_error naming the joint (input_checks.hpp).
template <class S>
const VectorX<S>& aba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                      const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau) {
  detail::aba_impl(model, data, q, qd, tau, static_cast<const ForceVector<S>*>(nullptr));
  detail::check_finite_result(model, "forward dynamics: the acceleration", data.qdd);
  return data.qdd;
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& aba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                      const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                      const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  detail::aba_impl(model, data, q, qd, tau, f_ext.data());
  detail::check_finite_result(model, "forward dynamics: the acceleration", data.qdd);
  return data.qdd;
}

}  // namespace spatial_dynamics
