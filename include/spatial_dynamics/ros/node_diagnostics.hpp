// The node's /diagnostics status, once a second: the SIMD backend, the joint-state pipeline's
// rates, drops and latency, each service's calls and failures, the external-torque estimate, a
// floating base's state, the robot served and, as the summary, what stops it serving (no model, a scene's error, a refused
// ~external_torques parameter) or waits (incomplete joint states).
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "spatial_dynamics/ros/base_state_tracker.hpp"
#include "spatial_dynamics/ros/external_torque_monitor.hpp"
#include "spatial_dynamics/ros/joint_state_pipeline.hpp"
#include "spatial_dynamics/ros/model_store.hpp"
#include "spatial_dynamics/ros/payload_identification_endpoint.hpp"
#include "spatial_dynamics/ros/service_endpoints.hpp"

namespace spatial_dynamics {

class NodeDiagnostics {
 public:
  NodeDiagnostics(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh, const ModelStore& store,
                  const ServiceEndpoints& services, JointStatePipeline& joint_states,
                  ExternalTorqueMonitor& external_torques, const PayloadIdentificationEndpoint& payload_identification,
                  const BaseStateTracker& base_state);

 private:
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  const ModelStore& store_;
  const ServiceEndpoints& services_;
  JointStatePipeline& joint_states_;
  ExternalTorqueMonitor& external_torques_;
  const PayloadIdentificationEndpoint& payload_identification_;
  const BaseStateTracker& base_state_;
  diagnostic_updater::Updater updater_;
  ros::Timer timer_;
};

/// The build of the compiled algorithms this process runs (simd_backend.hpp), or why there is none
/// (a bad SPATIAL_DYNAMICS_SIMD, which every algorithm call then reports as well).
std::string simd_backend_or_error();

}  // namespace spatial_dynamics
