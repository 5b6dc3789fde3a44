// Rigid-body spatial inertia stored as its ten parameters: mass m, first moment of mass
// h = m·c, and the rotational inertia Ī_O about the frame origin (Featherstone 2010, eq. 25):
//   I = [ Ī_O   h× ]      Ī_O = Ī_c + m c× c×ᵀ
//       [ -h×   m1 ]
#pragma once

#include "spatial_dynamics/spatial/cross.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"

namespace spatial_dynamics {

template <class S>
struct RigidInertia {
  S mass{0};
  Vector3<S> first_moment = Vector3<S>::Zero();          // h = m c
  Matrix3<S> rotational_inertia = Matrix3<S>::Zero();    // Ī_O, about the frame origin

  RigidInertia() = default;
  RigidInertia(const S& m, const Vector3<S>& h, const Matrix3<S>& inertia_about_origin)
      : mass(m), first_moment(h), rotational_inertia(inertia_about_origin) {}

  static RigidInertia Zero() { return RigidInertia(); }

  /// Whether all ten parameters are finite (x − x is 0 exactly for a finite x).
  bool allFinite() const {
    return mass - mass == S(0) && first_moment.allFinite() && rotational_inertia.allFinite();
  }

  /// From mass, centre of mass c and rotational inertia Ī_c about c (eq. 25).
  static RigidInertia FromMassCenterInertia(const S& m, const Vector3<S>& c, const Matrix3<S>& inertia_about_com) {
    const Matrix3<S> cx = skew(c);
    return RigidInertia(m, m * c, inertia_about_com - m * cx * cx);
  }

  /// Centre of mass; undefined (division by zero) for a massless body.
  Vector3<S> centerOfMass() const { return first_moment / mass; }

  /// Rotational inertia about the centre of mass, Ī_c = Ī_O - m c× c×ᵀ (eq. 25 solved for Ī_c).
  Matrix3<S> inertiaAboutCenterOfMass() const {
    const Matrix3<S> hx = skew(first_moment);
    return rotational_inertia + hx * hx / mass;
  }

  /// I v = (Ī_O ω + h×v ; m v − h×ω)   (eq. 25 applied to a motion vector)
  SD_INLINE ForceVector<S> operator*(const MotionVector<S>& v) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      using namespace packed3;
      Packed3 I0, I1, I2;
      load_columns(rotational_inertia, I0, I1, I2);
      const Packed3 h = load3(first_moment), w = load3(v.angular), lin = load3(v.linear);
      return {to_vector3(mat_vec(I0, I1, I2, w) + cross(h, lin)), to_vector3(mass * lin - cross(h, w))};
    }
#endif
    return {rotational_inertia * v.angular + cross_3d(first_moment, v.linear),
            mass * v.linear - cross_3d(first_moment, v.angular)};
  }

  /// The velocity-product (bias) force v ×* I v (eq. 29 with a = 0), as
  ///   (ω × Ī_O ω + h × (ω × v) ; m ω × v − ω × (h × ω)).
  /// Expanding v ×* (I v) = (ω × n + v × f ; ω × f) with I v = (n ; f) gives the same terms plus
  /// v × m v, which is zero but, computed, is the rounding of m v crossed with v: on a light body
  /// far out on a fast chain that noise (ε m |v|²) outweighs the force. The two remaining terms
  /// ω × (h × v) − v × (h × ω) are h × (ω × v) by the Jacobi identity.
  SD_INLINE ForceVector<S> biasForce(const MotionVector<S>& v) const {
    const Vector3<S>& w = v.angular;
    const Matrix3<S>& J = rotational_inertia;  // Ī_O ω written out: Eigen's product costs ~15 ns a body here
    const Vector3<S> J_w(J(0, 0) * w.x() + J(0, 1) * w.y() + J(0, 2) * w.z(),
                         J(1, 0) * w.x() + J(1, 1) * w.y() + J(1, 2) * w.z(),
                         J(2, 0) * w.x() + J(2, 1) * w.y() + J(2, 2) * w.z());
    const Vector3<S> w_cross_v = cross_3d(w, v.linear);
    const Vector3<S> h_cross_w = cross_3d(first_moment, w);
    return {Vector3<S>(cross_3d(w, J_w) + cross_3d(first_moment, w_cross_v)),
            Vector3<S>(mass * w_cross_v - cross_3d(w, h_cross_w))};
  }

  /// Composite inertia of two bodies rigidly joined: I = I_1 + I_2 (eq. 24).
  RigidInertia& operator+=(const RigidInertia& o) {
    mass += o.mass;
    first_moment += o.first_moment;
    rotational_inertia += o.rotational_inertia;
    return *this;
  }
  RigidInertia operator+(const RigidInertia& o) const {
    RigidInertia r = *this;
    r += o;
    return r;
  }

  /// The 6×6 matrix of eq. (25).
  Matrix6<S> toMatrix() const {
    Matrix6<S> m;
    const Matrix3<S> hx = skew(first_moment);
    m.template topLeftCorner<3, 3>() = rotational_inertia;
    m.template topRightCorner<3, 3>() = hx;
    m.template bottomLeftCorner<3, 3>() = -hx;
    m.template bottomRightCorner<3, 3>() = mass * Matrix3<S>::Identity();
    return m;
  }

  template <class T>
  RigidInertia<T> cast() const {
    return RigidInertia<T>(T(mass), first_moment.template cast<T>(), rotational_inertia.template cast<T>());
  }
};

/// Momentum of a rigid body, h = I v (eq. 23).
template <class S>
ForceVector<S> momentum(const RigidInertia<S>& inertia, const MotionVector<S>& v) {
  return inertia * v;
}

/// Kinetic energy T = ½ v · I v (eq. 28).
template <class S>
S kinetic_energy(const RigidInertia<S>& inertia, const MotionVector<S>& v) {
  return dot(v, inertia * v) / S(2);
}

/// Equation of motion of a rigid body: f = I a + v ×* I v (eq. 29).
template <class S>
ForceVector<S> equation_of_motion(const RigidInertia<S>& inertia, const MotionVector<S>& v, const MotionVector<S>& a) {
  return inertia * a + cross(v, inertia * v);
}

/// Gravity force on a rigid body, f_g = I a_g, with a_g = (0; g) the gravitational acceleration.
template <class S>
ForceVector<S> gravity_force(const RigidInertia<S>& inertia, const Vector3<S>& g) {
  return inertia * MotionVector<S>(Vector3<S>::Zero(), g);
}

/// Time derivative of a body's inertia expressed in fixed coordinates while the body moves with
/// velocity v: d/dt I = v ×* I − I v×   (eq. 27).
template <class S>
Matrix6<S> inertia_time_derivative(const RigidInertia<S>& inertia, const MotionVector<S>& v) {
  const Matrix6<S> I = inertia.toMatrix();
  return force_cross_matrix(v) * I - I * motion_cross_matrix(v);
}

}  // namespace spatial_dynamics
