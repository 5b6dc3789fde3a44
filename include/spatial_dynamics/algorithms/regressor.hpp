// Inverse dynamics linear in the inertial parameters (Atkeson, An and Hollerbach 1986; Khalil and
// Dombre §9): each body's force f_i = I_i a_i + v_i ×* I_i v_i (eq. 29) is A(v_i, a_i) π_i, with π_i
// its ten parameters about its origin (RigidInertia::toParameters), and joint j carries S_jᵀ of the
// forces of the bodies it supports. So
//   joint_torque_regressor: τ = Y π + armature ⊙ q̈  (Y is nv × 10 N; π = model.inertial_parameters()),
//   payload_regressor:      a rigid payload with parameters π_P about a frame's origin adds Y_P π_P,
// and the actuators' effort is row k of Y_actuator · (armature_k, damping_k, friction_k). Each force
// column is carried to base coordinates once (^0X_i*), where it projects onto every supporting joint
// through that joint's columns S in base coordinates: no chain of transforms per column.
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

/// v_i and a_i (less the base's −a_g) in body coordinates — the RNEA's forward pass, run whole —
/// then ^iX_0 and the columns of S_i in base coordinates, for every body.
template <class S>
void regressor_kinematics(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                          const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  rnea_impl(model, data, q, qd, qdd, static_cast<const ForceVector<S>*>(nullptr));  // data.X_up, v, a
  data.X_base[0] = PluckerTransform<S>::Identity();
  for (int i = 1; i < model.nbodies(); ++i) {
    const PluckerTransform<S>& X = data.X_base[i] = data.X_up[i] * data.X_base[model.parent[i]];  // ^iX_0
    for (int k = 0; k < model.joints[i].nv; ++k) data.S_base[i][k] = X.applyInverse(body_subspace_column(model, data, i, k));
  }
}

/// Column `col` of Y gets the joint forces of a force F (base coordinates) acting on body i: S_jᵀ F
/// for body i's joint and each ancestor's, k_j S_jᵀ F added to the master's coordinate for a
/// coupled joint (Y zeroed first).
template <class S>
SD_INLINE void project_onto_supporting_joints(const Model<S>& model, const Data<S>& data, int i, const ForceVector<S>& F,
                                             MatrixX<S>& Y, Eigen::Index col) {
  for (int j = i; j > 0; j = model.parent[j]) {
    const Joint<S>& joint = model.joints[j];
    for (int l = 0; l < joint.nv; ++l) {
      const S entry = dot(data.S_base[j][l], F);
      if (model.has_coupled_joints)
        Y(joint.idx_v + l, col) += coupling_multiplier(joint) * entry;
      else
        Y(joint.idx_v + l, col) = entry;
    }
  }
}

}  // namespace detail

/// Y(q, q̇, q̈) into data.Y with τ = Y π + armature ⊙ q̈ = ID(q, q̇, q̈) (π: model.inertial_parameters()).
/// Entries of joints that do not support a body are structural zeros. A non-finite entry throws
/// std::domain_error naming its coordinate.
template <class S>
const MatrixX<S>& joint_torque_regressor(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                                         const ConstVectorRef<S>& qd, const ConstVectorRef<S>& qdd) {
  detail::regressor_kinematics(model, data, q, qd, qdd);
  if (model.has_coupled_joints) data.Y.setZero();
  ForceVector<S> columns[10];
  for (int i = 1; i < model.nbodies(); ++i) {
    RigidInertia<S>::parameterColumns(data.v[i], data.a[i], columns);  // f_i = A(v_i, a_i) π_i
    for (int k = 0; k < 10; ++k)
      detail::project_onto_supporting_joints(model, data, i, data.X_base[i].applyInverse(columns[k]), data.Y,
                                             10 * (i - 1) + k);
  }
  detail::check_finite_result(model, "joint torque regressor: the row", data.Y.transpose());
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
  ForceVector<S> columns[10];  // f_P = A(v_F, a_F) π_P in frame coordinates
  RigidInertia<S>::parameterColumns(X_fb.apply(data.v[body]), X_fb.apply(data.a[body]), columns);
  const PluckerTransform<S> X_frame_base = X_fb * data.X_base[body];  // ^FX_0
  for (int k = 0; k < 10; ++k)
    detail::project_onto_supporting_joints(model, data, body, X_frame_base.applyInverse(columns[k]), data.Y_payload, k);
  for (int k = 0; k < model.nv; ++k) {
    data.Y_actuator(k, 0) = qdd[k];
    data.Y_actuator(k, 1) = qd[k];
    data.Y_actuator(k, 2) = detail::friction_ramp(model, k, qd[k]);
  }
  detail::check_finite_result(model, "payload regressor: the row", data.Y_payload.transpose());
  return data.Y_payload;
}

}  // namespace spatial_dynamics
