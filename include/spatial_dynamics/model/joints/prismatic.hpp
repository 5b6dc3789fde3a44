// Prismatic joint: translation q along a general unit axis a of the joint frame; S = (0 ; a),
// constant (RBDA Table 4.1). Axes along x, y or z are PrismaticAxisJoint.
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {

template <class S>
struct PrismaticJoint {
  static constexpr int nq = 1, nv = 1;
  static constexpr int angle_coordinate = -1;
  Vec3<S> axis = Vec3<S>::UnitZ();

  /// ^iX_λ = xlt(q a) X_tree: E = E_tree, r = r_tree + E_treeᵀ (q a).
  SD_INLINE PluckerTransform<S> transform(const PluckerTransform<S>& X_tree, const S* q, const S&, const S&,
                                          const JointLabel&) const {
    return {X_tree.E, X_tree.r + X_tree.E.transposeTimes(axis * q[0])};
  }
  /// S q̇ = (0 ; q̇ a).
  SD_INLINE MotionVector<S> motion(const S* qd, const S&, const S&) const {
    return {Vec3<S>(), axis * qd[0]};
  }
  /// c_J + v × S q̇ = (0 ; ω × q̇ a): c_J = 0.
  SD_INLINE MotionVector<S> velocity_product(const MotionVector<S>& v, const S* qd, const S&, const S&) const {
    return {Vec3<S>(), cross(v.angular, axis * qd[0])};
  }
  /// Sᵀ f = a · f.
  SD_INLINE Eigen::Matrix<S, 1, 1> project(const ForceVector<S>& f, const S&, const S&) const {
    return Eigen::Matrix<S, 1, 1>(dot(axis, f.linear));
  }

  MotionVector<S> column(int, const S&, const S&) const { return {Vec3<S>(), axis}; }
  /// S̊ = dS/dt in child coordinates, column k: zero (S is constant).
  MotionVector<S> column_rate(int, const S*, const S&, const S&) const { return MotionVector<S>::Zero(); }

  static std::vector<std::string> position_names(const std::string& joint) { return {joint}; }
  static std::vector<std::string> velocity_names(const std::string& joint) { return {joint}; }
};

}  // namespace spatial_dynamics
