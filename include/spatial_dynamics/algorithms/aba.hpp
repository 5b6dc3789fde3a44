// Articulated-body algorithm, q̈ = FD(q, q̇, τ, f_ext)   (RBDA Table 7.1). For float and double,
// gravity is split off first: the passes solve FD(q, q̇, τ − τ_g(q)) without it (gravity_split.hpp).
// A joint whose subtree has no inertia along its motion (D = Sᵀ Iᴬ S = 0, e.g. a massless leaf)
// makes forward dynamics undefined: the call fails with a message naming that joint.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "spatial_dynamics/algorithms/gravity_split.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/algorithms/vector3_form.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

template <class S>
[[noreturn]] void throw_singular_joint(const Model<S>& model, int i) {
  throw std::domain_error("joint '" + model.joint_names[i] +
                          "': its subtree has no inertia along the joint's motion (Sᵀ Iᴬ S = 0, e.g. a massless "
                          "leaf link), so forward dynamics is undefined");
}

template <class S>
SD_INLINE void check_aba_inputs(const Model<S>& model, const ConstVectorRef<S>& q, const ConstVectorRef<S>& qd,
                                const ConstVectorRef<S>& tau) {
  check_length("q", q.size(), model.nq);
  check_length("velocity", qd.size(), model.nv);
  check_length("effort", tau.size(), model.nv);
  if (model.has_coupled_joints)
    throw std::invalid_argument("the model has coupled mimic joints, which the ABA cannot solve; use forward_dynamics()");
}

/// Pass 1 (outward): transforms, velocities, velocity-product accelerations, rigid bias forces,
/// on the 3-vectors of this build (vector3_form.hpp); Iᴬ_i = I_i at a leaf (a parent's Iᴬ is
/// started by its first child in pass 2: data.first_child).
template <class S>
SD_INLINE void aba_velocity_pass(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                 const ConstVectorRef<S>& qd, const ForceVector<S>* f_ext, bool split_gravity) {
  using F = vec3::Form<S>;
  using V = typename F::Vector;
  joint_sines_and_cosines(model, data, q.data());
  data.v[0] = MotionVector<S>::Zero();
  if (split_gravity) gravity_split_start(model, data);
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    typename F::Rotation E;
    V r;
    F::up_transform(model, data, i, q.data(), E, r);                            // ^iX_λ into data.X_up[i]
    if (split_gravity) gravity_split_outward(model, data, i, E);                 // g_i = E g_λ
    // v_i = X v_λ + S q̇ (eq. 11), c_i = c_J + v_i × S q̇ (eq. 17)
    V w, v, cw, cv;
    const auto from_parent = [&]() SD_INLINE_LAMBDA {  // X v_λ
      F::load_six(data.v[model.parent[i]], w, v);
      vec3::motion_to_child<F>(body_up_rotation(data, i), E, r, w, v);
    };
    if (j.nv == 1 && model.parent[i] == 0) {  // v_0 = 0: v_i = S q̇, c_i = S q̇ × S q̇ = 0
      w = v = cw = cv = F::load(Vector3<S>(Vector3<S>::Zero()));
      F::add_axis(j, qd[j.idx_v], one_dof_rotates(j) ? w : v);
    } else if (j.nv == 1) {  // S q̇ = (q̇ a ; 0) or (0 ; q̇ a): the axis' products
      from_parent();
      const S qd_i = qd[j.idx_v];
      if (one_dof_rotates(j)) {
        F::add_axis(j, qd_i, w);
        cw = F::cross_axis(j, w, qd_i);
        cv = F::cross_axis(j, v, qd_i);
      } else {
        F::add_axis(j, qd_i, v);
        cw = F::load(Vector3<S>(Vector3<S>::Zero()));
        cv = F::cross_axis(j, w, qd_i);
      }
    } else {
      from_parent();
      const MotionVector<S> vJ = body_joint_motion(model, data, i, qd.data()), cJ = body_joint_bias(model, data, i, qd.data());
      const V jw = F::load(vJ.angular), jv = F::load(vJ.linear);
      w += jw;
      v += jv;
      cw = F::load(cJ.angular) + F::cross(w, jw);
      cv = F::load(cJ.linear) + (F::cross(w, jv) + F::cross(v, jw));
    }
    F::store_six(w, v, data.v[i]);
    F::store_six(cw, cv, data.c[i]);
    V n, f;  // pᴬ_i = v ×* I v − f_ext (eq. 29)
    F::bias_force(model.inertia[i], w, v, n, f);
    if (f_ext) {
      V n_ext, f_ext_i;
      F::load_six_settled(f_ext[i], n_ext, f_ext_i);
      n -= n_ext;
      f -= f_ext_i;
    }
    F::store_six(n, f, data.f[i]);
    if (!data.has_children[i]) data.IA[i].assign(model.inertia[i]);              // Iᴬ_i = I_i
  }
}

/// ^iX_λ's Eᵀ by its columns into Et where `about` (E's structure) tells nothing (otherwise Et is
/// left as it is): what the inward steps at body i share.
template <class S>
SD_INLINE void transposed_up_rotation(const Data<S>& data, int i, const RotationAboutAxis<S>& about,
                                      typename vec3::Form<S>::Rotation& Et) {
  using F = vec3::Form<S>;
  if (about.axis < 0) Et = F::transposed(F::rotation(data.X_up[i].E));
}

/// Pass 2's inertia part at a joint of n = nv > 1 coordinates (free, planar): U = Iᴬ S (6 × n),
/// D⁻¹ = (Sᵀ U)⁻¹ (n × n), and the articulated inertia passed to the parent. Out of line: a model
/// has one or a few such joints, and the pass's loop stays the 1-DoF code.
template <class S>
__attribute__((noinline)) void multi_dof_inertia_step(const Model<S>& model, Data<S>& data, int i) {
  const Joint<S>& j = model.joints[i];
  const int lambda = model.parent[i];
  Matrix6<S>& IA = data.IA[i].matrix;
  Matrix6<S>& U = data.U[i];  // columns n.. stay zero
  Matrix6<S> D = Matrix6<S>::Identity();  // D in the top-left block: D⁻¹ there, 1 elsewhere
  S column[6];
  inertia_times_subspace(j, data.joint_sin[i], data.joint_cos[i], IA, U);
  for (int k = 0; k < j.nv; ++k) {
    body_joint_project(model, data, i, ForceVector<S>(Vector6<S>(U.col(k))), column);
    for (int l = 0; l < j.nv; ++l) D(l, k) = column[l];
    if (model.has_armature) D(k, k) += model.armature[j.idx_v + k];  // D = Sᵀ U + armature (RBDA §7.3)
  }
  const Eigen::LLT<Matrix6<S>> llt(D);
  if (llt.info() != Eigen::Success) throw_singular_joint(model, i);
  data.D_inv[i] = llt.solve(Matrix6<S>::Identity());
  if (lambda > 0) {
    IA -= U * data.D_inv[i] * U.transpose();                                   // Iᵃ = Iᴬ − U D⁻¹ Uᵀ
    data.X_up[i].applyInverseAdd(data.IA[i], data.IA[lambda],                  // Iᴬ_λ += Xᵀ Iᵃ X
                                 data.first_child[i] ? &model.inertia[lambda] : nullptr);  // (I_λ + … first)
  }
}

/// Pass 2's inertia part at a 1-DoF joint: U = Iᴬ S, D⁻¹ = 1/(Sᵀ U), Iᴬ_λ += Xᵀ Iᵃ X with
/// Iᵃ = Iᴬ − U D⁻¹ Uᵀ, and Iᵃ c_i returned for the force part (zero at a joint on the base).
/// Iᴬ_i stays in data.IA[i]: the downdate is formed only on its way to the parent. The parent's
/// first child stores Iᴬ_λ = I_λ + Xᵀ Iᵃ X, the others add to it. `about` and Et as for
/// articulated_force_step.
template <class S, class TransposedRotation>
SD_INLINE ForceVector<S> one_dof_inertia_step(const Model<S>& model, Data<S>& data, int i,
                                              const RotationAboutAxis<S>& about, const TransposedRotation& Et) {
  const Joint<S>& j = model.joints[i];
  const int lambda = model.parent[i];
  const Matrix6<S>& IA = data.IA[i].matrix;
  using F = vec3::Form<S>;
  using V = typename F::Vector;
  V U_w, U_v;  // U = Iᴬ S
  F::inertia_times_axis(j, IA, U_w, U_v);
  const S S_dot_U = F::dot_axis(j, one_dof_rotates(j) ? U_w : U_v);
  const S D = model.has_armature ? S_dot_U + model.armature[j.idx_v] : S_dot_U;  // D = Sᵀ U (+ armature, RBDA §7.3)
  // D is numerically zero when it is below the rounding noise of the block it is taken from:
  // the rotational block (kg m²) for a revolute joint, the mass block (kg) for a prismatic one,
  // so that the test does not depend on the units (a millimetre robot is not singular). The block
  // is positive semi-definite, so its largest entry is on its diagonal.
  const int block = one_dof_rotates(j) ? 0 : 3;
  using std::abs;
  using std::max;
  const S scale = max(max(abs(IA(block, block)), abs(IA(block + 1, block + 1))), abs(IA(block + 2, block + 2)));
  if (!(D > S(64) * Eigen::NumTraits<S>::epsilon() * scale)) throw_singular_joint(model, i);
  const S D_inv = S(1) / D;
  F::store_halves(U_w, U_v, data.U[i].data());
  data.D_inv[i](0, 0) = D_inv;
  if (lambda == 0) return ForceVector<S>::Zero();
  const PluckerTransform<S>& X = data.X_up[i];
  V W_n = U_w, W_f = U_v;  // W = Xᵀ U, U taken to the parent as a force (eq. 12)
  vec3::force_to_parent<F>(transposed(about), Et, F::translation(X), W_n, W_f);
  ForceVector<S>& W_D_inv = data.XtU_D_inv[i];  // for pass 3's q̈ = D⁻¹(u − Uᵀ c) − (W D⁻¹)ᵀ a_λ
  F::store_six(W_n * D_inv, W_f * D_inv, W_D_inv);
  return X.applyInverseAddLessRankOne(data.IA[i], U_w, U_v, D_inv, W_n, W_f, data.c[i], data.IA[lambda],
                                      about, data.first_child[i] ? &model.inertia[lambda] : nullptr);
}

/// Pass 2's force part at body i, on the factorisation (U, D⁻¹, X_up) in data: u_i = τ_i − Sᵀ p_i,
/// then p_λ += Xᵀ pᵃ with pᵃ = p_i + U D⁻¹ u_i (+ Iᵃ c_i, `inertia_times_bias`, in the ABA; none
/// when solving M δ = r with the factorisation, aba_refined.hpp). p_i holds pᴬ_i on entry. `about`
/// is ^iX_λ's structure (body_up_rotation), Et its Eᵀ (transposed_up_rotation).
template <class S, class TransposedRotation>
SD_INLINE void articulated_force_step(const Model<S>& model, const Data<S>& data, int i, const S* tau,
                                      ForceVector<S>* p, Vector6<S>* u, const ForceVector<S>* inertia_times_bias,
                                      const RotationAboutAxis<S>& about, const TransposedRotation& Et) {
  using F = vec3::Form<S>;
  using V = typename F::Vector;
  const Joint<S>& j = model.joints[i];
  const int lambda = model.parent[i];
  V n, f;  // pᴬ, turned into pᵃ
  F::load_six(p[i], n, f);
  if (j.nv == 1) {
    u[i][0] = tau[j.idx_v] - F::dot_axis(j, one_dof_rotates(j) ? n : f);              // u = τ − Sᵀ pᴬ
    if (lambda == 0) return;
    V U_w, U_v;
    F::load_halves(data.U[i].data(), U_w, U_v);
    const S scaled = u[i][0] * data.D_inv[i](0, 0);
    n += U_w * scaled;                                                                  // pᵃ = pᴬ + U D⁻¹ u
    f += U_v * scaled;
  } else {
    S column[6];
    body_joint_project(model, data, i, p[i], column);
    for (int k = 0; k < j.nv; ++k) u[i][k] = tau[j.idx_v + k] - column[k];            // u = τ − Sᵀ pᴬ
    if (lambda == 0) return;
    const Vector6<S> U_D_inv_u = data.U[i] * (data.D_inv[i] * u[i]);                   // pᵃ = pᴬ + U D⁻¹ u
    V U_w, U_v;
    F::load_halves(U_D_inv_u.data(), U_w, U_v);
    n += U_w;
    f += U_v;
  }
  if (inertia_times_bias) {                                                             //      + Iᵃ c
    V Ia_c_n, Ia_c_f;
    F::load_six(*inertia_times_bias, Ia_c_n, Ia_c_f);
    n += Ia_c_n;
    f += Ia_c_f;
  }
  // pᴬ_λ += Xᵀ pᵃ (eq. 12)
  const PluckerTransform<S>& X = data.X_up[i];
  vec3::force_to_parent<F>(transposed(about), Et, F::translation(X), n, f);
  ForceVector<S>& parent = p[lambda];
  V parent_n, parent_f;
  F::load_six(parent, parent_n, parent_f);
  F::store_six(parent_n + n, parent_f + f, parent);
}

/// As above, E's structure and Eᵀ formed here (aba_refined's solve with the factorisation).
template <class S>
SD_INLINE void articulated_force_step(const Model<S>& model, const Data<S>& data, int i, const S* tau,
                                      ForceVector<S>* p, Vector6<S>* u, const ForceVector<S>* inertia_times_bias) {
  const auto about = body_up_rotation(data, i);
  typename vec3::Form<S>::Rotation Et{};
  transposed_up_rotation(data, i, about, Et);
  articulated_force_step(model, data, i, tau, p, u, inertia_times_bias, about, Et);
}

/// Pass 2 (inward): articulated inertias and bias forces, from data.X_up, c, IA = I at the leaves and f = pᴬ;
/// with split_gravity, the joint forces τ − τ_g(q) in place of τ. Leaves Iᴬ_i in data.IA[i] at a
/// 1-DoF joint and Iᵃ_i at a multi-DoF joint with a parent.
template <class S>
SD_INLINE void aba_inertia_pass(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& tau_in,
                                bool split_gravity) {
  const S* tau = split_gravity ? data.tau_less_gravity.data() : tau_in.data();
  using F = vec3::Form<S>;
  for (int i = model.nbodies() - 1; i >= 1; --i) {
    const auto about = body_up_rotation(data, i);
    typename F::Rotation Et{};
    transposed_up_rotation(data, i, about, Et);
    if (split_gravity) gravity_split_inward(model, data, i, tau_in, transposed(about), Et);  // τ − τ_g at joint i
    ForceVector<S> Ia_c;  // Iᵃ c
    if (model.joints[i].nv == 1) {
      Ia_c = one_dof_inertia_step(model, data, i, about, Et);
    } else {
      multi_dof_inertia_step(model, data, i);
      if (model.parent[i] > 0) Ia_c = data.IA[i] * data.c[i];                   // IA[i] holds Iᵃ here
    }
    articulated_force_step(model, data, i, tau, data.f.data(), data.u.data(), model.parent[i] == 0 ? nullptr : &Ia_c,
                           about, Et);
  }
}

/// Pass 3 (outward) on the factorisation in data, from a[0]: a'_i = X a_λ + c_i,
/// q̈_i = D⁻¹(u_i − Uᵀ a'_i), a_i = a'_i + S q̈_i. `c` is the ABA's velocity-product
/// accelerations; none (nullptr) when solving M δ = r with the factorisation. At a 1-DoF joint
/// with a moving parent q̈_i = D⁻¹(u_i − Uᵀ c_i) − (Xᵀ U D⁻¹)ᵀ a_λ (data.XtU_D_inv), which waits
/// on a_λ for one dot product rather than for a'_i; a leaf's a_i is then not formed (no child
/// reads it), and a[i] keeps what it held.
template <class S>
SD_INLINE void articulated_acceleration_pass(const Model<S>& model, const Data<S>& data, const MotionVector<S>* c,
                                             const Vector6<S>* u, MotionVector<S>* a, S* qdd) {
  using F = vec3::Form<S>;
  using V = typename F::Vector;
  const bool base_at_rest = (a[0].angular.array() == S(0)).all() && (a[0].linear.array() == S(0)).all();
  const V zero = F::load(Vector3<S>(Vector3<S>::Zero()));
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    const PluckerTransform<S>& X = data.X_up[i];
    const MotionVector<S>& parent = a[model.parent[i]];
    const bool from_rest = model.parent[i] == 0 && base_at_rest;  // a' = X a_0 + c = c
    V c_w = zero, c_l = zero;
    if (c) F::load_six_settled(c[i], c_w, c_l);  // stored in pass 1
    V w = c_w, l = c_l;
    const auto add_parent = [&]() SD_INLINE_LAMBDA {
      V Xa_w, Xa_l;
      F::load_six(parent, Xa_w, Xa_l);
      vec3::motion_to_child<F>(body_up_rotation(data, i), F::rotation(X.E), F::translation(X), Xa_w, Xa_l);  // a' = X a_λ
      w += Xa_w;                                                                                              //      + c
      l += Xa_l;
    };
    if (j.nv == 1) {
      V U_w, U_v;
      F::load_halves(data.U[i].data(), U_w, U_v);
      S qdd_i;
      const bool a_prime_first = model.parent[i] == 0 && !from_rest;  // a_0 is known from the start
      if (a_prime_first) {
        add_parent();
        qdd_i = data.D_inv[i](0, 0) * (u[i][0] - (F::dot(U_w, w) + F::dot(U_v, l)));  // q̈ = D⁻¹(u − Uᵀ a')
      } else {
        S u_less_Uc = u[i][0];  // u − Uᵀ c
        if (c) u_less_Uc -= F::dot(U_w, c_w) + F::dot(U_v, c_l);
        qdd_i = data.D_inv[i](0, 0) * u_less_Uc;                                        // q̈ = D⁻¹(u − Uᵀ c)
        if (!from_rest) {
          V W_n, W_f, a_w, a_l;
          F::load_six_settled(data.XtU_D_inv[i], W_n, W_f);  // stored in pass 2
          F::load_six(parent, a_w, a_l);
          qdd_i -= F::dot(W_n, a_w) + F::dot(W_f, a_l);                                 //      − (Xᵀ U D⁻¹)ᵀ a_λ
        }
      }
      qdd[j.idx_v] = qdd_i;
      if (!data.has_children[i]) continue;
      if (!a_prime_first && !from_rest) add_parent();
      F::add_axis(j, qdd_i, one_dof_rotates(j) ? w : l);                                  // a = a' + S q̈
      F::store_six(w, l, a[i]);
    } else {
      if (!from_rest) add_parent();
      F::store_six(w, l, a[i]);
      const Vector6<S> qdd_i = data.D_inv[i] * (u[i] - data.U[i].transpose() * a[i].toVector());  // zero past nv
      for (int k = 0; k < j.nv; ++k) qdd[j.idx_v + k] = qdd_i[k];
      a[i] += joint_motion(j, data.joint_sin[i], data.joint_cos[i], qdd_i.data());  // a = a' + S q̈
    }
  }
}

/// Pass 3 of the ABA: accelerations into data.qdd; gravity as a_0 = −a_g unless it was split off.
template <class S>
SD_INLINE void aba_acceleration_pass(const Model<S>& model, Data<S>& data, bool split_gravity) {
  data.a[0] = MotionVector<S>(Vector3<S>::Zero(), split_gravity ? Vector3<S>::Zero() : Vector3<S>(-model.gravity));
  articulated_acceleration_pass(model, data, data.c.data(), data.u.data(), data.a.data(), data.qdd.data());
}

template <class S>
const VectorX<S>& aba_impl(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                           const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                           const ForceVector<S>* f_ext) {
  check_aba_inputs(model, q, qd, tau);
  const bool split_gravity = splits_gravity(model);
  aba_velocity_pass(model, data, q, qd, f_ext, split_gravity);
  aba_inertia_pass(model, data, tau, split_gravity);
  aba_acceleration_pass(model, data, split_gravity);
  return data.qdd;
}

}  // namespace detail

/// Joint accelerations q̈ produced by joint forces τ at (q, q̇) under gravity. Result in data.qdd;
/// a non-finite one throws std::domain_error naming the joint (input_checks.hpp).
template <class S>
const VectorX<S>& aba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                      const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau) {
  detail::aba_impl(model, data, q, qd, tau, static_cast<const ForceVector<S>*>(nullptr));
  detail::check_finite_result(model, "forward dynamics: the acceleration", data.qdd);
  return data.qdd;
}

/// As above with external forces f_ext[i] acting on body i (body coordinates; entry 0 unused).
template <class S>
const VectorX<S>& aba(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                      const ConstVectorRef<S>& qd, const ConstVectorRef<S>& tau,
                      const std::vector<ForceVector<S>>& f_ext) {
  detail::check_external_forces(model, f_ext);
  detail::aba_impl(model, data, q, qd, tau, f_ext.data());
  detail::check_finite_result(model, "forward dynamics: the acceleration", data.qdd);
  return data.qdd;
}

}  // namespace spatial_dynamics
