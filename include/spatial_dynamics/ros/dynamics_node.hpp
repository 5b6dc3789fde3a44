// The ROS node (doc/node.md): reads robot_description, merges joint_states, serves inverse and
// forward dynamics, the mass matrix and wrench transforms for the whole robot and for configured
// scenes (reduced models), manages payloads, and publishes computed torques. It only wires its
// parts, each with one job: the configuration (node_config.hpp), the models served
// (model_store.hpp), a floating base's state (base_state_tracker.hpp), the services (service_endpoints.hpp), the joint-state pipeline
// (joint_state_pipeline.hpp), the external-torque estimate (external_torque_monitor.hpp), payload
// identification (payload_identification_endpoint.hpp) and diagnostics (node_diagnostics.hpp). The arithmetic is the
// library's; message ↔ vector translation is the service handlers' (service_handlers.hpp).
#pragma once

#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <ros/ros.h>

#include "spatial_dynamics/ros/base_state_tracker.hpp"
#include "spatial_dynamics/ros/joint_state_pipeline.hpp"
#include "spatial_dynamics/ros/model_store.hpp"
#include "spatial_dynamics/ros/node_diagnostics.hpp"
#include "spatial_dynamics/ros/payload_identification_endpoint.hpp"
#include "spatial_dynamics/ros/service_endpoints.hpp"
#include "spatial_dynamics/ros/tf_frames.hpp"

namespace spatial_dynamics {

class DynamicsNode {
 public:
  DynamicsNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);
  DynamicsNode(const DynamicsNode&) = delete;
  DynamicsNode& operator=(const DynamicsNode&) = delete;

 private:
  /// The store with the robot loaded, or with why there is none recorded and logged; each scene
  /// that cannot be served logged. Called before the services and joint_states start.
  ModelStore& loadedAtStartUp();

  ros::NodeHandle nh_, private_nh_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  TfFrames tf_frames_{tf_buffer_};
  const ModelStore::SourceReader read_source_;  // robot_description, ~gravity, ~actuator_model, ~actuators
  ModelStore store_;
  BaseStateTracker base_state_;  // a floating base's pose and twist: ~base_odometry or tf
  // Destroyed in reverse: diagnostics, then joint_states (unsubscribed before the store goes).
  ServiceEndpoints services_;
  ExternalTorqueMonitor external_torques_;
  JointStateRecorder recorder_;
  PayloadIdentificationEndpoint payload_identification_;
  JointStatePipeline joint_states_;
  NodeDiagnostics diagnostics_;
};

}  // namespace spatial_dynamics
