// Free joint (the floating root, or a URDF floating joint inside the tree): q = (x y z qx qy qz
// qw), the child's position and orientation in the joint frame; q̇ = (ω ; v) in child
// coordinates, so S = 1 and c_J = 0 (RBDA Table 4.1, with q̇ in the child's coordinates).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {

template <class S>
struct FreeJoint {
  static constexpr int nq = 7, nv = 6;
  static constexpr int angle_coordinate = -1;

  /// ^iX_λ = X_J X_tree with X_J = (Rᵀ, p): E = Rᵀ E_tree, r = r_tree + E_treeᵀ p. A quaternion
  /// that is not of unit norm (to 1e-6) throws std::invalid_argument naming the joint.
  PluckerTransform<S> transform(const PluckerTransform<S>& X_tree, const S* q, const S&, const S&,
                                const JointLabel& joint) const {
    const Eigen::Quaternion<S> quat(q[6], q[3], q[4], q[5]);
    using std::abs;
    if (!(abs(quat.squaredNorm() - S(1)) <= S(1e-6)))
      throw std::invalid_argument("joint '" + joint.name + "': the quaternion (q[" + std::to_string(joint.idx_q + 3) + ".." +
                                  std::to_string(joint.idx_q + 6) + "]) is not of unit norm");
    return {Mat3<S>(quat.toRotationMatrix().transpose()) * X_tree.E, X_tree.r + X_tree.E.transposeTimes(Vec3<S>(q[0], q[1], q[2]))};
  }
  /// S q̇ = q̇.
  SD_INLINE MotionVector<S> motion(const S* qd, const S&, const S&) const {
    return {Vec3<S>(qd[0], qd[1], qd[2]), Vec3<S>(qd[3], qd[4], qd[5])};
  }
  /// c_J + v × S q̇ = v × q̇: c_J = 0.
  SD_INLINE MotionVector<S> velocity_product(const MotionVector<S>& v, const S* qd, const S& s, const S& c) const {
    return cross(v, motion(qd, s, c));
  }
  /// Sᵀ f = (n ; f).
  SD_INLINE Vector6<S> project(const ForceVector<S>& f, const S&, const S&) const { return f.toVector(); }
  MotionVector<S> column(int k, const S&, const S&) const {
    Vector6<S> e = Vector6<S>::Zero();
    e[k] = S(1);
    return MotionVector<S>(e);
  }
  /// S̊ = dS/dt in child coordinates, column k: zero (S is constant).
  MotionVector<S> column_rate(int, const S*, const S&, const S&) const { return MotionVector<S>::Zero(); }

  static std::vector<std::string> position_names(const std::string& joint) {
    std::vector<std::string> names;
    for (const char* c : {"x", "y", "z", "qx", "qy", "qz", "qw"}) names.push_back(joint + "/" + c);
    return names;
  }
  static std::vector<std::string> velocity_names(const std::string& joint) {
    std::vector<std::string> names;
    for (const char* c : {"wx", "wy", "wz", "vx", "vy", "vz"}) names.push_back(joint + "/" + c);
    return names;
  }
};

}  // namespace spatial_dynamics
