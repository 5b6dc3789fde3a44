// Composite-rigid-body algorithm: the joint-space mass matrix M(q), both triangles filled
// (RBDA Table 6.2).
#pragma once

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/algorithms/kinematics.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {

/// M(q) in data.M. Entries coupling joints on different branches are structural zeros: Data
/// creates M zeroed and this function never writes them.
template <class S>
const MatrixX<S>& crba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  update_joint_transforms(model, data, q);
  const int n = model.nbodies();
  for (int i = 1; i < n; ++i) data.Ic[i] = model.inertia[i];
  for (int i = n - 1; i >= 1; --i) {
    const int lambda = model.parent[i];
    if (lambda > 0) data.Ic[lambda] += data.X_up[i].applyInverse(data.Ic[i]);   // Iᶜ_λ += Xᵀ Iᶜ_i X (eq. 24, 26)
  }
  S column[6];
  for (int i = 1; i < n; ++i) {
    const Joint<S>& ji = model.joints[i];
    for (int k = 0; k < ji.nv; ++k) {
      const int col = ji.idx_v + k;
      ForceVector<S> F = data.Ic[i] * joint_subspace_column(ji, k);              // F = Iᶜ_i S_i
      joint_project(ji, F, column);                                             // M_ii = Sᵢᵀ F
      for (int l = k; l < ji.nv; ++l) {  // lower triangle, mirrored: exactly symmetric
        data.M(ji.idx_v + l, col) = column[l];
        data.M(col, ji.idx_v + l) = column[l];
      }
      int j = i;
      while (model.parent[j] > 0) {
        F = data.X_up[j].applyInverse(F);                                       // F = ^jX_λᵀ F
        j = model.parent[j];
        const Joint<S>& jj = model.joints[j];
        joint_project(jj, F, column);                                           // M_ji = S_jᵀ F
        for (int l = 0; l < jj.nv; ++l) {
          data.M(jj.idx_v + l, col) = column[l];
          data.M(col, jj.idx_v + l) = column[l];
        }
      }
    }
  }
  return data.M;
}

}  // namespace spatial_dynamics
