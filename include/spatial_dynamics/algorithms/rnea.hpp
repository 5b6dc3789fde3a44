// Recursive Newton–Euler inverse dynamics, τ = ID(q, q̇, q̈, f_ext)   (RBDA Table 5.1).
// Gravity enters as a fictitious base acceleration a_0 = −a_g. External forces act on the
// bodies, each expressed in its body's coordinates.
#pragma once

#include <vector>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

/// τ = ID(q, q̇, q̈, f_ext) under gravity a_g (the model's, or another: zero for M q̈) into
/// data.tau (RBDA Table 5.1). Per body, in data: ^iX_λ, v, a and f. τ is stored, or accumulated
/// where a coupled joint shares its master's coordinate (τ zeroed first); the model's armature
/// adds its rotor inertia (RBDA §7.3). kKinematicsOnly: the forward pass's ^iX_λ, v and a alone (the
/// regressors'), data.f and data.tau left as they were.
template <class S, bool kKinematicsOnly = false>
const VectorX<S>& rnea_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd, const ForceVector<S>* f_ext,
                            const Vector3<S>& gravity) {
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  check_length("acceleration", qdd.size(), model.nv);
  joint_sines_and_cosines(model, data, q.data());
  data.v[0] = MotionVector<S>::Zero();
  data.a[0] = MotionVector<S>(Vector3<S>::Zero(), -gravity);  // a_0 = −a_g
  for (int i = 1; i < model.nbodies(); ++i) {
    const int lambda = model.parent[i];
    const BodyJoint<S> J(model, data, i, q.data(), qd.data(), qdd.data());
    J.visit([&](const auto& joint) SD_INLINE_LAMBDA {
      // ^iX_λ,  v_i = X v_λ + S q̇,  a_i = X a_λ + S q̈ + c_J + v_i × S q̇  (eqs. 5.7–5.8)
      const PluckerTransform<S>& X = data.X_up[i] = joint.transform(J.X_tree, J.q, J.s, J.c, J.label);
      data.v[i] = X.apply(data.v[lambda]) + joint.motion(J.qd, J.s, J.c);
      data.a[i] = X.apply(data.a[lambda]) + joint.motion(J.qdd, J.s, J.c) +
                  joint.velocity_product(data.v[i], J.qd, J.s, J.c);
    });
    if constexpr (kKinematicsOnly) continue;
    // f_i = I a_i + v_i ×* I v_i − f_ext,i  (eq. 5.9)
    const RigidInertia<S>& I = model.inertia[i];
    data.f[i] = I * data.a[i] + I.biasForce(data.v[i]);
    if (f_ext) data.f[i] -= f_ext[i];
  }
  if constexpr (kKinematicsOnly) return data.tau;
  // τ_i = Sᵢᵀ f_i,  f_λ += ^iX_λᵀ f_i  (eqs. 5.10–5.11)
  if (model.has_coupled_joints) data.tau.setZero();
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    write_joint_torque(model, data, i, data.f[i], data.tau.data(), model.has_coupled_joints);
    if (model.parent[i] > 0) data.f[model.parent[i]] += data.X_up[i].applyInverse(data.f[i]);
  }
  if (model.has_armature)  // + armature ⊙ q̈
    for (int k = 0; k < model.nv; ++k) data.tau[k] += model.armature[k] * qdd[k];
  return data.tau;
}

template <class S>
const VectorX<S>& rnea_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd, const ForceVector<S>* f_ext) {
  return rnea_impl(model, data, q, qd, qdd, f_ext, model.gravity);
}

/// M(q) x = ID(q, 0, x) without gravity (RBDA eq. 5.1 with q̇ = 0 and a_g = 0); data.zero_v as q̇.
template <class S>
const VectorX<S>& mass_matrix_times(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                    const ConstVectorRef<S>& x) {
  return rnea_impl<S>(model, data, q, data.zero_v, x, nullptr, Vector3<S>(Vector3<S>::Zero()));
}

}  // namespace detail

/// Joint forces τ that produce accelerations q̈ at (q, q̇) under gravity. Result in data.tau;
/// a non-finite one throws std::domain_error naming the joint (input_checks.hpp).
template <class S>
const VectorX<S>& rnea(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                       const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  detail::rnea_impl(model, data, q, qd, qdd, static_cast<const ForceVector<S>*>(nullptr));
  detail::check_finite_result(model, "inverse dynamics: the joint force", data.tau);
  return data.tau;
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& rnea(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                       const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                       const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  detail::rnea_impl(model, data, q, qd, qdd, f_ext.data());
  detail::check_finite_result(model, "inverse dynamics: the joint force", data.tau);
  return data.tau;
}

/// Gravity torques g(q) = ID(q, 0, 0).
template <class S>
const VectorX<S>& gravity_torques(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  return rnea<S>(model, data, q, data.zero_v, data.zero_v);
}

/// Nonlinear effects C(q, q̇) q̇ + g(q) = ID(q, q̇, 0).
template <class S>
const VectorX<S>& nonlinear_effects(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                    const ConstVectorRef<S>& qd) {
  return rnea<S>(model, data, q, qd, data.zero_v);
}

}  // namespace spatial_dynamics
