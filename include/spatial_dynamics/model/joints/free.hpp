// Free joint (the floating root, or a URDF floating joint inside the tree): q = (x y z qx qy qz
// qw), the child's position and orientation in the joint frame; q̇ = (ω ; v) in child
// coordinates, so S = 1 and c_J = 0 (RBDA Table 4.1, with q̇ in the child's coordinates).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "spatial_dynamics/model/joint.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

template <class S>
struct FreeJoint {
  static constexpr int nq = 7, nv = 6;
  static constexpr int angle_coordinate = -1;

  /// ^iX_λ = X_J X_tree with X_J = (Rᵀ, p): E = Rᵀ E_tree, r = r_tree + E_treeᵀ p. A quaternion
  /// that is not of unit norm (to 1e-6) throws std::invalid_argument naming the joint.
  static void up_transform(const Joint<S>& j, const PluckerTransform<S>& Xt, const std::string& name, const S* q,
                           const S&, const S&, PluckerTransform<S>& X) {
    const Eigen::Quaternion<S> quat(q[6], q[3], q[4], q[5]);
    using std::abs;
    if (!(abs(quat.squaredNorm() - S(1)) <= S(1e-6)))
      throw std::invalid_argument("joint '" + name + "': the quaternion (q[" + std::to_string(j.idx_q + 3) + ".." +
                                  std::to_string(j.idx_q + 6) + "]) is not of unit norm");
    const Vector3<S> p(q[0], q[1], q[2]);
    X.E = quat.toRotationMatrix().transpose() * Xt.E;
    X.r = Xt.r + Xt.E.transpose() * p;
  }
  /// S q̇ = q̇.
  static SD_INLINE MotionVector<S> motion(const Joint<S>&, const S&, const S&, const S* qd) {
    return {Vector3<S>(qd[0], qd[1], qd[2]), Vector3<S>(qd[3], qd[4], qd[5])};
  }
  static SD_INLINE MotionVector<S> bias(const Joint<S>&, const S&, const S&, const S*) { return MotionVector<S>::Zero(); }
  /// Sᵀ (n ; f) = (n ; f).
  template <class T>
  static SD_INLINE void project(const Joint<S>&, const S&, const S&, const T* n, const T* f, T* out) {
    for (int k = 0; k < 3; ++k) {
      out[k] = n[k];
      out[k + 3] = f[k];
    }
  }
  /// U = Iᴬ S = Iᴬ.
  static SD_INLINE void inertia_times_subspace(const Joint<S>&, const S&, const S&, const Matrix6<S>& I, Matrix6<S>& U) {
    U = I;
  }
  static MotionVector<S> subspace_column(const Joint<S>&, const S&, const S&, int k) {
    Vector6<S> e = Vector6<S>::Zero();
    e[k] = S(1);
    return MotionVector<S>(e);
  }
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
