// Recursive Newton–Euler inverse dynamics, τ = ID(q, q̇, q̈, f_ext)   (RBDA Table 5.1).
// Gravity enters as a fictitious base acceleration a_0 = −a_g. External forces act on the
// bodies, each expressed in its body's coordinates.
#pragma once

#include <vector>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/algorithms/vector3_form.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

/// The RNEA's two passes, τ = ID(q, q̇, q̈, f_ext) under gravity a_g, on the 3-vectors of form F:
/// one state (vector3_form.hpp, `work` a Data) or L states in lanes (joint_kernels_lanes.hpp,
/// `work` a BatchData), F::Scalar per coordinate. Per body v, a, f and ^iX_λ in work.rnea; τ is
/// stored, or accumulated where a coupled joint shares its master's coordinate (τ zeroed first);
/// the model's armature adds its rotor inertia.
template <class F, class S, class Work>
SD_INLINE void rnea_passes(const Model<S>& model, Work& work, const typename F::Scalar* q,
                           const typename F::Scalar* qd, const typename F::Scalar* qdd, const ForceVector<S>* f_ext,
                           const Vector3<S>& gravity, typename F::Scalar* tau) {
  using V = typename F::Vector;
  using T = typename F::Scalar;
  auto* body = work.rnea.data();
  for (auto* zero : {&body[0].w, &body[0].v, &body[0].aw}) F::store(F::load(Vector3<S>(Vector3<S>::Zero())), *zero);
  F::store(F::load(Vector3<S>(-gravity)), body[0].al);  // a_0 = −a_g
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    auto& b = body[i];
    const auto& p = body[model.parent[i]];
    typename F::Rotation E;
    V r;
    F::up_transform(model, work, i, q, b, E, r);  // ^iX_λ into b, and its E and r
    // v_i = X v_λ + S q̇, a_i = X a_λ + S q̈ + c_J + v_i × S q̇ with X m = (E ω ; E (v − r × ω)) (eqs. 11, 17)
    V w = F::load(p.w), v = F::load(p.v), aw = F::load(p.aw), al = F::load(p.al);
    const auto about = F::up_rotation(work, i);  // E's structure (Data::up_rotation_axis)
    vec3::motion_to_child<F>(about, E, r, w, v);
    vec3::motion_to_child<F>(about, E, r, aw, al);
    if (j.nv == 1) {  // S q̇ = (q̇ a ; 0) or (0 ; q̇ a): the axis' products
      const S k = coupling_multiplier(j);  // q̇ = k q̇_master
      const T qd_i = k * qd[j.idx_v], qdd_i = k * qdd[j.idx_v];
      if (one_dof_rotates(j)) {
        F::add_axis(j, qd_i, w);
        aw += F::cross_axis(j, w, qd_i);
        F::add_axis(j, qdd_i, aw);
        al += F::cross_axis(j, v, qd_i);
      } else {
        F::add_axis(j, qd_i, v);
        al += F::cross_axis(j, w, qd_i);
        F::add_axis(j, qdd_i, al);
      }
    } else {
      V jw, jv, aJw, aJl;  // S q̇ and S q̈ + c_J
      F::joint_motion(model, work, i, qd, qdd, jw, jv, aJw, aJl);
      w += jw;
      v += jv;
      aw += aJw + F::cross(w, jw);
      al += aJl + (F::cross(w, jv) + F::cross(v, jw));
    }
    F::store(w, b.w);
    F::store(v, b.v);
    F::store(aw, b.aw);
    F::store(al, b.al);
    // f_i = I a_i + v_i ×* I v_i (eq. 29)
    V n, f, n_bias, f_bias;
    F::inertia_times(model.inertia[i], aw, al, n, f);
    F::bias_force(model.inertia[i], w, v, n_bias, f_bias);
    n += n_bias;
    f += f_bias;
    if (f_ext) {
      n -= F::load(f_ext[i].angular);
      f -= F::load(f_ext[i].linear);
    }
    F::store(n, b.n);
    F::store(f, b.f);
  }
  // τ_i = Sᵢᵀ f_i (summed over a coupled joint's bodies), f_λ += ^iX_λᵀ f_i = (Eᵀ n + r × Eᵀ f ; Eᵀ f) (eq. 12),
  // and the rotors' inertia τ_i += armature ⊙ q̈_i (RBDA §7.3): at the joint, or once per coordinate
  // after the pass where coupled joints share coordinates.
  const bool accumulate = model.has_coupled_joints;
  const bool armature_at_joint = model.has_armature && !accumulate;
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    const Joint<S>& j = model.joints[i];
    const auto& b = body[i];
    V n = F::load(b.n), f = F::load(b.f);
    if (j.nv == 1 && !accumulate) {
      const T projected = F::dot_axis(j, one_dof_rotates(j) ? n : f);
      tau[j.idx_v] = armature_at_joint ? projected + model.armature[j.idx_v] * qdd[j.idx_v] : projected;
    } else {
      F::store_force(model, work, i, n, f, tau, accumulate);
      if (armature_at_joint)
        for (int k = j.idx_v; k < j.idx_v + j.nv; ++k) tau[k] += model.armature[k] * qdd[k];
    }
    const int lambda = model.parent[i];
    if (lambda == 0) continue;
    vec3::force_to_parent<F>(transposed(F::up_rotation(work, i)), F::transposed_rotation(b), F::translation(b), n, f);
    auto& parent = body[lambda];
    F::store(F::load(parent.n) + n, parent.n);
    F::store(F::load(parent.f) + f, parent.f);
  }
  if (model.has_armature && accumulate)
    for (int k = 0; k < model.nv; ++k) tau[k] += model.armature[k] * qdd[k];
}

/// τ = ID(q, q̇, q̈, f_ext) under gravity a_g (the model's, or another: zero for M q̈) into
/// data.tau, on the 3-vectors of form F.
template <class F, class S>
const VectorX<S>& rnea_with_form(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                 const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd, const ForceVector<S>* f_ext,
                                 const Vector3<S>& gravity) {
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  check_length("acceleration", qdd.size(), model.nv);
  joint_sines_and_cosines(model, data, q.data());
  if (model.has_coupled_joints) data.tau.setZero();
  rnea_passes<F>(model, data, q.data(), qd.data(), qdd.data(), f_ext, gravity, data.tau.data());
  return data.tau;
}

/// The RNEA on this build's 3-vectors (packed for double where the CPU has them).
template <class S>
const VectorX<S>& rnea_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd, const ForceVector<S>* f_ext,
                            const Vector3<S>& gravity) {
  return rnea_with_form<vec3::Form<S>>(model, data, q, qd, qdd, f_ext, gravity);
}

template <class S>
const VectorX<S>& rnea_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd, const ForceVector<S>* f_ext) {
  return rnea_impl(model, data, q, qd, qdd, f_ext, model.gravity);
}

/// M(q) x = ID(q, 0, x) without gravity (RBDA eq. 5.1 with q̇ = 0 and a_g = 0); data.zero_v as q̇.
template <class S>
const VectorX<S>& mass_matrix_times(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                    const ConstVectorRef<S>& x) {
  return rnea_impl<S>(model, data, q, data.zero_v, x, nullptr, Vector3<S>(Vector3<S>::Zero()));
}

}  // namespace detail

/// Joint forces τ that produce accelerations q̈ at (q, q̇) under gravity. Result in data.tau;
/// a non-finite one throws std::domain_error naming the joint (input_checks.hpp).
template <class S>
const VectorX<S>& rnea(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                       const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  detail::rnea_impl(model, data, q, qd, qdd, static_cast<const ForceVector<S>*>(nullptr));
  detail::check_finite_result(model, "inverse dynamics: the joint force", data.tau);
  return data.tau;
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& rnea(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                       const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                       const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  detail::rnea_impl(model, data, q, qd, qdd, f_ext.data());
  detail::check_finite_result(model, "inverse dynamics: the joint force", data.tau);
  return data.tau;
}

/// Gravity torques g(q) = ID(q, 0, 0).
template <class S>
const VectorX<S>& gravity_torques(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  return rnea<S>(model, data, q, data.zero_v, data.zero_v);
}

/// Nonlinear effects C(q, q̇) q̇ + g(q) = ID(q, q̇, 0).
template <class S>
const VectorX<S>& nonlinear_effects(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                    const ConstVectorRef<S>& qd) {
  return rnea<S>(model, data, q, qd, data.zero_v);
}

}  // namespace spatial_dynamics
