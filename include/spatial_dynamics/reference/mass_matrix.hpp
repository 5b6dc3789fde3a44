// The reference's joint-space mass matrix: the composite-rigid-body algorithm of RBDA Table 6.2
// on 6×6 matrices (the H of spatial_v2's HandC), both triangles filled. With coupled mimic
// joints it is formed over every body's own coordinates and reduced, M = Gᵀ M_full G.
#pragma once

#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reference/joint_model.hpp"
#include "spatial_dynamics/reference/spatial_matrices.hpp"

namespace spatial_dynamics {
namespace reference {

template <class S>
MatX<S> mass_matrix(const Model<S>& model, const VectorArg<S>& q) {
  const int n = model.nbodies();
  const CoordinateMap<S> map = coordinate_map(model);
  const std::vector<Mat6<S>> X_up = up_transforms(model, q);                  // ^iX_λ(i) = X_J X_T(i)
  std::vector<Mat6<S>> Ic(n, Mat6<S>::Zero());
  for (int i = 1; i < n; ++i) Ic[i] = body_inertia(model, i);                 // Iᶜ_i = I_i
  for (int i = n - 1; i >= 1; --i) {
    const int lambda = model.parent[i];
    if (lambda != 0) Ic[lambda] += X_up[i].transpose() * Ic[i] * X_up[i];      // Iᶜ_λ += ^iX_λᵀ Iᶜ_i ^iX_λ
  }
  MatX<S> H = MatX<S>::Zero(map.n_full, map.n_full);
  for (int i = 1; i < n; ++i) {
    const Mat6X<S> S_i = motion_subspace(model.joints[i]);
    const int ni = model.joints[i].nv, oi = map.offset[i];
    Mat6X<S> F = Ic[i] * S_i;                                                  // F = Iᶜ_i S_i
    H.block(oi, oi, ni, ni) = S_i.transpose() * F;                             // H_ii = S_iᵀ F
    for (int j = i; model.parent[j] != 0;) {
      F = X_up[j].transpose() * F;                                             // F = ^jX_λ(j)ᵀ F
      j = model.parent[j];                                                     // j = λ(j)
      const int nj = model.joints[j].nv, oj = map.offset[j];
      H.block(oi, oj, ni, nj) = F.transpose() * motion_subspace(model.joints[j]);  // H_ij = Fᵀ S_j
      H.block(oj, oi, nj, ni) = H.block(oi, oj, ni, nj).transpose();          // H_ji = H_ijᵀ
    }
  }
  MatX<S> M = map.reduce(H, model.nv);                                        // M = Gᵀ H G
  if (static_cast<int>(model.armature.size()) == model.nv)
    for (int k = 0; k < model.nv; ++k) M(k, k) += model.armature[k];           // + diag(armature)
  return M;
}

}  // namespace reference
}  // namespace spatial_dynamics
