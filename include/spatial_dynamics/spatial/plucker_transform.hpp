// Plücker coordinate transform ^BX_A from frame A to frame B, stored as (E, r) and never as a
// 6×6 matrix on the hot path (Featherstone 2010, eqs. 11–12):
//   E  rotates A coordinates into B coordinates,
//   r  is the position of B's origin relative to A's, in A coordinates.
//   ^BX_A  = [ E      0 ]        ^BX_A* = [ E   −E r× ]  = (^BX_A)^-T   (eq. 2)
//            [ −E r×  E ]                 [ 0    E    ]
#pragma once

#include "spatial_dynamics/spatial/articulated_inertia.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/mat3.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"

namespace spatial_dynamics {

template <class S>
struct PluckerTransform {
  Mat3<S> E = Mat3<S>::Identity();
  Vec3<S> r;

  PluckerTransform() = default;
  PluckerTransform(const Mat3<S>& rotation, const Vec3<S>& translation) : E(rotation), r(translation) {}

  static PluckerTransform Identity() { return PluckerTransform(); }

  bool allFinite() const { return E.allFinite() && r.allFinite(); }

  /// From the pose of frame B in frame A: B's axes in A coordinates (R) and B's origin (p).
  static PluckerTransform FromPose(const Mat3<S>& R, const Vec3<S>& p) { return {R.transpose(), p}; }

  /// Pose of B in A: rotation (B's axes in A coordinates) and position of B's origin.
  Mat3<S> rotation() const { return E.transpose(); }
  const Vec3<S>& translation() const { return r; }

  // ---- motions: X m = (E ω ; E (v − r×ω))   (eq. 11) -------------------------------------
  SD_INLINE MotionVector<S> apply(const MotionVector<S>& m) const {
    return {E * m.angular, E * (m.linear - cross(r, m.angular))};
  }
  /// X^-1 m = (Eᵀ ω ; Eᵀ v + r × Eᵀ ω)
  SD_INLINE MotionVector<S> applyInverse(const MotionVector<S>& m) const {
    const Mat3<S> Et = E.transpose();
    const Vec3<S> w = Et * m.angular;
    return {w, Et * m.linear + cross(r, w)};
  }

  // ---- forces: X* f = (E (n − r×f) ; E f)   (eq. 12) ------------------------------------
  SD_INLINE ForceVector<S> apply(const ForceVector<S>& f) const {
    return {E * (f.angular - cross(r, f.linear)), E * f.linear};
  }
  /// (X*)^-1 f = Xᵀ f = (Eᵀ n + r × Eᵀ f ; Eᵀ f); f in S or in S's wider type (the gravity split's).
  template <class T>
  SD_INLINE ForceVector<T> applyInverse(const ForceVector<T>& f) const {
    const Mat3<S> Et = E.transpose();
    const Vec3<T> lin = Et * f.linear;
    return {Et * f.angular + cross(r, lin), lin};
  }

  // ---- rigid inertias: I_B = X* I_A X^-1   (eq. 26) ---------------------------------------
  // The reference point moved to B's origin r, then the axes turned by E; no division by the
  // mass, so massless bodies work.
  SD_INLINE RigidInertia<S> apply(const RigidInertia<S>& I) const { return I.aboutPoint(r).rotated(E); }
  /// I_A = Xᵀ I_B X: the inverse of apply(RigidInertia).
  SD_INLINE RigidInertia<S> applyInverse(const RigidInertia<S>& I) const {
    return I.rotated(E.transpose()).aboutPoint(-r);
  }
  /// out += Xᵀ I X (composite inertias, eq. 26 inverted).
  SD_INLINE void applyInverseAdd(const RigidInertia<S>& I, RigidInertia<S>& out) const { out += applyInverse(I); }

  /// Xᵀ Iᴬ X for an articulated inertia [A B; Bᵀ C] given in B coordinates: with A' = Eᵀ A E,
  /// B' = Eᵀ B E, C' = Eᵀ C E and G = B' + r×C', [A' − G r× + r×B'ᵀ,  G ;  Gᵀ,  C'].
  /// Products with r× are cross products and sums of columns: column k of M r× is M (r × e_k).
  SD_INLINE ArticulatedInertia<S> applyInverse(const ArticulatedInertia<S>& Ia) const {
    const Mat3<S> A = (Ia.A * E).transpose() * E;   // (A E)ᵀ E = Eᵀ A E (A symmetric)
    const Mat3<S> C = (Ia.C * E).transpose() * E;
    const Mat3<S> Bt = (Ia.B * E).transpose() * E;  // (B E)ᵀ E = B'ᵀ
    const Mat3<S> Gt = Bt - C.timesSkew(r);         // Gᵀ = B'ᵀ − C' r× (C' symmetric)
    const Mat3<S> G = Gt.transpose();
    const Mat3<S> top_left = A - G.timesSkew(r) + Bt.skewTimes(r);
    return ArticulatedInertia<S>(top_left, G, C);
  }

  // ---- composition and inverse ----------------------------------------------------------
  /// ^CX_A = ^CX_B ^BX_A:  E = E_CB E_BA,  r = r_BA + E_BAᵀ r_CB.
  PluckerTransform operator*(const PluckerTransform& BA) const { return {E * BA.E, BA.r + BA.E.transposeTimes(r)}; }
  /// ^AX_B = (^BX_A)^-1:  (Eᵀ, −E r).
  PluckerTransform inverse() const { return {E.transpose(), -(E * r)}; }

  // ---- 6×6 forms (tests, not the hot path) ---------------------------------------------------
  Matrix6<S> toMotionMatrix() const {
    Matrix6<S> X = Matrix6<S>::Zero();
    const Matrix3<S> Ee = E.eigen();
    X.template topLeftCorner<3, 3>() = Ee;
    X.template bottomLeftCorner<3, 3>() = -Ee * skew(r.eigen());
    X.template bottomRightCorner<3, 3>() = Ee;
    return X;
  }
  Matrix6<S> toForceMatrix() const {
    Matrix6<S> X = Matrix6<S>::Zero();
    const Matrix3<S> Ee = E.eigen();
    X.template topLeftCorner<3, 3>() = Ee;
    X.template topRightCorner<3, 3>() = -Ee * skew(r.eigen());
    X.template bottomRightCorner<3, 3>() = Ee;
    return X;
  }

  template <class T>
  PluckerTransform<T> cast() const {
    return {E.template cast<T>(), r.template cast<T>()};
  }
};

/// Rotation matrix E of a coordinate transform rotating by angle θ about unit axis a:
/// E = rot(a, θ)ᵀ = cos θ 1 − sin θ a× + (1 − cos θ) a aᵀ (RBDA eq. 2.24, transposed).
template <class S>
Mat3<S> coordinate_rotation(const Vec3<S>& axis, const S& angle) {
  using std::cos;
  using std::sin;
  const S c = cos(angle), s = sin(angle);
  return Mat3<S>::Identity() * c - skew(axis) * s + Mat3<S>::Outer(axis, axis) * (S(1) - c);
}

}  // namespace spatial_dynamics
