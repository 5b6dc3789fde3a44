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

/// M's entries S̃ⱼᵀ F of body j's coordinates from `first_row` on in column `col`, and their mirror
/// in row `col`: an ancestor's (first_row 0) or the column's own body's, from the column's own
/// coordinate on, so that each entry of the symmetric block is computed once. S̃ⱼ and F are in
/// base axes, F about body j's origin. With coupled mimic joints (M = Gᵀ M_free G, M zeroed first)
/// every entry accumulates k_j k_col S̃ⱼᵀ F instead, and its mirror too unless it is the own
/// block's diagonal.
template <class S>
SD_INLINE void set_mass_entries(const Model<S>& model, Data<S>& data, int j, const ForceVector<S>& F,
                                Eigen::Index col, const S& k_col, int first_row, bool ancestor) {
  const Joint<S>& joint = model.joints[j];
  for (int l = first_row; l < joint.nv; ++l) {
    const Eigen::Index row = joint.idx_v + l;
    const S entry = dot(data.S_base[j][l], F);
    if (!model.has_coupled_joints) {
      data.M(row, col) = entry;
      data.M(col, row) = entry;
      continue;
    }
    const S value = k_col * coupling_multiplier(joint) * entry;
    data.M(row, col) += value;
    if (row != col || ancestor) data.M(col, row) += value;
  }
}

/// The composite inertias in base axes about each body's own origin p_i (data.Ic) and the columns of
/// S in the same axes (data.S_base): S̃_i = E_0iᵀ S_i and Ĩ_i = E_0iᵀ I_i E_0i (eq. 26 with r = 0);
/// Iᶜ_i = Ĩ_i + Σ Iᶜ_j about p_i over the children (eq. 26 with E = 1). Also data.X_base.
template <class S>
void composite_inertias(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  check_length("q", q.size(), model.nq);
  joint_sines_and_cosines(model, data, q.data());
  data.X_base[0] = PluckerTransform<S>::Identity();
  for (int i = 1; i < model.nbodies(); ++i) {
    body_up_transform(model, data, i, q.data(), data.X_up[i]);
    const PluckerTransform<S>& X = data.X_base[i] = data.X_up[i] * data.X_base[model.parent[i]];  // ^iX_0
    const Mat3<S> to_base = X.E.transpose();
    data.Ic[i] = model.inertia[i].rotated(to_base);  // Ĩ_i
    const Joint<S>& joint = model.joints[i];
    for (int k = 0; k < joint.nv; ++k) {  // S̃_i
      const MotionVector<S> column = body_subspace_column(model, data, i, k);
      data.S_base[i][k] = MotionVector<S>(to_base * column.angular, to_base * column.linear);
    }
  }
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    const int lambda = model.parent[i];
    if (lambda > 0) data.Ic[lambda] += data.Ic[i].aboutPoint(data.X_base[lambda].r - data.X_base[i].r);  // eq. 26
  }
}

/// M(q) into data.M (RBDA Table 6.2) from the composite inertias above: for each column of S_i,
/// F = Iᶜ_i S̃_i, M_ii = S̃ᵢᵀ F and, for every ancestor λ, M_λi = S̃_λᵀ F about p_λ. In these axes a
/// column reaches an ancestor by moving its moment's reference point, not by a chain of transforms.
template <class S>
void crba_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  composite_inertias(model, data, q);
  if (model.has_coupled_joints) data.M.setZero();
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& joint = model.joints[i];
    const S k_col = coupling_multiplier(joint);
    for (int k = 0; k < joint.nv; ++k) {
      const Eigen::Index col = joint.idx_v + k;
      const ForceVector<S> F = data.Ic[i] * data.S_base[i][k];  // F = Iᶜ_i S̃_i
      set_mass_entries(model, data, i, F, col, k_col, k, false);  // M_ii = S̃ᵢᵀ F
      for (int j = model.parent[i]; j > 0; j = model.parent[j])  // M_λi = S̃_λᵀ F about p_λ
        set_mass_entries(model, data, j, F.aboutPoint(data.X_base[j].r - data.X_base[i].r), col, k_col, 0, true);
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
