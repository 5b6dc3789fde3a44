// What the algorithms ask of a joint, through the one dispatch (model/joints/joint_dispatch.hpp)
// to the joint models of model/joints/: X_J(q) X_tree, S q̇, c_J, Sᵀ f and the columns of S; the
// 1-DoF shortcuts of the passes (RBDA Table 4.1 with S = (a ; 0) or (0 ; a)); and the whole-vector
// access that handles coupled mimic joints and the joints' angles.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/joints/joint_axis_shortcuts.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/lane_trigonometry.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

/// ^iX_λ(i) = X_J(q_i) X_tree(i) (RBDA Table 4.1 joint models). `q` points at the joint's first
/// configuration coordinate; s and c are the sine and cosine of its angle (a revolute or planar
/// joint), unused by the other types.
template <class S>
SD_INLINE void joint_up_transform(const Model<S>& model, int i, const S* q, const S& s, const S& c,
                                  PluckerTransform<S>& X) {
  visit_joint(model.joints[i], [&](const auto& joint) SD_INLINE_LAMBDA {
    X = joint.transform(model.X_tree[i], q, s, c, JointLabel{model.joint_names[i], model.joints[i].idx_q});
  });
}

/// As above, computing the angle's sine and cosine from q.
template <class S>
SD_INLINE void joint_up_transform(const Model<S>& model, int i, const S* q, PluckerTransform<S>& X) {
  const int angle = angle_coordinate(model.joints[i]);
  S s(0), c(1);
  if (angle >= 0) detail::joint_sin_cos(q[angle], s, c);
  joint_up_transform(model, i, q, s, c, X);
}

/// Whether a 1-DoF joint's axis is its rotation (revolute: S = (a ; 0)) or its translation
/// (prismatic: S = (0 ; a)). The 1-DoF shortcuts below are taken only where j.nv == 1.
template <class S>
SD_INLINE bool one_dof_rotates(const Joint<S>& j) {
  return j.type == JointType::Revolute;
}

/// S q̇ for a 1-DoF joint with velocity (or acceleration) v.
template <class S>
SD_INLINE MotionVector<S> one_dof_motion(const Joint<S>& j, const S& v) {
  if (one_dof_rotates(j)) return {detail::scaled_axis(j, v), Vector3<S>::Zero()};
  return {Vector3<S>::Zero(), detail::scaled_axis(j, v)};
}

// ---- any joint, through its type (model/joints/); s and c are its angle's sine and cosine ----

/// S q̇; `qd` points at the joint's first velocity coordinate.
template <class S>
SD_INLINE MotionVector<S> joint_motion(const Joint<S>& j, const S& s, const S& c, const S* qd) {
  return visit_joint(j, [&](const auto& joint) SD_INLINE_LAMBDA { return joint.motion(qd, s, c); });
}

/// c_J = S̊ q̇, the joint's own velocity-product acceleration (zero where S is constant).
template <class S>
SD_INLINE MotionVector<S> joint_bias(const Joint<S>& j, const S& s, const S& c, const S* qd) {
  return visit_joint(j, [&](const auto& joint) SD_INLINE_LAMBDA {
    return joint.velocity_product(MotionVector<S>::Zero(), qd, s, c);  // c_J + 0 × S q̇
  });
}

/// U = I S (6 × nv, in U's first nv columns) for a 6 × 6 inertia I.
template <class S>
SD_INLINE void inertia_times_subspace(const Joint<S>& j, const S& s, const S& c, const Matrix6<S>& I, Matrix6<S>& U) {
  visit_joint(j, [&](const auto& joint) SD_INLINE_LAMBDA {
    U.template leftCols<std::decay_t<decltype(joint)>::nv>() = joint.inertia_times(I, s, c);
  });
}

/// Column k of the motion subspace S.
template <class S>
inline MotionVector<S> joint_subspace_column(const Joint<S>& j, const S& s, const S& c, int k) {
  return visit_joint(j, [&](const auto& joint) SD_INLINE_LAMBDA { return joint.column(k, s, c); });
}

/// Sᵀ (n ; f) written to out[0 .. nv), column by column; n, f and out are 3-arrays of any scalar
/// (a wider one too).
template <class S, class T>
SD_INLINE void joint_project(const Joint<S>& j, const S& s, const S& c, const T* n, const T* f, T* out) {
  for (int k = 0; k < j.nv; ++k) {
    const MotionVector<S> column = joint_subspace_column(j, s, c, k);
    T sum = T(0);
    for (int m = 0; m < 3; ++m) sum = sum + n[m] * column.angular[m] + f[m] * column.linear[m];
    out[k] = sum;
  }
}

/// Sᵀ f written to out[0 .. nv).
template <class S>
SD_INLINE void joint_project(const Joint<S>& j, const S& s, const S& c, const ForceVector<S>& f, S* out) {
  visit_joint(j, [&](const auto& joint) SD_INLINE_LAMBDA {
    const auto projected = joint.project(f, s, c);
    for (int k = 0; k < projected.size(); ++k) out[k] = projected[k];
  });
}

// ---- whole-vector access: handles coupled mimic joints ---------------------------------------

/// Body i's joint angle (revolute θ, planar ψ): its coordinate, or k q_master + offset for a
/// coupled joint.
template <class S>
SD_INLINE S joint_angle(const Joint<S>& j, const S* q) {
  if (j.coupled) return j.mimic.multiplier * q[j.idx_q] + j.mimic.offset;
  return q[j.idx_q + angle_coordinate(j)];
}

/// sin and cos of every joint angle into data.joint_sin and data.joint_cos, as many angles at
/// once as a vector register holds (lane_trigonometry.hpp): no call per joint in the passes.
/// Scalars without vector lanes take one angle at a time.
template <class S>
SD_INLINE void joint_sines_and_cosines(const Model<S>& model, Data<S>& data, const S* q) {
  constexpr int L = std::is_same<S, double>::value ? kRegisterLanes<S> : 1;  // vector sin/cos: double only
  const int count = static_cast<int>(data.angle_bodies.size());
  for (int start = 0; start < count; start += L) {
    const int lanes = std::min(L, count - start);
    const int* bodies = data.angle_bodies.data() + start;
    Lanes<S, L> angle = Lanes<S, L>::Zero(), sine, cosine;
    for (int l = 0; l < lanes; ++l) angle.set(l, joint_angle(model.joints[bodies[l]], q));
    sincos_lanes(angle, sine, cosine);
    for (int l = 0; l < lanes; ++l) {
      data.joint_sin[bodies[l]] = sine[l];
      data.joint_cos[bodies[l]] = cosine[l];
    }
  }
}

/// ^iX_λ(i) from the whole configuration vector q; the joint angle's sin and cos are read from
/// data (joint_sines_and_cosines, called before).
template <class S>
SD_INLINE void body_up_transform(const Model<S>& model, const Data<S>& data, int i, const S* q, PluckerTransform<S>& X) {
  const Joint<S>& j = model.joints[i];
  if (j.coupled) {  // q = k q_master + offset
    const S coupled_q = j.mimic.multiplier * q[j.idx_q] + j.mimic.offset;
    joint_up_transform(model, i, &coupled_q, data.joint_sin[i], data.joint_cos[i], X);
  } else {
    joint_up_transform(model, i, q + j.idx_q, data.joint_sin[i], data.joint_cos[i], X);
  }
}

/// What is known of ^iX_λ(i)'s rotation beyond its coefficients (Data::up_rotation_axis); the
/// joint angle's sin and cos as body_up_transform reads them.
template <class S>
SD_INLINE RotationAboutAxis<S> body_up_rotation(const Data<S>& data, int i) {
  return {data.up_rotation_axis[i], data.joint_sin[i], data.joint_cos[i]};
}

/// S q̇ (or S q̈) of body i's joint from the whole velocity (acceleration) vector.
template <class S>
SD_INLINE MotionVector<S> body_joint_motion(const Model<S>& model, const Data<S>& data, int i, const S* qd) {
  const Joint<S>& j = model.joints[i];
  if (j.coupled) return one_dof_motion(j, S(j.mimic.multiplier * qd[j.idx_v]));  // q̇ = k q̇_master
  return joint_motion(j, data.joint_sin[i], data.joint_cos[i], qd + j.idx_v);
}

/// c_J of body i's joint from the whole velocity vector (zero for a coupled, 1-DoF joint).
template <class S>
SD_INLINE MotionVector<S> body_joint_bias(const Model<S>& model, const Data<S>& data, int i, const S* qd) {
  const Joint<S>& j = model.joints[i];
  if (j.coupled) return MotionVector<S>::Zero();
  return joint_bias(j, data.joint_sin[i], data.joint_cos[i], qd + j.idx_v);
}

/// Column k of body i's S.
template <class S>
SD_INLINE MotionVector<S> body_subspace_column(const Model<S>& model, const Data<S>& data, int i, int k) {
  return joint_subspace_column(model.joints[i], data.joint_sin[i], data.joint_cos[i], k);
}

/// Sᵀ f of body i's joint written to out[0 .. nv).
template <class S>
SD_INLINE void body_joint_project(const Model<S>& model, const Data<S>& data, int i, const ForceVector<S>& f, S* out) {
  joint_project(model.joints[i], data.joint_sin[i], data.joint_cos[i], f, out);
}

/// τ ← Sᵀ f for body i's joint coordinates; with `accumulate` (models with coupled joints, τ
/// zeroed first) τ += k Sᵀ f instead, k the coupling multiplier (1 for a joint of its own): by
/// virtual power a coupled joint's force acts on its master's coordinate scaled by k.
template <class S>
SD_INLINE void store_joint_force(const Model<S>& model, const Data<S>& data, int i, const ForceVector<S>& f, S* tau,
                                 bool accumulate) {
  const Joint<S>& j = model.joints[i];
  if (!accumulate) {
    body_joint_project(model, data, i, f, tau + j.idx_v);
    return;
  }
  S projected[6];
  body_joint_project(model, data, i, f, projected);
  const S k = j.coupled ? j.mimic.multiplier : S(1);
  for (int l = 0; l < j.nv; ++l) tau[j.idx_v + l] += k * projected[l];
}

/// The coupling multiplier of a joint's coordinates (1 for a joint of its own).
template <class S>
SD_INLINE S coupling_multiplier(const Joint<S>& j) {
  return j.coupled ? j.mimic.multiplier : S(1);
}

}  // namespace spatial_dynamics
