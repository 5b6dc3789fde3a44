// What each service computes, from a request message to a response message, on one served
// scene. No node handle, master or tf2 here: frames outside the robot come through FrameLookup,
// so the handlers run (and are fuzzed and tested) without ROS running. Errors are exceptions whose
// message names the culprit; the node turns them into success = false.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <geometry_msgs/WrenchStamped.h>
#include <sensor_msgs/JointState.h>

#include "spatial_dynamics/CentroidalState.h"
#include "spatial_dynamics/ForwardDynamics.h"
#include "spatial_dynamics/InverseDynamics.h"
#include "spatial_dynamics/InverseDynamicsTrajectory.h"
#include "spatial_dynamics/MassMatrix.h"
#include "spatial_dynamics/TransformWrench.h"
#include "spatial_dynamics/model/batch_data.hpp"
#include "spatial_dynamics/model/data.hpp"
#include "spatial_dynamics/ros/base_state.hpp"
#include "spatial_dynamics/ros/served_model.hpp"

namespace spatial_dynamics {

/// Whether an answer includes the actuator terms: the node has an actuator model (~actuator_model)
/// and the request did not ask for rigid_body_only.
inline bool with_actuators(const ServedScene& scene, bool rigid_body_only) {
  return scene.robot->actuator_model != ActuatorModel::RigidBody && !rigid_body_only;
}

/// The model an answer is computed on: the scene's, or the same without actuator terms.
inline const Model<double>& model_for(const ServedScene& scene, bool rigid_body_only) {
  return rigid_body_only ? *scene.rigid_model : *scene.model;
}

/// Adds `more` to a response message ("a; b").
void append_message(std::string& message, const std::string& more);

/// Frames that are not part of the robot model (tf2 in the node).
class FrameLookup {
 public:
  virtual ~FrameLookup() = default;
  virtual bool hasFrame(const std::string& frame) const = 0;
  /// ^{target}X_{source} at `stamp` (zero = latest); throws naming the frames when it cannot.
  virtual PluckerTransform<double> transform(const std::string& target, const std::string& source,
                                             const ros::Time& stamp) const = 0;
};

/// Inverse dynamics; a floating base's state from the request or `base`, with the contacts of the
/// call (contact_answers.hpp): τ of the joints, λ, and the wrench left on the base.
void compute_inverse_dynamics(const ServedScene& scene, const BaseStateSource& base, Workspace& ws,
                              const InverseDynamics::Request& req, InverseDynamics::Response& res);
/// τ at every point of a trajectory (batched RNEA), with peak efforts and effort-limit violations;
/// missing velocities and accelerations by finite differences (trajectory_handler.cpp). Fixed
/// bases only.
void compute_inverse_dynamics_trajectory(const ServedScene& scene, Workspace& ws,
                                         const InverseDynamicsTrajectory::Request& req,
                                         InverseDynamicsTrajectory::Response& res);
/// Forward dynamics; with contacts, q̈ and λ of the constrained system; a floating base's acceleration.
void compute_forward_dynamics(const ServedScene& scene, const BaseStateSource& base, Workspace& ws,
                              const ForwardDynamics::Request& req, ForwardDynamics::Response& res);
/// M(q), a floating base's six rows and columns first.
void compute_mass_matrix(const ServedScene& scene, const BaseStateSource& base, Workspace& ws,
                         const MassMatrix::Request& req, MassMatrix::Response& res);
void compute_transform_wrench(const ServedScene& scene, Workspace& ws, const FrameLookup& frames,
                              const TransformWrench::Request& req, TransformWrench::Response& res);

/// ~computed_torques: ID(q, q̇, 0) of the latest joint states; for a floating base the base at rest at
/// its pose at `stamp` and, with the scene's contacts, the contact-consistent torques and the
/// contact wrenches (`wrenches`, else empty). False when the joint states are incomplete.
bool compute_latest_torques(const ServedScene& scene, const BaseStateSource& base, Workspace& ws, const ros::Time& stamp,
                            sensor_msgs::JointState& torques, std::vector<geometry_msgs::WrenchStamped>& wrenches);

/// ~centroidal_state of the latest joint states (and a floating base's state at `stamp`): the centre
/// of mass, its velocity and the momentum about it, in the world frame (a fixed base's root link).
/// False when the joint states are incomplete.
bool compute_centroidal_state(const ServedScene& scene, const BaseStateSource& base, Workspace& ws,
                              const ros::Time& stamp, CentroidalState& out);

}  // namespace spatial_dynamics
