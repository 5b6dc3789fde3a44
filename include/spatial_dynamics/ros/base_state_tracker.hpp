// A floating base's state from ROS (doc/node.md, "Floating base"): the latest nav_msgs/Odometry on
// ~base_odometry when it is set (pose in header.frame_id, twist in child_frame_id, which must be the
// root link, as REP-105 and nav_msgs say), else tf from ~world_frame to the root link (the pose
// only: the base velocity is then zero, and diagnostics and answers say so). Either is refused when
// missing or older than ~max_state_age.
#pragma once

#include <atomic>
#include <mutex>
#include <string>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>

#include "spatial_dynamics/ros/base_state.hpp"

namespace spatial_dynamics {

class BaseStateTracker : public BaseStateSource {
 public:
  /// Subscribes `odometry_topic` under `nh` when it is not empty; otherwise looks up tf in `buffer`
  /// from `world_frame`.
  BaseStateTracker(ros::NodeHandle nh, const tf2_ros::Buffer& buffer, std::string odometry_topic,
                   std::string world_frame, double max_age);

  void state(const std::string& root_link, const ros::Time& stamp, BaseState& out) const override;

  /// The source, the latest state's age and what the base velocity is taken from.
  void report(diagnostic_updater::DiagnosticStatusWrapper& status) const;

 private:
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void fromOdometry(const std::string& root_link, BaseState& out) const;
  void fromTf(const std::string& root_link, const ros::Time& stamp, BaseState& out) const;

  const tf2_ros::Buffer& buffer_;
  const std::string odometry_topic_;  // resolved name, "" for tf
  const std::string world_frame_;
  const double max_age_;
  mutable std::mutex mutex_;
  nav_msgs::Odometry latest_;        // guarded by mutex_
  double received_ = -1.0;           // steady clock [s] of latest_; < 0: none yet
  mutable std::atomic<double> last_age_{-1.0};  // of the last state served, for diagnostics
  ros::Subscriber subscriber_;
};

}  // namespace spatial_dynamics
