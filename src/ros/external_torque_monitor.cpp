#include "spatial_dynamics/ros/external_torque_monitor.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <geometry_msgs/WrenchStamped.h>

#include "spatial_dynamics/CollisionState.h"
#include "spatial_dynamics/ros/node_config.hpp"

namespace spatial_dynamics {
namespace {

std::string scene_label(const SceneConfig& config) { return config.name.empty() ? "the robot" : "scene '" + config.name + "'"; }

std::string joined(const std::vector<std::string>& names, std::size_t limit = 8) {
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < limit; ++k) out += (k ? ", " : "") + names[k];
  if (names.size() > limit) out += ", … (" + std::to_string(names.size()) + " in all)";
  return out;
}

}  // namespace

ExternalTorqueMonitor::ExternalTorqueMonitor(ros::NodeHandle private_nh, const ModelStore& store)
    : private_nh_(std::move(private_nh)), store_(store) {
  for (std::size_t k = 0; k < store_.sceneCount(); ++k) {
    scenes_.push_back(std::make_unique<Scene>());
    const SceneConfig& config = store_.config().scenes[k];
    Scene& scene = *scenes_.back();
    scene.torques = private_nh_.advertise<sensor_msgs::JointState>(config.resolve("external_torques"), 100);
    scene.collision = private_nh_.advertise<CollisionState>(config.resolve("collision"), 1, /*latch=*/true);
    scene.tare_service = private_nh_.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
        config.resolve("tare_external_torques"),
        [this, k](std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res) { return onTare(k, req, res); });
  }
  reconfigure();
}

void ExternalTorqueMonitor::reconfigure() {
  ExternalTorqueSettings settings = read_external_torque_settings(private_nh_);
  if (!settings.error.empty()) ROS_ERROR("dynamics: external torques stay off: %s", settings.error.c_str());
  {
    std::lock_guard<std::mutex> lock(settings_mutex_);
    settings_ = settings;
  }
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    Scene& scene = *scenes_[k];
    std::lock_guard<std::mutex> lock(scene.mutex);
    scene.tare.clear();  // ~reload clears the tare
    scene.estimator.reset();
    scene.model.reset();
    scene.error.clear();
    const std::shared_ptr<const ServedScene> served = store_.scene(k);
    if (settings.enabled && settings.error.empty() && served && served->model) rebuild(k, scene, *served);
  }
}

void ExternalTorqueMonitor::rebuild(std::size_t k, Scene& scene, const ServedScene& served) {
  ExternalTorqueSettings settings;
  {
    std::lock_guard<std::mutex> lock(settings_mutex_);
    settings = settings_;
  }
  if (scene.estimator) scene.tare = scene.estimator->tareByJoint();
  scene.estimator.reset();
  scene.model = served.model;
  scene.collision_published = false;
  std::vector<std::string> locked;
  for (const auto& lock : served.locks) locked.push_back(served.robot->cache->jointNames()[lock.first]);
  try {
    scene.estimator = std::make_unique<ExternalTorqueEstimator>(served.model, settings, served.robot->leaf_links,
                                                               locked, scene.tare);
    scene.error.clear();
  } catch (const std::exception& e) {
    scene.error = e.what();
    ROS_ERROR("dynamics: external torques of %s stay off: %s", scene_label(store_.config().scenes[k]).c_str(), e.what());
    return;
  }
  const SceneConfig& config = store_.config().scenes[k];
  for (const std::string& frame : scene.estimator->frames()) {
    if (scene.wrenches.count(frame)) continue;
    try {
      scene.wrenches[frame] = private_nh_.advertise<geometry_msgs::WrenchStamped>(config.resolve("external_wrench/" + frame), 100);
    } catch (const ros::InvalidNameException& e) {
      ROS_ERROR("dynamics: no external wrench topic for frame '%s' (%s)", frame.c_str(), e.what());
    }
  }
}

void ExternalTorqueMonitor::onJointStates(const sensor_msgs::JointState& msg,
                                          const std::shared_ptr<const ServedRobot>& robot) {
  {
    std::lock_guard<std::mutex> lock(settings_mutex_);
    if (!settings_.enabled || !settings_.error.empty()) return;
  }
  const ros::Time stamp = msg.header.stamp.isZero() ? ros::Time::now() : msg.header.stamp;
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    Scene& scene = *scenes_[k];
    std::lock_guard<std::mutex> lock(scene.mutex);
    const std::shared_ptr<const ServedScene> served = store_.scene(k);
    if (!served || !served->model || served->robot != robot) continue;
    if (served->model != scene.model) rebuild(k, scene, *served);  // a refused model is not tried again
    if (scene.estimator) estimate(k, scene, *served, msg, stamp);
  }
}

void ExternalTorqueMonitor::estimate(std::size_t k, Scene& scene, const ServedScene& served,
                                     const sensor_msgs::JointState& msg, const ros::Time& stamp) {
  ExternalTorqueEstimator& estimator = *scene.estimator;
  const std::vector<std::string>& joints = estimator.jointNames();
  const int n = static_cast<int>(joints.size());
  const WorkspacePool::Lease ws = served.workspaces.acquire(*served.model);
  // The measured effort of each of the scene's joints, by name; velocity and position from the
  // cache the message was merged into.
  ws->x.resize(n);
  std::vector<std::string> missing;
  if (msg.effort.size() != msg.name.size()) {
    missing = joints;
  } else {
    std::map<std::string, double> effort;
    for (std::size_t j = 0; j < msg.name.size(); ++j) effort[msg.name[j]] = msg.effort[j];
    for (int i = 0; i < n; ++i) {
      const auto it = effort.find(joints[i]);
      if (it == effort.end())
        missing.push_back(joints[i]);
      else
        ws->x[i] = it->second;
    }
  }
  if (!missing.empty()) {  // no estimate from this message
    ++scene.without_effort;
    scene.missing_effort = joined(missing);
    return;
  }
  scene.missing_effort.clear();
  served.robot->cache->snapshot(ws->state);
  const JointRequestDecoder& decoder = *served.decoder;
  std::vector<std::string> no_velocity;
  for (int i = 0; i < n; ++i)
    if (!ws->state.position_known[decoder.stateIndex(i)] || !ws->state.velocity_known[decoder.stateIndex(i)])
      no_velocity.push_back(joints[i]);
  if (!no_velocity.empty()) {
    ++scene.skipped;
    scene.last_skip = "no position or velocity yet for " + joined(no_velocity);
    return;
  }
  std::string error = decoder.decode("position", {}, {}, {}, JointRequestDecoder::Default::LatestPosition, ws->state, ws->q);
  if (error.empty())
    error = decoder.decode("velocity", {}, {}, {}, JointRequestDecoder::Default::LatestVelocity, ws->state, ws->qd);
  const ExternalTorqueEstimator::Estimate* result = nullptr;
  if (error.empty()) {
    try {
      result = &estimator.update(stamp.toSec(), ws->q, ws->qd, ws->x);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!result) {
    ++scene.skipped;
    scene.last_skip = error;
    ROS_WARN_THROTTLE(5.0, "dynamics: external torques: joint_states message skipped: %s", error.c_str());
    return;
  }
  ++scene.estimates;
  const SceneConfig& config = store_.config().scenes[k];
  if (result->restarted && result->restart_reason != "first sample") {
    scene.last_restart = result->restart_reason;
    ROS_WARN("dynamics: external torques of %s restarted: %s", scene_label(config).c_str(), result->restart_reason.c_str());
  }
  sensor_msgs::JointState torques;
  torques.header = msg.header;
  torques.header.stamp = stamp;
  torques.name = joints;
  torques.effort.assign(result->torques->data(), result->torques->data() + n);
  scene.torques.publish(torques);
  for (std::size_t f = 0; f < estimator.frames().size(); ++f) {
    const auto publisher = scene.wrenches.find(estimator.frames()[f]);
    if (publisher == scene.wrenches.end()) continue;
    geometry_msgs::WrenchStamped wrench;
    wrench.header.stamp = stamp;
    wrench.header.frame_id = estimator.frames()[f];
    const ForceVector<double>& F = result->wrenches[f].wrench;
    wrench.wrench.torque.x = F.angular[0], wrench.wrench.torque.y = F.angular[1], wrench.wrench.torque.z = F.angular[2];
    wrench.wrench.force.x = F.linear[0], wrench.wrench.force.y = F.linear[1], wrench.wrench.force.z = F.linear[2];
    publisher->second.publish(wrench);
  }
  bool detect = false;
  {
    std::lock_guard<std::mutex> settings_lock(settings_mutex_);
    detect = settings_.detect_collisions;
  }
  if (detect && (result->collision_changed || !scene.collision_published)) {
    CollisionState state;
    state.header = torques.header;
    state.in_collision = result->in_collision;
    for (int i : result->over_threshold) {
      state.name.push_back(joints[i]);
      state.external_effort.push_back((*result->torques)[i]);
    }
    if (result->best_frame >= 0) state.frame = estimator.frames()[result->best_frame];
    scene.collision.publish(state);
    scene.collision_published = true;
    if (result->collision_changed && result->in_collision)
      ROS_WARN("dynamics: collision on %s: %s (best explained at frame '%s')", scene_label(config).c_str(),
               joined(state.name).c_str(), state.frame.c_str());
  }
}

void ExternalTorqueMonitor::onDropped(const std::string& why) {
  for (const auto& scene : scenes_) {
    std::lock_guard<std::mutex> lock(scene->mutex);
    if (!scene->estimator) continue;
    ++scene->skipped;
    scene->last_skip = "joint_states message dropped: " + why;
  }
}

bool ExternalTorqueMonitor::onTare(std::size_t k, std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  Scene& scene = *scenes_[k];
  std::lock_guard<std::mutex> lock(scene.mutex);
  if (!scene.estimator) {
    res.success = false;
    res.message = scene.error.empty() ? "external torques are off (~external_torques/enabled is false)"
                                      : "external torques are off: " + scene.error;
    return true;
  }
  res.success = scene.estimator->tare();
  res.message = res.success ? "the current estimate is the zero from now on"
                            : "no estimate yet: joint_states with effort for every joint are needed first";
  return true;
}

void ExternalTorqueMonitor::report(diagnostic_updater::DiagnosticStatusWrapper& status) {
  ExternalTorqueSettings settings;
  {
    std::lock_guard<std::mutex> lock(settings_mutex_);
    settings = settings_;
  }
  if (!settings.error.empty()) {
    status.add("external torques", "off: " + settings.error);
    return;
  }
  if (!settings.enabled) {
    status.add("external torques", "off");
    return;
  }
  for (std::size_t k = 0; k < scenes_.size(); ++k) {
    Scene& scene = *scenes_[k];
    std::lock_guard<std::mutex> lock(scene.mutex);
    const SceneConfig& config = store_.config().scenes[k];
    const std::string prefix = config.name.empty() ? "external torques" : "external torques [" + config.name + "]";
    if (!scene.estimator) {
      status.add(prefix, scene.error.empty() ? "waiting for a model" : "off: " + scene.error);
      continue;
    }
    status.add(prefix, scene.estimates > 0 ? "estimating" : "waiting for joint_states with effort");
    status.add(prefix + ": estimates", scene.estimates);
    status.add(prefix + ": joints without measured effort", scene.missing_effort.empty() ? "none" : scene.missing_effort);
    status.add(prefix + ": messages without effort for every joint", scene.without_effort);
    status.add(prefix + ": skipped samples", scene.skipped);
    if (!scene.last_skip.empty()) status.add(prefix + ": last skipped", scene.last_skip);
    status.add(prefix + ": restarts", scene.estimator->restarts());
    if (!scene.last_restart.empty()) status.add(prefix + ": last restart", scene.last_restart);
    const std::pair<double, std::string> largest = scene.estimator->takeLargest();
    status.add(prefix + ": largest |external torque| since last report", largest.first);
    if (!largest.second.empty()) status.add(prefix + ": at joint", largest.second);
    if (!scene.estimator->lockedJoints().empty())
      status.add(prefix + ": locked joints (effort ignored)", joined(scene.estimator->lockedJoints()));
    status.add(prefix + ": frames", joined(scene.estimator->frames()));
  }
}

std::string ExternalTorqueMonitor::error() const {
  {
    std::lock_guard<std::mutex> lock(settings_mutex_);
    if (!settings_.error.empty()) return "external torques off: " + settings_.error;
    if (!settings_.enabled) return "";
  }
  std::string out;
  for (const auto& scene : scenes_) {
    std::lock_guard<std::mutex> lock(scene->mutex);
    if (!scene->error.empty()) out += (out.empty() ? "external torques off: " : "; ") + scene->error;
  }
  return out;
}

}  // namespace spatial_dynamics
