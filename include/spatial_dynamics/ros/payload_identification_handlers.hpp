// What ~identify_payload and ~excitation_trajectory compute, from request to response
// (doc/payload_identification.md). No node handle or master here: the endpoint
// (payload_identification_endpoint.hpp) records, picks the model and attaches the result, so these
// run (and are fuzzed and tested) without ROS running. Errors are exceptions whose message names
// the culprit; the endpoint turns them into success = false.
#pragma once

#include <string>
#include <vector>

#include <trajectory_msgs/JointTrajectory.h>

#include "spatial_dynamics/ExcitationTrajectory.h"
#include "spatial_dynamics/IdentifyPayload.h"
#include "spatial_dynamics/estimation/payload_identification.hpp"
#include "spatial_dynamics/ros/joint_request_decoder.hpp"
#include "spatial_dynamics/ros/joint_state_cache.hpp"

namespace spatial_dynamics {

/// What a payload on a frame is identified against: the robot with every other payload attached
/// (mimic joints coupled as the node serves them), the joint-state decoder for it, and the payload
/// attached to the frame now (the prior; mass 0 when none).
struct PayloadIdentificationInput {
  const Model<double>& model;
  const JointRequestDecoder& decoder;
  const JointStateCache::Snapshot& state;
  Payload prior;
};

/// The samples of `trajectory` on the input's model, by joint name (the model's order when
/// joint_names is empty). Joints left out hold their latest joint state at rest and their efforts
/// are not used (`measured` lists the coordinates whose efforts are); a mimic joint the model couples
/// to its master is skipped. Empty accelerations in every point: the velocities' finite differences
/// over time_from_start (trajectory_differences.hpp). Throws std::invalid_argument naming the field,
/// the point and the joint.
PayloadSamples decode_payload_samples(const PayloadIdentificationInput& input, const trajectory_msgs::JointTrajectory& trajectory,
                                      std::vector<int>& measured);

/// Identifies the payload on `frame` from `samples` into `res` (every field but success and message).
void compute_identify_payload(const PayloadIdentificationInput& input, const std::string& frame,
                              const trajectory_msgs::JointTrajectory& samples, bool identify_friction,
                              IdentifyPayload::Response& res);

/// The excitation trajectory of the request's joints on `model` (the others at their latest joint
/// state, else zero) into `res`: points every 10 ms.
void compute_excitation_trajectory(const PayloadIdentificationInput& input, const ExcitationTrajectory::Request& req,
                                   ExcitationTrajectory::Response& res);

}  // namespace spatial_dynamics
