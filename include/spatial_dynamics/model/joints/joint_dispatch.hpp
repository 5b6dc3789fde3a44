// The one place that maps a joint's type to its model (one file each in this directory). A
// switch without default, compiled with -Werror=switch: a joint type added to JointType does not
// compile until it is listed here, and every algorithm reaches the joints through this switch.
#pragma once

#include "spatial_dynamics/model/joint.hpp"
#include "spatial_dynamics/model/joints/free.hpp"
#include "spatial_dynamics/model/joints/planar.hpp"
#include "spatial_dynamics/model/joints/prismatic.hpp"
#include "spatial_dynamics/model/joints/revolute.hpp"

namespace spatial_dynamics {

/// visit(model) with the joint model of j's type: RevoluteJoint<S>(), PrismaticJoint<S>(), ...
template <class S, class Visitor>
SD_INLINE decltype(auto) visit_joint(const Joint<S>& j, Visitor&& visit) {
  switch (j.type) {
    case JointType::Revolute: return visit(RevoluteJoint<S>());
    case JointType::Prismatic: return visit(PrismaticJoint<S>());
    case JointType::Free: return visit(FreeJoint<S>());
    case JointType::Planar: return visit(PlanarJoint<S>());
  }
  __builtin_unreachable();  // j.type holds one of the enumerators above
}

/// Where the joint's angle sits among its coordinates (revolute 0, planar 2), −1 for none.
template <class S>
SD_INLINE int angle_coordinate(const Joint<S>& j) {
  return visit_joint(j, [](auto joint) SD_INLINE_LAMBDA { return joint.angle_coordinate; });
}

}  // namespace spatial_dynamics
