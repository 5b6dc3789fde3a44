// Recursive Newton–Euler inverse dynamics, τ = ID(q, q̇, q̈, f_ext)   (RBDA Table 5.1).
// Gravity enters as a fictitious base acceleration a_0 = −a_g. External forces act on the
// bodies, each expressed in its body's coordinates.
#pragma once

#include <vector>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/algorithms/rnea_packed.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

/// The inward pass from the body forces in data.f: τ_i = Sᵢᵀ f_i (summed over a coupled joint's
/// bodies), f_λ += ^iX_λᵀ f_i.
template <class S>
SD_INLINE void rnea_backward_pass(const Model<S>& model, Data<S>& data) {
  const bool accumulate = model.has_coupled_joints;
  if (accumulate) data.tau.setZero();
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    store_joint_force(model, data, i, data.f[i], data.tau.data(), accumulate);     // τ_i = Sᵢᵀ f_i
    const int lambda = model.parent[i];
    if (lambda > 0) data.f[lambda] += data.X_up[i].applyInverse(data.f[i]);        // f_λ += Xᵀ f_i
  }
}

/// τ = ID(q, q̇, q̈, f_ext) under gravity a_g (the model's, or another: zero for M q̈).
template <class S>
const VectorX<S>& rnea_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                            const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                            const ForceVector<S>* f_ext, const Vector3<S>& gravity) {
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  check_length("acceleration", qdd.size(), model.nv);
  joint_sines_and_cosines(model, data, q.data());
  data.v[0] = MotionVector<S>::Zero();
  data.a[0] = MotionVector<S>(Vector3<S>::Zero(), -gravity);  // a_0 = −a_g
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    const int lambda = model.parent[i];
    body_up_transform(model, data, i, q.data(), data.X_up[i]);
    if (j.nv == 1 && lambda == 0) {  // v_0 = 0, a_0 = (0 ; −a_g): v_i = S q̇, v_i × S q̇ = 0, X a_0 = (0 ; E a_0)
      const S k = coupling_multiplier(j);                                          // q̇ = k q̇_master
      const S qd_i = k * qd[j.idx_v], qdd_i = k * qdd[j.idx_v];
      data.v[i] = one_dof_motion(j, qd_i);
      MotionVector<S>& a = data.a[i];
      a = data.X_up[i].applyToLinear(data.a[0].linear);
      add_one_dof_motion(j, qdd_i, a);                                             // a_i = X a_0 + S q̈
      data.f[i] = model.inertia[i] * a + one_dof_bias_force(j, model.inertia[i], qd_i);  // f_i = I a + v ×* I v
      if (f_ext) data.f[i] -= f_ext[i];
      continue;
    }
    if (j.nv == 1) {  // S q̇ and S q̈ have one axis: no 6-vector products with zeros
      const S k = coupling_multiplier(j);
      const S qd_i = k * qd[j.idx_v], qdd_i = k * qdd[j.idx_v];
      MotionVector<S>& v = data.v[i];
      MotionVector<S>& a = data.a[i];
      v = data.X_up[i].apply(data.v[lambda]);
      add_one_dof_motion(j, qd_i, v);                                              // v_i = X v_λ + S q̇
      a = data.X_up[i].apply(data.a[lambda]) + cross_one_dof_motion(v, j, qd_i);   // a_i = X a_λ + v_i × S q̇
      add_one_dof_motion(j, qdd_i, a);                                             //       + S q̈
    } else {
      const MotionVector<S> vJ = body_joint_motion(model, data, i, qd.data());     // S q̇
      data.v[i] = data.X_up[i].apply(data.v[lambda]) + vJ;                         // v_i = X v_λ + S q̇
      data.a[i] = data.X_up[i].apply(data.a[lambda]) + body_joint_motion(model, data, i, qdd.data()) +
                  body_joint_bias(model, data, i, qd.data()) + cross(data.v[i], vJ);  // a_i = X a_λ + S q̈ + c_J + v_i × S q̇
    }
    const ForceVector<S> Iv = model.inertia[i] * data.v[i];
    data.f[i] = model.inertia[i] * data.a[i] + cross(data.v[i], Iv);               // f_i = I a + v ×* I v (eq. 29)
    if (f_ext) data.f[i] -= f_ext[i];
  }
  rnea_backward_pass(model, data);
  return data.tau;
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

/// The packed path (rnea_packed.hpp) where it applies, rnea_impl otherwise.
template <class S>
SD_INLINE void rnea_dispatch(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd,
                             const ConstVectorRef<S>& qdd, const ForceVector<S>* f_ext) {
#ifdef SD_PACKED3
  if constexpr (std::is_same<S, double>::value) {
    if (rnea_takes_packed_path(model)) {
      rnea_packed_impl(model, data, q, qd, qdd, f_ext);
      return;
    }
  }
#endif
  rnea_impl(model, data, q, qd, qdd, f_ext);
}

}  // namespace detail

/// Joint forces τ that produce accelerations q̈ at (q, q̇) under gravity. Result in data.tau;
/// a non-finite one throws std::domain_error naming the joint (input_checks.hpp).
template <class S>
const VectorX<S>& rnea(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                       const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  detail::rnea_dispatch(model, data, q, qd, qdd, static_cast<const ForceVector<S>*>(nullptr));
  detail::check_finite_result(model, "inverse dynamics: the joint force", data.tau);
  return data.tau;
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& rnea(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                       const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd,
                       const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  detail::rnea_dispatch(model, data, q, qd, qdd, f_ext.data());
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

#ifdef SD_COMPILED_DOUBLE
// The double instances: compiled into the library, portable and AVX2 + FMA (simd_backend.hpp).
const VectorX<double>& rnea(const Model<double>& model, Data<double>& data, const ConstVectorRef<double>& q,
                            const ConstVectorRef<double>& qd, const ConstVectorRef<double>& qdd);
const VectorX<double>& rnea(const Model<double>& model, Data<double>& data, const ConstVectorRef<double>& q,
                            const ConstVectorRef<double>& qd, const ConstVectorRef<double>& qdd,
                            const std::vector<ForceVector<double>>& f_ext);
const VectorX<double>& gravity_torques(const Model<double>& model, Data<double>& data, const ConstVectorRef<double>& q);
const VectorX<double>& nonlinear_effects(const Model<double>& model, Data<double>& data,
                                         const ConstVectorRef<double>& q, const ConstVectorRef<double>& qd);
#endif

}  // namespace spatial_dynamics
