// Planar joint (URDF planar): motion in the plane normal to the unit axis n of the joint frame.
// q = (x, y, ψ): the translation x e₁ + y e₂ along the joint frame's in-plane axes (e₂ = n × e₁,
// Joint::plane_x and plane_y), then the rotation ψ about n; q̇ is the time derivative of q. It is
// two prismatic joints (e₁, e₂) and a revolute joint (n) between massless links, written as one.
// In child coordinates e₁ and e₂ read u₁ = c e₁ − s e₂ and u₂ = s e₁ + c e₂ (c, s of ψ), so
//   S = [ (0 ; u₁)  (0 ; u₂)  (n ; 0) ],   c_J = S̊ q̇ = (0 ; −ψ̇ n × (ẋ u₁ + ẏ u₂)),
// the derivative of u₁ and u₂ as the child turns (RBDA §4.4, c_J for a joint whose S varies).
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

template <class S>
struct PlanarJoint {
  static constexpr int nq = 3, nv = 3;
  static constexpr int angle_coordinate = 2;  // ψ = q[2]

  /// ^iX_λ = rot(E_J(ψ)) xlt(x e₁ + y e₂) X_tree: E = E_J(ψ) E_tree, r = r_tree + E_treeᵀ (x e₁ + y e₂).
  static SD_INLINE void up_transform(const Joint<S>& j, const PluckerTransform<S>& Xt, const std::string&, const S* q,
                                     const S& s, const S& c, PluckerTransform<S>& X) {
    detail::rotate_about_joint_axis(j, Xt.E, s, c, X.E);
    X.r = Xt.r + Xt.E.transpose() * Vector3<S>(j.plane_x * q[0] + j.plane_y * q[1]);
  }
  /// ẋ u₁ + ẏ u₂ = (c ẋ + s ẏ) e₁ + (c ẏ − s ẋ) e₂: the translation rate in child coordinates.
  static SD_INLINE Vector3<S> translation_rate(const Joint<S>& j, const S& s, const S& c, const S* qd) {
    return Vector3<S>(j.plane_x * (c * qd[0] + s * qd[1]) + j.plane_y * (c * qd[1] - s * qd[0]));
  }
  /// S q̇ = (ψ̇ n ; ẋ u₁ + ẏ u₂).
  static SD_INLINE MotionVector<S> motion(const Joint<S>& j, const S& s, const S& c, const S* qd) {
    return {detail::scaled_axis(j, qd[2]), translation_rate(j, s, c, qd)};
  }
  /// c_J = (0 ; −ψ̇ n × (ẋ u₁ + ẏ u₂)) = (0 ; (ẋ u₁ + ẏ u₂) × ψ̇ n).
  static SD_INLINE MotionVector<S> bias(const Joint<S>& j, const S& s, const S& c, const S* qd) {
    return {Vector3<S>::Zero(), detail::cross_axis(j, translation_rate(j, s, c, qd), qd[2])};
  }
  /// Sᵀ (n ; f) = (u₁ · f, u₂ · f, n · n).
  template <class T>
  static SD_INLINE void project(const Joint<S>& j, const S& s, const S& c, const T* n, const T* f, T* out) {
    const T f1 = j.plane_x[0] * f[0] + j.plane_x[1] * f[1] + j.plane_x[2] * f[2];  // e₁ · f
    const T f2 = j.plane_y[0] * f[0] + j.plane_y[1] * f[1] + j.plane_y[2] * f[2];  // e₂ · f
    out[0] = c * f1 - s * f2;
    out[1] = s * f1 + c * f2;
    out[2] = detail::dot_axis(j, n);
  }
  /// U = Iᴬ S = (Iᴬ (0 ; u₁), Iᴬ (0 ; u₂), Iᴬ (n ; 0)).
  static SD_INLINE void inertia_times_subspace(const Joint<S>& j, const S& s, const S& c, const Matrix6<S>& I,
                                               Matrix6<S>& U) {
    U.col(0) = I.template rightCols<3>() * Vector3<S>(c * j.plane_x - s * j.plane_y);
    U.col(1) = I.template rightCols<3>() * Vector3<S>(s * j.plane_x + c * j.plane_y);
    U.col(2) = detail::combine_columns_along_axis(j, I, 0);
  }
  static MotionVector<S> subspace_column(const Joint<S>& j, const S& s, const S& c, int k) {
    if (k == 2) return {j.axis, Vector3<S>::Zero()};
    const Vector3<S> u = k == 0 ? Vector3<S>(c * j.plane_x - s * j.plane_y) : Vector3<S>(s * j.plane_x + c * j.plane_y);
    return {Vector3<S>::Zero(), u};
  }
  /// The names of q's and q̇'s coordinates (the same for this joint).
  static std::vector<std::string> position_names(const std::string& joint) { return velocity_names(joint); }
  static std::vector<std::string> velocity_names(const std::string& joint) {
    return {joint + "/x", joint + "/y", joint + "/yaw"};
  }
};

}  // namespace spatial_dynamics
