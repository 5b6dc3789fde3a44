// CRBA (RBDA Table 6.2) on packed 3-vectors (spatial/packed3.hpp), for the models and builds
// without floating base, coupled joints or multi-DoF joints in the tree. The columns are carried one force transform per
// ancestor or, with data.crba_in_base_coordinates, from base coordinates (crba_base_carry.hpp).
// The same formulas as crba.hpp and PluckerTransform::applyInverseAdd; the rounding differs only
// in the order of fused operations.
#pragma once

#include "spatial_dynamics/algorithms/crba_base_carry.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/algorithms/vector3_form.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/packed3.hpp"

namespace spatial_dynamics {
namespace detail {

/// Whether crba() takes the packed path for this model and scalar (with either carry).
template <class S>
bool crba_takes_packed_path(const Model<S>& model, const Data<S>&) {
#ifdef SD_PACKED3
  return std::is_same<S, double>::value && !model.floating_base && !model.has_coupled_joints &&
         !model.has_multi_dof_tree_joints;  // written for 1-DoF trees
#else
  (void)model;
  return false;
#endif
}

#ifdef SD_PACKED3

/// F = Iᶜ_i S_i (eq. 25): (Ī a ; −h × a) for a revolute joint, (h × a ; m a) for a prismatic one.
SD_INLINE void packed_composite_force(const Joint<double>& j, const PackedWorkspace::CrbaBody& b,
                                      packed3::Packed3& n, packed3::Packed3& f) {
  using namespace packed3;
  const Packed3 axis = make(j.axis.x(), j.axis.y(), j.axis.z());
  if (one_dof_rotates(j)) {
    n = mat_vec(load(b.I0), load(b.I1), load(b.I2), axis);
    f = cross(axis, load(b.h));
  } else {
    n = cross(load(b.h), axis);
    f = b.mass * axis;
  }
}

/// The columns from base coordinates, once the transforms and composite inertias are in
/// data.packed.crba: the poses ^iX_0 (rows of E_0i = E_i E_0λ, r_0i = r_0λ + E_0λᵀ r_i), each
/// origin and axis into the arrays of crba_base_carry.hpp, then per column F in base orientation
/// about body i's origin, carried to the runs of revolute ancestors L at a time
/// (M_ji = a_j · (n + f × (p_j − p_i))) and to prismatic ones one by one (M_ji = a_j · f).
inline void crba_packed_columns_in_base(const Model<double>& model, Data<double>& data) {
  using namespace packed3;
  PackedWorkspace::CrbaBody* body = data.packed.crba.data();
  const int nb = model.nbodies();
  const int soa_stride = static_cast<int>(data.base_origin_and_axis.size()) / 6;
  double* soa = data.base_origin_and_axis.data();
  for (int i = 1; i < nb; ++i) {
    PackedWorkspace::CrbaBody& b = body[i];
    const Packed3 t0 = load(b.t0), t1 = load(b.t1), t2 = load(b.t2), r = load(b.r);
    Packed3 base_t0 = t0, base_t1 = t1, base_t2 = t2, base_r = r;
    const int lambda = model.parent[i];
    if (lambda > 0) {
      const PackedWorkspace::CrbaBody& p = body[lambda];
      const Packed3 p0 = load(p.base_t0), p1 = load(p.base_t1), p2 = load(p.base_t2);
      base_t0 = mat_vec(p0, p1, p2, t0);  // row m of E_i E_0λ = Σ_k E_i(m, k) · row k of E_0λ
      base_t1 = mat_vec(p0, p1, p2, t1);
      base_t2 = mat_vec(p0, p1, p2, t2);
      base_r = load(p.base_r) + mat_vec(p0, p1, p2, r);
    }
    store(base_t0, b.base_t0);
    store(base_t1, b.base_t1);
    store(base_t2, b.base_t2);
    store(base_r, b.base_r);
    const Joint<double>& j = model.joints[i];
    const Packed3 axis = mat_vec(base_t0, base_t1, base_t2, make(j.axis.x(), j.axis.y(), j.axis.z()));  // E_0iᵀ a
    for (int k = 0; k < 3; ++k) {
      soa[k * soa_stride + i] = base_r[k];
      soa[(3 + k) * soa_stride + i] = axis[k];
    }
  }
  double* M = data.M.data();
  const Eigen::Index stride = data.M.outerStride();
  for (int i = 1; i < nb; ++i) {
    const Joint<double>& ji = model.joints[i];
    const PackedWorkspace::CrbaBody& b = body[i];
    Packed3 n, f;
    packed_composite_force(ji, b, n, f);
    const Eigen::Index col = ji.idx_v;
    M[col + col * stride] = vec3::PackedForm::dot_axis(ji, one_dof_rotates(ji) ? n : f);  // M_ii = Sᵢᵀ F
    const Packed3 base_t0 = load(b.base_t0), base_t1 = load(b.base_t1), base_t2 = load(b.base_t2);
    const Packed3 n_base = mat_vec(base_t0, base_t1, base_t2, n), f_base = mat_vec(base_t0, base_t1, base_t2, f);
    const Vector3<double> n3(n_base[0], n_base[1], n_base[2]), f3(f_base[0], f_base[1], f_base[2]);
    const Packed3 p_i = load(b.base_r);
    const Vector3<double> p3(p_i[0], p_i[1], p_i[2]);
    for (int j = model.parent[i]; j > 0;) {
      const int first = data.revolute_run_start[j];
      if (first > 0) {
        carry_over_revolute_run(model, data, n3, f3, p3, first, j, static_cast<int>(col));
        j = model.parent[first];
        continue;
      }
      // Every revolute joint is in a run (of one at least): j is prismatic, M_ji = a_j · f.
      const Joint<double>& jj = model.joints[j];
      const Packed3 ax = make(soa[3 * soa_stride + j], soa[4 * soa_stride + j], soa[5 * soa_stride + j]) * f_base;
      const double m = ax[0] + ax[1] + ax[2];
      M[jj.idx_v + col * stride] = m;
      M[col + jj.idx_v * stride] = m;
      j = model.parent[j];
    }
  }
}

/// M(q) into data.M; the caller has checked crba_takes_packed_path.
inline const MatrixX<double>& crba_packed_impl(const Model<double>& model, Data<double>& data,
                                               const ConstVectorRef<double>& q) {
  using namespace packed3;
  check_length("q", q.size(), model.nq);
  joint_sines_and_cosines(model, data, q.data());
  PackedWorkspace::CrbaBody* body = data.packed.crba.data();
  const int nb = model.nbodies();
  for (int i = 1; i < nb; ++i) {  // Iᶜ_i = I_i
    const RigidInertia<double>& I = model.inertia[i];
    Packed3 I0, I1, I2;
    load_columns(I.rotational_inertia, I0, I1, I2);
    store(I0, body[i].I0);
    store(I1, body[i].I1);
    store(I2, body[i].I2);
    store(load(I.first_moment.data()), body[i].h);
    body[i].mass = I.mass;
  }
  for (int i = nb - 1; i >= 1; --i) {
    PackedWorkspace::CrbaBody& b = body[i];
    vec3::PackedForm::Rotation E;
    Packed3 r;
    vec3::PackedForm::up_transform(model, data, i, q.data(), b, E, r);  // ^iX_λ; the rows of E and r into b
    const Packed3 c0 = E.c0, c1 = E.c1, c2 = E.c2;
    const vec3::PackedForm::Rotation Et = vec3::PackedForm::transposed_rotation(b);
    const Packed3 t0 = Et.c0, t1 = Et.c1, t2 = Et.c2;
    const int lambda = model.parent[i];
    if (lambda == 0) continue;
    // Iᶜ_λ += Xᵀ Iᶜ_i X (eq. 26 inverted): h' = Eᵀ h, column c of Eᵀ Ī E = Eᵀ (Ī E_c), then the
    // shift by r with h_A = h' + m r: column c − r h'_c − h_A r_c + (m r·r + 2 h'·r) e_c.
    const Packed3 I0 = load(b.I0), I1 = load(b.I1), I2 = load(b.I2), h = load(b.h);
    const double m = b.mass;
    const Packed3 h_rot = mat_vec(t0, t1, t2, h);
    const Packed3 h_shifted = h_rot + m * r;
    const Packed3 rr = r * (h_shifted + h_rot);
    const double diagonal = rr[0] + rr[1] + rr[2];  // m r·r + 2 h'·r
    const Packed3 columns[3] = {mat_vec(t0, t1, t2, mat_vec(I0, I1, I2, c0)), mat_vec(t0, t1, t2, mat_vec(I0, I1, I2, c1)),
                                mat_vec(t0, t1, t2, mat_vec(I0, I1, I2, c2))};
    PackedWorkspace::CrbaBody& p = body[lambda];
    store(load(p.I0) + (columns[0] - r * h_rot[0] - h_shifted * r[0] + make(diagonal, 0, 0)), p.I0);
    store(load(p.I1) + (columns[1] - r * h_rot[1] - h_shifted * r[1] + make(0, diagonal, 0)), p.I1);
    store(load(p.I2) + (columns[2] - r * h_rot[2] - h_shifted * r[2] + make(0, 0, diagonal)), p.I2);
    store(load(p.h) + h_shifted, p.h);
    p.mass += m;
  }
  if (data.crba_in_base_coordinates) {
    crba_packed_columns_in_base(model, data);
    return data.M;
  }
  double* M = data.M.data();
  const Eigen::Index stride = data.M.outerStride();
  const int* parent = model.parent.data();
  const Joint<double>* joints = model.joints.data();
  for (int i = 1; i < nb; ++i) {
    const Joint<double>& ji = joints[i];
    const PackedWorkspace::CrbaBody& b = body[i];
    Packed3 n, f;
    packed_composite_force(ji, b, n, f);  // F = Iᶜ_i S_i
    const Eigen::Index col = ji.idx_v;
    M[col + col * stride] = vec3::PackedForm::dot_axis(ji, one_dof_rotates(ji) ? n : f);  // M_ii = Sᵢᵀ F
    for (int j = i, lambda = parent[i]; lambda > 0; j = lambda, lambda = parent[j]) {
      const PackedWorkspace::CrbaBody& x = body[j];  // F = ^jX_λᵀ F = (Eᵀ n + r × Eᵀ f ; Eᵀ f)
      const Packed3 t0 = load(x.t0), t1 = load(x.t1), t2 = load(x.t2);
      f = mat_vec(t0, t1, t2, f);
      n = mat_vec(t0, t1, t2, n) + cross(load(x.r), f);
      const Joint<double>& jl = joints[lambda];
      const double m = vec3::PackedForm::dot_axis(jl, one_dof_rotates(jl) ? n : f);  // M_λi = S_λᵀ F
      const Eigen::Index row = jl.idx_v;
      M[row + col * stride] = m;
      M[col + row * stride] = m;
    }
  }
  return data.M;
}

#endif  // SD_PACKED3

}  // namespace detail
}  // namespace spatial_dynamics
