// joint_states in, ~computed_torques out (doc/node.md): each message is merged into the robot's
// joint-state cache by name, a scene whose locked joint has moved is rebuilt, each scene
// publishes ID(q, q̇, 0) at the latest complete state (a floating base at rest, with its contacts'
// wrenches on ~computed_contact_wrenches), the robot its ~centroidal_state, and the message's
// effort goes to the external-torque estimate (external_torque_monitor.hpp). joint_states never wait behind service
// calls: by default (~inline_joint_states) each message is handled at once in roscpp's receiving
// thread; otherwise, or when that is busy, by a thread of its own, so that a burst of service
// calls never delays (or, through a full queue, drops) a joint state and its computed torques.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "spatial_dynamics/CentroidalState.h"
#include "spatial_dynamics/ContactWrenches.h"
#include "spatial_dynamics/ros/base_state.hpp"
#include "spatial_dynamics/ros/external_torque_monitor.hpp"
#include "spatial_dynamics/ros/joint_state_recorder.hpp"
#include "spatial_dynamics/ros/inline_callback_queue.hpp"
#include "spatial_dynamics/ros/latency_recorder.hpp"
#include "spatial_dynamics/ros/model_store.hpp"

namespace spatial_dynamics {

class JointStatePipeline {
 public:
  /// Subscribes joint_states under `nh` and advertises each scene's computed_torques (and
  /// computed_contact_wrenches) and the centroidal_state under `private_nh`; a floating base's state
  /// comes from `base`; each merged message also goes to `external_torques` and to `recorder`.
  JointStatePipeline(ros::NodeHandle nh, ros::NodeHandle private_nh, ModelStore& store, const BaseStateSource& base,
                     ExternalTorqueMonitor& external_torques, JointStateRecorder& recorder);
  /// Stops joint_states first, so that no callback runs while the members it uses are destroyed.
  ~JointStatePipeline();
  JointStatePipeline(const JointStatePipeline&) = delete;
  JointStatePipeline& operator=(const JointStatePipeline&) = delete;

  /// Rates since the last report, the latest message's age, drops and the torques' latency.
  void report(diagnostic_updater::DiagnosticStatusWrapper& status);

 private:
  void onJointStates(const ros::MessageEvent<sensor_msgs::JointState const>& event);
  /// ~centroidal_state of the main scene at the latest joint states.
  void publishCentroidalState(const ros::Time& stamp, const std::shared_ptr<const ServedRobot>& robot);
  /// Warns once per joint name that joint_states gives but the model does not have.
  void warnUnknown(const std::vector<std::string>& unknown);

  ModelStore& store_;
  const BaseStateSource& base_;
  ExternalTorqueMonitor& external_torques_;
  JointStateRecorder& recorder_;
  std::vector<ros::Publisher> computed_torques_;           // one per scene
  std::vector<ros::Publisher> computed_contact_wrenches_;  // one per scene
  ros::Publisher centroidal_state_;
  InlineCallbackQueue queue_;
  ros::Subscriber subscriber_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;

  std::atomic<long> messages_{0}, drops_{0}, torque_messages_{0};
  std::atomic<double> last_message_time_{0.0};
  // From a joint_states message's arrival (roscpp's receipt time) to its last ~computed_torques
  // message being handed to roscpp, in µs: the last 10 s at 1 kHz.
  LatencyRecorder torque_latency_us_{10000};
  std::mutex warned_mutex_;
  std::set<std::string> warned_unknown_joints_;
  long reported_messages_ = 0, reported_torques_ = 0;
  ros::WallTime reported_time_;
};

}  // namespace spatial_dynamics
