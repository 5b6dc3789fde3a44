// The node's parameters (doc/node.md), each read and checked here and nowhere else: a refusal
// names the parameter. The configuration is read once at start-up; what a model is loaded from
// (robot_description, ~gravity, ~actuator_model, ~actuators, ~root_joint) is read again on every ~reload.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "spatial_dynamics/ros/actuator_parameters.hpp"
#include "spatial_dynamics/ros/contact_spec.hpp"
#include "spatial_dynamics/ros/external_torque_settings.hpp"
#include "spatial_dynamics/ros/joint_state_cache.hpp"

namespace ros {
class NodeHandle;
}

namespace spatial_dynamics {

/// A scene as the parameters configure it (fixed for the node's life).
struct SceneConfig {
  std::string name;                 // "" for the node's main services
  std::string parameter;            // where it was configured, for messages
  bool reduced = false;             // false: the whole robot
  std::vector<std::string> joints;  // kept joints, or
  std::string root_link;            // root link and tip links
  std::vector<std::string> tip_links;
  std::string error;                // a configuration error, reported by the scene's services

  /// A service or topic of this scene under the node: `name` for the main scene, else <scene>/name.
  std::string resolve(const std::string& topic) const { return name.empty() ? topic : name + "/" + topic; }
};

struct NodeConfig {
  bool publish_computed_torques = true;  // ~publish_computed_torques
  bool publish_centroidal_state = true;  // ~publish_centroidal_state
  double relock_tolerance = 1e-6;        // ~relock_tolerance: a locked joint that moves further rebuilds its scene
  double max_state_age = 1.0;            // ~max_state_age [s]
  bool coupled_mimic_joints = false;     // ~mimic_joints: 'coupled' (true) or 'independent'
  JointStateCache::UnknownJoints unknown_joints = JointStateCache::UnknownJoints::kDrop;  // ~unknown_joints
  bool inline_joint_states = true;       // ~inline_joint_states
  std::string base_odometry;             // ~base_odometry: nav_msgs/Odometry topic of a floating base ("" : tf)
  std::string world_frame = "odom";      // ~world_frame: tf's frame of a floating base's pose
  ContactSpec contacts;                  // ~contacts: [{frame, kind, friction}], until ~set_contacts
  std::vector<SceneConfig> scenes;       // [0]: the main services (~joints, ~root_link, ~tip_links); ~scenes/<name>
  std::string error;                     // the first bad parameter: the node then loads no model and says why
};

/// Every start-up parameter under the node's private namespace. A bad scene is kept with its error
/// (its services report it); an invalid ~scenes or scene name is logged and not served.
NodeConfig read_node_config(const ros::NodeHandle& private_nh);

/// ~external_torques/* as they are now (read at start-up and on every ~reload); a malformed one
/// is named in the result's `error` (the values are checked against each model by
/// ExternalTorqueEstimator).
ExternalTorqueSettings read_external_torque_settings(const ros::NodeHandle& private_nh);

/// What a robot model is built from.
struct RobotSource {
  std::string urdf;                                  // robot_description
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};          // ~gravity
  ActuatorSettings actuators;                        // ~actuator_model, ~actuators
  bool floating_base = false;                        // ~root_joint: fixed (false) or floating
};

/// robot_description, ~gravity, ~actuator_model, ~actuators and ~root_joint as they are now; throws
/// std::runtime_error naming the parameter that is missing or malformed.
RobotSource read_robot_source(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);

}  // namespace spatial_dynamics
