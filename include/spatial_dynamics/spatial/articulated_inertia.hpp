// Articulated-body inertia: a general symmetric 6×6 matrix [A B; Bᵀ C] (RBDA §7.2), used by the
// ABA. Rigid inertia is the special case B = h×, C = m1.
#pragma once

#include <type_traits>

#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/number/packed3_articulated_inertia.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"

namespace spatial_dynamics {

template <class S>
struct ArticulatedInertia {
  Matrix6<S> matrix = Matrix6<S>::Zero();

  ArticulatedInertia() = default;
  explicit ArticulatedInertia(const Matrix6<S>& m) : matrix(m) {}
  explicit ArticulatedInertia(const RigidInertia<S>& rigid) { assign(rigid); }

  SD_INLINE void assign(const RigidInertia<S>& rigid) {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      packed3::store_rigid(rigid.mass, rigid.first_moment, rigid.rotational_inertia, matrix);
      return;
    }
#endif
    const Matrix3<S> hx = skew(rigid.first_moment);
    matrix.template topLeftCorner<3, 3>() = rigid.rotational_inertia;
    matrix.template topRightCorner<3, 3>() = hx;
    matrix.template bottomLeftCorner<3, 3>() = -hx;
    matrix.template bottomRightCorner<3, 3>() = rigid.mass * Matrix3<S>::Identity();
  }

  SD_INLINE ForceVector<S> operator*(const MotionVector<S>& v) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {  // [A ω + B v ; Bᵀ ω + C v] on the blocks' columns
      using namespace packed3;
      Packed3 top, bottom;
      times_motion(load_blocks(matrix), v.angular.data(), v.linear.data(), top, bottom);
      return {to_vector3(top), to_vector3(bottom)};
    }
#endif
    return {matrix.template topLeftCorner<3, 3>() * v.angular + matrix.template topRightCorner<3, 3>() * v.linear,
            matrix.template bottomLeftCorner<3, 3>() * v.angular + matrix.template bottomRightCorner<3, 3>() * v.linear};
  }

  ArticulatedInertia& operator+=(const ArticulatedInertia& o) { matrix += o.matrix; return *this; }
};

}  // namespace spatial_dynamics
