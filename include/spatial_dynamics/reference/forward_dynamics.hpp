// The reference's forward dynamics: the articulated-body algorithm of RBDA Table 7.1 on 6×6
// matrices (spatial_v2's FDab), q̈ = FD(q, q̇, τ, f_ext), f_ext[i] acting on body i in its own
// coordinates (entry 0 unused). Models with coupled mimic joints are refused (std::invalid_argument):
// the ABA has no place for a coordinate shared by two joints.
#pragma once

#include <Eigen/LU>
#include <stdexcept>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reference/joint_model.hpp"
#include "spatial_dynamics/reference/spatial_matrices.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"

namespace spatial_dynamics {
namespace reference {

template <class S>
VecX<S> forward_dynamics(const Model<S>& model, const VectorArg<S>& q, const VectorArg<S>& qd, const VectorArg<S>& tau,
                         const std::vector<ForceVector<S>>& f_ext = {}) {
  if (model.has_coupled_joints) throw std::invalid_argument("reference: the ABA cannot solve coupled mimic joints");
  if (qd.size() != model.nv || tau.size() != model.nv)
    throw std::invalid_argument("reference: q̇ or τ has the wrong length");
  if (!f_ext.empty() && static_cast<int>(f_ext.size()) != model.nbodies())
    throw std::invalid_argument("reference: one external force per body (entry 0 unused)");
  const int n = model.nbodies();
  const std::vector<Mat6<S>> X_up = up_transforms(model, q);                  // ^iX_λ(i) = X_J X_T(i)
  std::vector<Mat6X<S>> S_(n), U(n);
  std::vector<MatX<S>> D_inv(n);
  std::vector<VecX<S>> u(n);
  std::vector<Vec6<S>> v(n, Vec6<S>::Zero()), c(n, Vec6<S>::Zero()), pA(n, Vec6<S>::Zero());
  std::vector<Vec6<S>> a(n, Vec6<S>::Zero());
  std::vector<Mat6<S>> IA(n, Mat6<S>::Zero());
  for (int i = 1; i < n; ++i) {  // pass 1, outward
    const Joint<S>& j = model.joints[i];
    S_[i] = motion_subspace(j);
    const Vec6<S> vJ = S_[i] * qd.segment(j.idx_v, j.nv);                     // v_J = S_i q̇_i
    v[i] = X_up[i] * v[model.parent[i]] + vJ;                                  // v_i = ^iX_λ v_λ + v_J
    c[i] = crm(v[i]) * vJ;                                                     // c_i = c_J + v_i × v_J, c_J = 0
    IA[i] = body_inertia(model, i);                                            // Iᴬ_i = I_i
    pA[i] = crf(v[i]) * (IA[i] * v[i]);                                        // pᴬ_i = v_i ×* I_i v_i
    if (!f_ext.empty()) pA[i] -= f_ext[i].toVector();                          //        − f_i^x (body coordinates)
  }
  for (int i = n - 1; i >= 1; --i) {  // pass 2, inward
    const Joint<S>& j = model.joints[i];
    U[i] = IA[i] * S_[i];                                                      // U_i = Iᴬ_i S_i
    MatX<S> D = S_[i].transpose() * U[i];                                      // D_i = S_iᵀ U_i
    if (static_cast<int>(model.armature.size()) == model.nv)
      for (int k = 0; k < j.nv; ++k) D(k, k) += model.armature[j.idx_v + k];   //       + armature
    D_inv[i] = D.inverse();
    u[i] = tau.segment(j.idx_v, j.nv) - S_[i].transpose() * pA[i];             // u_i = τ_i − S_iᵀ pᴬ_i
    const int lambda = model.parent[i];
    if (lambda == 0) continue;
    const Mat6<S> Ia = IA[i] - U[i] * D_inv[i] * U[i].transpose();            // Iᵃ = Iᴬ_i − U_i D_i⁻¹ U_iᵀ
    const Vec6<S> pa = pA[i] + Ia * c[i] + U[i] * (D_inv[i] * u[i]);          // pᵃ = pᴬ_i + Iᵃ c_i + U_i D_i⁻¹ u_i
    IA[lambda] += X_up[i].transpose() * Ia * X_up[i];                          // Iᴬ_λ += ^iX_λᵀ Iᵃ ^iX_λ
    pA[lambda] += X_up[i].transpose() * pa;                                    // pᴬ_λ += ^iX_λᵀ pᵃ
  }
  VecX<S> qdd(model.nv);
  a[0] = -gravity_acceleration<S>(model.gravity);                              // a_0 = −a_g
  for (int i = 1; i < n; ++i) {  // pass 3, outward
    const Joint<S>& j = model.joints[i];
    const Vec6<S> a_prime = X_up[i] * a[model.parent[i]] + c[i];               // a'_i = ^iX_λ a_λ + c_i
    const VecX<S> qdd_i = D_inv[i] * (u[i] - U[i].transpose() * a_prime);      // q̈_i = D_i⁻¹ (u_i − U_iᵀ a'_i)
    qdd.segment(j.idx_v, j.nv) = qdd_i;
    a[i] = a_prime + S_[i] * qdd_i;                                            // a_i = a'_i + S_i q̈_i
  }
  return qdd;
}

}  // namespace reference
}  // namespace spatial_dynamics
