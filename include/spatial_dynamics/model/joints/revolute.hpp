// Revolute joint about a general unit axis a of the joint frame (URDF revolute and continuous):
// S = (a ; 0), constant (RBDA Table 4.1); E_J(θ) = rot(a, θ)ᵀ (RBDA eq. 2.24, transposed).
// Axes along x, y or z are RevoluteAxisJoint.
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {

template <class S>
struct RevoluteJoint {
  static constexpr int nq = 1, nv = 1;
  static constexpr int angle_coordinate = 0;  // θ = q[0]; s, c = sin θ, cos θ
  Vec3<S> axis = Vec3<S>::UnitZ();

  /// ^iX_λ = X_J(θ) X_tree: E = rot(a, θ)ᵀ E_tree, r = r_tree.
  SD_INLINE PluckerTransform<S> transform(const PluckerTransform<S>& X_tree, const S*, const S& s, const S& c,
                                          const JointLabel&) const {
    PluckerTransform<S> X;
    X.E = detail::rotated_about_axis(X_tree.E, axis, c, s);
    X.r = X_tree.r;
    return X;
  }
  /// S q̇ = (q̇ a ; 0).
  SD_INLINE MotionVector<S> motion(const S* qd, const S&, const S&) const {
    return {axis * qd[0], Vec3<S>()};
  }
  /// c_J + v × S q̇ = (ω × q̇ a ; v_O × q̇ a): c_J = 0.
  SD_INLINE MotionVector<S> velocity_product(const MotionVector<S>& v, const S* qd, const S&, const S&) const {
    const Vec3<S> w = axis * qd[0];
    return {cross(v.angular, w), cross(v.linear, w)};
  }
  /// Sᵀ f = a · n.
  SD_INLINE Eigen::Matrix<S, 1, 1> project(const ForceVector<S>& f, const S&, const S&) const {
    return Eigen::Matrix<S, 1, 1>(dot(axis, f.angular));
  }

  MotionVector<S> column(int, const S&, const S&) const { return {axis, Vec3<S>()}; }
  /// S̊ = dS/dt in child coordinates, column k: zero (S is constant).
  MotionVector<S> column_rate(int, const S*, const S&, const S&) const { return MotionVector<S>::Zero(); }

  static std::vector<std::string> position_names(const std::string& joint) { return {joint}; }
  static std::vector<std::string> velocity_names(const std::string& joint) { return {joint}; }
};

}  // namespace spatial_dynamics
