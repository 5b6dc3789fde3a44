// Per-joint arithmetic: the joint transform X_J(q) composed with X_tree, the motion subspace S
// and its transpose. Axis-aligned revolute joints rotate two rows of E instead of multiplying
// 3×3 matrices; axis-aligned projections read one component instead of a dot product.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/lane_trigonometry.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {
namespace detail {

/// a · x, reading one component for an axis-aligned joint.
template <class S>
SD_INLINE S along_axis(const Joint<S>& j, const Vector3<S>& x) {
  switch (j.axis_kind) {
    case AxisKind::X: return x.x();
    case AxisKind::Y: return x.y();
    case AxisKind::Z: return x.z();
    default: return j.axis.dot(x);
  }
}

/// k · a.
template <class S>
SD_INLINE Vector3<S> scaled_axis(const Joint<S>& j, const S& k) {
  switch (j.axis_kind) {
    case AxisKind::X: return Vector3<S>(k, S(0), S(0));
    case AxisKind::Y: return Vector3<S>(S(0), k, S(0));
    case AxisKind::Z: return Vector3<S>(S(0), S(0), k);
    default: return Vector3<S>(j.axis.x() * k, j.axis.y() * k, j.axis.z() * k);
  }
}

/// x × (k a): two products for a coordinate axis (x × e_x = (0, x_z, −x_y), cyclic).
template <class S>
SD_INLINE Vector3<S> cross_axis(const Joint<S>& j, const Vector3<S>& x, const S& k) {
  switch (j.axis_kind) {
    case AxisKind::X: return Vector3<S>(S(0), x.z() * k, -(x.y() * k));
    case AxisKind::Y: return Vector3<S>(-(x.z() * k), S(0), x.x() * k);
    case AxisKind::Z: return Vector3<S>(x.y() * k, -(x.x() * k), S(0));
    default: return cross_3d(x, Vector3<S>(j.axis.x() * k, j.axis.y() * k, j.axis.z() * k));
  }
}

/// x += k a.
template <class S>
SD_INLINE void add_along_axis(const Joint<S>& j, Vector3<S>& x, const S& k) {
  switch (j.axis_kind) {
    case AxisKind::X: x.x() += k; return;
    case AxisKind::Y: x.y() += k; return;
    case AxisKind::Z: x.z() += k; return;
    default: x += j.axis * k; return;
  }
}

/// sin θ and cos θ of one angle: the batched routine on one lane (lane_trigonometry.hpp, within
/// 1 ulp for double and |θ| ≤ 1e5); other scalars and larger angles take std::sin and std::cos.
template <class S>
SD_INLINE void joint_sin_cos(const S& angle, S& s, S& c) {
  Lanes<S, 1> sine, cosine;
  sincos_lanes(Lanes<S, 1>::Constant(angle), sine, cosine);
  s = sine[0];
  c = cosine[0];
}

/// Rows (m, n) of E become (c·row_m + s·row_n, −s·row_m + c·row_n): E ← rot_axis(θ) E
/// for a coordinate rotation about the remaining axis.
template <class S>
SD_INLINE void rotate_rows(Matrix3<S>& E, int m, int n, const S& c, const S& s) {
  for (int k = 0; k < 3; ++k) {
    const S em = E(m, k), en = E(n, k);
    E(m, k) = c * em + s * en;
    E(n, k) = c * en - s * em;
  }
}

/// E ← rot(a, θ)ᵀ E column by column, from c = cos θ and s = sin θ (RBDA eq. 2.24, transposed):
/// each column e becomes c e − s a×e + (1 − c)(a·e) a, without forming the rotation matrix.
template <class S>
SD_INLINE void rotate_about_axis(Matrix3<S>& E, const Vector3<S>& a, const S& c, const S& s) {
  for (int k = 0; k < 3; ++k) {
    const Vector3<S> e = E.col(k);
    E.col(k) = c * e - s * cross_3d(a, e) + ((S(1) - c) * a.dot(e)) * a;
  }
}

}  // namespace detail

/// ^iX_λ(i) of the free joint: q = (x y z qx qy qz qw), the base pose in its parent; X_J = (Rᵀ, p).
template <class S>
void free_joint_up_transform(const Model<S>& model, int i, const S* q, PluckerTransform<S>& X) {
  const Joint<S>& j = model.joints[i];
  const PluckerTransform<S>& Xt = model.X_tree[i];
  const Eigen::Quaternion<S> quat(q[6], q[3], q[4], q[5]);
  using std::abs;
  if (!(abs(quat.squaredNorm() - S(1)) <= S(1e-6)))
    throw std::invalid_argument("joint '" + model.joint_names[i] + "': the quaternion (q[" + std::to_string(j.idx_q + 3) +
                                ".." + std::to_string(j.idx_q + 6) + "]) is not of unit norm");
  const Vector3<S> p(q[0], q[1], q[2]);
  X.E = quat.toRotationMatrix().transpose() * Xt.E;
  X.r = Xt.r + Xt.E.transpose() * p;
}

/// ^iX_λ(i) = X_J(θ) X_tree(i) of a revolute joint from s = sin θ and c = cos θ (RBDA Table 4.1).
template <class S>
SD_INLINE void revolute_up_transform(const Joint<S>& j, const PluckerTransform<S>& Xt, const S& s, const S& c,
                                     PluckerTransform<S>& X) {
  X.r = Xt.r;
  X.E = Xt.E;
  switch (j.axis_kind) {
    case AxisKind::X: detail::rotate_rows(X.E, 1, 2, c, s); break;
    case AxisKind::Y: detail::rotate_rows(X.E, 2, 0, c, s); break;
    case AxisKind::Z: detail::rotate_rows(X.E, 0, 1, c, s); break;
    default: detail::rotate_about_axis(X.E, j.axis, c, s); break;
  }
}

/// ^iX_λ(i) = X_J(q_i) X_tree(i)   (RBDA Table 4.1 joint models; eq. 4.x composition).
/// `q` points at the joint's first configuration coordinate.
template <class S>
SD_INLINE void joint_up_transform(const Model<S>& model, int i, const S* q, PluckerTransform<S>& X) {
  const Joint<S>& j = model.joints[i];
  const PluckerTransform<S>& Xt = model.X_tree[i];
  switch (j.type) {
    case JointType::Revolute: {
      S s, c;
      detail::joint_sin_cos(q[0], s, c);
      revolute_up_transform(j, Xt, s, c, X);
      return;
    }
    case JointType::Prismatic:
      X.E = Xt.E;
      X.r = Xt.r + Xt.E.transpose() * detail::scaled_axis(j, q[0]);
      return;
    case JointType::Free: free_joint_up_transform(model, i, q, X); return;
  }
}

/// S q̇ for a 1-DoF joint with velocity (or acceleration) v.
template <class S>
SD_INLINE MotionVector<S> one_dof_motion(const Joint<S>& j, const S& v) {
  if (j.type == JointType::Revolute) return {detail::scaled_axis(j, v), Vector3<S>::Zero()};
  return {Vector3<S>::Zero(), detail::scaled_axis(j, v)};
}

/// m += S x for a 1-DoF joint.
template <class S>
SD_INLINE void add_one_dof_motion(const Joint<S>& j, const S& x, MotionVector<S>& m) {
  detail::add_along_axis(j, j.type == JointType::Revolute ? m.angular : m.linear, x);
}

/// v × S q̇ for a 1-DoF joint (eq. 17 with S q̇ = (q̇ a; 0) or (0; q̇ a)): (ω × q̇a ; v_O × q̇a) for a
/// revolute joint, (0 ; ω × q̇a) for a prismatic one.
template <class S>
SD_INLINE MotionVector<S> cross_one_dof_motion(const MotionVector<S>& v, const Joint<S>& j, const S& qd) {
  if (j.type == JointType::Revolute) return {detail::cross_axis(j, v.angular, qd), detail::cross_axis(j, v.linear, qd)};
  return {Vector3<S>::Zero(), detail::cross_axis(j, v.angular, qd)};
}

/// I S for a 1-DoF joint from the ten parameters (eq. 25 with v = S): (Ī_O a ; −h × a) for a
/// revolute joint, (h × a ; m a) for a prismatic one; a coordinate axis reads a column of Ī_O.
template <class S>
SD_INLINE ForceVector<S> inertia_times_one_dof_subspace(const Joint<S>& j, const RigidInertia<S>& I) {
  if (j.type == JointType::Prismatic) return {detail::cross_axis(j, I.first_moment, S(1)), detail::scaled_axis(j, I.mass)};
  switch (j.axis_kind) {
    case AxisKind::X: return {I.rotational_inertia.col(0), detail::cross_axis(j, I.first_moment, S(-1))};
    case AxisKind::Y: return {I.rotational_inertia.col(1), detail::cross_axis(j, I.first_moment, S(-1))};
    case AxisKind::Z: return {I.rotational_inertia.col(2), detail::cross_axis(j, I.first_moment, S(-1))};
    default: return {I.rotational_inertia * j.axis, detail::cross_axis(j, I.first_moment, S(-1))};
  }
}

/// v ×* I v for v = S q̇ of a 1-DoF joint (eq. 29 with v = S q̇): q̇² (a × F_n ; a × F_f) for a
/// revolute joint, F = I S; 0 for a prismatic one (v = (0 ; q̇ a), I v = (h × q̇ a ; m q̇ a), and
/// q̇ a × m q̇ a = 0). The bias force of a body whose parent is the fixed base, without the
/// 6-vector product I v.
template <class S>
SD_INLINE ForceVector<S> one_dof_bias_force(const Joint<S>& j, const RigidInertia<S>& I, const S& qd) {
  if (j.type != JointType::Revolute) return ForceVector<S>::Zero();
  const ForceVector<S> F = inertia_times_one_dof_subspace(j, I);
  const S k = -(qd * qd);  // a × x = x × (−a), and cross_axis(j, x, k) = x × (k a)
  return {detail::cross_axis(j, F.angular, k), detail::cross_axis(j, F.linear, k)};
}

/// S q̇ for one joint; `qd` points at the joint's first velocity coordinate.
template <class S>
SD_INLINE MotionVector<S> joint_motion(const Joint<S>& j, const S* qd) {
  if (j.type == JointType::Free) return {Vector3<S>(qd[0], qd[1], qd[2]), Vector3<S>(qd[3], qd[4], qd[5])};
  return one_dof_motion(j, qd[0]);
}

/// Column k of the motion subspace S.
template <class S>
inline MotionVector<S> joint_subspace_column(const Joint<S>& j, int k) {
  if (j.type == JointType::Free) {
    Vector6<S> e = Vector6<S>::Zero();
    e[k] = S(1);
    return MotionVector<S>(e);
  }
  return one_dof_motion(j, S(1));
}

/// Sᵀ f written to out[0 .. nv).
template <class S>
SD_INLINE void joint_project(const Joint<S>& j, const ForceVector<S>& f, S* out) {
  switch (j.type) {
    case JointType::Revolute: out[0] = detail::along_axis(j, f.angular); return;
    case JointType::Prismatic: out[0] = detail::along_axis(j, f.linear); return;
    default:
      for (int k = 0; k < 3; ++k) {
        out[k] = f.angular[k];
        out[k + 3] = f.linear[k];
      }
      return;
  }
}

/// Sᵀ x for a 1-DoF joint and a force-like 6-vector x (angular part first).
template <class S>
SD_INLINE S joint_project(const Joint<S>& j, const Vector6<S>& x) {
  return j.type == JointType::Revolute ? detail::along_axis<S>(j, x.template head<3>())
                                       : detail::along_axis<S>(j, x.template tail<3>());
}

/// Iᴬ S for a 1-DoF joint: one column of Iᴬ for an axis-aligned joint.
template <class S>
inline Vector6<S> inertia_times_subspace(const Joint<S>& j, const Matrix6<S>& I) {
  const int offset = j.type == JointType::Revolute ? 0 : 3;
  switch (j.axis_kind) {
    case AxisKind::X: return I.col(offset);
    case AxisKind::Y: return I.col(offset + 1);
    case AxisKind::Z: return I.col(offset + 2);
    default: return I.template middleCols<3>(offset) * j.axis;
  }
}

// ---- whole-vector access: handles coupled mimic joints ---------------------------------------

/// Body i's first joint coordinate: q_i, or k q_master + offset for a coupled joint.
template <class S>
SD_INLINE S joint_coordinate(const Joint<S>& j, const S* q) {
  return j.coupled ? j.mimic.multiplier * q[j.idx_q] + j.mimic.offset : q[j.idx_q];
}

/// sin and cos of every revolute joint's angle into data.joint_sin and data.joint_cos, as many
/// angles at once as a vector register holds (lane_trigonometry.hpp): no call per joint in the
/// passes. Scalars without vector lanes take one angle at a time.
template <class S>
SD_INLINE void joint_sines_and_cosines(const Model<S>& model, Data<S>& data, const S* q) {
  constexpr int L = std::is_same<S, double>::value ? kRegisterLanes<S> : 1;  // vector sin/cos: double only
  const int count = static_cast<int>(data.revolute_bodies.size());
  for (int start = 0; start < count; start += L) {
    const int lanes = std::min(L, count - start);
    const int* bodies = data.revolute_bodies.data() + start;
    Lanes<S, L> angle = Lanes<S, L>::Zero(), sine, cosine;
    for (int l = 0; l < lanes; ++l) angle.set(l, joint_coordinate(model.joints[bodies[l]], q));
    sincos_lanes(angle, sine, cosine);
    for (int l = 0; l < lanes; ++l) {
      data.joint_sin[bodies[l]] = sine[l];
      data.joint_cos[bodies[l]] = cosine[l];
    }
  }
}

/// ^iX_λ(i) from the whole configuration vector q; a revolute joint's sin and cos are read from
/// data (joint_sines_and_cosines, called before).
template <class S>
SD_INLINE void body_up_transform(const Model<S>& model, const Data<S>& data, int i, const S* q, PluckerTransform<S>& X) {
  const Joint<S>& j = model.joints[i];
  if (j.type == JointType::Revolute) {
    revolute_up_transform(j, model.X_tree[i], data.joint_sin[i], data.joint_cos[i], X);
  } else {
    const S qi = joint_coordinate(j, q);
    joint_up_transform(model, i, j.coupled ? &qi : q + j.idx_q, X);
  }
}

/// S q̇ (or S q̈) of body i's joint from the whole velocity (acceleration) vector.
template <class S>
SD_INLINE MotionVector<S> body_joint_motion(const Joint<S>& j, const S* qd) {
  if (j.coupled) return one_dof_motion(j, S(j.mimic.multiplier * qd[j.idx_v]));  // q̇ = k q̇_master
  return joint_motion(j, qd + j.idx_v);
}

/// τ ← Sᵀ f for the joint's coordinates; with `accumulate` (models with coupled joints, τ zeroed
/// first) τ += k Sᵀ f instead, k the coupling multiplier (1 for a joint of its own): by virtual
/// power a coupled joint's force acts on its master's coordinate scaled by k.
template <class S>
SD_INLINE void store_joint_force(const Joint<S>& j, const ForceVector<S>& f, S* tau, bool accumulate) {
  if (!accumulate) {
    joint_project(j, f, tau + j.idx_v);
    return;
  }
  S projected[6];
  joint_project(j, f, projected);
  const S k = j.coupled ? j.mimic.multiplier : S(1);
  for (int l = 0; l < j.nv; ++l) tau[j.idx_v + l] += k * projected[l];
}

/// The coupling multiplier of a joint's coordinates (1 for a joint of its own).
template <class S>
SD_INLINE S coupling_multiplier(const Joint<S>& j) {
  return j.coupled ? j.mimic.multiplier : S(1);
}

}  // namespace spatial_dynamics
