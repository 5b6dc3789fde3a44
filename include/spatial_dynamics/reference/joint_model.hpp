// The reference's joint calculation (spatial_v2's jcalc): the joint transform X_J(q) and the
// motion subspace S of the model's joint types (RBDA Table 4.1), written from the axis and the
// quaternion alone, and the map from the model's coordinates to every body's own joint
// coordinates, which a coupled mimic joint shares with its master.
#pragma once

#include <cmath>
#include <stdexcept>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reference/spatial_matrices.hpp"

namespace spatial_dynamics {
namespace reference {

/// Coordinate rotation E by angle θ about the unit axis a (the transpose of Rodrigues' rotation
/// matrix): E = cos θ 1 − sin θ a× + (1 − cos θ) a aᵀ   (RBDA Table 4.1, revolute, for any axis).
template <class S>
Mat3<S> axis_rotation(const Vec3<S>& a, const S& theta) {
  using std::cos;
  using std::sin;
  const S c = cos(theta), s = sin(theta);
  return c * Mat3<S>::Identity() - s * skew3(a) + (S(1) - c) * a * a.transpose();
}

/// Coordinate rotation E of the unit quaternion (w; x, y, z) whose rotation matrix R turns the
/// body's axes into the parent's: E = Rᵀ   (RBDA eq. 4.12; its diagonal 2(w² + x²) − 1 written as
/// 1 − 2(y² + z²), equal for a unit quaternion).
template <class S>
Mat3<S> quaternion_rotation(const S& w, const S& x, const S& y, const S& z) {
  Mat3<S> E;
  E << S(1) - S(2) * (y * y + z * z), S(2) * (x * y + w * z), S(2) * (x * z - w * y),
       S(2) * (x * y - w * z), S(1) - S(2) * (x * x + z * z), S(2) * (y * z + w * x),
       S(2) * (x * z + w * y), S(2) * (y * z - w * x), S(1) - S(2) * (x * x + y * y);
  return E;
}

/// X_J(q) of one joint, q its own coordinates (RBDA Table 4.1):
///   revolute   X_J = rot(E(a, q)),
///   prismatic  X_J = xlt(q a),
///   free       X_J = rot(E) xlt(p), q = (p; quaternion x y z w), E = Rᵀ of the quaternion,
///   planar     X_J = rot(E(n, ψ)) xlt(x e₁ + y e₂), q = (x, y, ψ),
///   helical    X_J = rot(E(a, q)) xlt(h q a), h the pitch.
template <class S>
Mat6<S> joint_transform(const Joint<S>& j, const VectorArg<S>& q) {
  switch (j.type) {
    case JointType::Revolute: return rot(axis_rotation<S>(j.axis, q[0]));
    case JointType::Prismatic: return xlt<S>(q[0] * j.axis);
    case JointType::Free: return plucker(quaternion_rotation(q[6], q[3], q[4], q[5]), Vec3<S>(q[0], q[1], q[2]));
    case JointType::Planar: return plucker(axis_rotation<S>(j.axis, q[2]), Vec3<S>(q[0] * j.plane_x + q[1] * j.plane_y));
    case JointType::Helical: return plucker(axis_rotation<S>(j.axis, q[0]), Vec3<S>(j.pitch * q[0] * j.axis));
  }
  throw std::invalid_argument("reference: unknown joint type");
}

/// S of one joint, 6 × n_v, constant in joint coordinates (RBDA Table 4.1): (a; 0) revolute,
/// (0; a) prismatic, 1 (q̇ = (ω; v) in body coordinates) free, (a; h a) helical.
template <class S>
Mat6X<S> motion_subspace(const Joint<S>& j) {
  switch (j.type) {
    case JointType::Revolute: return (Mat6X<S>(6, 1) << j.axis, Vec3<S>::Zero()).finished();
    case JointType::Prismatic: return (Mat6X<S>(6, 1) << Vec3<S>::Zero(), j.axis).finished();
    case JointType::Free: return Mat6X<S>(Mat6<S>::Identity());
    case JointType::Helical: return (Mat6X<S>(6, 1) << j.axis, j.pitch * j.axis).finished();
    case JointType::Planar:  // S varies with q: the reference checks it as its elementary joints
      throw std::invalid_argument("reference: a planar joint is checked as two prismatic joints and a revolute one");
  }
  throw std::invalid_argument("reference: unknown joint type");
}

/// Every body's own joint coordinates, stacked in body order: body i's velocity coordinates are
/// rows offset[i] .. offset[i] + n_v,i of q̇_full = G q̇. Each row r of G holds one entry, k[r] in
/// column column[r]: 1 for a coordinate of a joint of its own, the multiplier k in the master's
/// column for a coupled joint (q̇ = k q̇_master). By virtual power τ = Gᵀ τ_full, M = Gᵀ M_full G.
template <class S>
struct CoordinateMap {
  std::vector<int> offset;  // per body; entry 0 unused
  int n_full = 0;
  std::vector<int> column;  // per row of G
  std::vector<S> k;         // per row of G

  /// G x.
  VecX<S> expand(const VecX<S>& x) const {
    VecX<S> y(n_full);
    for (int r = 0; r < n_full; ++r) y[r] = k[r] * x[column[r]];
    return y;
  }
  /// Gᵀ y.
  VecX<S> reduce(const VecX<S>& y, int nv) const {
    VecX<S> x = VecX<S>::Zero(nv);
    for (int r = 0; r < n_full; ++r) x[column[r]] += k[r] * y[r];
    return x;
  }
  /// Gᵀ H G.
  MatX<S> reduce(const MatX<S>& H, int nv) const {
    MatX<S> M = MatX<S>::Zero(nv, nv);
    for (int c = 0; c < n_full; ++c)
      for (int r = 0; r < n_full; ++r) M(column[r], column[c]) += k[r] * k[c] * H(r, c);
    return M;
  }
};

template <class S>
CoordinateMap<S> coordinate_map(const Model<S>& model) {
  CoordinateMap<S> map;
  map.offset.assign(model.nbodies(), 0);
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    map.offset[i] = map.n_full;
    map.n_full += j.nv;
    for (int l = 0; l < j.nv; ++l) {
      map.column.push_back(j.idx_v + l);
      map.k.push_back(j.coupled ? j.mimic.multiplier : S(1));  // q̇_i = k q̇_master
    }
  }
  return map;
}

/// Body i's own configuration coordinates: q[idx_q ..], or k q_master + offset for a coupled joint.
template <class S>
VecX<S> joint_configuration(const Joint<S>& j, const VectorArg<S>& q) {
  if (j.coupled) return VecX<S>::Constant(1, j.mimic.multiplier * q[j.idx_q] + j.mimic.offset);
  return q.segment(j.idx_q, j.nq);
}

/// Body i's rigid-body inertia as a 6×6 matrix, from the model's ten parameters (RBDA eq. 2.63).
template <class S>
Mat6<S> body_inertia(const Model<S>& model, int i) {
  const RigidInertia<S>& I = model.inertia[i];
  return rigid_inertia(I.mass, I.first_moment.eigen(), I.rotational_inertia.eigen());
}

/// ^iX_λ(i) = X_J(q_i) X_T(i) of every body (entry 0 unused), X_T = model.X_tree as a 6×6 matrix.
template <class S>
std::vector<Mat6<S>> up_transforms(const Model<S>& model, const VectorArg<S>& q) {
  if (q.size() != model.nq) throw std::invalid_argument("reference: q has the wrong length");
  std::vector<Mat6<S>> X_up(model.nbodies(), Mat6<S>::Identity());
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<S>& j = model.joints[i];
    X_up[i] = joint_transform(j, joint_configuration(j, q)) * plucker(model.X_tree[i].E.eigen(), model.X_tree[i].r.eigen());
  }
  return X_up;
}

}  // namespace reference
}  // namespace spatial_dynamics
