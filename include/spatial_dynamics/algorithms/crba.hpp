// Composite-rigid-body algorithm: the joint-space mass matrix M(q), both triangles filled
// (RBDA Table 6.2). Every model and joint type.
#pragma once

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

namespace detail {

/// M's entries Sⱼᵀ F of body j's coordinates from `first_row` on in column `col`, and their mirror
/// in row `col`: an ancestor's (first_row 0) or the column's own body's, from the column's own
/// coordinate on, so that each entry of the symmetric block is computed once. With coupled mimic
/// joints (M = Gᵀ M_free G, M zeroed first) every entry accumulates k_j k_col Sⱼᵀ F instead, and
/// its mirror too unless it is the own block's diagonal.
template <class S>
SD_INLINE void set_mass_entries(const Model<S>& model, Data<S>& data, int j, const ForceVector<S>& F,
                                  Eigen::Index col, const S& k_col, int first_row, bool ancestor) {
  const Joint<S>& joint = model.joints[j];
  S entries[6];
  body_joint_project(model, data, j, F, entries);
  for (int l = first_row; l < joint.nv; ++l) {
    const Eigen::Index row = joint.idx_v + l;
    if (!model.has_coupled_joints) {
      data.M(row, col) = entries[l];
      data.M(col, row) = entries[l];
      continue;
    }
    const S value = k_col * coupling_multiplier(joint) * entries[l];
    data.M(row, col) += value;
    if (row != col || ancestor) data.M(col, row) += value;
  }
}

/// M(q) into data.M (RBDA Table 6.2): Iᶜ_i = I_i + Σ ^jX_iᵀ Iᶜ_j ^jX_i over the children, then
/// for each column of S_i, F = Iᶜ_i S_i, M_ii = Sᵢᵀ F and, F = ^jX_λᵀ F on the way down,
/// M_λi = S_λᵀ F for every ancestor λ.
template <class S>
void crba_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  check_length("q", q.size(), model.nq);
  joint_sines_and_cosines(model, data, q.data());
  for (int i = 1; i < model.nbodies(); ++i) {
    body_up_transform(model, data, i, q.data(), data.X_up[i]);
    data.Ic[i] = model.inertia[i];
  }
  for (int i = model.nbodies() - 1; i >= 1; --i)
    if (model.parent[i] > 0) data.X_up[i].applyInverseAdd(data.Ic[i], data.Ic[model.parent[i]]);  // eq. 26
  if (model.has_coupled_joints) data.M.setZero();
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& joint = model.joints[i];
    for (int k = 0; k < joint.nv; ++k) {
      const Eigen::Index col = joint.idx_v + k;
      const S k_col = coupling_multiplier(joint);
      ForceVector<S> F = data.Ic[i] * body_subspace_column(model, data, i, k);  // F = Iᶜ_i S_i
      set_mass_entries(model, data, i, F, col, k_col, k, false);                    // M_ii = Sᵢᵀ F
      for (int j = i; model.parent[j] > 0; j = model.parent[j]) {
        F = data.X_up[j].applyInverse(F);                                        // F = ^jX_λᵀ F
        set_mass_entries(model, data, model.parent[j], F, col, k_col, 0, true);    // M_λi = S_λᵀ F
      }
    }
  }
  if (model.has_armature)  // M + diag(armature) (RBDA §7.3)
    for (int k = 0; k < model.nv; ++k) data.M(k, k) += model.armature[k];
}

}  // namespace detail

/// M(q) in data.M. Entries coupling joints on different branches are structural zeros: Data
/// creates M zeroed and this function never writes them (unless the model has coupled joints,
/// when M is zeroed and accumulated). A non-finite entry throws std::domain_error naming its column.
template <class S>
const MatrixX<S>& crba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  detail::crba_impl(model, data, q);
  detail::check_finite_result(model, "mass matrix: the column", data.M);
  return data.M;
}

}  // namespace spatial_dynamics
