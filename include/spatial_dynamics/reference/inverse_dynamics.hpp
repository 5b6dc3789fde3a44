// The reference's inverse dynamics: the recursive Newton–Euler algorithm of RBDA Table 5.1 on
// 6×6 matrices (spatial_v2's ID), τ = ID(q, q̇, q̈, f_ext). External forces f_ext[i] act on body i
// in its own coordinates (entry 0 unused). A coupled mimic joint moves with its master
// (q̇_i = k q̇_master, q̈_i = k q̈_master) and its force acts on the master's coordinate: τ = Gᵀ τ_full.
#pragma once

#include <stdexcept>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reference/joint_model.hpp"
#include "spatial_dynamics/reference/spatial_matrices.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"

namespace spatial_dynamics {
namespace reference {

template <class S>
VecX<S> inverse_dynamics(const Model<S>& model, const VectorArg<S>& q, const VectorArg<S>& qd, const VectorArg<S>& qdd,
                         const std::vector<ForceVector<S>>& f_ext = {}) {
  if (qd.size() != model.nv || qdd.size() != model.nv)
    throw std::invalid_argument("reference: q̇ or q̈ has the wrong length");
  if (!f_ext.empty() && static_cast<int>(f_ext.size()) != model.nbodies())
    throw std::invalid_argument("reference: one external force per body (entry 0 unused)");
  const int n = model.nbodies();
  const CoordinateMap<S> map = coordinate_map(model);
  const VecX<S> qd_full = map.expand(qd), qdd_full = map.expand(qdd);        // every body's q̇_i = (G q̇)_i, q̈_i
  const std::vector<Mat6<S>> X_up = up_transforms(model, q);                  // ^iX_λ(i) = X_J X_T(i)
  std::vector<Vec6<S>> v(n, Vec6<S>::Zero()), a(n, Vec6<S>::Zero()), f(n, Vec6<S>::Zero());
  a[0] = -gravity_acceleration<S>(model.gravity);                              // v_0 = 0, a_0 = −a_g
  for (int i = 1; i < n; ++i) {
    const Joint<S>& j = model.joints[i];
    const Mat6X<S> S_i = motion_subspace(j);
    const Vec6<S> vJ = S_i * qd_full.segment(map.offset[i], j.nv);             // v_J = S_i q̇_i
    const Vec6<S> aJ = S_i * qdd_full.segment(map.offset[i], j.nv);            // S_i q̈_i (Ṡ_i = 0)
    const int lambda = model.parent[i];
    v[i] = X_up[i] * v[lambda] + vJ;                                           // v_i = ^iX_λ v_λ + v_J
    a[i] = X_up[i] * a[lambda] + aJ + crm(v[i]) * vJ;                          // a_i = ^iX_λ a_λ + S q̈ + v_i × v_J
                                                                               //       (+ c_J, 0 for these joints)
    const Mat6<S> I = body_inertia(model, i);                                  // I_i in body coordinates
    f[i] = I * a[i] + crf(v[i]) * (I * v[i]);                                  // f_i = I_i a_i + v_i ×* I_i v_i
    if (!f_ext.empty()) f[i] -= f_ext[i].toVector();                           //       − f_i^x (body coordinates)
  }
  VecX<S> tau_full(map.n_full);
  for (int i = n - 1; i >= 1; --i) {
    const Mat6X<S> S_i = motion_subspace(model.joints[i]);
    tau_full.segment(map.offset[i], model.joints[i].nv) = S_i.transpose() * f[i];  // τ_i = S_iᵀ f_i
    const int lambda = model.parent[i];
    if (lambda != 0) f[lambda] += X_up[i].transpose() * f[i];                  // f_λ += ^iX_λᵀ f_i
  }
  VecX<S> tau = map.reduce(tau_full, model.nv);                               // τ = Gᵀ τ_full
  if (static_cast<int>(model.armature.size()) == model.nv)
    for (int k = 0; k < model.nv; ++k) tau[k] += model.armature[k] * qdd[k];  // + armature ⊙ q̈
  return tau;
}

/// g(q) = ID(q, 0, 0): the joint forces that hold the robot still under gravity.
template <class S>
VecX<S> gravity_torques(const Model<S>& model, const VectorArg<S>& q) {
  return inverse_dynamics(model, q, VecX<S>::Zero(model.nv), VecX<S>::Zero(model.nv));
}

/// C(q, q̇) q̇ + g(q) = ID(q, q̇, 0).
template <class S>
VecX<S> nonlinear_effects(const Model<S>& model, const VectorArg<S>& q, const VectorArg<S>& qd) {
  return inverse_dynamics(model, q, qd, VecX<S>::Zero(model.nv));
}

}  // namespace reference
}  // namespace spatial_dynamics
