// What the algorithms ask of body i's joint, through the one dispatch (joint_dispatch.hpp) to the
// joint types of this directory: ^iX_λ = X_J(q) X_tree, S q̇, c_J + v × S q̇, Sᵀ f and the
// columns of S (RBDA Table 4.1), read from the model's whole vectors q, q̇, q̈ and τ, with the
// coupled mimic joints (q = k q_master + offset) and the joints' angles handled here.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "spatial_dynamics/model/data.hpp"
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

// ---- any joint, through its type (model/joints/); s and c are its angle's sine and cosine ----

/// Column k of the motion subspace S.
template <class S>
inline MotionVector<S> joint_subspace_column(const Joint<S>& j, const S& s, const S& c, int k) {
  return visit_joint(j, [&](const auto& joint) SD_INLINE_LAMBDA { return joint.column(k, s, c); });
}

/// Sᵀ (n ; f) written to out[0 .. nv), column by column, for n and f in any scalar (a wider one
/// too).
template <class S, class T>
SD_INLINE void joint_project(const Joint<S>& j, const S& s, const S& c, const Vec3<T>& n, const Vec3<T>& f, T* out) {
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

/// Body i's joint at a state, for one visit of its type per body (visit): the joint's coordinates
/// in q, q̇ and q̈ (pointers into them, or for a coupled joint k q_master + offset, k q̇_master and
/// k q̈_master held here; a vector not given is not read), its angle's sine and cosine (joint_sines_and_cosines, called before),
/// its tree transform and its label for error messages.
template <class S>
struct BodyJoint {
  const Joint<S>& joint;
  const PluckerTransform<S>& X_tree;
  JointLabel label;
  S s, c;
  const S *q, *qd, *qdd;
  S own_q[7], own_qd[6], own_qdd[6];  // a coupled joint's (sized for any joint type's reads)

  SD_INLINE BodyJoint(const Model<S>& model, const Data<S>& data, int i, const S* q_all, const S* qd_all = nullptr,
                      const S* qdd_all = nullptr)
      : joint(model.joints[i]),
        X_tree(model.X_tree[i]),
        label{model.joint_names[i], model.joints[i].idx_q},
        s(data.joint_sin[i]),
        c(data.joint_cos[i]) {
    if (!joint.coupled) {
      q = q_all ? q_all + joint.idx_q : nullptr;
      qd = qd_all ? qd_all + joint.idx_v : nullptr;
      qdd = qdd_all ? qdd_all + joint.idx_v : nullptr;
      return;
    }
    const S k = joint.mimic.multiplier;
    own_q[0] = q_all ? k * q_all[joint.idx_q] + joint.mimic.offset : S(0);
    own_qd[0] = qd_all ? k * qd_all[joint.idx_v] : S(0);
    own_qdd[0] = qdd_all ? k * qdd_all[joint.idx_v] : S(0);
    q = own_q;
    qd = own_qd;
    qdd = own_qdd;
  }

  /// visit(joint type) (joint_dispatch.hpp).
  template <class Visitor>
  SD_INLINE decltype(auto) visit(Visitor&& visitor) const {
    return visit_joint(joint, std::forward<Visitor>(visitor));
  }
};

/// ^iX_λ(i) from the whole configuration vector q; the joint angle's sin and cos are read from
/// data (joint_sines_and_cosines, called before).
template <class S>
SD_INLINE void body_up_transform(const Model<S>& model, const Data<S>& data, int i, const S* q, PluckerTransform<S>& X) {
  const BodyJoint<S> J(model, data, i, q);
  J.visit([&](const auto& joint) SD_INLINE_LAMBDA { X = joint.transform(J.X_tree, J.q, J.s, J.c, J.label); });
}

/// S q̇ (or S q̈) of body i's joint from the whole velocity (acceleration) vector.
template <class S>
SD_INLINE MotionVector<S> body_joint_motion(const Model<S>& model, const Data<S>& data, int i, const S* qd) {
  const BodyJoint<S> J(model, data, i, nullptr, qd);
  return J.visit([&](const auto& joint) SD_INLINE_LAMBDA { return joint.motion(J.qd, J.s, J.c); });
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
SD_INLINE void write_joint_torque(const Model<S>& model, const Data<S>& data, int i, const ForceVector<S>& f, S* tau,
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
