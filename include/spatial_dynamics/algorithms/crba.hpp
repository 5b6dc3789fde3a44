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
/// creates M zeroed and this function never writes them (unless the model has coupled joints,
/// when M is zeroed and accumulated). A non-finite entry throws std::domain_error naming its column.
template <class S>
const MatrixX<S>& crba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  update_joint_transforms(model, data, q);
  const int n = model.nbodies();
  for (int i = 1; i < n; ++i) data.Ic[i] = model.inertia[i];
  for (int i = n - 1; i >= 1; --i) {
    const int lambda = model.parent[i];
    if (lambda > 0) data.Ic[lambda] += data.X_up[i].applyInverse(data.Ic[i]);   // Iᶜ_λ += Xᵀ Iᶜ_i X (eq. 24, 26)
  }
  // With coupled mimic joints M = Gᵀ M_independent G: every entry accumulates k_i k_j Sᵢᵀ F.
  const bool accumulate = model.has_coupled_joints;
  if (accumulate) data.M.setZero();
  auto write_pair = [&](int r, int c, const S& value) {  // M(r, c) and M(c, r) of two distinct coordinates
    if (accumulate) {
      data.M(r, c) += value;
      data.M(c, r) += value;
    } else {
      data.M(r, c) = value;
      data.M(c, r) = value;
    }
  };
  S column[6];
  for (int i = 1; i < n; ++i) {
    const Joint<S>& ji = model.joints[i];
    const S ki = coupling_multiplier(ji);
    for (int k = 0; k < ji.nv; ++k) {
      const int col = ji.idx_v + k;
      ForceVector<S> F = data.Ic[i] * joint_subspace_column(ji, k);              // F = Iᶜ_i S_i
      joint_project(ji, F, column);                                             // M_ii = Sᵢᵀ F
      if (accumulate) data.M(col, col) += ki * ki * column[k];
      else data.M(col, col) = column[k];
      for (int l = k + 1; l < ji.nv; ++l) write_pair(ji.idx_v + l, col, column[l]);  // mirrored: exactly symmetric
      int j = i;
      while (model.parent[j] > 0) {
        F = data.X_up[j].applyInverse(F);                                       // F = ^jX_λᵀ F
        j = model.parent[j];
        const Joint<S>& jj = model.joints[j];
        joint_project(jj, F, column);                                           // M_ji = S_jᵀ F
        const S kk = ki * coupling_multiplier(jj);
        for (int l = 0; l < jj.nv; ++l) write_pair(jj.idx_v + l, col, kk * column[l]);
      }
    }
  }
  detail::check_finite_result(model, "mass matrix: the column", data.M);
  return data.M;
}

}  // namespace spatial_dynamics
