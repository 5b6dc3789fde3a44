#include "spatial_dynamics/ros/node_diagnostics.hpp"

#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

std::string simd_backend_or_error() {
  try {
    return simd_backend();
  } catch (const std::exception& e) {
    return std::string("none: ") + e.what();
  }
}

NodeDiagnostics::NodeDiagnostics(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh, const ModelStore& store,
                                 const ServiceEndpoints& services, JointStatePipeline& joint_states,
                                 ExternalTorqueMonitor& external_torques,
                                 const PayloadIdentificationEndpoint& payload_identification,
                                 const BaseStateTracker& base_state)
    : store_(store),
      services_(services),
      joint_states_(joint_states),
      external_torques_(external_torques),
      payload_identification_(payload_identification),
      base_state_(base_state),
      updater_(nh, private_nh) {
  updater_.setHardwareID("none");
  updater_.add("Dynamics", this, &NodeDiagnostics::diagnose);
  timer_ = ros::NodeHandle(private_nh).createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
}

void NodeDiagnostics::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  status.add("simd backend", simd_backend_or_error());
  joint_states_.report(status);
  services_.report(status);
  external_torques_.report(status);
  payload_identification_.report(status);
  std::string scene_errors;
  for (std::size_t k = 0; k < store_.sceneCount(); ++k) {
    const auto s = store_.scene(k);
    if (s && !s->error.empty()) append_message(scene_errors, s->error);
  }
  const std::string external_torque_error = external_torques_.error();
  if (!external_torque_error.empty()) append_message(scene_errors, external_torque_error);
  const std::shared_ptr<const ServedRobot> robot = store_.robot();
  if (!robot) {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no robot model: " + store_.loadError());
    return;
  }
  updater_.setHardwareID(robot->robot_name);
  status.add("joints", static_cast<int>(robot->cache->jointNames().size()));
  status.add("base", robot->floating_base ? "floating" : "fixed");
  if (robot->floating_base) base_state_.report(status);
  status.add("contacts", static_cast<int>(robot->contacts.frames.size()));
  status.add("actuator model", to_string(robot->actuator_model));
  if (!scene_errors.empty())
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, scene_errors);
  else if (!robot->cache->complete())
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "model loaded; waiting for joint_states of every joint");
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "model loaded; joint states complete");
}

}  // namespace spatial_dynamics
