// External torques, wrenches and collisions from joint_states' measured effort (doc/node.md,
// doc/external_torques.md): per scene, an ExternalTorqueEstimator fed by every joint_states
// message that carries effort for each of the scene's joints, publishing ~external_torques,
// ~external_wrench/<frame> and the latched ~collision, serving ~tare_external_torques, and
// reporting to diagnostics. Off unless ~external_torques/enabled. Its parameters are read at
// start-up and on every ~reload; a bad one is logged at ERROR and shown in diagnostics, and the
// estimate stays off while everything else is served. A scene whose model is rebuilt (a payload,
// a locked joint that moved) gets a new observer, which keeps the tare.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include "spatial_dynamics/ros/external_torque_estimator.hpp"
#include "spatial_dynamics/ros/model_store.hpp"

namespace spatial_dynamics {

class ExternalTorqueMonitor {
 public:
  /// Reads ~external_torques/* and advertises each scene's topics and tare service under `private_nh`.
  ExternalTorqueMonitor(ros::NodeHandle private_nh, const ModelStore& store);

  /// ~external_torques/* read again and every observer rebuilt (after ~reload): the tare is cleared.
  void reconfigure();

  /// One joint_states message, merged into `robot`'s cache already.
  void onJointStates(const sensor_msgs::JointState& msg, const std::shared_ptr<const ServedRobot>& robot);

  /// A joint_states message the cache refused (a non-finite position or velocity, ...): skipped.
  void onDropped(const std::string& why);

  /// Per scene: state, joints without effort, restarts, skipped samples, the largest |r̂|.
  void report(diagnostic_updater::DiagnosticStatusWrapper& status);
  /// Why the estimate is off where it should be on ("" when it is not): for the summary.
  std::string error() const;

 private:
  struct Scene {
    std::mutex mutex;  // the estimator, its publishers and counters below
    std::unique_ptr<ExternalTorqueEstimator> estimator;
    std::shared_ptr<const Model<double>> model;  // the scene model it was built for
    std::map<std::string, double> tare;          // carried over to a rebuilt observer
    std::string error;                           // why this scene has no estimate
    ros::Publisher torques, collision;
    std::map<std::string, ros::Publisher> wrenches;  // by frame
    ros::ServiceServer tare_service;
    long estimates = 0, skipped = 0, without_effort = 0;
    std::string missing_effort, last_skip, last_restart;
    bool collision_published = false;
  };

  /// Builds scene k's estimator for `served` (lock held); records and logs a refusal.
  void rebuild(std::size_t k, Scene& scene, const ServedScene& served);
  void estimate(std::size_t k, Scene& scene, const ServedScene& served, const sensor_msgs::JointState& msg,
                const ros::Time& stamp);
  bool onTare(std::size_t k, std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  ros::NodeHandle private_nh_;
  const ModelStore& store_;
  mutable std::mutex settings_mutex_;
  ExternalTorqueSettings settings_;
  std::vector<std::unique_ptr<Scene>> scenes_;
};

}  // namespace spatial_dynamics
