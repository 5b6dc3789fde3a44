// Prismatic joint: translation q along the unit axis a of the joint frame; S = (0 ; a),
// constant (RBDA Table 4.1).
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/joints/axis_operations.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

template <class S>
struct PrismaticJoint {
  static constexpr int nq = 1, nv = 1;
  static constexpr int angle_coordinate = -1;

  /// ^iX_λ = xlt(q a) X_tree: E = E_tree, r = r_tree + E_treeᵀ (q a).
  static SD_INLINE void up_transform(const Joint<S>& j, const PluckerTransform<S>& Xt, const std::string&, const S* q,
                                     const S&, const S&, PluckerTransform<S>& X) {
    X.E = Xt.E;
    X.r = Xt.r + Xt.E.transpose() * detail::scaled_axis(j, q[0]);
  }
  /// S q̇ = (0 ; q̇ a).
  static SD_INLINE MotionVector<S> motion(const Joint<S>& j, const S&, const S&, const S* qd) {
    return {Vector3<S>::Zero(), detail::scaled_axis(j, qd[0])};
  }
  /// c_J = 0: S is constant.
  static SD_INLINE MotionVector<S> bias(const Joint<S>&, const S&, const S&, const S*) { return MotionVector<S>::Zero(); }
  /// Sᵀ (n ; f) = a · f.
  template <class T>
  static SD_INLINE void project(const Joint<S>& j, const S&, const S&, const T*, const T* f, T* out) {
    out[0] = detail::dot_axis(j, f);
  }
  /// U = Iᴬ S: one column of Iᴬ for a coordinate axis.
  static SD_INLINE void inertia_times_subspace(const Joint<S>& j, const S&, const S&, const Matrix6<S>& I, Matrix6<S>& U) {
    U.col(0) = detail::combine_columns_along_axis(j, I, 3);
  }
  static MotionVector<S> subspace_column(const Joint<S>& j, const S&, const S&, int) {
    return {Vector3<S>::Zero(), j.axis};
  }
  /// The names of q's and q̇'s coordinates (the same for this joint).
  static std::vector<std::string> position_names(const std::string& joint) { return velocity_names(joint); }
  static std::vector<std::string> velocity_names(const std::string& joint) { return {joint}; }
};

}  // namespace spatial_dynamics
