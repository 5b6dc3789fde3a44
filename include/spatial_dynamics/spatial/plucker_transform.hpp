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
  /// (X*)^-1 f = Xᵀ f = (Eᵀ n + r × Eᵀ f ; Eᵀ f)
  SD_INLINE ForceVector<S> applyInverse(const ForceVector<S>& f) const {
    const Mat3<S> Et = E.transpose();
    const Vec3<S> lin = Et * f.linear;
    return {Et * f.angular + cross(r, lin), lin};
  }

  // ---- rigid inertias: I_B = X* I_A X^-1   (eq. 26) ---------------------------------------
  // Shifting the reference point by r: h' = h − m r, Ī' = Ī_O + h×r× + r×h× − m r×r×,
  // then rotating: h_B = E h', Ī_B = E Ī' Eᵀ. No division by the mass, so massless bodies work.
  // With a×b× = b aᵀ − (a·b)1 the shift is symmetric rank-2 terms (shift_rotational_inertia).
  RigidInertia<S> apply(const RigidInertia<S>& I) const {
    const Mat3<S> shifted = shift_rotational_inertia(I.rotational_inertia, I.first_moment, I.mass, r, S(1));
    return RigidInertia<S>(I.mass, E * (I.first_moment - r * I.mass), rotate_symmetric(E, shifted));
  }
  /// I_A = Xᵀ I_B X: the inverse of apply(RigidInertia).
  SD_INLINE RigidInertia<S> applyInverse(const RigidInertia<S>& I) const {
    const Mat3<S> Et = E.transpose();
    const Vec3<S> h = Et * I.first_moment;                     // first moment about B's origin, A axes
    const Mat3<S> rotated = (Et * I.rotational_inertia) * E;  // Eᵀ Ī E (the shift reads its lower triangle)
    return RigidInertia<S>(I.mass, h + r * I.mass, shift_rotational_inertia(rotated, h, I.mass, r, S(-1)));
  }
  /// out += Xᵀ I X (the CRBA's composite inertias, eq. 26 inverted).
  SD_INLINE void applyInverseAdd(const RigidInertia<S>& I, RigidInertia<S>& out) const { out += applyInverse(I); }

  /// Ī + σ(h×r× + r×h×) − m r×r× = Ī + σ(r hᵀ + h rᵀ − 2(h·r)1) − m(r rᵀ − (r·r)1), its lower
  /// triangle computed from Ī's and copied to the upper one (exactly symmetric).
  static SD_INLINE Mat3<S> shift_rotational_inertia(const Mat3<S>& I, const Vec3<S>& h, const S& m, const Vec3<S>& r,
                                                    const S& sigma) {
    // m r is formed first, so a massless body far away gives 0, not 0 · ∞.
    const Vec3<S> sh = h * sigma;
    const Vec3<S> mr = r * m;
    const S diagonal = dot(mr, r) - S(2) * dot(sh, r);
    const Vec3<S> sh_less_mr = sh - mr;
    Mat3<S> out;
    for (int c = 0; c < 3; ++c)  // column c: I_c + r sh_c + (sh − mr) r_c, then + diagonal e_c
      out.column[c] = I.column[c] + (r * sh[c] + sh_less_mr * r[c]);
    out = out.plusDiagonal(diagonal);
    out.symmetrize_from_lower();
    return out;
  }
  /// R Ī Rᵀ for a symmetric Ī, its upper triangle copied from the lower so that it is exactly symmetric.
  static SD_INLINE Mat3<S> rotate_symmetric(const Mat3<S>& R, const Mat3<S>& I) {
    Mat3<S> out = (R * I) * R.transpose();
    out.symmetrize_from_lower();
    return out;
  }

  /// Xᵀ Iᴬ X for an articulated inertia [A B; Bᵀ C] given in B coordinates: with A' = Eᵀ A E,
  /// B' = Eᵀ B E and C' = Eᵀ C E, [A' − B'r× − (B'r×)ᵀ − r×C'r×,  B' + r×C' ;  ·,  C'].
  SD_INLINE ArticulatedInertia<S> applyInverse(const ArticulatedInertia<S>& Ia) const {
    const Mat3<S> Et = E.transpose(), rx = Mat3<S>::Skew(r);
    const Mat3<S> A = (Et * Ia.A) * E, B = (Et * Ia.B) * E, C = (Et * Ia.C) * E;
    const Mat3<S> B_rx = B * rx, rx_C = rx * C;
    ArticulatedInertia<S> out(A - B_rx - B_rx.transpose() - rx_C * rx, B + rx_C, C);
    out.A.symmetrize_from_lower();  // symmetric blocks stay exactly symmetric
    out.C.symmetrize_from_lower();
    return out;
  }
  /// out += Xᵀ Iᴬ X: the ABA's inward accumulation.
  SD_INLINE void applyInverseAdd(const ArticulatedInertia<S>& Ia, ArticulatedInertia<S>& out) const {
    out += applyInverse(Ia);
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
