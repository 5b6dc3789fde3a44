// Per-joint arithmetic of joint_kernels.hpp over L lanes (spatial/lanes.hpp): X_J(q) X_tree,
// S q̇, v × S q̇ and Sᵀ f, each lane holding one state. The joint type and axis are the same in
// every lane, so the dispatch happens once per block of lanes; the arithmetic follows the
// one-state kernels formula by formula.
#pragma once

#include "spatial_dynamics/algorithms/joint_kernels.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/lane_trigonometry.hpp"
#include "spatial_dynamics/spatial/lanes.hpp"

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

/// m += S q̇ (or S q̈); `qd` points at the lanes of the joint's first velocity coordinate.
template <class S, int L>
SD_LANE_INLINE void add_joint_motion(const Joint<S>& j, const Lanes<S, L>* qd, LaneMotion<S, L>& m) {
  switch (j.type) {
    case JointType::Revolute: detail::add_along_axis(j, qd[0], m.angular); return;
    case JointType::Prismatic: detail::add_along_axis(j, qd[0], m.linear); return;
    case JointType::Free:
      for (int k = 0; k < 3; ++k) {
        m.angular[k] += qd[k];
        m.linear[k] += qd[k + 3];
      }
      return;
    case JointType::Planar: return;  // rnea_batch leaves planar joints to the one-state RNEA
  }
}

/// v × S q̇   (eq. 17 with the joint's motion; the zero half of S q̇ skipped)
template <class S, int L>
SD_LANE_INLINE LaneMotion<S, L> joint_motion_cross(const Joint<S>& j, const LaneMotion<S, L>& v,
                                                   const Lanes<S, L>* qd) {
  switch (j.type) {
    case JointType::Revolute:  // S q̇ = (a q̇; 0): (ω × a q̇ ; v × a q̇)
      return {detail::cross_with_axis(j, v.angular, qd[0]), detail::cross_with_axis(j, v.linear, qd[0])};
    case JointType::Prismatic:  // S q̇ = (0; a q̇): (0 ; ω × a q̇)
      return {LaneVector3<S, L>::Zero(), detail::cross_with_axis(j, v.angular, qd[0])};
    case JointType::Free: {
      const LaneMotion<S, L> vJ{{qd[0], qd[1], qd[2]}, {qd[3], qd[4], qd[5]}};
      return cross(v, vJ);
    }
    case JointType::Planar: break;  // rnea_batch leaves planar joints to the one-state RNEA
  }
  return LaneMotion<S, L>::Zero();
}

/// τ = Sᵀ f written to tau[0 .. nv) (lanes of the joint's velocity coordinates).
template <class S, int L>
SD_LANE_INLINE void joint_project_lanes(const Joint<S>& j, const LaneForce<S, L>& f, Lanes<S, L>* tau) {
  switch (j.type) {
    case JointType::Revolute: tau[0] = detail::along_axis_lanes(j, f.angular); return;
    case JointType::Prismatic: tau[0] = detail::along_axis_lanes(j, f.linear); return;
    case JointType::Free:
      for (int k = 0; k < 3; ++k) {
        tau[k] = f.angular[k];
        tau[k + 3] = f.linear[k];
      }
      return;
    case JointType::Planar: return;  // rnea_batch leaves planar joints to the one-state RNEA
  }
}

}  // namespace spatial_dynamics
