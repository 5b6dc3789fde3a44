// Planar joint (URDF planar): motion in the plane normal to the unit axis n of the joint frame.
// q = (x, y, ψ): the translation x e₁ + y e₂ along the joint frame's in-plane axes (e₂ = n × e₁),
// then the rotation ψ about n; q̇ is the time derivative of q. It is two prismatic joints (e₁, e₂)
// and a revolute joint (n) between massless links, written as one. In child coordinates e₁ and e₂
// read u₁ = c e₁ − s e₂ and u₂ = s e₁ + c e₂ (c, s of ψ), so
//   S = [ (0 ; u₁)  (0 ; u₂)  (n ; 0) ],   c_J = S̊ q̇ = (0 ; −ψ̇ n × (ẋ u₁ + ẏ u₂)),
// the derivative of u₁ and u₂ as the child turns (RBDA §4.4, c_J for a joint whose S varies).
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"

namespace spatial_dynamics {

template <class S>
struct PlanarJoint {
  static constexpr int nq = 3, nv = 3;
  static constexpr int angle_coordinate = 2;  // ψ = q[2]
  Vec3<S> axis = Vec3<S>::UnitZ();      // n
  Vec3<S> plane_x = Vec3<S>::UnitX();   // e₁
  Vec3<S> plane_y = Vec3<S>::UnitY();   // e₂

  /// ^iX_λ = rot(E_J(ψ)) xlt(x e₁ + y e₂) X_tree: E = E_J(ψ) E_tree, r = r_tree + E_treeᵀ (x e₁ + y e₂).
  SD_INLINE PluckerTransform<S> transform(const PluckerTransform<S>& X_tree, const S* q, const S& s, const S& c,
                                          const JointLabel&) const {
    return {detail::rotated_about_axis(X_tree.E, axis, c, s),
            X_tree.r + X_tree.E.transposeTimes(plane_x * q[0] + plane_y * q[1])};
  }
  /// u₁ and u₂, the in-plane axes in child coordinates.
  SD_INLINE Vec3<S> u1(const S& s, const S& c) const { return plane_x * c - plane_y * s; }
  SD_INLINE Vec3<S> u2(const S& s, const S& c) const { return plane_x * s + plane_y * c; }
  /// S q̇ = (ψ̇ n ; ẋ u₁ + ẏ u₂).
  SD_INLINE MotionVector<S> motion(const S* qd, const S& s, const S& c) const {
    return {axis * qd[2], u1(s, c) * qd[0] + u2(s, c) * qd[1]};
  }
  /// c_J + v × S q̇ with c_J = (0 ; (ẋ u₁ + ẏ u₂) × ψ̇ n).
  SD_INLINE MotionVector<S> velocity_product(const MotionVector<S>& v, const S* qd, const S& s, const S& c) const {
    const MotionVector<S> vJ = motion(qd, s, c);
    return MotionVector<S>(Vec3<S>(), cross(vJ.linear, vJ.angular)) + cross(v, vJ);
  }
  /// Sᵀ (n ; f) = (u₁ · f, u₂ · f, n · n).
  SD_INLINE Vector3<S> project(const ForceVector<S>& f, const S& s, const S& c) const {
    return {dot(u1(s, c), f.linear), dot(u2(s, c), f.linear), dot(axis, f.angular)};
  }

  MotionVector<S> column(int k, const S& s, const S& c) const {
    if (k == 2) return {axis, Vec3<S>()};
    return {Vec3<S>(), k == 0 ? u1(s, c) : u2(s, c)};
  }
  /// S̊ = dS/dt in child coordinates, column k: u̇₁ = −ψ̇ n × u₁ and u̇₂ = −ψ̇ n × u₂ as the child
  /// turns; n is constant (Σ_k S̊_k q̇_k is c_J).
  MotionVector<S> column_rate(int k, const S* qd, const S& s, const S& c) const {
    if (k == 2) return MotionVector<S>::Zero();
    return {Vec3<S>(), cross(axis, k == 0 ? u1(s, c) : u2(s, c)) * (-qd[2])};
  }

  static std::vector<std::string> position_names(const std::string& joint) { return velocity_names(joint); }
  static std::vector<std::string> velocity_names(const std::string& joint) {
    return {joint + "/x", joint + "/y", joint + "/yaw"};
  }
};

}  // namespace spatial_dynamics
