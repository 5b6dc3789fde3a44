// Revolute joint about the joint frame's x, y or z axis (k = 0, 1, 2; URDF revolute and continuous
// with such an axis): S = (e_k ; 0), constant (RBDA Table 4.1); E_J(θ) is rx, ry or rz (Table 2.2),
// so that its products read the two coordinates it mixes.
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {

template <class S, int k>
struct RevoluteAxisJoint {
  static constexpr int nq = 1, nv = 1;
  static constexpr int angle_coordinate = 0;  // θ = q[0]; s, c = sin θ, cos θ

  /// ^iX_λ = X_J(θ) X_tree: E = rot_k(θ) E_tree, r = r_tree.
  SD_INLINE PluckerTransform<S> transform(const PluckerTransform<S>& X_tree, const S*, const S& s, const S& c,
                                          const JointLabel&) const {
    return {detail::rotated_about_coordinate_axis<k>(X_tree.E, c, s), X_tree.r};
  }
  /// S q̇ = (q̇ e_k ; 0).
  SD_INLINE MotionVector<S> motion(const S* qd, const S&, const S&) const {
    return {detail::unit_axis<S, k>(qd[0]), Vec3<S>()};
  }
  /// c_J + v × S q̇ = (ω × q̇ e_k ; v_O × q̇ e_k): c_J = 0.
  SD_INLINE MotionVector<S> velocity_product(const MotionVector<S>& v, const S* qd, const S&, const S&) const {
    return {detail::cross_unit_axis<k>(v.angular, qd[0]), detail::cross_unit_axis<k>(v.linear, qd[0])};
  }
  /// Sᵀ f = n_k.
  SD_INLINE Eigen::Matrix<S, 1, 1> project(const ForceVector<S>& f, const S&, const S&) const {
    return Eigen::Matrix<S, 1, 1>(f.angular[k]);
  }
  MotionVector<S> column(int, const S&, const S&) const { return {detail::unit_axis<S, k>(S(1)), Vec3<S>()}; }
  /// S̊ = dS/dt in child coordinates, column k: zero (S is constant).
  MotionVector<S> column_rate(int, const S*, const S&, const S&) const { return MotionVector<S>::Zero(); }

  static std::vector<std::string> position_names(const std::string& joint) { return {joint}; }
  static std::vector<std::string> velocity_names(const std::string& joint) { return {joint}; }
};

}  // namespace spatial_dynamics
