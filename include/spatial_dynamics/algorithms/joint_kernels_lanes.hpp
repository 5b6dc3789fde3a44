// Per-joint arithmetic of joint_kernels.hpp over L lanes (spatial/number/lanes.hpp): X_J(q) X_tree,
// S q̇ and Sᵀ f, each lane holding one state, and the lanes' form of the RNEA's passes (rnea.hpp).
// The joint type and axis are the same in every lane, so the dispatch happens once per block of
// lanes; the arithmetic follows the one-state kernels formula by formula.
#pragma once

#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/number/lane_trigonometry.hpp"
#include "spatial_dynamics/spatial/number/lanes.hpp"

namespace spatial_dynamics {
namespace detail {

/// Rows (m, n) of E become (c·row_m + s·row_n, −s·row_m + c·row_n) of the constant E_t, as
/// rotate_rows; the third row stays E_t's.
template <class S, int L>
SD_LANE_INLINE void rotate_rows_lanes(const Matrix3<S>& Et, int m, int n, const Lanes<S, L>& c, const Lanes<S, L>& s,
                              LaneMatrix3<S, L>& E) {
  const int k = 3 - m - n;
  for (int col = 0; col < 3; ++col) {
    E.m[m][col] = c * Et(m, col) + s * Et(n, col);
    E.m[n][col] = c * Et(n, col) - s * Et(m, col);
    E.m[k][col] = Lanes<S, L>::Constant(Et(k, col));
  }
}

/// a × (e_axis k) for an axis-aligned unit vector, k per lane: two products instead of six.
template <class S, int L>
SD_LANE_INLINE LaneVector3<S, L> cross_with_axis(const Joint<S>& j, const LaneVector3<S, L>& a, const Lanes<S, L>& k) {
  using Lane = Lanes<S, L>;
  switch (j.axis_kind) {
    case AxisKind::X: return {Lane::Zero(), a.z * k, -(a.y * k)};
    case AxisKind::Y: return {-(a.z * k), Lane::Zero(), a.x * k};
    case AxisKind::Z: return {a.y * k, -(a.x * k), Lane::Zero()};
    default: return a.cross({j.axis.x() * k, j.axis.y() * k, j.axis.z() * k});
  }
}

/// v += a k for the joint's axis a, k per lane.
template <class S, int L>
SD_LANE_INLINE void add_along_axis(const Joint<S>& j, const Lanes<S, L>& k, LaneVector3<S, L>& v) {
  switch (j.axis_kind) {
    case AxisKind::X: v.x += k; return;
    case AxisKind::Y: v.y += k; return;
    case AxisKind::Z: v.z += k; return;
    default:
      v.x += j.axis.x() * k;
      v.y += j.axis.y() * k;
      v.z += j.axis.z() * k;
      return;
  }
}

/// a · x for the joint's axis.
template <class S, int L>
SD_LANE_INLINE Lanes<S, L> along_axis_lanes(const Joint<S>& j, const LaneVector3<S, L>& x) {
  switch (j.axis_kind) {
    case AxisKind::X: return x.x;
    case AxisKind::Y: return x.y;
    case AxisKind::Z: return x.z;
    default: return j.axis.x() * x.x + j.axis.y() * x.y + j.axis.z() * x.z;
  }
}

}  // namespace detail

/// ^iX_λ(i) = X_J(q_i) X_tree(i) per lane (RBDA Table 4.1); `q` points at the lanes of the joint's
/// first coordinate. A free joint's quaternion must already have been checked for unit norm.
template <class S, int L>
SD_LANE_INLINE void joint_up_transform_lanes(const Model<S>& model, int i, const Lanes<S, L>* q,
                                             LaneTransform<S, L>& X) {
  using Lane = Lanes<S, L>;
  const Joint<S>& j = model.joints[i];
  const PluckerTransform<S>& Xt = model.X_tree[i];
  switch (j.type) {
    case JointType::Revolute: {
      Lane c, s;
      sincos_lanes(q[0], s, c);
      X.r = LaneVector3<S, L>::Constant(Xt.r);
      switch (j.axis_kind) {
        case AxisKind::X: detail::rotate_rows_lanes(Xt.E, 1, 2, c, s, X.E); break;
        case AxisKind::Y: detail::rotate_rows_lanes(Xt.E, 2, 0, c, s, X.E); break;
        case AxisKind::Z: detail::rotate_rows_lanes(Xt.E, 0, 1, c, s, X.E); break;
        default: {
          // E = (c 1 − s a× + (1 − c) a aᵀ) E_t   (RBDA eq. 2.24, transposed; coordinate_rotation)
          const Vector3<S>& a = j.axis;
          const Matrix3<S> ax = skew(a);
          const Lane one_minus_c = S(1) - c;
          Lane R[3][3];
          for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) {
              const Lane diagonal = r == k ? c : Lane(Lane::Zero());
              R[r][k] = diagonal - s * ax(r, k) + (one_minus_c * a[r]) * a[k];
            }
          for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 3; ++col)
              X.E.m[r][col] = R[r][0] * Xt.E(0, col) + R[r][1] * Xt.E(1, col) + R[r][2] * Xt.E(2, col);
          break;
        }
      }
      return;
    }
    case JointType::Prismatic: {
      // E = E_t, r = r_t + E_tᵀ (a q)
      X.E = LaneMatrix3<S, L>::Constant(Xt.E);
      const LaneVector3<S, L> aq{j.axis.x() * q[0], j.axis.y() * q[0], j.axis.z() * q[0]};
      X.r = LaneVector3<S, L>::Constant(Xt.r) + LaneMatrix3<S, L>::Constant(Xt.E).transposeTimes(aq);
      return;
    }
    case JointType::Free: {
      // q = (x y z qx qy qz qw): X_J = (Rᵀ, p), R from the unit quaternion (Eigen's formula).
      const Lane& qx = q[3];
      const Lane& qy = q[4];
      const Lane& qz = q[5];
      const Lane& qw = q[6];
      const Lane tx = S(2) * qx, ty = S(2) * qy, tz = S(2) * qz;
      const Lane twx = tx * qw, twy = ty * qw, twz = tz * qw;
      const Lane txx = tx * qx, txy = ty * qx, txz = tz * qx;
      const Lane tyy = ty * qy, tyz = tz * qy, tzz = tz * qz;
      Lane R[3][3];
      R[0][0] = S(1) - (tyy + tzz);
      R[0][1] = txy - twz;
      R[0][2] = txz + twy;
      R[1][0] = txy + twz;
      R[1][1] = S(1) - (txx + tzz);
      R[1][2] = tyz - twx;
      R[2][0] = txz - twy;
      R[2][1] = tyz + twx;
      R[2][2] = S(1) - (txx + tyy);
      for (int r = 0; r < 3; ++r)  // E = Rᵀ E_t
        for (int col = 0; col < 3; ++col)
          X.E.m[r][col] = R[0][r] * Xt.E(0, col) + R[1][r] * Xt.E(1, col) + R[2][r] * Xt.E(2, col);
      const LaneVector3<S, L> p{q[0], q[1], q[2]};
      X.r = LaneVector3<S, L>::Constant(Xt.r) + LaneMatrix3<S, L>::Constant(Xt.E).transposeTimes(p);
      return;
    }
    case JointType::Planar: return;  // rnea_batch leaves planar joints to the one-state RNEA
  }
}

/// S q̇ (or S q̈) as its angular part w and linear part v; `qd` points at the lanes of the joint's
/// first velocity coordinate.
template <class S, int L>
SD_LANE_INLINE void joint_motion_lanes(const Joint<S>& j, const Lanes<S, L>* qd, LaneVector3<S, L>& w,
                                       LaneVector3<S, L>& v) {
  w = LaneVector3<S, L>::Zero();
  v = LaneVector3<S, L>::Zero();
  switch (j.type) {
    case JointType::Revolute: detail::add_along_axis(j, qd[0], w); return;
    case JointType::Prismatic: detail::add_along_axis(j, qd[0], v); return;
    case JointType::Free:
      w = {qd[0], qd[1], qd[2]};
      v = {qd[3], qd[4], qd[5]};
      return;
    case JointType::Planar: return;  // rnea_batch leaves planar joints to the one-state RNEA
  }
}

/// τ = Sᵀ (n ; f) written to tau[0 .. nv) (lanes of the joint's velocity coordinates).
template <class S, int L>
SD_LANE_INLINE void joint_project_lanes(const Joint<S>& j, const LaneVector3<S, L>& n, const LaneVector3<S, L>& f,
                                        Lanes<S, L>* tau) {
  switch (j.type) {
    case JointType::Revolute: tau[0] = detail::along_axis_lanes(j, n); return;
    case JointType::Prismatic: tau[0] = detail::along_axis_lanes(j, f); return;
    case JointType::Free:
      for (int k = 0; k < 3; ++k) {
        tau[k] = n[k];
        tau[k + 3] = f[k];
      }
      return;
    case JointType::Planar: return;  // rnea_batch leaves planar joints to the one-state RNEA
  }
}

namespace vec3 {

/// The RNEA's form on L states (rnea_passes in rnea.hpp, `work` a BatchData<S, L>): each 3-vector
/// a LaneVector3, each coordinate a Lanes; the model's constants the same in every lane. Models
/// with coupled joints or planar joints take the one-state forms (rnea_batch.hpp).
template <class S, int L>
struct LanesForm {
  using Scalar = Lanes<S, L>;
  using Vector = LaneVector3<S, L>;
  struct Rotation {  // E, kept in the body's storage
    const LaneMatrix3<S, L>* E;
  };
  struct TransposedRotation {
    const LaneMatrix3<S, L>* E;
  };

  // Copied lane by lane: a copy of the whole 96-byte struct is compiled to 16-byte moves, which
  // the next 32-byte loads of the same lanes then wait for (failed store forwarding).
  static SD_LANE_INLINE Vector load(const Vector& v) { return {v.x, v.y, v.z}; }
  static SD_LANE_INLINE Vector load(const Vector3<S>& v) { return Vector::Constant(v); }
  static SD_LANE_INLINE void store(const Vector& x, Vector& out) {
    out.x = x.x;
    out.y = x.y;
    out.z = x.z;
  }
  static SD_LANE_INLINE Vector times(const Rotation& R, const Vector& x) { return *R.E * x; }
  static SD_LANE_INLINE Vector times(const TransposedRotation& R, const Vector& x) { return R.E->transposeTimes(x); }
  static SD_LANE_INLINE Vector cross(const Vector& a, const Vector& b) { return a.cross(b); }
  /// The lanes' states each rotate by an angle of their own: every E is taken by its
  /// coefficients (no RotationAboutAxis), and its transpose too.
  struct NoRotationStructure {
    friend NoRotationStructure transposed(NoRotationStructure none) { return none; }
  };
  template <class Work>
  static SD_LANE_INLINE NoRotationStructure up_rotation(const Work&, int) {
    return {};
  }
  template <class R>
  static SD_LANE_INLINE void times_pair(NoRotationStructure, const R& E, Vector& x, Vector& y) {
    x = times(E, x);
    y = times(E, y);
  }
  template <class Body>
  static SD_LANE_INLINE TransposedRotation transposed_rotation(const Body& b) {
    return {&b.X.E};
  }
  template <class Body>
  static SD_LANE_INLINE Vector translation(const Body& b) {
    return load(b.X.r);
  }

  static SD_LANE_INLINE void add_axis(const Joint<S>& j, const Scalar& k, Vector& x) { detail::add_along_axis(j, k, x); }
  static SD_LANE_INLINE Vector cross_axis(const Joint<S>& j, const Vector& x, const Scalar& k) {
    return detail::cross_with_axis(j, x, k);
  }
  static SD_LANE_INLINE Scalar dot_axis(const Joint<S>& j, const Vector& x) { return detail::along_axis_lanes(j, x); }

  /// I (ω ; v) = (Ī_O ω + h × v ; m v − h × ω)   (eq. 25)
  static SD_LANE_INLINE void inertia_times(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n,
                                           Vector& f) {
    n = I.rotational_inertia * w + spatial_dynamics::cross(I.first_moment, v);
    f = Scalar::Constant(I.mass) * v - spatial_dynamics::cross(I.first_moment, w);
  }
  /// v ×* I v = (ω × Ī_O ω + h × (ω × v) ; m (ω × v) − ω × (h × ω)) (eq. 29 on eq. 25, as
  /// rigid_inertia.hpp's biasForce): without v × m v, zero but rounded to the size of m |v|².
  static SD_LANE_INLINE void bias_force(const RigidInertia<S>& I, const Vector& w, const Vector& v, Vector& n,
                                        Vector& f) {
    const Vector w_x_v = w.cross(v);
    n = w.cross(I.rotational_inertia * w) + spatial_dynamics::cross(I.first_moment, w_x_v);
    f = Scalar::Constant(I.mass) * w_x_v - w.cross(spatial_dynamics::cross(I.first_moment, w));
  }

  template <class Work, class Body>
  static SD_LANE_INLINE void up_transform(const Model<S>& model, Work&, int i, const Scalar* q, Body& b, Rotation& E,
                                          Vector& r) {
    joint_up_transform_lanes(model, i, q + model.joints[i].idx_q, b.X);
    E.E = &b.X.E;
    r = load(b.X.r);
  }
  /// S q̇ and S q̈ + c_J of a joint with several coordinates (a free joint: c_J = 0).
  template <class Work>
  static SD_LANE_INLINE void joint_motion(const Model<S>& model, const Work&, int i, const Scalar* qd,
                                          const Scalar* qdd, Vector& vw, Vector& vv, Vector& aw, Vector& al) {
    const Joint<S>& j = model.joints[i];
    joint_motion_lanes(j, qd + j.idx_v, vw, vv);   // S q̇
    joint_motion_lanes(j, qdd + j.idx_v, aw, al);  // S q̈ (c_J = 0)
  }
  template <class Work>
  static SD_LANE_INLINE void store_force(const Model<S>& model, const Work&, int i, const Vector& n, const Vector& f,
                                         Scalar* tau, bool) {
    const Joint<S>& j = model.joints[i];
    joint_project_lanes(j, n, f, tau + j.idx_v);
  }
};

}  // namespace vec3
}  // namespace spatial_dynamics
