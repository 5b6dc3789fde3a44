// Actuator-level dynamics: the model's armature, damping and Coulomb friction (model.hpp). The
// rotors' inertia is part of M wherever M acts (rnea, crba, aba: RBDA §7.3); here the joint forces
// of damping and friction, and inverse and forward dynamics that include them:
//   τ_a(q̇) = damping ⊙ q̇ + friction ⊙ ramp(q̇ / friction_velocity),  ramp(x) = max(−1, min(1, x))
//   ID_actuated(q, q̇, q̈) = ID(q, q̇, q̈) + τ_a(q̇)              (ID includes armature ⊙ q̈)
//   FD_actuated(q, q̇, τ): (M + diag(armature)) q̈ = τ − h(q, q̇) − τ_a(q̇), by forward_dynamics.
// The ramp makes the friction law continuous: linear through zero below friction_velocity, ±friction
// above it.
#pragma once

#include <vector>

#include "spatial_dynamics/algorithms/forward_dynamics.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

/// τ_a(q̇) = damping ⊙ q̇ + friction ⊙ ramp(q̇ / friction_velocity) in data.actuator_force.
template <class S>
const VectorX<S>& actuator_forces(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd) {
  detail::check_length("velocity", qd.size(), model.nv);
  for (int k = 0; k < model.nv; ++k) {
    const S x = qd[k] / model.friction_velocity[k];
    const S ramp = x > S(1) ? S(1) : (x < S(-1) ? S(-1) : x);
    data.actuator_force[k] = model.damping[k] * qd[k] + model.friction[k] * ramp;
  }
  return data.actuator_force;
}

/// The actuators' part of inverse_dynamics_actuated's τ: armature ⊙ q̈ + τ_a(q̇), in data.actuator_effort.
template <class S>
const VectorX<S>& actuator_effort(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd,
                                  const ConstVectorRef<S>& qdd) {
  detail::check_length("acceleration", qdd.size(), model.nv);
  actuator_forces<S>(model, data, qd);
  for (int k = 0; k < model.nv; ++k) data.actuator_effort[k] = data.actuator_force[k] + model.armature[k] * qdd[k];
  return data.actuator_effort;
}

namespace detail {

template <class S>
const VectorX<S>& add_actuator_forces(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd) {
  data.tau += actuator_forces<S>(model, data, qd);
  check_finite_result(model, "inverse dynamics: the joint force", data.tau);
  return data.tau;
}

template <class S>
const VectorX<S>& effort_less_actuator_forces(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& qd,
                                              const ConstVectorRef<S>& tau) {
  check_length("effort", tau.size(), model.nv);
  data.effort_less_actuator_force = tau - actuator_forces<S>(model, data, qd);
  return data.effort_less_actuator_force;
}

}  // namespace detail

/// τ = ID(q, q̇, q̈) + τ_a(q̇): the joint forces the actuators must produce, their rotor inertia,
/// damping and friction included. Result in data.tau; errors as rnea's.
template <class S>
const VectorX<S>& inverse_dynamics_actuated(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  rnea(model, data, q, qd, qdd);
  return detail::add_actuator_forces(model, data, qd);
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& inverse_dynamics_actuated(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                                            const std::vector<ForceVector<S>>& f_ext) {
  rnea(model, data, q, qd, qdd, f_ext);
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
