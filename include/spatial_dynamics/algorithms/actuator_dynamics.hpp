// Actuator-level dynamics: the model's armature, damping and Coulomb friction (model.hpp). The
// rotors' inertia is part of M wherever M acts (rnea, crba, aba: RBDA §7.3); here the joint forces
// of damping and friction, and inverse and forward dynamics that include them:
//   τ_a(q̇) = damping ⊙ q̇ + friction ⊙ ramp(q̇ / friction_velocity),  ramp(x) = max(−1, min(1, x))
//   ID_actuated(q, q̇, q̈) = ID(q, q̇, q̈) + τ_a(q̇)              (ID includes armature ⊙ q̈)
//   FD_actuated(q, q̇, τ): (M + diag(armature)) q̈ = τ − h(q, q̇) − τ_a(q̇), by forward_dynamics.
// The ramp makes the friction law continuous: linear through zero below friction_velocity, ±friction
// above it.
#pragma once

#include <algorithm>
#include <vector>

#include "spatial_dynamics/algorithms/forward_dynamics.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

namespace detail {

/// ramp(v / v_f) of coordinate k at speed v, dividing only inside the ramp (a moving joint's speed
/// is mostly outside it: a branch the CPU predicts); NaN stays NaN.
template <class S>
SD_INLINE S friction_ramp(const Model<S>& model, int k, const S& v) {
  using std::abs;
  const S v_f = model.friction_velocity[k];
  return abs(v) >= v_f ? (v > S(0) ? S(1) : S(-1)) : v / v_f;
}

/// τ_a of coordinate k at speed v: damping v + friction ramp(v / v_f).
template <class S>
SD_INLINE S actuator_force(const Model<S>& model, int k, const S& v) {
  return model.damping[k] * v + model.friction[k] * friction_ramp(model, k, v);
}

}  // namespace detail

/// τ_a(q̇) = damping ⊙ q̇ + friction ⊙ ramp(q̇ / friction_velocity) in data.actuator_force.
template <class S>
const VectorX<S>& actuator_forces(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd) {
  detail::check_length("velocity", qd.size(), model.nv);
  for (int k = 0; k < model.nv; ++k) data.actuator_force[k] = detail::actuator_force(model, k, qd[k]);
  return data.actuator_force;
}

/// The actuators' part of inverse_dynamics_actuated's τ: armature ⊙ q̈ + τ_a(q̇), in data.actuator_effort.
template <class S>
const VectorX<S>& actuator_effort(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd,
                                  const ConstVectorRef<S>& qdd) {
  detail::check_length("acceleration", qdd.size(), model.nv);
  detail::check_length("velocity", qd.size(), model.nv);
  for (int k = 0; k < model.nv; ++k)
    data.actuator_effort[k] = detail::actuator_force(model, k, qd[k]) + model.armature[k] * qdd[k];
  return data.actuator_effort;
}

namespace detail {

/// τ += τ_a(q̇) on the RNEA's τ in data.tau.
template <class S>
const VectorX<S>& add_actuator_forces(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd) {
  for (int k = 0; k < model.nv; ++k) data.tau[k] += actuator_force(model, k, qd[k]);
  check_finite_result(model, "inverse dynamics: the joint force", data.tau);
  return data.tau;
}

/// τ − τ_a(q̇), the joint forces left for the rigid body and the rotors.
template <class S>
const VectorX<S>& effort_less_actuator_forces(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd,
                                              const ConstVectorRef<S>& tau) {
  check_length("velocity", qd.size(), model.nv);
  check_length("effort", tau.size(), model.nv);
  for (int k = 0; k < model.nv; ++k) data.effort_less_actuator_force[k] = tau[k] - actuator_force(model, k, qd[k]);
  return data.effort_less_actuator_force;
}

}  // namespace detail

/// τ = ID(q, q̇, q̈) + τ_a(q̇): the joint forces the actuators must produce, their rotor inertia,
/// damping and friction included (the RNEA's passes, then the forces, then one check that τ is
/// finite). Result in data.tau; errors as rnea's.
template <class S>
const VectorX<S>& inverse_dynamics_actuated(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  detail::rnea_impl(model, data, q, qd, qdd, static_cast<const ForceVector<S>*>(nullptr));
  return detail::add_actuator_forces(model, data, qd);
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& inverse_dynamics_actuated(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                                            const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  detail::rnea_impl(model, data, q, qd, qdd, f_ext.data());
  return detail::add_actuator_forces(model, data, qd);
}

/// q̈ from (M + diag(armature)) q̈ = τ − h(q, q̇) − τ_a(q̇), in data.qdd; errors as forward_dynamics'.
template <class S>
const VectorX<S>& forward_dynamics_actuated(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau) {
  return forward_dynamics(model, data, q, qd, detail::effort_less_actuator_forces(model, data, qd, tau));
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& forward_dynamics_actuated(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                                            const std::vector<ForceVector<S>>& f_ext) {
  return forward_dynamics(model, data, q, qd, detail::effort_less_actuator_forces(model, data, qd, tau), f_ext);
}

}  // namespace spatial_dynamics
