// Composite-rigid-body algorithm: the joint-space mass matrix M(q), both triangles filled
// (RBDA Table 6.2).
#pragma once

#include "spatial_dynamics/algorithms/crba_base_carry.hpp"
#include "spatial_dynamics/algorithms/crba_packed.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/algorithms/kinematics.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

namespace detail {

/// Writes M(r, c) and M(c, r) of two distinct coordinates; with coupled mimic joints
/// (M = Gᵀ M_independent G) every entry accumulates k_i k_j Sᵢᵀ F instead.
template <class S>
SD_INLINE void write_mass_pair(const Model<S>& model, Data<S>& data, int r, int c, const S& value) {
  if (model.has_coupled_joints) {
    data.M(r, c) += value;
    data.M(c, r) += value;
  } else {
    data.M(r, c) = value;
    data.M(c, r) = value;
  }
}

/// Body poses ^iX_0 = ^iX_λ ^λX_0 and each 1-DoF joint's axis in base coordinates, Eᵀ a.
template <class S>
void base_poses_and_axes(const Model<S>& model, Data<S>& data) {
  data.X_base[0] = PluckerTransform<S>::Identity();
  for (int i = 1; i < model.nbodies(); ++i) {
    data.X_base[i] = data.X_up[i] * data.X_base[model.parent[i]];
    const Joint<S>& j = model.joints[i];
    if (j.nv != 1) continue;
    switch (j.axis_kind) {
      case AxisKind::X: data.axis_base[i] = data.X_base[i].E.row(0).transpose(); break;
      case AxisKind::Y: data.axis_base[i] = data.X_base[i].E.row(1).transpose(); break;
      case AxisKind::Z: data.axis_base[i] = data.X_base[i].E.row(2).transpose(); break;
      case AxisKind::General: data.axis_base[i] = data.X_base[i].E.transpose() * j.axis; break;
    }
  }
  // The same origins and axes as six arrays, for carry_over_revolute_run.
  const int stride = static_cast<int>(data.base_origin_and_axis.size()) / 6;
  S* soa = data.base_origin_and_axis.data();
  for (int i = 1; i < model.nbodies(); ++i)
    for (int k = 0; k < 3; ++k) {
      soa[k * stride + i] = data.X_base[i].r[k];
      soa[(3 + k) * stride + i] = data.axis_base[i][k];
    }
}

/// M_ji = S_jᵀ F for every ancestor j of body i, F = Iᶜ_i S_i (column `col`, coupling k_i) in
/// body i's coordinates, carried by one force transform per ancestor: F = ^jX_λᵀ F.
template <class S>
SD_INLINE void carry_column_per_ancestor(const Model<S>& model, Data<S>& data, int i, ForceVector<S> F, int col,
                                         const S& ki) {
  int j = i;
  if (!model.has_coupled_joints) {  // the common case, revolute ancestors and no coupling, without branches
    // Local pointers: Eigen's vector stores may alias any memory, so members read through
    // `model` and `data` would be reloaded after each of them.
    const int* parent = model.parent.data();
    const Joint<S>* joints = model.joints.data();
    const PluckerTransform<S>* X_up = data.X_up.data();
    S* M = data.M.data();
    const Eigen::Index stride = data.M.outerStride();
    Vector3<S> n = F.angular, f = F.linear;
    for (int lambda = parent[j]; lambda > 0 && joints[lambda].type == JointType::Revolute; lambda = parent[j]) {
      const PluckerTransform<S>& X = X_up[j];
      f = X.E.transpose() * f;                                                  // F = ^jX_λᵀ F:
      n = X.E.transpose() * n + cross_3d(X.r, f);                                   //   (Eᵀ n + r × Eᵀ f ; Eᵀ f)
      j = lambda;
      const S m = detail::along_axis(joints[j], n);                             // M_ji = S_jᵀ F
      const Eigen::Index row = joints[j].idx_v;
      M[row + col * stride] = m;
      M[col + row * stride] = m;
    }
    F = ForceVector<S>(n, f);
  }
  S column[6];
  while (model.parent[j] > 0) {
    F = data.X_up[j].applyInverse(F);                                           // F = ^jX_λᵀ F
    j = model.parent[j];
    const Joint<S>& jj = model.joints[j];
    body_joint_project(model, data, j, F, column);                              // M_ji = S_jᵀ F
    const S kk = ki * coupling_multiplier(jj);
    for (int l = 0; l < jj.nv; ++l) write_mass_pair(model, data, jj.idx_v + l, col, kk * column[l]);
  }
}

/// The same from base coordinates (data.X_base, data.axis_base filled): F once into base
/// orientation about body i's origin p_i, then for a revolute ancestor j M_ji = a_j · n_j with the
/// moment n_j = n + f × (p_j − p_i) about its origin, for a prismatic one M_ji = a_j · f.
template <class S>
SD_INLINE void carry_column_in_base(const Model<S>& model, Data<S>& data, int i, const ForceVector<S>& F, int col,
                                    const S& ki) {
  const PluckerTransform<S>& X_i = data.X_base[i];
  const Vector3<S> n_base = X_i.E.transpose() * F.angular;
  const Vector3<S> f_base = X_i.E.transpose() * F.linear;
  auto moment_about = [&](int j) -> Vector3<S> {  // n_j = n + f × (p_j − p_i)
    return n_base + cross_3d(f_base, Vector3<S>(data.X_base[j].r - X_i.r));
  };
  int j = model.parent[i];
  if (!model.has_coupled_joints) {  // the common case: runs of revolute ancestors, L bodies at a time
    while (j > 0 && data.revolute_run_start[j] > 0) {
      const int first = data.revolute_run_start[j];
      carry_over_revolute_run(model, data, n_base, f_base, X_i.r, first, j, col);
      j = model.parent[first];
    }
  }
  S column[6];
  for (; j > 0; j = model.parent[j]) {
    const Joint<S>& jj = model.joints[j];
    const S kk = ki * coupling_multiplier(jj);
    if (jj.nv == 1 && !one_dof_rotates(jj)) {
      write_mass_pair(model, data, jj.idx_v, col, kk * data.axis_base[j].dot(f_base));
      continue;
    }
    const Vector3<S> n_j = moment_about(j);
    if (jj.nv == 1) {
      write_mass_pair(model, data, jj.idx_v, col, kk * data.axis_base[j].dot(n_j));
    } else {  // several coordinates: Sᵀ F in body j coordinates
      const Matrix3<S>& E_j = data.X_base[j].E;
      body_joint_project(model, data, j, ForceVector<S>(Vector3<S>(E_j * n_j), Vector3<S>(E_j * f_base)), column);
      for (int l = 0; l < jj.nv; ++l) write_mass_pair(model, data, jj.idx_v + l, col, kk * column[l]);
    }
  }
}

}  // namespace detail

/// M(q) in data.M. Entries coupling joints on different branches are structural zeros: Data
/// creates M zeroed and this function never writes them (unless the model has coupled joints,
/// when M is zeroed and accumulated). A non-finite entry throws std::domain_error naming its column.
///
/// The composite inertias and F = Iᶜ_i S_i are formed in body coordinates, as in RBDA. F reaches
/// the ancestors by one force transform each, or on deep trees (data.crba_in_base_coordinates:
/// fewer operations per pair, once the poses in the base are known) from base coordinates, which
/// leaves data.X_base and data.axis_base filled on the scalar path. Where AVX2 and FMA are enabled,
/// double models without a floating base or coupled joints take crba_packed.hpp instead.
template <class S>
const MatrixX<S>& crba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) {
    if (detail::crba_takes_packed_path(model, data)) {  // crba_packed.hpp
      detail::crba_packed_impl(model, data, q);
      detail::check_finite_result(model, "mass matrix: the column", data.M);
      return data.M;
    }
  }
#endif
  update_joint_transforms(model, data, q);
  const int n = model.nbodies();
  for (int i = 1; i < n; ++i) data.Ic[i] = model.inertia[i];
  for (int i = n - 1; i >= 1; --i) {
    const int lambda = model.parent[i];
    if (lambda > 0) data.X_up[i].applyInverseAdd(data.Ic[i], data.Ic[lambda]);    // Iᶜ_λ += Xᵀ Iᶜ_i X (eq. 24, 26)
  }
  const bool in_base = data.crba_in_base_coordinates;
  if (in_base) detail::base_poses_and_axes(model, data);
  if (model.has_coupled_joints) data.M.setZero();
  S column[6];
  for (int i = 1; i < n; ++i) {
    const Joint<S>& ji = model.joints[i];
    const S ki = coupling_multiplier(ji);
    for (int k = 0; k < ji.nv; ++k) {
      const int col = ji.idx_v + k;
      const ForceVector<S> F = ji.nv == 1 ? inertia_times_one_dof_subspace(ji, data.Ic[i])
                                          : data.Ic[i] * body_subspace_column(model, data, i, k);  // F = Iᶜ_i S_i
      body_joint_project(model, data, i, F, column);                            // M_ii = Sᵢᵀ F
      if (model.has_coupled_joints) data.M(col, col) += ki * ki * column[k];
      else data.M(col, col) = column[k];
      for (int l = k + 1; l < ji.nv; ++l) detail::write_mass_pair(model, data, ji.idx_v + l, col, column[l]);  // exactly symmetric
      if (model.parent[i] == 0) continue;
      if (in_base) detail::carry_column_in_base(model, data, i, F, col, ki);
      else detail::carry_column_per_ancestor(model, data, i, F, col, ki);
    }
  }
  detail::check_finite_result(model, "mass matrix: the column", data.M);
  return data.M;
}

#ifdef SD_COMPILED_DOUBLE
// The double instances: compiled into the library, portable and AVX2 + FMA (simd_backend.hpp).
const MatrixX<double>& crba(const Model<double>& model, Data<double>& data, const ConstVectorRef<double>& q);
#endif

}  // namespace spatial_dynamics
