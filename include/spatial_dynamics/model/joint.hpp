// One joint per body: its type, axis (in the joint frame, which is the child body's frame),
// where its coordinates sit in q and in q̇, and its limits.
#pragma once

#include <limits>
#include <string>

#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {

enum class JointType {
  Revolute,   // 1 DoF, rotation about `axis` (URDF revolute and continuous)
  Prismatic,  // 1 DoF, translation along `axis`
  Free,       // 6 DoF: the floating root or a URDF floating joint, q = (x y z qx qy qz qw), q̇ = (ω; v) in the body frame
  Planar,     // 3 DoF, q = (x, y, yaw): translation along plane_x and plane_y, rotation about `axis` (the normal)
};
// Each type's arithmetic is its own file, model/joints/<type>.hpp, reached through visit_joint.

/// Axis-aligned joints take cheaper code paths than a general unit axis.
enum class AxisKind { X, Y, Z, General };

template <class S>
struct JointLimits {
  S position_lower = -std::numeric_limits<S>::infinity();
  S position_upper = std::numeric_limits<S>::infinity();
  S velocity = std::numeric_limits<S>::infinity();
  S effort = std::numeric_limits<S>::infinity();

  template <class T>
  JointLimits<T> cast() const {
    return {T(position_lower), T(position_upper), T(velocity), T(effort)};
  }
};

/// Mimic relation recorded from URDF: q_this = multiplier · q_master + offset. The joint stays an
/// independent coordinate of the model (what KDL and RBDL do); this is information for callers.
template <class S>
struct MimicRelation {
  int master_body = -1;  // body whose joint is mimicked; -1 when the joint mimics nothing
  S multiplier{1};
  S offset{0};

  bool active() const { return master_body >= 0; }
  template <class T>
  MimicRelation<T> cast() const {
    return {master_body, T(multiplier), T(offset)};
  }
};

template <class S>
struct Joint {
  JointType type = JointType::Revolute;
  AxisKind axis_kind = AxisKind::Z;
  Vector3<S> axis = Vector3<S>::UnitZ();  // unit axis in the joint (= child body) frame
  // A planar joint's in-plane axes e₁ and e₂ = axis × e₁ (joint frame); zero for other types.
  Vector3<S> plane_x = Vector3<S>::Zero();
  Vector3<S> plane_y = Vector3<S>::Zero();
  int idx_q = 0;                          // first coordinate in q
  int idx_v = 0;                          // first coordinate in q̇, q̈, τ
  int nq = 1;
  int nv = 1;
  JointLimits<S> limits;
  MimicRelation<S> mimic;
  /// Coupled mimic joint: it has no coordinates of its own; idx_q/idx_v point at its master's and
  /// q = multiplier · q_master + offset, q̇ = multiplier · q̇_master (see couple_mimic_joints).
  bool coupled = false;

  template <class T>
  Joint<T> cast() const {
    Joint<T> j;
    j.type = type;
    j.axis_kind = axis_kind;
    j.axis = axis.template cast<T>();
    j.plane_x = plane_x.template cast<T>();
    j.plane_y = plane_y.template cast<T>();
    j.idx_q = idx_q;
    j.idx_v = idx_v;
    j.nq = nq;
    j.nv = nv;
    j.limits = limits.template cast<T>();
    j.mimic = mimic.template cast<T>();
    j.coupled = coupled;
    return j;
  }
};

/// Classifies a unit axis: exactly +x, +y or +z take the cheap paths.
template <class S>
AxisKind classify_axis(const Vector3<S>& a) {
  if (a == Vector3<S>::UnitX()) return AxisKind::X;
  if (a == Vector3<S>::UnitY()) return AxisKind::Y;
  if (a == Vector3<S>::UnitZ()) return AxisKind::Z;
  return AxisKind::General;
}

}  // namespace spatial_dynamics
