// Articulated-body inertia: a symmetric 6×6 matrix [A B; Bᵀ C] (RBDA §7.2), used by the ABA,
// held as its blocks (A and C symmetric). Rigid inertia is the special case A = Ī_O, B = h×, C = m1.
#pragma once

#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/mat3.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"

namespace spatial_dynamics {

template <class S>
struct ArticulatedInertia {
  Mat3<S> A, B, C;

  ArticulatedInertia() = default;
  // Copied block by block: a whole-object copy of this size would be a string move (rep movs).
  SD_INLINE ArticulatedInertia(const ArticulatedInertia& o) : A(o.A), B(o.B), C(o.C) {}
  SD_INLINE ArticulatedInertia& operator=(const ArticulatedInertia& o) {
    A = o.A;
    B = o.B;
    C = o.C;
    return *this;
  }
  ArticulatedInertia(const Mat3<S>& a, const Mat3<S>& b, const Mat3<S>& c) : A(a), B(b), C(c) {}
  explicit ArticulatedInertia(const Matrix6<S>& m)
      : A(Matrix3<S>(m.template topLeftCorner<3, 3>())),
        B(Matrix3<S>(m.template topRightCorner<3, 3>())),
        C(Matrix3<S>(m.template bottomRightCorner<3, 3>())) {}
  /// [Ī_O h×; −h× m1] (eq. 25)
  SD_INLINE explicit ArticulatedInertia(const RigidInertia<S>& rigid)
      : A(rigid.rotational_inertia),
        B(Mat3<S>::Skew(rigid.first_moment)),
        C(Mat3<S>::Diagonal(rigid.mass, rigid.mass, rigid.mass)) {}

  /// The 6×6 matrix.
  Matrix6<S> matrix() const {
    Matrix6<S> m;
    m.template topLeftCorner<3, 3>() = A.eigen();
    m.template topRightCorner<3, 3>() = B.eigen();
    m.template bottomLeftCorner<3, 3>() = B.eigen().transpose();
    m.template bottomRightCorner<3, 3>() = C.eigen();
    return m;
  }

  /// Iᴬ v = (A ω + B v ; Bᵀ ω + C v)
  SD_INLINE ForceVector<S> operator*(const MotionVector<S>& v) const {
    return {A * v.angular + B * v.linear, B.transposeTimes(v.angular) + C * v.linear};
  }

  /// Iᴬ − U Wᵀ for forces U = (U_n ; U_f) and W = (W_n ; W_f): the ABA's downdate U D⁻¹ Uᵀ, one
  /// column of U at a time with W = U D⁻¹'s matching column.
  SD_INLINE void subtractOuter(const ForceVector<S>& U, const ForceVector<S>& W) {
    A -= Mat3<S>::Outer(U.angular, W.angular);
    B -= Mat3<S>::Outer(U.angular, W.linear);
    C -= Mat3<S>::Outer(U.linear, W.linear);
  }

  ArticulatedInertia& operator+=(const ArticulatedInertia& o) {
    A += o.A;
    B += o.B;
    C += o.C;
    return *this;
  }
};

}  // namespace spatial_dynamics
