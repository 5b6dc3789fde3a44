// Composite-rigid-body algorithm: the joint-space mass matrix M(q), both triangles filled
// (RBDA Table 6.2), on the 3-vectors of this build's form (vector3_form.hpp): packed registers for
// double where the CPU has AVX2 and FMA, Eigen's 3-vectors otherwise. Every model and joint type.
#pragma once

#include "spatial_dynamics/algorithms/crba_base_carry.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/algorithms/vector3_form.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

namespace detail {

/// Writes M's entries through local pointers (Eigen's stores may alias any memory, so members read
/// through `model` and `data` would be reloaded after each of them). kOneDof: the model's joints
/// each have one coordinate and none is coupled, so that the other cases' branches compile away.
template <class S, bool kOneDof>
struct MassMatrixEntries {
  S* M;
  Eigen::Index stride;
  const Joint<S>* joints;
  bool coupled;

  MassMatrixEntries(const Model<S>& model, Data<S>& data)
      : M(data.M.data()),
        stride(data.M.outerStride()),
        joints(model.joints.data()),
        coupled(!kOneDof && model.has_coupled_joints) {}

  /// M(row, col) and M(col, row) = value for a coordinate `row` of body j's joint; with coupled
  /// mimic joints (M = Gᵀ M_independent G) both accumulate k_i k_j value instead.
  SD_INLINE void pair(int j, Eigen::Index row, Eigen::Index col, const S& ki, const S& value) const {
    if (coupled) {
      const S kk = ki * coupling_multiplier(joints[j]);
      M[row + col * stride] += kk * value;
      M[col + row * stride] += kk * value;
    } else {
      M[row + col * stride] = value;
      M[col + row * stride] = value;
    }
  }

  /// Sⱼᵀ (n ; f) into the entries of body j's coordinates and column `col` (coupling k_i); (n ; f)
  /// in body j's coordinates.
  template <class F>
  SD_INLINE void projection(const Model<S>& model, const Data<S>& data, int j, const typename F::Vector& n,
                            const typename F::Vector& f, Eigen::Index col, const S& ki) const {
    const Joint<S>& jj = joints[j];
    if (kOneDof || jj.nv == 1) {
      pair(j, jj.idx_v, col, ki, F::dot_axis(jj, one_dof_rotates(jj) ? n : f));
      return;
    }
    ForceVector<S> force;
    F::store(n, force.angular);
    F::store(f, force.linear);
    S column[6];
    body_joint_project(model, data, j, force, column);
    for (int l = 0; l < jj.nv; ++l) pair(j, jj.idx_v + l, col, ki, column[l]);
  }
};

/// (n ; f) = Iᶜ (ω ; v) = (Ī_O ω + h × v ; m v − h × ω) for the composite inertia kept in b (eq. 25).
template <class F, class Body>
SD_INLINE void composite_times(const Body& b, const typename F::Vector& w, const typename F::Vector& v,
                               typename F::Vector& n, typename F::Vector& f) {
  const typename F::Vector h = F::load(b.h);
  n = F::times(F::columns(b.I0, b.I1, b.I2), w) + F::cross(h, v);
  f = b.mass * v - F::cross(h, w);
}

/// F = Iᶜ_i S_i for column k of body i's joint: (Ī_O a ; a × h) for a revolute joint, (h × a ; m a)
/// for a prismatic one, Iᶜ times the column of S otherwise (eq. 25).
template <class F, bool kOneDof, class S>
SD_INLINE void composite_force(const Model<S>& model, const Data<S>& data, int i, int k, typename F::Vector& n,
                               typename F::Vector& f) {
  const Joint<S>& j = model.joints[i];
  const auto& b = data.crba[i];
  if (kOneDof || j.nv == 1) {
    const typename F::Vector h = F::load(b.h);
    if (one_dof_rotates(j)) {
      n = F::times_axis(F::columns(b.I0, b.I1, b.I2), j);
      f = F::cross_axis(j, h, S(-1));
    } else {
      n = F::cross_axis(j, h, S(1));
      f = F::axis_times(j, b.mass);
    }
    return;
  }
  const MotionVector<S> s_k = body_subspace_column(model, data, i, k);
  composite_times<F>(b, F::load(s_k.angular), F::load(s_k.linear), n, f);
}

/// The poses ^iX_0 in base coordinates (rows of E_0i = E_i E_0λ, r_0i = r_0λ + E_0λᵀ r_i), and each
/// origin and 1-DoF axis (E_0iᵀ a) into the arrays of crba_base_carry.hpp.
template <class F, class S>
SD_INLINE void base_poses_and_axes(const Model<S>& model, Data<S>& data) {
  using V = typename F::Vector;
  const int stride = static_cast<int>(data.base_origin_and_axis.size()) / 6;
  S* soa = data.base_origin_and_axis.data();
  for (int i = 1; i < model.nbodies(); ++i) {
    auto& b = data.crba[i];
    V t0 = F::load(b.t0), t1 = F::load(b.t1), t2 = F::load(b.t2), r = F::load(b.r);
    const int lambda = model.parent[i];
    if (lambda > 0) {
      const auto& p = data.crba[lambda];
      const auto E_0lambda_T = F::columns(p.base_t0, p.base_t1, p.base_t2);
      t0 = F::times(E_0lambda_T, t0);  // row m of E_i E_0λ = E_0λᵀ (row m of E_i)
      t1 = F::times(E_0lambda_T, t1);
      t2 = F::times(E_0lambda_T, t2);
      r = F::load(p.base_r) + F::times(E_0lambda_T, r);
    }
    F::store(t0, b.base_t0);
    F::store(t1, b.base_t1);
    F::store(t2, b.base_t2);
    F::store(r, b.base_r);
    const Joint<S>& j = model.joints[i];
    for (int k = 0; k < 3; ++k) soa[k * stride + i] = r[k];
    if (j.nv != 1) continue;
    const V axis = F::times_axis(F::columns(b.base_t0, b.base_t1, b.base_t2), j);
    for (int k = 0; k < 3; ++k) soa[(3 + k) * stride + i] = axis[k];
  }
}

/// Column `col`'s F = (n ; f) of body i (its coordinates) to every ancestor j from base
/// coordinates: F once into base orientation about body i's origin p_i, then for a revolute j
/// M_ji = a_j · n_j with the moment n_j = n + f × (p_j − p_i) about its origin (runs of them L at a
/// time), for a prismatic one M_ji = a_j · f, for several coordinates Sⱼᵀ (E_0j n_j ; E_0j f).
template <class F, bool kOneDof, class S>
SD_INLINE void carry_column_in_base(const Model<S>& model, Data<S>& data, const MassMatrixEntries<S, kOneDof>& M, int i,
                                    const typename F::Vector& n, const typename F::Vector& f, int col, const S& ki) {
  using V = typename F::Vector;
  const auto& b = data.crba[i];
  const auto E_0i_T = F::columns(b.base_t0, b.base_t1, b.base_t2);
  const V n_base = F::times(E_0i_T, n), f_base = F::times(E_0i_T, f), p_i = F::load(b.base_r);
  const int stride = static_cast<int>(data.base_origin_and_axis.size()) / 6;
  const S* soa = data.base_origin_and_axis.data();
  Vector3<S> n3, f3, p3;  // for the runs' lanes
  F::store(n_base, n3);
  F::store(f_base, f3);
  F::store(p_i, p3);
  for (int j = model.parent[i]; j > 0;) {
    const int first = data.revolute_run_start[j];
    if (first > 0 && !M.coupled) {
      carry_over_revolute_run(model, data, n3, f3, p3, first, j, col);
      j = model.parent[first];
      continue;
    }
    const Joint<S>& jj = model.joints[j];
    const auto& bj = data.crba[j];
    const V n_j = n_base + F::cross(f_base, F::load(bj.base_r) - p_i);  // moment about p_j
    if (kOneDof || jj.nv == 1) {
      const V axis = F::load(Vector3<S>(soa[3 * stride + j], soa[4 * stride + j], soa[5 * stride + j]));
      M.pair(j, jj.idx_v, col, ki, F::dot(axis, one_dof_rotates(jj) ? n_j : f_base));
    } else {  // into body j's coordinates: E_0j x = (rows of E_0j) · x
      const V t0 = F::load(bj.base_t0), t1 = F::load(bj.base_t1), t2 = F::load(bj.base_t2);
      const ForceVector<S> force(Vector3<S>(F::dot(t0, n_j), F::dot(t1, n_j), F::dot(t2, n_j)),
                                 Vector3<S>(F::dot(t0, f_base), F::dot(t1, f_base), F::dot(t2, f_base)));
      S column[6];
      body_joint_project(model, data, j, force, column);
      for (int l = 0; l < jj.nv; ++l) M.pair(j, jj.idx_v + l, col, ki, column[l]);
    }
    j = model.parent[j];
  }
}

/// The columns of M (Table 6.2's inner loop): for each coordinate of body i, F = Iᶜ_i S_i and
/// M_ii = Sᵢᵀ F, then F carried to the ancestors, one force transform each or from base coordinates.
template <class F, bool kOneDof, class S>
void mass_matrix_columns(const Model<S>& model, Data<S>& data) {
  using V = typename F::Vector;
  const bool in_base = data.crba_in_base_coordinates;
  if (in_base) base_poses_and_axes<F>(model, data);
  if (model.has_coupled_joints) data.M.setZero();
  const MassMatrixEntries<S, kOneDof> M(model, data);
  const int* parent = model.parent.data();
  const auto* body = data.crba.data();
  S own[6];
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& ji = M.joints[i];
    const S ki = coupling_multiplier(ji);
    for (int k = 0; k < (kOneDof ? 1 : ji.nv); ++k) {
      const Eigen::Index col = ji.idx_v + k;
      V n, f;
      composite_force<F, kOneDof>(model, data, i, k, n, f);  // F = Iᶜ_i S_i
      if (kOneDof || ji.nv == 1) {                          // M_ii = Sᵢᵀ F
        own[k] = F::dot_axis(ji, one_dof_rotates(ji) ? n : f);
      } else {
        ForceVector<S> force;
        F::store(n, force.angular);
        F::store(f, force.linear);
        body_joint_project(model, data, i, force, own);
      }
      M.M[col + col * M.stride] = M.coupled ? M.M[col + col * M.stride] + ki * ki * own[k] : own[k];
      for (int l = k + 1; l < (kOneDof ? 1 : ji.nv); ++l) M.pair(i, ji.idx_v + l, col, ki, own[l]);  // exactly symmetric
      if (parent[i] == 0) continue;
      if (in_base) {
        carry_column_in_base<F>(model, data, M, i, n, f, col, ki);
        continue;
      }
      for (int j = i, lambda = parent[i]; lambda > 0; j = lambda, lambda = parent[j]) {
        vec3::force_to_parent<F>(F::transposed_rotation(body[j]), F::translation(body[j]), n, f);  // F = ^jX_λᵀ F
        M.template projection<F>(model, data, lambda, n, f, col, ki);  // M_λi = S_λᵀ F
      }
    }
  }
}

/// M(q) into data.M on the 3-vectors of form F.
template <class F, class S>
void crba_with_form(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  using V = typename F::Vector;
  check_length("q", q.size(), model.nq);
  joint_sines_and_cosines(model, data, q.data());
  const int nb = model.nbodies();
  auto* body = data.crba.data();
  for (int i = 1; i < nb; ++i) {  // Iᶜ_i = I_i
    const RigidInertia<S>& I = model.inertia[i];
    F::store_columns(I.rotational_inertia, body[i].I0, body[i].I1, body[i].I2);
    F::store(F::load(I.first_moment), body[i].h);
    body[i].mass = I.mass;
  }
  for (int i = nb - 1; i >= 1; --i) {
    auto& b = body[i];
    typename F::Rotation E;
    V r;
    F::up_transform(model, data, i, q.data(), b, E, r);  // ^iX_λ into b, and its E and r
    const int lambda = model.parent[i];
    if (lambda == 0) continue;
    // Iᶜ_λ += ^iX_λᵀ Iᶜ_i ^iX_λ (Table 6.2; eq. 26 inverted): h' = Eᵀ h, column c of Eᵀ Ī E is
    // Eᵀ (Ī E_c), then the shift by r with h_λ = h' + m r: column c − r h'_c − h_λ r_c + (m r·r + 2 h'·r) e_c.
    const auto Et = F::transposed_rotation(b);
    const auto I = F::columns(b.I0, b.I1, b.I2);
    const S m = b.mass;
    const V h_rot = F::times(Et, F::load(b.h));
    const V h_shifted = h_rot + m * r;
    const S diagonal = F::dot(r, h_shifted + h_rot);  // m r·r + 2 h'·r
    V c0 = F::times(Et, F::times(I, F::column(E, 0))) - r * h_rot[0] - h_shifted * r[0];
    V c1 = F::times(Et, F::times(I, F::column(E, 1))) - r * h_rot[1] - h_shifted * r[1];
    V c2 = F::times(Et, F::times(I, F::column(E, 2))) - r * h_rot[2] - h_shifted * r[2];
    c0[0] += diagonal;
    c1[1] += diagonal;
    c2[2] += diagonal;
    auto& p = body[lambda];
    F::store(F::load(p.I0) + c0, p.I0);
    F::store(F::load(p.I1) + c1, p.I1);
    F::store(F::load(p.I2) + c2, p.I2);
    F::store(F::load(p.h) + h_shifted, p.h);
    p.mass += m;
  }
  if (!model.floating_base && !model.has_coupled_joints && !model.has_multi_dof_tree_joints)
    mass_matrix_columns<F, true>(model, data);
  else
    mass_matrix_columns<F, false>(model, data);
  if (model.has_armature)  // M + diag(armature) (RBDA §7.3)
    for (int k = 0; k < model.nv; ++k) data.M(k, k) += model.armature[k];
}

}  // namespace detail

/// M(q) in data.M. Entries coupling joints on different branches are structural zeros: Data
/// creates M zeroed and this function never writes them (unless the model has coupled joints,
/// when M is zeroed and accumulated). A non-finite entry throws std::domain_error naming its column.
///
/// The composite inertias and F = Iᶜ_i S_i are formed in body coordinates, as in RBDA. F reaches
/// the ancestors by one force transform each or, on deep trees (data.crba_in_base_coordinates:
/// fewer operations per pair once the poses in the base are known), from base coordinates.
template <class S>
const MatrixX<S>& crba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  detail::crba_with_form<vec3::Form<S>>(model, data, q);
  detail::check_finite_result(model, "mass matrix: the column", data.M);
  return data.M;
}

}  // namespace spatial_dynamics
