// Forward kinematics: the pose of every body and frame in base coordinates, optionally the
// body velocities v_i = ^iX_λ v_λ + S_i q̇_i (RBDA eq. 5.7, first line).
#pragma once

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/model/joints/body_joint.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

/// ^iX_λ(i) for every body.
template <class S>
void update_joint_transforms(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  detail::check_length("q", q.size(), model.nq);
  joint_sines_and_cosines(model, data, q.data());
  for (int i = 1; i < model.nbodies(); ++i) body_up_transform(model, data, i, q.data(), data.X_up[i]);
}

/// ^iX_0 = ^iX_λ ^λX_0 for every body, from data.X_up.
template <class S>
void update_body_poses(const Model<S>& model, Data<S>& data) {
  data.X_base[0] = PluckerTransform<S>::Identity();
  for (int i = 1; i < model.nbodies(); ++i) data.X_base[i] = data.X_up[i] * data.X_base[model.parent[i]];
}

/// Body poses ^iX_0 = ^iX_λ ^λX_0 and frame poses ^FX_0 = ^FX_B ^BX_0. The pose of body i in
/// the base is (data.X_base[i].rotation(), data.X_base[i].translation()). A non-finite pose (a
/// non-finite q, or an overflow) throws std::domain_error naming the body or frame.
template <class S>
void forward_kinematics(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q) {
  update_joint_transforms(model, data, q);
  update_body_poses(model, data);
  for (int i = 1; i < model.nbodies(); ++i) {
    if (!data.X_base[i].allFinite())
      throw std::domain_error("forward kinematics: the pose of body '" + model.body_names[i] + "'" +
                              detail::non_finite_reason());
  }
  for (std::size_t k = 0; k < model.frames.size(); ++k) {
    data.X_frame_base[k] = model.frames[k].X_frame_body * data.X_base[model.frames[k].body];
    if (!data.X_frame_base[k].allFinite())
      throw std::domain_error("forward kinematics: the pose of frame '" + model.frames[k].name + "'" +
                              detail::non_finite_reason());
  }
}

/// Poses as above, plus body velocities data.v (body coordinates).
template <class S>
void forward_kinematics(const Model<S>& model, Data<S>& data, const ConstVectorRef<S>& q,
                        const ConstVectorRef<S>& qd) {
  detail::check_length("velocity", qd.size(), model.nv);
  forward_kinematics<S>(model, data, q);
  data.v[0] = MotionVector<S>::Zero();
  for (int i = 1; i < model.nbodies(); ++i) {
    data.v[i] = data.X_up[i].apply(data.v[model.parent[i]]) + body_joint_motion(model, data, i, qd.data());
    if (!data.v[i].angular.allFinite() || !data.v[i].linear.allFinite())
      throw std::domain_error("forward kinematics: the velocity of body '" + model.body_names[i] + "'" +
                              detail::non_finite_reason());
  }
}

}  // namespace spatial_dynamics
