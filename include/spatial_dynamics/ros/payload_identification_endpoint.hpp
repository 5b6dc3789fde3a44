// ~identify_payload and ~excitation_trajectory (doc/payload_identification.md), on a callback queue
// of their own with two threads: a recording (record_seconds, up to 600 s) holds one while every
// other service keeps being served on the node's queue, and a second identification asked for
// during it is refused, named. Each call builds the model the payload is identified against (the
// robot with every other payload attached), runs the ROS-free handler
// (payload_identification_handlers.hpp) and, with `apply`, attaches the result through the store
// as ~set_payload does.
#pragma once

#include <atomic>
#include <memory>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "spatial_dynamics/ExcitationTrajectory.h"
#include "spatial_dynamics/IdentifyPayload.h"
#include "spatial_dynamics/ros/joint_state_recorder.hpp"
#include "spatial_dynamics/ros/model_store.hpp"

namespace spatial_dynamics {

class PayloadIdentificationEndpoint {
 public:
  PayloadIdentificationEndpoint(ros::NodeHandle private_nh, ModelStore& store, JointStateRecorder& recorder);
  /// Stops the services' threads before the members they use go.
  ~PayloadIdentificationEndpoint();
  PayloadIdentificationEndpoint(const PayloadIdentificationEndpoint&) = delete;
  PayloadIdentificationEndpoint& operator=(const PayloadIdentificationEndpoint&) = delete;

  /// Calls, failures and whether a recording runs.
  void report(diagnostic_updater::DiagnosticStatusWrapper& status) const;

 private:
  bool onIdentify(IdentifyPayload::Request& req, IdentifyPayload::Response& res);
  bool onExcitation(ExcitationTrajectory::Request& req, ExcitationTrajectory::Response& res);
  /// The samples to identify from: the request's, or a recording of record_seconds.
  trajectory_msgs::JointTrajectory samplesFor(const IdentifyPayload::Request& req, std::string& note);

  ModelStore& store_;
  JointStateRecorder& recorder_;
  ros::CallbackQueue queue_;
  ros::ServiceServer identify_, excitation_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  std::atomic<long> identify_calls_{0}, identify_failures_{0}, excitation_calls_{0}, excitation_failures_{0};
};

}  // namespace spatial_dynamics
