// One joint per body: its kind, axis (in the joint frame, which is the child body's frame),
// where its coordinates sit in q and in q̇, and its limits.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <variant>

#include "spatial_dynamics/model/joints/joint_dispatch.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {


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
  S pitch{0};  // a screw joint's translation along `axis` per radian of rotation (0 for the others)
  int idx_q = 0;                          // first coordinate in q
  int idx_v = 0;                          // first coordinate in q̇, q̈, τ
  int nq = 1;
  int nv = 1;
  JointLimits<S> limits;
  MimicRelation<S> mimic;
  /// Coupled mimic joint: it has no coordinates of its own; idx_q/idx_v point at its master's and
  /// q = multiplier · q_master + offset, q̇ = multiplier · q̇_master (see couple_mimic_joints).
  bool coupled = false;
  /// The joint type (model/joints/) of `type` and the axes above: set by update_model(), which
  /// Model::finalize() calls for every joint.
  JointModel<S> model;

  void update_model() { model = make_joint_model(type, axis, plane_x, plane_y, pitch); }

  template <class T>
  Joint<T> cast() const {
    Joint<T> j;
    j.type = type;
    j.axis_kind = axis_kind;
    j.axis = axis.template cast<T>();
    j.plane_x = plane_x.template cast<T>();
    j.plane_y = plane_y.template cast<T>();
    j.pitch = T(pitch);
    j.idx_q = idx_q;
    j.idx_v = idx_v;
    j.nq = nq;
    j.nv = nv;
    j.limits = limits.template cast<T>();
    j.mimic = mimic.template cast<T>();
    j.coupled = coupled;
    j.update_model();
    return j;
  }
};

/// visit(joint) with the joint type of j (model/joints/joint_dispatch.hpp).
template <class S, class Visitor>
SD_INLINE decltype(auto) visit_joint(const Joint<S>& j, Visitor&& visit) {
  return visit_joint_model<S>(j.model, std::forward<Visitor>(visit));
}

/// Where the joint's angle sits among its coordinates (revolute 0, planar 2), −1 for none.
template <class S>
SD_INLINE int angle_coordinate(const Joint<S>& j) {
  return visit_joint(j, [](const auto& joint) SD_INLINE_LAMBDA { return joint.angle_coordinate; });
}

/// Classifies a unit axis: exactly +x, +y or +z take the cheap paths.
template <class S>
AxisKind classify_axis(const Vector3<S>& a) {
  if (a == Vector3<S>::UnitX()) return AxisKind::X;
  if (a == Vector3<S>::UnitY()) return AxisKind::Y;
  if (a == Vector3<S>::UnitZ()) return AxisKind::Z;
  return AxisKind::General;
}

}  // namespace spatial_dynamics
