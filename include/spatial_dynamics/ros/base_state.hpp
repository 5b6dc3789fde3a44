// A floating base's state as the services and joint_states use it (doc/node.md, "Floating base"):
// the root link's pose in the world frame and its velocity in its own axes. Where it comes from
// (~base_odometry or tf, base_state_tracker.hpp) is behind BaseStateSource, so the service handlers
// run, and are tested and fuzzed, without ROS running.
#pragma once

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <ros/time.h>

namespace spatial_dynamics {

struct BaseState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();                   // root link origin, world frame
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();      // root link axes in the world frame
  Eigen::Matrix<double, 6, 1> twist = Eigen::Matrix<double, 6, 1>::Zero();  // (ω ; v), root link axes
  std::string world_frame;                                              // the frame of the pose
  std::string note;  // what an answer should say of it ("" : nothing), e.g. a velocity taken as zero
};

class BaseStateSource {
 public:
  virtual ~BaseStateSource() = default;
  /// The state of `root_link` at `stamp` (zero: the latest); throws std::runtime_error naming the
  /// source (topic or tf frames) when there is none yet or it is older than ~max_state_age.
  virtual void state(const std::string& root_link, const ros::Time& stamp, BaseState& out) const = 0;
};

}  // namespace spatial_dynamics
