#include "spatial_dynamics/ros/payload_identification_endpoint.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/ros/payload_identification_handlers.hpp"

namespace spatial_dynamics {

namespace {

/// The robot with `payloads` attached, mimic joints coupled as the node serves them.
Model<double> identification_model(const ServedRobot& robot, const std::map<std::string, Payload>& payloads, bool coupled) {
  Model<double> model = with_payloads(*robot.bare, payloads);
  return coupled ? couple_mimic_joints(model) : model;
}

}  // namespace

PayloadIdentificationEndpoint::PayloadIdentificationEndpoint(ros::NodeHandle private_nh, ModelStore& store,
                                                             JointStateRecorder& recorder)
    : store_(store), recorder_(recorder) {
  private_nh.setCallbackQueue(&queue_);
  identify_ = private_nh.advertiseService("identify_payload", &PayloadIdentificationEndpoint::onIdentify, this);
  excitation_ = private_nh.advertiseService("excitation_trajectory", &PayloadIdentificationEndpoint::onExcitation, this);
  spinner_ = std::make_unique<ros::AsyncSpinner>(2, &queue_);
  spinner_->start();
}

PayloadIdentificationEndpoint::~PayloadIdentificationEndpoint() {
  identify_.shutdown();
  excitation_.shutdown();
  if (spinner_) spinner_->stop();
}

trajectory_msgs::JointTrajectory PayloadIdentificationEndpoint::samplesFor(const IdentifyPayload::Request& req,
                                                                           std::string& note) {
  const bool given = !req.samples.points.empty();
  if (given && req.record_seconds != 0.0)
    throw std::invalid_argument("give samples or record_seconds, not both");
  if (given) return req.samples;
  if (!std::isfinite(req.record_seconds) || req.record_seconds <= 0.0 || req.record_seconds > 600.0)
    throw std::invalid_argument("record_seconds: " + std::to_string(req.record_seconds) +
                                " is not in (0, 600] (and samples is empty)");
  if (!recorder_.start()) throw std::runtime_error("record_seconds: a recording for ~identify_payload is already in progress; try again when it ends");
  ros::WallDuration(req.record_seconds).sleep();
  JointStateRecorder::Recording r = recorder_.finish();
  std::ostringstream skipped;
  if (r.without_effort) skipped << r.without_effort << " joint_states messages without velocity or effort; ";
  if (r.other_joints) skipped << r.other_joints << " of other sets of joints than the recorded one; ";
  if (r.not_later) skipped << r.not_later << " not stamped after the previous one; ";
  if (r.samples.points.size() < 2)
    throw std::invalid_argument("record_seconds: joint_states gave " + std::to_string(r.samples.points.size()) +
                                " samples with effort in " + std::to_string(req.record_seconds) + " s (" + skipped.str() +
                                "joint_states must carry position, velocity and effort)");
  note = "recorded " + std::to_string(r.samples.points.size()) + " joint_states messages" +
         (skipped.str().empty() ? "" : " (skipped " + skipped.str().substr(0, skipped.str().size() - 2) + ")");
  return std::move(r.samples);
}

bool PayloadIdentificationEndpoint::onIdentify(IdentifyPayload::Request& req, IdentifyPayload::Response& res) {
  ++identify_calls_;
  res = IdentifyPayload::Response();
  try {
    const std::shared_ptr<const ServedRobot> robot = store_.robot();
    if (!robot) throw std::runtime_error("no robot model is loaded: " + store_.loadError());
    if (!robot->bare->hasFrame(req.frame)) throw std::invalid_argument("frame: unknown frame '" + req.frame + "' (not a link of the robot model)");
    std::map<std::string, Payload> payloads = store_.payloads();
    Payload prior;
    if (payloads.count(req.frame)) prior = payloads[req.frame];
    payloads.erase(req.frame);
    std::string note;
    const trajectory_msgs::JointTrajectory samples = samplesFor(req, note);
    const Model<double> model = identification_model(*robot, payloads, store_.config().coupled_mimic_joints);
    const JointRequestDecoder decoder(model, robot->cache->jointNames());
    JointStateCache::Snapshot state;
    robot->cache->snapshot(state);
    compute_identify_payload({model, decoder, state, prior}, req.frame, samples, req.identify_friction, res);
    std::ostringstream message;
    message.precision(4);
    message << "identified on '" << req.frame << "' from " << samples.points.size() << " samples: mass " << res.inertia.m
            << " kg (σ " << res.stddev.m << "), condition number " << res.condition_number;
    if (!note.empty()) message << "; " << note;
    if (!res.unidentifiable.empty()) {
      message << "; held at the prior (the data cannot determine them):";
      for (const std::string& name : res.unidentifiable) message << " " << name;
    }
    res.message = message.str();
    res.success = true;
    if (req.apply) {
      Payload payload;
      const geometry_msgs::Inertia& in = res.inertia;
      payload.mass = in.m;
      payload.center_of_mass = Eigen::Vector3d(in.com.x, in.com.y, in.com.z);
      payload.inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      std::string attached;
      res.success = store_.setPayload(req.frame, payload, attached);
      res.message += "; " + attached;
      if (res.success) ROS_INFO("dynamics: %s", res.message.c_str());
    }
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  if (!res.success) ++identify_failures_;
  return true;
}

bool PayloadIdentificationEndpoint::onExcitation(ExcitationTrajectory::Request& req, ExcitationTrajectory::Response& res) {
  ++excitation_calls_;
  res = ExcitationTrajectory::Response();
  try {
    const std::shared_ptr<const ServedRobot> robot = store_.robot();
    if (!robot) throw std::runtime_error("no robot model is loaded: " + store_.loadError());
    const Model<double> model = identification_model(*robot, store_.payloads(), store_.config().coupled_mimic_joints);
    const JointRequestDecoder decoder(model, robot->cache->jointNames());
    JointStateCache::Snapshot state;
    robot->cache->snapshot(state);
    compute_excitation_trajectory({model, decoder, state, Payload{}}, req, res);
    std::ostringstream message;
    message.precision(4);
    message << res.trajectory.points.size() << " points over " << req.duration << " s, condition number "
            << res.condition_number;
    res.message = message.str();
    res.success = true;
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  if (!res.success) ++excitation_failures_;
  return true;
}

void PayloadIdentificationEndpoint::report(diagnostic_updater::DiagnosticStatusWrapper& status) const {
  status.add("identify_payload calls", static_cast<long>(identify_calls_));
  status.add("identify_payload failures", static_cast<long>(identify_failures_));
  status.add("excitation_trajectory calls", static_cast<long>(excitation_calls_));
  status.add("excitation_trajectory failures", static_cast<long>(excitation_failures_));
  status.add("identify_payload recording", recorder_.recording());
}

}  // namespace spatial_dynamics
