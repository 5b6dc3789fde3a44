// The models the node serves: the robot as loaded (payloads attached, actuator terms set) and one
// model per scene.
// Immutable once built; the node swaps whole objects, so a call in progress keeps its own.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "spatial_dynamics/model/contact_set.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/ros/actuator_parameters.hpp"
#include "spatial_dynamics/ros/contact_spec.hpp"
#include "spatial_dynamics/ros/joint_request_decoder.hpp"
#include "spatial_dynamics/ros/joint_state_cache.hpp"
#include "spatial_dynamics/ros/workspace_pool.hpp"

namespace spatial_dynamics {

/// The robot as loaded: immutable, replaced on ~reload, ~set_payload and ~set_contacts.
struct ServedRobot {
  std::shared_ptr<const Model<double>> bare;  // from robot_description, independent joints, with the
                                              // actuator terms of ~actuator_model and ~actuators
  std::shared_ptr<const Model<double>> full;  // with the payloads attached
  std::shared_ptr<JointStateCache> cache;     // every joint of the robot (not a floating base's); survives
                                              // payload and contact changes
  std::string robot_name;
  std::string root_frame;                     // the URDF root link: the frame tf chains through, a floating base
  bool floating_base = false;                 // ~root_joint floating: the root link's free joint leads q
  ContactSpec contacts;                       // ~contacts, or the last ~set_contacts
  std::vector<std::string> leaf_links;        // the URDF links without children (external wrench frames)
  ActuatorModel actuator_model = ActuatorModel::RigidBody;
};

/// One scene's model: immutable, replaced when a locked joint moves or the robot changes.
struct ServedScene {
  std::shared_ptr<const ServedRobot> robot;
  std::shared_ptr<const Model<double>> model;
  std::shared_ptr<const Model<double>> rigid_model;  // the same without actuator terms (rigid_body_only)
  std::unique_ptr<JointRequestDecoder> decoder;
  ContactSet<double> contacts;                // the robot's contacts on this scene's model
  std::string contacts_error;                 // why they do not resolve on it ("" when they do)
  std::vector<std::pair<int, double>> locks;  // (joint-state index, locked position)
  std::string error;                          // why the scene has no model ("" when it has one)
  WorkspacePool workspaces;                   // the calls' buffers for this scene's model
};

}  // namespace spatial_dynamics
