// The joint types (one file each in this directory) and the one dispatch that reaches them: a
// std::variant, visited by the algorithms with a generic lambda, so that every algorithm step is
// compiled once per joint type and no algorithm tests a joint's kind, axis or number of
// coordinates. A joint type added to the list below is served by every algorithm; one that does
// not provide what they ask of a joint (transform, motion, velocity_product, project,
// column, column_rate, names) does not compile.
#pragma once

#include <variant>

#include "spatial_dynamics/model/joints/free.hpp"
#include "spatial_dynamics/model/joints/helical.hpp"
#include "spatial_dynamics/model/joints/planar.hpp"
#include "spatial_dynamics/model/joints/prismatic.hpp"
#include "spatial_dynamics/model/joints/prismatic_axis.hpp"
#include "spatial_dynamics/model/joints/revolute.hpp"
#include "spatial_dynamics/model/joints/revolute_axis.hpp"

namespace spatial_dynamics {

/// A joint's kind as a URDF names it (with its axis it selects the joint type below).
enum class JointType {
  Revolute,   // 1 DoF, rotation about `axis` (URDF revolute and continuous)
  Prismatic,  // 1 DoF, translation along `axis`
  Free,       // 6 DoF: the floating root or a URDF floating joint, q = (x y z qx qy qz qw), q̇ = (ω; v) in the body frame
  Planar,     // 3 DoF, q = (x, y, yaw): translation along plane_x and plane_y, rotation about `axis` (the normal)
  Helical,    // 1 DoF, a screw: rotation θ about `axis` and translation pitch · θ along it
};

template <class S>
using JointModel = std::variant<RevoluteAxisJoint<S, 0>, RevoluteAxisJoint<S, 1>, RevoluteAxisJoint<S, 2>,
                                RevoluteJoint<S>, PrismaticAxisJoint<S, 0>, PrismaticAxisJoint<S, 1>,
                                PrismaticAxisJoint<S, 2>, PrismaticJoint<S>, FreeJoint<S>, PlanarJoint<S>,
                                HelicalJoint<S>>;

/// The joint type of a kind, unit axis (the plane's normal for a planar joint), for a planar
/// joint its in-plane axes and for a screw joint its pitch; an axis along +x, +y or +z takes the
/// axis-aligned types.
template <class S>
JointModel<S> make_joint_model(JointType type, const Vector3<S>& axis, const Vector3<S>& plane_x,
                               const Vector3<S>& plane_y, const S& pitch) {
  const int k = axis == Vector3<S>::UnitX() ? 0 : axis == Vector3<S>::UnitY() ? 1 : axis == Vector3<S>::UnitZ() ? 2 : -1;
  switch (type) {
    case JointType::Revolute:
      if (k == 0) return RevoluteAxisJoint<S, 0>();
      if (k == 1) return RevoluteAxisJoint<S, 1>();
      if (k == 2) return RevoluteAxisJoint<S, 2>();
      return RevoluteJoint<S>{Vec3<S>(axis)};
    case JointType::Prismatic:
      if (k == 0) return PrismaticAxisJoint<S, 0>();
      if (k == 1) return PrismaticAxisJoint<S, 1>();
      if (k == 2) return PrismaticAxisJoint<S, 2>();
      return PrismaticJoint<S>{Vec3<S>(axis)};
    case JointType::Free: return FreeJoint<S>();
    case JointType::Planar: return PlanarJoint<S>{Vec3<S>(axis), Vec3<S>(plane_x), Vec3<S>(plane_y)};
    case JointType::Helical: return HelicalJoint<S>{Vec3<S>(axis), pitch};
  }
  __builtin_unreachable();  // type holds one of the enumerators above
}

/// visit(joint) with the joint type held in `model`: a test of the index per alternative, inlined
/// into the caller (std::visit's table of function pointers keeps each step out of line).
template <class S, class Visitor, std::size_t I = 0>
SD_INLINE decltype(auto) visit_joint_model(const JointModel<S>& model, Visitor&& visit) {
  if constexpr (I + 1 == std::variant_size_v<JointModel<S>>) {
    return visit(*std::get_if<I>(&model));
  } else {
    if (model.index() == I) return visit(*std::get_if<I>(&model));
    return visit_joint_model<S, Visitor, I + 1>(model, std::forward<Visitor>(visit));
  }
}

}  // namespace spatial_dynamics
