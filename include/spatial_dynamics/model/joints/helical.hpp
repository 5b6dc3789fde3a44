// Helical (screw) joint about a unit axis a of the joint frame with pitch h: a rotation by θ about
// a and a translation h θ along it, S = (a ; h a), constant (RBDA Table 4.1's helical joint;
// spatial_v2's jcalc 'H'). E_J(θ) = rot(a, θ)ᵀ (RBDA eq. 2.24, transposed); the translation along
// the axis is the same in both frames.
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {

template <class S>
struct HelicalJoint {
  static constexpr int nq = 1, nv = 1;
  static constexpr int angle_coordinate = 0;  // θ = q[0]; s, c = sin θ, cos θ
  Vec3<S> axis = Vec3<S>::UnitZ();
  S pitch{0};

  /// ^iX_λ = X_J(θ) X_tree: E = rot(a, θ)ᵀ E_tree, r = r_tree + E_treeᵀ (h θ a).
  SD_INLINE PluckerTransform<S> transform(const PluckerTransform<S>& X_tree, const S* q, const S& s, const S& c,
                                          const JointLabel&) const {
    return {detail::rotated_about_axis(X_tree.E, axis, c, s), X_tree.r + X_tree.E.transposeTimes(axis * (pitch * q[0]))};
  }
  /// S q̇ = (q̇ a ; h q̇ a).
  SD_INLINE MotionVector<S> motion(const S* qd, const S&, const S&) const {
    const Vec3<S> w = axis * qd[0];
    return {w, w * pitch};
  }
  /// c_J + v × S q̇ = v × S q̇: c_J = 0.
  SD_INLINE MotionVector<S> velocity_product(const MotionVector<S>& v, const S* qd, const S& s, const S& c) const {
    return cross(v, motion(qd, s, c));
  }
  /// Sᵀ f = a · n + h a · f.
  SD_INLINE Eigen::Matrix<S, 1, 1> project(const ForceVector<S>& f, const S&, const S&) const {
    return Eigen::Matrix<S, 1, 1>(dot(axis, f.angular) + pitch * dot(axis, f.linear));
  }
  MotionVector<S> column(int, const S&, const S&) const { return {axis, axis * pitch}; }
  /// S̊ = dS/dt in child coordinates, column k: zero (S is constant).
  MotionVector<S> column_rate(int, const S*, const S&, const S&) const { return MotionVector<S>::Zero(); }

  static std::vector<std::string> position_names(const std::string& joint) { return {joint}; }
  static std::vector<std::string> velocity_names(const std::string& joint) { return {joint}; }
};

}  // namespace spatial_dynamics
