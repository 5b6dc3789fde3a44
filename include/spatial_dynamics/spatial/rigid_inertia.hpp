// Rigid-body spatial inertia stored as its ten parameters: mass m, first moment of mass
// h = m·c, and the rotational inertia Ī_O about the frame origin (Featherstone 2010, eq. 25):
//   I = [ Ī_O   h× ]      Ī_O = Ī_c + m c× c×ᵀ
//       [ -h×   m1 ]
#pragma once

#include "spatial_dynamics/spatial/cross.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/mat3.hpp"

namespace spatial_dynamics {

template <class S>
struct RigidInertia {
  S mass{0};
  Vec3<S> first_moment;          // h = m c
  Mat3<S> rotational_inertia;    // Ī_O, about the frame origin

  RigidInertia() = default;
  RigidInertia(const S& m, const Vec3<S>& h, const Mat3<S>& inertia_about_origin)
      : mass(m), first_moment(h), rotational_inertia(inertia_about_origin) {}

  static RigidInertia Zero() { return RigidInertia(); }

  /// Whether all ten parameters are finite (x − x is 0 exactly for a finite x).
  bool allFinite() const { return mass - mass == S(0) && first_moment.allFinite() && rotational_inertia.allFinite(); }

  /// From mass, centre of mass c and rotational inertia Ī_c about c (eq. 25).
  static RigidInertia FromMassCenterInertia(const S& m, const Vec3<S>& c, const Mat3<S>& inertia_about_com) {
    const Mat3<S> cx = skew(c);
    return RigidInertia(m, c * m, inertia_about_com - (cx * cx) * m);
  }

  /// Centre of mass; undefined (division by zero) for a massless body.
  Vec3<S> centerOfMass() const { return first_moment / mass; }

  /// Rotational inertia about the centre of mass, Ī_c = Ī_O - m c× c×ᵀ (eq. 25 solved for Ī_c).
  Mat3<S> inertiaAboutCenterOfMass() const {
    const Mat3<S> hx = skew(first_moment);
    const Mat3<S> hxhx = hx * hx;
    return rotational_inertia + Mat3<S>(hxhx.col(0) / mass, hxhx.col(1) / mass, hxhx.col(2) / mass);
  }

  /// I v = (Ī_O ω + h×v ; m v − h×ω)   (eq. 25 applied to a motion vector)
  SD_INLINE ForceVector<S> operator*(const MotionVector<S>& v) const {
    return {rotational_inertia * v.angular + cross(first_moment, v.linear),
            v.linear * mass - cross(first_moment, v.angular)};
  }

  /// The velocity-product (bias) force v ×* I v (eq. 29 with a = 0), as
  ///   (ω × Ī_O ω + h × (ω × v) ; m ω × v − ω × (h × ω)).
  /// Expanding v ×* (I v) = (ω × n + v × f ; ω × f) with I v = (n ; f) gives the same terms plus
  /// v × m v, which is zero but, computed, is the rounding of m v crossed with v: on a light body
  /// far out on a fast chain that noise (ε m |v|²) outweighs the force. The two remaining terms
  /// ω × (h × v) − v × (h × ω) are h × (ω × v) by the Jacobi identity.
  SD_INLINE ForceVector<S> biasForce(const MotionVector<S>& v) const {
    const Vec3<S>& w = v.angular;
    const Vec3<S> w_cross_v = cross(w, v.linear);
    return {cross(w, rotational_inertia * w) + cross(first_moment, w_cross_v),
            w_cross_v * mass - cross(w, cross(first_moment, w))};
  }

  /// The same body's inertia in axes turned by R (x ↦ R x): (m, R h, R Ī_O Rᵀ), Ī_O's
  /// upper triangle copied from its lower one so that it stays exactly symmetric.
  SD_INLINE RigidInertia rotated(const Mat3<S>& R) const {
    Mat3<S> turned = (R * rotational_inertia).timesTransposed(R);  // (R Ī) Rᵀ
    turned.symmetrize_from_lower();
    return RigidInertia(mass, R * first_moment, turned);
  }

  /// The same body's inertia about the point p (from the frame origin, same axes) (eq. 26 with
  /// E = 1): h − m p and Ī_O + h×p× + p×h× − m p×p× = Ī_O + p hᵀ + (h − m p) pᵀ + (m p·p − 2 h·p)1
  /// (a×b× = b aᵀ − (a·b)1). m p is formed first, so a massless body far away gives 0, not 0 · ∞.
  SD_INLINE RigidInertia aboutPoint(const Vec3<S>& p) const {
    const Vec3<S> mp = p * mass;
    const Vec3<S> h_less_mp = first_moment - mp;
    Mat3<S> shifted;
    for (int c = 0; c < 3; ++c)  // column c: Ī_c + p h_c + (h − m p) p_c
      shifted.column[c] = rotational_inertia.column[c] + (p * first_moment[c] + h_less_mp * p[c]);
    shifted = shifted.plusDiagonal(dot(mp, p) - S(2) * dot(first_moment, p));
    shifted.symmetrize_from_lower();
    return RigidInertia(mass, h_less_mp, shifted);
  }

  /// The rate of change, in fixed coordinates, of the inertia of a body moving with velocity
  /// v = (ω ; v_O): İ = v×* I − I v× (eq. 27) has eq. (25)'s form with m = 0, with
  /// ḣ = m v_O + ω × h and d/dt Ī_O = P + Pᵀ + 2 (h · v_O) 1, P = ω× Ī_O − h v_Oᵀ.
  SD_INLINE RigidInertia rate(const MotionVector<S>& v) const {
    const Mat3<S> P = skew(v.angular) * rotational_inertia - Mat3<S>::Outer(first_moment, v.linear);
    return RigidInertia(S(0), v.linear * mass + cross(v.angular, first_moment),
                        (P + P.transpose()).plusDiagonal(S(2) * dot(first_moment, v.linear)));
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

  /// The ten inertial parameters π = (m, h_x, h_y, h_z, I_xx, I_xy, I_yy, I_xz, I_yz, I_zz), h = m c
  /// and I = Ī_O about the frame origin (eq. 25; Pinocchio's order), written to out[0 .. 10).
  void toParameters(S* out) const {
    out[0] = mass;
    for (int k = 0; k < 3; ++k) out[1 + k] = first_moment[k];
    const Mat3<S>& I = rotational_inertia;
    out[4] = I(0, 0), out[5] = I(0, 1), out[6] = I(1, 1), out[7] = I(0, 2), out[8] = I(1, 2), out[9] = I(2, 2);
  }

  /// The body with the ten parameters π at p[0 .. 10) (toParameters' order).
  static RigidInertia FromParameters(const S* p) {
    const Vec3<S> row_x(p[4], p[5], p[7]), row_y(p[5], p[6], p[8]), row_z(p[7], p[8], p[9]);
    return RigidInertia(p[0], Vec3<S>(p[1], p[2], p[3]), Mat3<S>(row_x, row_y, row_z));  // symmetric: columns = rows
  }

  /// The columns of f = I a + v ×* I v (eqs. 25 and 29) as a function of π, f = Σ_k A_k π_k, by
  /// component: row k of `moments` is A_k's moment (rows 0–9; rows 10–11 are left as they are, for
  /// callers that pad to whole SIMD packets), row k of `forces` its force (k = 0–3; the six Ī columns
  /// are couples). With ω, v_O the parts of v, ω̇, a_O those of a, and g = a_O + ω × v_O:
  ///   m: (0 ; g);   h along e_k: (e_k × g ; ω̇ × e_k − |ω|² e_k + ω_k ω);   Ī_O entry E: (E ω̇ + ω × E ω ; 0),
  /// written out per entry of E (ones at (r, c) and (c, r)).
  static void parameterColumns(const MotionVector<S>& v, const MotionVector<S>& a, Eigen::Matrix<S, 12, 3>& moments,
                               Eigen::Matrix<S, 4, 3>& forces) {
    const Vector3<S> w = v.angular.eigen(), w_dot = a.angular.eigen();
    const Vector3<S> g = (a.linear + cross(v.angular, v.linear)).eigen();
    const S wx = w[0], wy = w[1], wz = w[2], ax = w_dot[0], ay = w_dot[1], az = w_dot[2];
    const S xx = wx * wx, yy = wy * wy, zz = wz * wz, xy = wx * wy, xz = wx * wz, yz = wy * wz;
    moments.template topRows<4>() << S(0), S(0), S(0),
                                     S(0), -g[2], g[1],
                                     g[2], S(0), -g[0],
                                     -g[1], g[0], S(0);
    forces << g[0], g[1], g[2],
              -(yy + zz), az + xy, xz - ay,
              xy - az, -(xx + zz), ax + yz,
              xz + ay, yz - ax, -(xx + yy);
    moments.template middleRows<6>(4) << ax, xz, -xy,          // I_xx
                                         ay - xz, ax + yz, xx - yy,  // I_xy
                                         -yz, ay, xy,          // I_yy
                                         az + xy, zz - xx, ax - yz,  // I_xz
                                         yy - zz, az - xy, ay + xz,  // I_yz
                                         yz, -xz, az;          // I_zz
  }

  /// The 6×6 matrix of eq. (25).
  Matrix6<S> toMatrix() const {
    Matrix6<S> m;
    const Matrix3<S> hx = skew(first_moment).eigen();
    m.template topLeftCorner<3, 3>() = rotational_inertia.eigen();
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
template <class S, class Vector>
ForceVector<S> gravity_force(const RigidInertia<S>& inertia, const Vector& g) {
  return inertia * MotionVector<S>(Vec3<S>(), Vec3<S>(g));
}

/// Time derivative of a body's inertia expressed in fixed coordinates while the body moves with
/// velocity v: d/dt I = v ×* I − I v×   (eq. 27).
template <class S>
Matrix6<S> inertia_time_derivative(const RigidInertia<S>& inertia, const MotionVector<S>& v) {
  const Matrix6<S> I = inertia.toMatrix();
  return force_cross_matrix(v) * I - I * motion_cross_matrix(v);
}

}  // namespace spatial_dynamics
