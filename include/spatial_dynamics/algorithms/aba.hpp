// Articulated-body algorithm, q̈ = FD(q, q̇, τ, f_ext)   (RBDA Table 7.1). For float and double,
// gravity is split off first: the passes solve FD(q, q̇, τ − τ_g(q)) without it (gravity_split.hpp).
// A joint whose subtree has no inertia along its motion (D = Sᵀ Iᴬ S = 0, e.g. a massless leaf)
// makes forward dynamics undefined: the call fails with a message naming that joint.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "spatial_dynamics/algorithms/gravity_split_packed.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
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

/// Pass 1 (outward): transforms, velocities, velocity-product accelerations, rigid bias forces.
template <class S>
SD_INLINE void aba_velocity_pass(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                 const ConstVectorRef<S>& qd, const ForceVector<S>* f_ext, bool split_gravity) {
  joint_sines_and_cosines(model, data, q.data());
  data.v[0] = MotionVector<S>::Zero();
  if (split_gravity) split_gravity_start(model, data);
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    body_up_transform(model, data, i, q.data(), data.X_up[i]);
    if (split_gravity) split_gravity_outward(model, data, i);                    // g_i = E g_λ
    if (j.nv == 1 && model.parent[i] == 0) {  // v_0 = 0: v_i = S q̇, c_i = S q̇ × S q̇ = 0
      data.v[i] = one_dof_motion(j, qd[j.idx_v]);
      data.c[i] = MotionVector<S>::Zero();
      data.IA[i].assign(model.inertia[i]);                                      // Iᴬ_i = I_i
      data.f[i] = one_dof_bias_force(j, model.inertia[i], qd[j.idx_v]);        // pᴬ_i = v ×* I v
      if (f_ext) data.f[i] -= f_ext[i];                                         //        − f_ext
      continue;
    } else if (j.nv == 1) {  // S q̇ has one axis: no 6-vector products with zeros
      const S qd_i = qd[j.idx_v];
      data.v[i] = data.X_up[i].apply(data.v[model.parent[i]]);
      add_one_dof_motion(j, qd_i, data.v[i]);                                   // v_i = X v_λ + S q̇
      data.c[i] = cross_one_dof_motion(data.v[i], j, qd_i);                     // c_i = v_i × S q̇
    } else {
      const MotionVector<S> vJ = body_joint_motion(model, data, i, qd.data());
      data.v[i] = data.X_up[i].apply(data.v[model.parent[i]]) + vJ;             // v_i = X v_λ + S q̇
      data.c[i] = body_joint_bias(model, data, i, qd.data()) + cross(data.v[i], vJ);  // c_i = c_J + v_i × S q̇
    }
    data.IA[i].assign(model.inertia[i]);                                        // Iᴬ_i = I_i
    data.f[i] = model.inertia[i].biasForce(data.v[i]);                          // pᴬ_i = v ×* I v
    if (f_ext) data.f[i] -= f_ext[i];                                           //        − f_ext
  }
}

/// Pass 2 at a joint of n = nv > 1 coordinates (free, planar): U = Iᴬ S (6 × n), D = Sᵀ U
/// (n × n), u = τ − Sᵀ pᴬ, and the articulated inertia and bias force passed to the parent. Out
/// of line: a model has one or a few such joints, and the pass's loop stays the 1-DoF code (the
/// timing with and without this was the same within the machine's noise).
template <class S>
__attribute__((noinline)) void multi_dof_inertia_step(const Model<S>& model, Data<S>& data, int i,
                                                       const ConstVectorRef<S>& tau) {
  const Joint<S>& j = model.joints[i];
  const int lambda = model.parent[i];
  Matrix6<S>& IA = data.IA[i].matrix;
  const Vector6<S> pA = data.f[i].toVector();
  Matrix6<S>& U = data.U[i];  // columns n.. stay zero
  Matrix6<S> D = Matrix6<S>::Identity();  // D in the top-left block: D⁻¹ there, 1 elsewhere
  S column[6];
  inertia_times_subspace(j, data.joint_sin[i], data.joint_cos[i], IA, U);
  for (int k = 0; k < j.nv; ++k) {
    body_joint_project(model, data, i, ForceVector<S>(Vector6<S>(U.col(k))), column);
    for (int l = 0; l < j.nv; ++l) D(l, k) = column[l];
  }
  const Eigen::LLT<Matrix6<S>> llt(D);
  if (llt.info() != Eigen::Success) throw_singular_joint(model, i);
  data.D_inv[i] = llt.solve(Matrix6<S>::Identity());
  body_joint_project(model, data, i, data.f[i], column);
  for (int k = 0; k < j.nv; ++k) data.u[i][k] = tau[j.idx_v + k] - column[k];
  if (lambda > 0) {
    const Matrix6<S> UD_inv = U * data.D_inv[i];
    IA -= UD_inv * U.transpose();                                              // Iᵃ = Iᴬ − U D⁻¹ Uᵀ
    const Vector6<S> pa = pA + IA * data.c[i].toVector() + UD_inv * data.u[i];  // pᵃ = pᴬ + Iᵃ c + U D⁻¹ u
    data.X_up[i].applyInverseAdd(data.IA[i], data.IA[lambda]);                 // Iᴬ_λ += Xᵀ Iᵃ X
    data.f[lambda] += data.X_up[i].applyInverse(ForceVector<S>(pa));           // pᴬ_λ += Xᵀ pᵃ
  }
}

/// Pass 2 (inward): articulated inertias and bias forces, from data.X_up, c, IA = I and f = pᴬ;
/// with split_gravity, the joint forces τ − τ_g(q) in place of τ.
template <class S>
SD_INLINE void aba_inertia_pass(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& tau_in,
                                bool split_gravity) {
  const ConstVectorRef<S> tau = split_gravity ? ConstVectorRef<S>(data.tau_less_gravity) : tau_in;
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    const Joint<S>& j = model.joints[i];
    const int lambda = model.parent[i];
    if (split_gravity) split_gravity_inward(model, data, i, tau_in);            // τ − τ_g at joint i
    Matrix6<S>& IA = data.IA[i].matrix;  // Iᴬ_i, turned into Iᵃ_i in place below
    const Vector6<S> pA = data.f[i].toVector();
    if (j.nv == 1) {
      const Vector6<S> U = inertia_times_subspace(j, IA);                       // U = Iᴬ S
      const S D = joint_project(j, U);                                           // D = Sᵀ U
      // D is numerically zero when it is below the rounding noise of the block it is taken from:
      // the rotational block (kg m²) for a revolute joint, the mass block (kg) for a prismatic one,
      // so that the test does not depend on the units (a millimetre robot is not singular).
      const S scale = one_dof_rotates(j) ? IA.template topLeftCorner<3, 3>().cwiseAbs().maxCoeff()
                                         : IA.template bottomRightCorner<3, 3>().cwiseAbs().maxCoeff();
      if (!(D > S(64) * Eigen::NumTraits<S>::epsilon() * scale)) throw_singular_joint(model, i);
      const S u = tau[j.idx_v] - joint_project(j, pA);                           // u = τ − Sᵀ pᴬ
      data.U[i].col(0) = U;
      data.D_inv[i](0, 0) = S(1) / D;
      data.u[i][0] = u;
      if (lambda > 0) {
        for (int c = 0; c < 6; ++c) IA.col(c) -= U * (U[c] / D);                 // Iᵃ = Iᴬ − U D⁻¹ Uᵀ
        const Vector6<S> pa = pA + IA * data.c[i].toVector() + U * (u / D);     // pᵃ = pᴬ + Iᵃ c + U D⁻¹ u
        data.X_up[i].applyInverseAdd(data.IA[i], data.IA[lambda]);               // Iᴬ_λ += Xᵀ Iᵃ X
        data.f[lambda] += data.X_up[i].applyInverse(ForceVector<S>(pa));         // pᴬ_λ += Xᵀ pᵃ
      }
    } else {
      multi_dof_inertia_step(model, data, i, tau);
    }
  }
}

/// Pass 3 (outward): accelerations into data.qdd; gravity as a_0 = −a_g unless it was split off.
template <class S>
SD_INLINE void aba_acceleration_pass(const Model<S>& model, Data<S>& data, bool split_gravity) {
  data.a[0] = MotionVector<S>(Vector3<S>::Zero(), split_gravity ? Vector3<S>::Zero() : Vector3<S>(-model.gravity));
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    const int lambda = model.parent[i];
    const MotionVector<S> a_prime = lambda == 0  // X a_0 = (0 ; E a_0) for a_0 = (0 ; −a_g)
                                        ? data.X_up[i].applyToLinear(data.a[0].linear) + data.c[i]
                                        : data.X_up[i].apply(data.a[lambda]) + data.c[i];
    const Vector6<S> ap = a_prime.toVector();
    if (j.nv == 1) {
      const S qdd = data.D_inv[i](0, 0) * (data.u[i][0] - data.U[i].col(0).dot(ap));  // q̈ = D⁻¹(u − Uᵀ a')
      data.qdd[j.idx_v] = qdd;
      data.a[i] = a_prime + one_dof_motion(j, qdd);                                    // a_i = a' + S q̈
    } else {
      const Vector6<S> qdd = data.D_inv[i] * (data.u[i] - data.U[i].transpose() * ap);  // q̈ = D⁻¹(u − Uᵀ a'), zero past nv
      data.qdd.segment(j.idx_v, j.nv) = qdd.head(j.nv);
      data.a[i] = a_prime + joint_motion(j, data.joint_sin[i], data.joint_cos[i], qdd.data());  // a_i = a' + S q̈
    }
  }
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

#ifdef SD_COMPILED_DOUBLE
// The double instances: compiled into the library, portable and AVX2 + FMA (simd_backend.hpp).
const VectorX<double>& aba(const Model<double>& model, Data<double>& data, const ConstVectorRef<double>& q,
                           const ConstVectorRef<double>& qd, const ConstVectorRef<double>& tau);
const VectorX<double>& aba(const Model<double>& model, Data<double>& data, const ConstVectorRef<double>& q,
                           const ConstVectorRef<double>& qd, const ConstVectorRef<double>& tau,
                           const std::vector<ForceVector<double>>& f_ext);
#endif

}  // namespace spatial_dynamics
