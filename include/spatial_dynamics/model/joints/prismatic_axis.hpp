// Prismatic joint along the joint frame's x, y or z axis (k = 0, 1, 2): translation q e_k,
// S = (0 ; e_k), constant (RBDA Table 4.1).
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {

template <class S, int k>
struct PrismaticAxisJoint {
  static constexpr int nq = 1, nv = 1;
  static constexpr int angle_coordinate = -1;

  /// ^iX_λ = xlt(q e_k) X_tree: E = E_tree, r = r_tree + E_treeᵀ q e_k (row k of E_tree, times q).
  SD_INLINE PluckerTransform<S> transform(const PluckerTransform<S>& X_tree, const S* q, const S&, const S&,
                                          const JointLabel&) const {
    return {X_tree.E, X_tree.r + X_tree.E.row(k) * q[0]};
  }
  /// S q̇ = (0 ; q̇ e_k).
  SD_INLINE MotionVector<S> motion(const S* qd, const S&, const S&) const {
    return {Vec3<S>(), detail::unit_axis<S, k>(qd[0])};
  }
  /// c_J + v × S q̇ = (0 ; ω × q̇ e_k): c_J = 0.
  SD_INLINE MotionVector<S> velocity_product(const MotionVector<S>& v, const S* qd, const S&, const S&) const {
    return {Vec3<S>(), detail::cross_unit_axis<k>(v.angular, qd[0])};
  }
  /// Sᵀ f = f_k.
  SD_INLINE Eigen::Matrix<S, 1, 1> project(const ForceVector<S>& f, const S&, const S&) const {
    return Eigen::Matrix<S, 1, 1>(f.linear[k]);
  }
  MotionVector<S> column(int, const S&, const S&) const { return {Vec3<S>(), detail::unit_axis<S, k>(S(1))}; }
  /// S̊ = dS/dt in child coordinates, column k: zero (S is constant).
  MotionVector<S> column_rate(int, const S*, const S&, const S&) const { return MotionVector<S>::Zero(); }

  static std::vector<std::string> position_names(const std::string& joint) { return {joint}; }
  static std::vector<std::string> velocity_names(const std::string& joint) { return {joint}; }
};

}  // namespace spatial_dynamics
