#include "spatial_dynamics/ros/base_state_tracker.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <tf2/exceptions.h>

#include "spatial_dynamics/ros/joint_state_cache.hpp"

namespace spatial_dynamics {
namespace {

std::string stale(const std::string& source, double age, double max_age) {
  std::ostringstream why;
  why << "the base state from " << source << " is " << age << " s old, older than max_state_age (" << max_age << " s)";
  return why.str();
}

/// The pose of a message as the base's; throws naming `source` when it is not finite or not a rotation.
template <class Translation>
void set_pose(const Translation& p, const geometry_msgs::Quaternion& o, const std::string& source, BaseState& out) {
  out.position = Eigen::Vector3d(p.x, p.y, p.z);
  out.orientation = Eigen::Quaterniond(o.w, o.x, o.y, o.z);
  if (!out.position.allFinite() || !out.orientation.coeffs().allFinite())
    throw std::runtime_error("the base pose from " + source + " is not finite");
  if (std::abs(out.orientation.squaredNorm() - 1.0) > 1e-6)
    throw std::runtime_error("the base orientation from " + source + " is not a unit quaternion");
}

}  // namespace

BaseStateTracker::BaseStateTracker(ros::NodeHandle nh, const tf2_ros::Buffer& buffer, std::string odometry_topic,
                                   std::string world_frame, double max_age)
    : buffer_(buffer),
      odometry_topic_(odometry_topic.empty() ? "" : nh.resolveName(odometry_topic)),
      world_frame_(std::move(world_frame)),
      max_age_(max_age) {
  if (!odometry_topic_.empty())
    subscriber_ = nh.subscribe(odometry_topic_, 10, &BaseStateTracker::onOdometry, this, ros::TransportHints().tcpNoDelay());
}

void BaseStateTracker::onOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  latest_ = *msg;
  received_ = JointStateCache::steadyNow();
}

void BaseStateTracker::state(const std::string& root_link, const ros::Time& stamp, BaseState& out) const {
  if (odometry_topic_.empty())
    fromTf(root_link, stamp, out);
  else
    fromOdometry(root_link, out);
}

void BaseStateTracker::fromOdometry(const std::string& root_link, BaseState& out) const {
  const std::string source = "odometry '" + odometry_topic_ + "' (~base_odometry)";
  std::lock_guard<std::mutex> lock(mutex_);
  if (received_ < 0) throw std::runtime_error("no base state yet: nothing received on " + source);
  const double age = JointStateCache::steadyNow() - received_;
  last_age_ = age;
  if (age > max_age_) throw std::runtime_error(stale(source, age, max_age_));
  if (latest_.child_frame_id != root_link)
    throw std::runtime_error("the base state from " + source + " has child_frame_id '" + latest_.child_frame_id +
                             "', not the robot's root link '" + root_link + "': its twist must be the root link's");
  set_pose(latest_.pose.pose.position, latest_.pose.pose.orientation, source, out);
  const geometry_msgs::Twist& t = latest_.twist.twist;
  out.twist << t.angular.x, t.angular.y, t.angular.z, t.linear.x, t.linear.y, t.linear.z;
  if (!out.twist.allFinite()) throw std::runtime_error("the base twist from " + source + " is not finite");
  out.world_frame = latest_.header.frame_id;
  out.note.clear();
}

void BaseStateTracker::fromTf(const std::string& root_link, const ros::Time& stamp, BaseState& out) const {
  const std::string source = "tf ('" + world_frame_ + "' to '" + root_link + "', ~world_frame)";
  geometry_msgs::TransformStamped t;
  try {
    try {
      t = buffer_.lookupTransform(world_frame_, root_link, stamp);
    } catch (const tf2::ExtrapolationException&) {
      if (stamp.isZero()) throw;
      t = buffer_.lookupTransform(world_frame_, root_link, ros::Time(0));  // the latest, if recent enough
    }
  } catch (const tf2::TransformException& e) {
    throw std::runtime_error("no base state from " + source + ": " + e.what());
  }
  if (!t.header.stamp.isZero()) {  // a static transform never ages
    const ros::Time reference = stamp.isZero() ? ros::Time::now() : stamp;
    const double age = std::abs((reference - t.header.stamp).toSec());
    last_age_ = age;
    if (age > max_age_) throw std::runtime_error(stale(source, age, max_age_));
  } else {
    last_age_ = 0.0;
  }
  set_pose(t.transform.translation, t.transform.rotation, source, out);
  out.twist.setZero();
  out.world_frame = world_frame_;
  out.note = "note: the base velocity is taken as zero (tf gives the base's pose only; set ~base_odometry for its twist)";
}

void BaseStateTracker::report(diagnostic_updater::DiagnosticStatusWrapper& status) const {
  status.add("base state source", odometry_topic_.empty() ? "tf from '" + world_frame_ + "'" : "odometry '" + odometry_topic_ + "'");
  status.add("base state age [s]", static_cast<double>(last_age_));
  status.add("base velocity", odometry_topic_.empty() ? "zero (tf gives the pose only)" : "from odometry");
}

}  // namespace spatial_dynamics
