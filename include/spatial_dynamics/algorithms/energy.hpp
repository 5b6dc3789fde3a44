// System kinetic energy (eq. 28 summed over bodies) and total spatial momentum (eq. 23 summed
// over bodies, each moved to base coordinates by X*).
#pragma once

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/kinematics.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

/// T = Σ ½ v_i · I_i v_i + Σ ½ armature_k q̇_k² (the rotors': T = ½ q̇ᵀ (M + diag(armature)) q̇).
template <class S>
S kinetic_energy(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd) {
  forward_kinematics<S>(model, data, q, qd);
  S T(0);
  for (int i = 1; i < model.nbodies(); ++i) T += kinetic_energy(model.inertia[i], data.v[i]);
  if (model.has_armature)
    for (int k = 0; k < model.nv; ++k) T += S(0.5) * model.armature[k] * qd[k] * qd[k];
  detail::check_finite_value(model, "kinetic energy", Eigen::Matrix<S, 1, 1>::Constant(T));
  return T;
}

/// h = Σ ^0X_i* (I_i v_i), in base coordinates about the base origin: the links' momentum (the
/// armature, a reflected scalar inertia, has no spatial momentum of its own here).
template <class S>
ForceVector<S> total_momentum(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                              const ConstVectorRef<S>& qd) {
  forward_kinematics<S>(model, data, q, qd);
  ForceVector<S> h = ForceVector<S>::Zero();
  for (int i = 1; i < model.nbodies(); ++i) h += data.X_base[i].applyInverse(momentum(model.inertia[i], data.v[i]));
  detail::check_finite_value(model, "total momentum", h.toVector());
  return h;
}

}  // namespace spatial_dynamics
