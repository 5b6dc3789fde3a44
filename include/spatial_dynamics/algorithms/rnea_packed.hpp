// RNEA (RBDA Table 5.1) on packed 3-vectors (spatial/packed3.hpp): the same passes and formulas as
// rnea.hpp, each 3-vector in one 4-lane register. For double on fixed-base models without
// coupled joints (every joint revolute or prismatic, one coordinate each) where AVX2 and FMA are
// enabled; rnea() dispatches here then. Rounding differs from the scalar code only in the order of
// fused operations (a few ulps of each body quantity; the accuracy tests bound both).
#pragma once

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/packed3.hpp"

namespace spatial_dynamics {
namespace detail {

/// Whether rnea() takes the packed path for this model and scalar.
template <class S>
bool rnea_takes_packed_path(const Model<S>& model) {
#ifdef SD_PACKED3
  return std::is_same<S, double>::value && !model.floating_base && !model.has_coupled_joints &&
         !model.has_multi_dof_tree_joints;  // written for 1-DoF trees
#else
  (void)model;
  return false;
#endif
}

#ifdef SD_PACKED3

/// ^iX_λ = X_J(q_i) X_tree(i) (RBDA Table 4.1) of a revolute or prismatic joint: the columns
/// c0..c2 of E, its rows t0..t2, r, and the joint's axis; sin and cos from data.
SD_INLINE void packed_up_transform(const Model<double>& model, const Data<double>& data, int i, const double* q,
                                   packed3::Packed3& c0, packed3::Packed3& c1, packed3::Packed3& c2,
                                   packed3::Packed3& t0, packed3::Packed3& t1, packed3::Packed3& t2,
                                   packed3::Packed3& r, packed3::Packed3& axis) {
  using namespace packed3;
  const Joint<double>& j = model.joints[i];
  const PluckerTransform<double>& Xt = model.X_tree[i];
  load_columns(Xt.E, c0, c1, c2);
  r = load_after(Xt.E.data() + 8);
  if (one_dof_rotates(j)) {
    packed_rotate_about_joint_axis(j, data.joint_sin[i], data.joint_cos[i], c0, c1, c2);
  }
  axis = make(j.axis.x(), j.axis.y(), j.axis.z());
  transpose(c0, c1, c2, t0, t1, t2);
  if (!one_dof_rotates(j)) r += mat_vec(t0, t1, t2, q[j.idx_q] * axis);  // r = r_tree + E_treeᵀ (q a)
}

/// I x for a rigid inertia (eq. 25): (Ī ω + h × v ; m v − h × ω).
SD_INLINE void packed_inertia_times(packed3::Packed3 I0, packed3::Packed3 I1, packed3::Packed3 I2, packed3::Packed3 h,
                                    double m, packed3::Packed3 w, packed3::Packed3 v, packed3::Packed3& n,
                                    packed3::Packed3& f) {
  using namespace packed3;
  n = mat_vec(I0, I1, I2, w) + cross(h, v);
  f = m * v - cross(h, w);
}

/// Component a · x of a force's part along the joint axis: one lane for a coordinate axis.
SD_INLINE double packed_along_axis(const Joint<double>& j, packed3::Packed3 x) {
  switch (j.axis_kind) {
    case AxisKind::X: return x[0];
    case AxisKind::Y: return x[1];
    case AxisKind::Z: return x[2];
    default: return j.axis.x() * x[0] + j.axis.y() * x[1] + j.axis.z() * x[2];
  }
}

/// τ = ID(q, q̇, q̈, f_ext) into data.tau; the caller has checked rnea_takes_packed_path.
inline const VectorX<double>& rnea_packed_impl(const Model<double>& model, Data<double>& data,
                                               const ConstVectorRef<double>& q, const ConstVectorRef<double>& qd,
                                               const ConstVectorRef<double>& qdd, const ForceVector<double>* f_ext) {
  using namespace packed3;
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  check_length("acceleration", qdd.size(), model.nv);
  joint_sines_and_cosines(model, data, q.data());
  PackedWorkspace::RneaBody* body = data.packed.rnea.data();
  const Packed3 zero = splat(0);
  store(zero, body[0].w);
  store(zero, body[0].v);
  store(zero, body[0].aw);
  store(-make(model.gravity.x(), model.gravity.y(), model.gravity.z()), body[0].al);  // a_0 = −a_g
  const int nb = model.nbodies();
  for (int i = 1; i < nb; ++i) {
    const Joint<double>& j = model.joints[i];
    PackedWorkspace::RneaBody& b = body[i];
    const PackedWorkspace::RneaBody& p = body[model.parent[i]];
    Packed3 c0, c1, c2, t0, t1, t2, r, axis;
    packed_up_transform(model, data, i, q.data(), c0, c1, c2, t0, t1, t2, r, axis);
    store(t0, b.t0);
    store(t1, b.t1);
    store(t2, b.t2);
    store(r, b.r);
    // v_i = X v_λ + S q̇, a_i = X a_λ + S q̈ + v_i × S q̇ (eqs. 11, 17).
    const Packed3 pw = load(p.w), paw = load(p.aw);
    const Packed3 s_qd = qd[j.idx_v] * axis, s_qdd = qdd[j.idx_v] * axis;
    Packed3 w = mat_vec(c0, c1, c2, pw);
    Packed3 v = mat_vec(c0, c1, c2, load(p.v) - cross(r, pw));
    Packed3 aw = mat_vec(c0, c1, c2, paw);
    Packed3 al = mat_vec(c0, c1, c2, load(p.al) - cross(r, paw));
    if (one_dof_rotates(j)) {
      w += s_qd;
      aw += cross(w, s_qd);
      aw += s_qdd;
      al += cross(v, s_qd);
    } else {
      v += s_qd;
      al += cross(w, s_qd);
      al += s_qdd;
    }
    store(w, b.w);
    store(v, b.v);
    store(aw, b.aw);
    store(al, b.al);
    // f_i = I a_i + v_i ×* I v_i (eq. 29), v ×* (n ; f) = (ω × n + v × f ; ω × f) (eq. 18).
    const RigidInertia<double>& I = model.inertia[i];
    Packed3 I0, I1, I2;
    load_columns(I.rotational_inertia, I0, I1, I2);
    const Packed3 h = load(I.first_moment.data());
    Packed3 n_v, f_v, n_a, f_a;
    packed_inertia_times(I0, I1, I2, h, I.mass, w, v, n_v, f_v);
    packed_inertia_times(I0, I1, I2, h, I.mass, aw, al, n_a, f_a);
    Packed3 n = n_a + (cross(w, n_v) + cross(v, f_v));
    Packed3 f = f_a + cross(w, f_v);
    if (f_ext) {
      const ForceVector<double>& e = f_ext[i];
      n -= make(e.angular.x(), e.angular.y(), e.angular.z());
      f -= make(e.linear.x(), e.linear.y(), e.linear.z());
    }
    store(n, b.n);
    store(f, b.f);
  }
  // τ_i = Sᵢᵀ f_i, f_λ += ^iX_λᵀ f_i = (Eᵀ n + r × Eᵀ f ; Eᵀ f) (eq. 12).
  double* tau = data.tau.data();
  for (int i = nb - 1; i >= 1; --i) {
    const Joint<double>& j = model.joints[i];
    const PackedWorkspace::RneaBody& b = body[i];
    const Packed3 n = load(b.n), f = load(b.f);
    tau[j.idx_v] = packed_along_axis(j, one_dof_rotates(j) ? n : f);
    const int lambda = model.parent[i];
    if (lambda > 0) {
      const Packed3 t0 = load(b.t0), t1 = load(b.t1), t2 = load(b.t2);
      const Packed3 lin = mat_vec(t0, t1, t2, f);
      PackedWorkspace::RneaBody& pb = body[lambda];
      store(load(pb.n) + mat_vec(t0, t1, t2, n) + cross(load(b.r), lin), pb.n);
      store(load(pb.f) + lin, pb.f);
    }
  }
  return data.tau;
}

#endif  // SD_PACKED3

}  // namespace detail
}  // namespace spatial_dynamics
