#include "spatial_dynamics/ros/joint_state_pipeline.hpp"

#include <algorithm>

#include "spatial_dynamics/ros/service_handlers.hpp"

namespace spatial_dynamics {

JointStatePipeline::JointStatePipeline(ros::NodeHandle nh, ros::NodeHandle private_nh, ModelStore& store,
                                       const BaseStateSource& base, ExternalTorqueMonitor& external_torques,
                                       JointStateRecorder& recorder)
    : store_(store),
      base_(base),
      external_torques_(external_torques),
      recorder_(recorder),
      reported_time_(ros::WallTime::now()) {
  for (const SceneConfig& scene : store_.config().scenes) {
    computed_torques_.push_back(private_nh.advertise<sensor_msgs::JointState>(scene.resolve("computed_torques"), 1000));
    computed_contact_wrenches_.push_back(
        private_nh.advertise<ContactWrenches>(scene.resolve("computed_contact_wrenches"), 1000));
  }
  centroidal_state_ = private_nh.advertise<CentroidalState>("centroidal_state", 1000);
  if (store_.config().inline_joint_states)
    nh.setCallbackQueue(&queue_);
  else
    nh.setCallbackQueue(&queue_.fallback());
  subscriber_ = nh.subscribe("joint_states", 1000, &JointStatePipeline::onJointStates, this,
                             ros::TransportHints().tcpNoDelay());
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_.fallback());
  spinner_->start();
}

JointStatePipeline::~JointStatePipeline() {
  // Unsubscribing waits for a callback running in roscpp's receiving thread; then the fallback
  // thread stops. Only then may the members the callback uses go.
  subscriber_.shutdown();
  if (spinner_) spinner_->stop();
}

void JointStatePipeline::warnUnknown(const std::vector<std::string>& unknown) {
  std::lock_guard<std::mutex> lock(warned_mutex_);
  for (const std::string& name : unknown)
    if (warned_unknown_joints_.insert(name).second)
      ROS_WARN("dynamics: joint_states names joint '%s', which the robot model does not have; it is "
               "ignored (~unknown_joints: ignore)",
               name.c_str());
}

void JointStatePipeline::onJointStates(const ros::MessageEvent<sensor_msgs::JointState const>& event) {
  const sensor_msgs::JointState::ConstPtr& msg = event.getConstMessage();
  ++messages_;
  last_message_time_ = ros::WallTime::now().toSec();
  const std::shared_ptr<const ServedRobot> robot = store_.robot();
  if (!robot) return;
  std::vector<std::string> unknown;
  const std::string error = robot->cache->update(msg->name, msg->position, msg->velocity, &unknown);
  if (!error.empty()) {
    ++drops_;
    ROS_WARN_THROTTLE(5.0, "dynamics: joint_states message dropped: %s", error.c_str());
    external_torques_.onDropped(error);
    return;
  }
  if (!unknown.empty()) warnUnknown(unknown);
  bool published = false;
  for (std::size_t k = 0; k < computed_torques_.size(); ++k) {
    std::shared_ptr<const ServedScene> served = store_.scene(k);
    if (!served || !served->model || served->robot != robot) continue;
    std::string moved;  // locked joints follow joint_states
    served = store_.followLockedJoints(k, served, robot, moved);
    if (!moved.empty()) {
      const std::string& name = store_.config().scenes[k].name;
      const std::string scene = name.empty() ? "the main scene" : "scene '" + name + "'";
      ROS_DEBUG("dynamics: %s; rebuilding %s", moved.c_str(), scene.c_str());
    }
    if (!store_.config().publish_computed_torques || !served->model) continue;
    try {
      sensor_msgs::JointState out;
      ContactWrenches wrenches;
      const WorkspacePool::Lease ws = served->workspaces.acquire(*served->model);
      if (!compute_latest_torques(*served, base_, *ws, msg->header.stamp, out, wrenches.wrenches)) continue;
      out.header = msg->header;
      computed_torques_[k].publish(out);
      if (!wrenches.wrenches.empty()) {
        wrenches.header = msg->header;
        computed_contact_wrenches_[k].publish(wrenches);
      }
      ++torque_messages_;
      published = true;
    } catch (const std::exception& e) {
      ROS_WARN_THROTTLE(5.0, "dynamics: no computed torques for this joint state: %s", e.what());
    }
  }
  if (store_.config().publish_centroidal_state) publishCentroidalState(msg->header.stamp, robot);
  if (published) torque_latency_us_.record((ros::Time::now() - event.getReceiptTime()).toSec() * 1e6);
  external_torques_.onJointStates(*msg, robot);
  recorder_.add(*msg);
}

void JointStatePipeline::publishCentroidalState(const ros::Time& stamp, const std::shared_ptr<const ServedRobot>& robot) {
  const std::shared_ptr<const ServedScene> served = store_.scene(0);
  if (!served || !served->model || served->robot != robot) return;
  try {
    CentroidalState out;
    const WorkspacePool::Lease ws = served->workspaces.acquire(*served->model);
    if (compute_centroidal_state(*served, base_, *ws, stamp, out)) centroidal_state_.publish(out);
  } catch (const std::exception& e) {
    ROS_WARN_THROTTLE(5.0, "dynamics: no centroidal state for this joint state: %s", e.what());
  }
}

void JointStatePipeline::report(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const ros::WallTime now = ros::WallTime::now();
  const double elapsed = std::max(1e-9, (now - reported_time_).toSec());
  const long messages = messages_, torques = torque_messages_;
  status.add("joint_states rate [Hz]", (messages - reported_messages_) / elapsed);
  status.add("computed_torques rate [Hz]", (torques - reported_torques_) / elapsed);
  reported_messages_ = messages;
  reported_torques_ = torques;
  reported_time_ = now;
  const double last = last_message_time_;
  status.add("joint_states age [s]", last > 0 ? now.toSec() - last : -1.0);
  status.add("joint_states dropped", static_cast<long>(drops_));
  const LatencyRecorder::Summary latency = torque_latency_us_.summary();
  status.add("computed_torques latency window [messages]", latency.count);
  status.add("computed_torques latency p50 [us]", latency.p50);
  status.add("computed_torques latency p99 [us]", latency.p99);
  status.add("computed_torques latency max [us]", latency.max);
}

}  // namespace spatial_dynamics
