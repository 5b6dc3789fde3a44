// Inverse dynamics linear in the inertial parameters (Atkeson, An and Hollerbach 1986; Khalil and
// Dombre §9): each body's force f_i = I_i a_i + v_i ×* I_i v_i (eq. 29) is A(v_i, a_i) π_i, with π_i
// its ten parameters about its origin (RigidInertia::toParameters), and joint j carries S_jᵀ of the
// forces of the bodies it supports. So
//   joint_torque_regressor: τ = Y π + armature ⊙ q̈  (Y is nv × 10 N; π = model.inertial_parameters()),
//   payload_regressor:      a rigid payload with parameters π_P about a frame's origin adds Y_P π_P,
// and the actuators' effort is row k of Y_actuator · (armature_k, damping_k, friction_k). A body's ten
// force columns are carried once to the coordinates of its tree's root body (^rX_i*), where they
// project onto each supporting joint through that joint's S in root coordinates: no chain of
// transforms per column.
#pragma once

#include "spatial_dynamics/algorithms/actuator_dynamics.hpp"
#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace spatial_dynamics {
namespace detail {

/// v_i and a_i (less the base's −a_g) in body coordinates — the RNEA's forward pass —
/// then ^iX_r and the columns of S_i in root coordinates for every body (r: the root body of i's tree,
/// the child of the world that i descends from).
template <class S>
void regressor_kinematics(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                          const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  rnea_impl<S, true>(model, data, q, qd, qdd, nullptr, model.gravity);  // data.X_up, v, a
  for (int i = 1; i < model.nbodies(); ++i) {
    const int lambda = model.parent[i];
    if (lambda == 0) {  // a root: its own coordinates
      data.X_root[i] = PluckerTransform<S>::Identity();
      for (int k = 0; k < model.joints[i].nv; ++k) data.S_root[i][k] = body_subspace_column(model, data, i, k);
      continue;
    }
    const PluckerTransform<S>& X = data.X_root[i] = data.X_up[i] * data.X_root[lambda];  // ^iX_r
    for (int k = 0; k < model.joints[i].nv; ++k) data.S_root[i][k] = X.applyInverse(body_subspace_column(model, data, i, k));
  }
}

/// The ten force columns of a body's parameters (RigidInertia::parameterColumns, v and a in the body's
/// coordinates) carried to root coordinates, by component, so that each joint column s gives the ten
/// projections sᵀ A_k at once. With X_body_root = ^iX_r = (E, r), a column (n ; f) becomes
/// (Eᵀ n + r × Eᵀ f ; Eᵀ f): as rows, nᵀ E − (fᵀ E) r×. The moments fill 12 rows (the last two zero)
/// so that the products run on whole SIMD packets.
template <class S>
struct ParameterForces {
  Eigen::Matrix<S, 12, 3> moments = Eigen::Matrix<S, 12, 3>::Zero();
  Eigen::Matrix<S, 4, 3> forces;
  Eigen::Matrix<S, 12, 3> body_moments = Eigen::Matrix<S, 12, 3>::Zero();  // in body coordinates
  Eigen::Matrix<S, 4, 3> body_forces;

  SD_INLINE void set(const MotionVector<S>& v, const MotionVector<S>& a, const PluckerTransform<S>& X_body_root) {
    RigidInertia<S>::parameterColumns(v, a, body_moments, body_forces);
    const Matrix3<S> E = X_body_root.E.eigen();
    moments.noalias() = body_moments.lazyProduct(E);
    forces.noalias() = body_forces.lazyProduct(E);
    moments.template topRows<4>().noalias() -= forces.lazyProduct(skew(X_body_root.r).eigen());
  }
  /// (sᵀ A_k)_k; entries 10 and 11 zero.
  SD_INLINE Eigen::Matrix<S, 12, 1> project(const MotionVector<S>& s) const {
    Eigen::Matrix<S, 12, 1> entries = moments.lazyProduct(s.angular.eigen());
    entries.template head<4>() += forces.lazyProduct(s.linear.eigen());
    return entries;
  }
};

/// Y(:, col .. col + 9) gets the joint forces of a body's ten parameter columns A (root coordinates):
/// S_jᵀ A for body i's joint and each ancestor's, k_j S_jᵀ A added to the master's coordinate for a
/// coupled joint (Y zeroed first). `probe` gathers entry − entry: NaN once an entry is not finite.
template <class S, class Matrix>
SD_INLINE void project_onto_supporting_joints(const Model<S>& model, const Data<S>& data, int i,
                                             const ParameterForces<S>& A, Matrix& Y, Eigen::Index col,
                                             Eigen::Matrix<S, 12, 1>& probe) {
  for (int j = i; j > 0; j = model.parent[j]) {
    const Joint<S>& joint = model.joints[j];
    const S k_j = coupling_multiplier(joint);
    for (int l = 0; l < joint.nv; ++l) {
      const Eigen::Matrix<S, 12, 1> entries = A.project(data.S_root[j][l]);
      probe += entries - entries;
      if (model.has_coupled_joints)
        Y.row(joint.idx_v + l).template segment<10>(col) += k_j * entries.template head<10>().transpose();
      else
        Y.row(joint.idx_v + l).template segment<10>(col) = entries.template head<10>().transpose();
    }
  }
}

/// A probe that is not zero: name the first non-finite entry of Y (only on that path).
template <class S, class Matrix>
void check_regressor_probe(const Model<S>& model, const Eigen::Matrix<S, 12, 1>& probe, const Matrix& Y,
                           const char* what) {
  if (probe.sum() == S(0)) return;
  check_finite_result(model, what, Y.transpose());
  throw_non_finite(model, what, -1);
}

}  // namespace detail

/// Y(q, q̇, q̈) into data.Y with τ = Y π + armature ⊙ q̈ = ID(q, q̇, q̈) (π: model.inertial_parameters()).
/// Entries of joints that do not support a body are structural zeros. A non-finite entry throws
/// std::domain_error naming its coordinate.
template <class S>
const RowMajorMatrixX<S>& joint_torque_regressor(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                         const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  detail::regressor_kinematics(model, data, q, qd, qdd);
  if (model.has_coupled_joints) data.Y.setZero();
  detail::ParameterForces<S> A;
  Eigen::Matrix<S, 12, 1> probe = Eigen::Matrix<S, 12, 1>::Zero();
  for (int i = 1; i < model.nbodies(); ++i) {
    A.set(data.v[i], data.a[i], data.X_root[i]);  // f_i = A(v_i, a_i) π_i
    detail::project_onto_supporting_joints(model, data, i, A, data.Y, 10 * (i - 1), probe);
  }
  detail::check_regressor_probe(model, probe, data.Y, "joint torque regressor: the row");
  return data.Y;
}

/// The joint forces of a rigid payload fixed to `frame`, Y_P π_P with π_P its ten parameters about the
/// frame's origin in the frame's axes, into data.Y_payload (nv × 10); and the actuator columns into
/// data.Y_actuator (nv × 3): row k is (q̈_k, q̇_k, ramp(q̇_k / friction_velocity_k)), so that the
/// actuators' effort is Y_actuator(k, :) · (armature_k, damping_k, friction_k) (actuator_dynamics.hpp).
/// Throws std::out_of_range for an unknown frame, std::domain_error for a non-finite result.
template <class S>
const MatrixX<S>& payload_regressor(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                    const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd, const std::string& frame_name) {
  const Frame<S>& frame = model.frames[model.frameIndex(frame_name)];
  detail::regressor_kinematics(model, data, q, qd, qdd);
  data.Y_payload.setZero();
  const int body = frame.body;
  const PluckerTransform<S>& X_fb = frame.X_frame_body;
  detail::ParameterForces<S> A;  // f_P = A(v_F, a_F) π_P, carried from frame to root coordinates (^FX_r)
  A.set(X_fb.apply(data.v[body]), X_fb.apply(data.a[body]), X_fb * data.X_root[body]);
  Eigen::Matrix<S, 12, 1> probe = Eigen::Matrix<S, 12, 1>::Zero();
  detail::project_onto_supporting_joints(model, data, body, A, data.Y_payload, 0, probe);
  for (int k = 0; k < model.nv; ++k) {
    data.Y_actuator(k, 0) = qdd[k];
    data.Y_actuator(k, 1) = qd[k];
    data.Y_actuator(k, 2) = detail::friction_ramp(model, k, qd[k]);
  }
  detail::check_regressor_probe(model, probe, data.Y_payload, "payload regressor: the row");
  return data.Y_payload;
}

}  // namespace spatial_dynamics
