// Revolute joint (URDF revolute and continuous): rotation θ about the unit axis a of the joint
// frame; S = (a ; 0), constant (RBDA Table 4.1).
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

template <class S>
struct RevoluteJoint {
  static constexpr int nq = 1, nv = 1;
  static constexpr int angle_coordinate = 0;  // θ = q[0]; its sine s and cosine c are computed once per call

  /// ^iX_λ = X_J(θ) X_tree: E = E_J(θ) E_tree, r = r_tree.
  static SD_INLINE void up_transform(const Joint<S>& j, const PluckerTransform<S>& Xt, const std::string&, const S*,
                                     const S& s, const S& c, PluckerTransform<S>& X) {
    X.r = Xt.r;
    detail::rotate_about_joint_axis(j, Xt.E, s, c, X.E);
  }
  /// S q̇ = (q̇ a ; 0).
  static SD_INLINE MotionVector<S> motion(const Joint<S>& j, const S&, const S&, const S* qd) {
    return {detail::scaled_axis(j, qd[0]), Vector3<S>::Zero()};
  }
  /// c_J = S̊ q̇ = 0: S is constant.
  static SD_INLINE MotionVector<S> bias(const Joint<S>&, const S&, const S&, const S*) { return MotionVector<S>::Zero(); }
  /// Sᵀ (n ; f) = a · n.
  template <class T>
  static SD_INLINE void project(const Joint<S>& j, const S&, const S&, const T* n, const T*, T* out) {
    out[0] = detail::dot_axis(j, n);
  }
  /// U = Iᴬ S: one column of Iᴬ for a coordinate axis.
  static SD_INLINE void inertia_times_subspace(const Joint<S>& j, const S&, const S&, const Matrix6<S>& I, Matrix6<S>& U) {
    U.col(0) = detail::combine_columns_along_axis(j, I, 0);
  }
  static MotionVector<S> subspace_column(const Joint<S>& j, const S&, const S&, int) {
    return {j.axis, Vector3<S>::Zero()};
  }
  /// The names of q's and q̇'s coordinates (the same for this joint).
  static std::vector<std::string> position_names(const std::string& joint) { return velocity_names(joint); }
  static std::vector<std::string> velocity_names(const std::string& joint) { return {joint}; }
};

}  // namespace spatial_dynamics
