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
#include "spatial_dynamics/spatial/number/packed3.hpp"
#include "spatial_dynamics/spatial/number/packed3_articulated_inertia.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"
#include "spatial_dynamics/spatial/rotation_about_axis.hpp"

namespace spatial_dynamics {

template <class S>
struct PluckerTransform {
  Matrix3<S> E = Matrix3<S>::Identity();
  Vector3<S> r = Vector3<S>::Zero();

  PluckerTransform() = default;
  PluckerTransform(const Matrix3<S>& rotation, const Vector3<S>& translation) : E(rotation), r(translation) {}

  static PluckerTransform Identity() { return PluckerTransform(); }

  bool allFinite() const { return E.allFinite() && r.allFinite(); }

  /// From the pose of frame B in frame A: B's axes in A coordinates (R) and B's origin (p).
  static PluckerTransform FromPose(const Matrix3<S>& R, const Vector3<S>& p) { return {R.transpose(), p}; }

  /// Pose of B in A: rotation (B's axes in A coordinates) and position of B's origin.
  Matrix3<S> rotation() const { return E.transpose(); }
  const Vector3<S>& translation() const { return r; }

  // ---- motions: X m = (E ω ; E (v − r×ω))   (eq. 11) -------------------------------------
  SD_INLINE MotionVector<S> apply(const MotionVector<S>& m) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      using namespace packed3;
      Packed3 c0, c1, c2;
      load_columns(E, c0, c1, c2);
      const Packed3 w = load3(m.angular), v = load3(m.linear);
      return {to_vector3(mat_vec(c0, c1, c2, w)), to_vector3(mat_vec(c0, c1, c2, v - cross(load3(r), w)))};
    }
#endif
    return {E * m.angular, E * (m.linear - cross_3d(r, m.angular))};
  }
  /// X^-1 m = (Eᵀ ω ; Eᵀ v + r × Eᵀ ω)
  SD_INLINE MotionVector<S> applyInverse(const MotionVector<S>& m) const {
    const Vector3<S> w = E.transpose() * m.angular;
    return {w, E.transpose() * m.linear + cross_3d(r, w)};
  }

  // ---- forces: X* f = (E (n − r×f) ; E f)   (eq. 12) ------------------------------------
  SD_INLINE ForceVector<S> apply(const ForceVector<S>& f) const {
    return {E * (f.angular - cross_3d(r, f.linear)), E * f.linear};
  }
  /// (X*)^-1 f = Xᵀ f = (Eᵀ n + r × Eᵀ f ; Eᵀ f)
  SD_INLINE ForceVector<S> applyInverse(const ForceVector<S>& f) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      using namespace packed3;
      Packed3 c0, c1, c2, t0, t1, t2;
      load_columns(E, c0, c1, c2);
      transpose(c0, c1, c2, t0, t1, t2);
      const Packed3 lin = mat_vec(t0, t1, t2, load3(f.linear));
      return {to_vector3(mat_vec(t0, t1, t2, load3(f.angular)) + cross(load3(r), lin)), to_vector3(lin)};
    }
#endif
    const Vector3<S> lin = E.transpose() * f.linear;
    return {E.transpose() * f.angular + cross_3d(r, lin), lin};
  }

  // ---- rigid inertias: I_B = X* I_A X^-1   (eq. 26) ---------------------------------------
  // Shifting the reference point by r: h' = h − m r, Ī' = Ī_O + h×r× + r×h× − m r×r×,
  // then rotating: h_B = E h', Ī_B = E Ī' Eᵀ. No division by the mass, so massless bodies work.
  // With a×b× = b aᵀ − (a·b)1 the shift is symmetric rank-2 terms (shift_rotational_inertia).
  RigidInertia<S> apply(const RigidInertia<S>& I) const {
    const Matrix3<S> shifted = shift_rotational_inertia(I.rotational_inertia, I.first_moment, I.mass, r, S(1));
    return RigidInertia<S>(I.mass, E * (I.first_moment - I.mass * r), rotate_symmetric(E, shifted));
  }
  /// I_A = Xᵀ I_B X: the inverse of apply(RigidInertia).
  RigidInertia<S> applyInverse(const RigidInertia<S>& I) const {
    const Vector3<S> h = E.transpose() * I.first_moment;  // first moment about B's origin, A axes
    const Matrix3<S> rotated = rotate_symmetric(Matrix3<S>(E.transpose()), I.rotational_inertia);
    return RigidInertia<S>(I.mass, h + I.mass * r, shift_rotational_inertia(rotated, h, I.mass, r, S(-1)));
  }

  /// out += Xᵀ I X (the CRBA's composite inertias, eq. 26 inverted), with the same terms as
  /// applyInverse: h' = Eᵀ h, Ī' = Eᵀ Ī E (lower triangle, from T = Ī E), then the shift by r
  /// with σ = −1 and h_A = h' + m r. Written out so that no 3×3 temporary reaches memory.
  SD_INLINE void applyInverseAdd(const RigidInertia<S>& I, RigidInertia<S>& out) const {
    const Matrix3<S>& Ib = I.rotational_inertia;
    const S m = I.mass;
    S h[3], mr[3], T[3][3];  // T[c] = column c of Ī E
    for (int c = 0; c < 3; ++c) {
      h[c] = E(0, c) * I.first_moment[0] + E(1, c) * I.first_moment[1] + E(2, c) * I.first_moment[2];
      mr[c] = m * r[c];
      for (int k = 0; k < 3; ++k) T[c][k] = Ib(k, 0) * E(0, c) + Ib(k, 1) * E(1, c) + Ib(k, 2) * E(2, c);
    }
    const S diagonal = (mr[0] * r[0] + mr[1] * r[1] + mr[2] * r[2]) + S(2) * (h[0] * r[0] + h[1] * r[1] + h[2] * r[2]);
    Matrix3<S>& Io = out.rotational_inertia;
    for (int c = 0; c < 3; ++c)
      for (int k = c; k < 3; ++k) {
        const S rotated = E(0, k) * T[c][0] + E(1, k) * T[c][1] + E(2, k) * T[c][2];  // (Eᵀ Ī E)(k, c)
        const S v = rotated - r[k] * h[c] - h[k] * r[c] - mr[k] * r[c] + (k == c ? diagonal : S(0));
        Io(k, c) += v;
        if (k != c) Io(c, k) += v;
      }
    for (int c = 0; c < 3; ++c) out.first_moment[c] += h[c] + mr[c];
    out.mass += m;
  }

  /// Ī + σ(h×r× + r×h×) − m r×r× = Ī + σ(r hᵀ + h rᵀ − 2(h·r)1) − m(r rᵀ − (r·r)1), symmetric.
  static Matrix3<S> shift_rotational_inertia(const Matrix3<S>& I, const Vector3<S>& h, const S& m, const Vector3<S>& r,
                                             const S& sigma) {
    // m r is formed first, so a massless body far away gives 0, not 0 · ∞.
    const Vector3<S> sh = sigma * h;
    const Vector3<S> mr = m * r;
    const S diagonal = mr.dot(r) - S(2) * sh.dot(r);
    Matrix3<S> out;
    for (int c = 0; c < 3; ++c)
      for (int k = c; k < 3; ++k) {
        const S v = I(k, c) + r[k] * sh[c] + sh[k] * r[c] - mr[k] * r[c] + (k == c ? diagonal : S(0));
        out(k, c) = v;
        out(c, k) = v;
      }
    return out;
  }
  /// R Ī Rᵀ for a symmetric Ī, its upper triangle copied from the lower so that it is exactly symmetric.
  static Matrix3<S> rotate_symmetric(const Matrix3<S>& R, const Matrix3<S>& I) {
    Matrix3<S> out = R * I * R.transpose();
    out(0, 1) = out(1, 0);
    out(0, 2) = out(2, 0);
    out(1, 2) = out(2, 1);
    return out;
  }

  /// Xᵀ Iᴬ X for an articulated inertia [A B; Bᵀ C] given in B coordinates, with
  /// A' = Eᵀ A E etc.:  [A' − B'r× + r×B'ᵀ − r×C'r×,  B' + r×C' ;  B'ᵀ − C'r×,  C'].
  /// Row k of B'r× is b'_k × r, column c of r×C' is r × c'_c, and row k of r×C'r× is
  /// (row k of r×C') × r: cross products instead of products with skew matrices.
  ArticulatedInertia<S> applyInverse(const ArticulatedInertia<S>& Ia) const {
    ArticulatedInertia<S> out;  // zero
    applyInverseAdd(Ia, out);
    return out;
  }
  /// out += Xᵀ Iᴬ X: the ABA's inward accumulation without a temporary 6×6 matrix; with
  /// `out_base`, out = *out_base + Xᵀ Iᴬ X (the first child's step, out's rigid inertia not yet in it).
  SD_INLINE void applyInverseAdd(const ArticulatedInertia<S>& Ia, ArticulatedInertia<S>& out,
                                 const RigidInertia<S>* out_base = nullptr) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<S, double>::value) {
      packed3::RigidColumns base;
      if (out_base) base = packed3::rigid_columns(out_base->mass, out_base->first_moment, out_base->rotational_inertia);
      packed3::add_transformed(E, r, packed3::load_blocks(Ia.matrix), out.matrix, -1, 0, 1, nullptr,
                               out_base ? &base : nullptr);
      return;
    }
#endif
    if (out_base) out.assign(*out_base);
    const Matrix3<S> Et = E.transpose();
    const Matrix3<S> A = Et * Ia.matrix.template topLeftCorner<3, 3>() * E;
    const Matrix3<S> B = Et * Ia.matrix.template topRightCorner<3, 3>() * E;
    const Matrix3<S> C = Et * Ia.matrix.template bottomRightCorner<3, 3>() * E;
    Matrix3<S> Brx, rxC, rxCrx;
    for (int k = 0; k < 3; ++k) {
      Brx.row(k) = Vector3<S>(B.row(k).transpose()).cross(r).transpose();
      rxC.col(k) = r.cross(Vector3<S>(C.col(k)));
    }
    for (int k = 0; k < 3; ++k) rxCrx.row(k) = Vector3<S>(rxC.row(k).transpose()).cross(r).transpose();
    const Matrix3<S> B_plus_rxC = B + rxC;
    out.matrix.template topLeftCorner<3, 3>() += A - Brx - Brx.transpose() - rxCrx;
    out.matrix.template topRightCorner<3, 3>() += B_plus_rxC;
    out.matrix.template bottomLeftCorner<3, 3>() += B_plus_rxC.transpose();
    out.matrix.template bottomRightCorner<3, 3>() += C;
  }

  /// out += Xᵀ Iᵃ X for Iᵃ = Iᴬ − U D⁻¹ Uᵀ at a 1-DoF joint (U = Iᴬ S, RBDA Table 7.1), and
  /// Iᵃ c returned: the ABA's inward step at such a joint, without forming Iᵃ in memory. The
  /// downdate is subtracted after the transform, as W D⁻¹ Wᵀ with W = Xᵀ U (the caller's, U taken
  /// to the parent as a force), so that the transform of Iᴬ does not wait for D⁻¹. U = (U_w ; U_v)
  /// and W = (W_n ; W_f) by their halves, as the caller's 3-vectors hold them (V: packed3's
  /// registers for double where SD_PACKED3 is defined, else Vector3<S>). `about` may tell that E
  /// is a rotation about a coordinate axis (the packed products then take its structure). With
  /// `out_base`, out = *out_base + Xᵀ Iᵃ X, as applyInverseAdd.
  template <class V>
  SD_INLINE ForceVector<S> applyInverseAddLessRankOne(const ArticulatedInertia<S>& Ia, const V& U_w, const V& U_v,
                                                      const S& D_inv, const V& W_n, const V& W_f,
                                                      const MotionVector<S>& c, ArticulatedInertia<S>& out,
                                                      const RotationAboutAxis<S>& about = {},
                                                      const RigidInertia<S>* out_base = nullptr) const {
#ifdef SD_PACKED3
    if constexpr (std::is_same<V, packed3::Packed3>::value) {
      using namespace packed3;
      const InertiaBlocks blocks = load_blocks(Ia.matrix);
      Packed3 top, bottom;  // Iᴬ c
      times_motion(blocks, c.angular.data(), c.linear.data(), top, bottom);
      const Packed3 d = splat(D_inv);
      const RankOne downdate{W_n, W_f, W_n * d, W_f * d};  // W D⁻¹ Wᵀ
      RigidColumns base;
      if (out_base) base = rigid_columns(out_base->mass, out_base->first_moment, out_base->rotational_inertia);
      add_transformed(E, r, blocks, out.matrix, about.axis, about.s, about.c, &downdate, out_base ? &base : nullptr);
      const Packed3 uc = U_w * load3(c.angular) + U_v * load3(c.linear);
      const Packed3 k = splat(D_inv * (uc[0] + uc[1] + uc[2]));                // D⁻¹ Uᵀ c
      return {to_vector3(top - U_w * k), to_vector3(bottom - U_v * k)};         // Iᵃ c = Iᴬ c − U D⁻¹ Uᵀ c
    } else
#endif
    {
      static_cast<void>(about);  // the Eigen products take E's coefficients
      Vector6<S> U, W;
      U << U_w, U_v;
      W << W_n, W_f;
      applyInverseAdd(Ia, out, out_base);
      out.matrix -= W * (D_inv * W.transpose());
      return ForceVector<S>((Ia * c).toVector() - U * (D_inv * U.dot(c.toVector())));
    }
  }

  // ---- composition and inverse ----------------------------------------------------------
  /// ^CX_A = ^CX_B ^BX_A:  E = E_CB E_BA,  r = r_BA + E_BAᵀ r_CB.
  PluckerTransform operator*(const PluckerTransform& BA) const {
    return {E * BA.E, BA.r + BA.E.transpose() * r};
  }
  /// ^AX_B = (^BX_A)^-1:  (Eᵀ, −E r).
  PluckerTransform inverse() const { return {E.transpose(), -(E * r)}; }

  // ---- 6×6 forms (tests, not the hot path) ---------------------------------------------------
  Matrix6<S> toMotionMatrix() const {
    Matrix6<S> X = Matrix6<S>::Zero();
    X.template topLeftCorner<3, 3>() = E;
    X.template bottomLeftCorner<3, 3>() = -E * skew(r);
    X.template bottomRightCorner<3, 3>() = E;
    return X;
  }
  Matrix6<S> toForceMatrix() const {
    Matrix6<S> X = Matrix6<S>::Zero();
    X.template topLeftCorner<3, 3>() = E;
    X.template topRightCorner<3, 3>() = -E * skew(r);
    X.template bottomRightCorner<3, 3>() = E;
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
Matrix3<S> coordinate_rotation(const Vector3<S>& axis, const S& angle) {
  using std::cos;
  using std::sin;
  const S c = cos(angle), s = sin(angle);
  return c * Matrix3<S>::Identity() - s * skew(axis) + (S(1) - c) * axis * axis.transpose();
}

}  // namespace spatial_dynamics
