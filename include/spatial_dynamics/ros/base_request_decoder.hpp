// A service request's floating-base fields (base_pose, base_twist, base_acceleration) into the base's
// coordinates, which lead q (x y z qx qy qz qw), q̇ and q̈ ((ω ; v) and its derivative, root link
// axes): from the request when it gives base_pose, else from the node's base state. On a fixed base
// the fields must be left unset. Every refusal names the field or the source. ROS-free but for the
// message types, so it is tested and fuzzed without a master.
#pragma once

#include <string>

#include <Eigen/Core>
#include <geometry_msgs/Accel.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Twist.h>

#include "spatial_dynamics/ros/base_state.hpp"

namespace spatial_dynamics {

/// base_pose is given: its orientation is not all zero.
bool base_pose_given(const geometry_msgs::Pose& pose);

/// (angular ; linear) of a twist or an acceleration; throws naming `field` when not finite.
Eigen::Matrix<double, 6, 1> angular_linear(const geometry_msgs::Twist& twist, const std::string& field);
Eigen::Matrix<double, 6, 1> angular_linear(const geometry_msgs::Accel& acceleration, const std::string& field);

/// q's first seven and q̇'s first six from a base state.
void set_base_coordinates(const BaseState& state, Eigen::VectorXd& q, Eigen::VectorXd& qd);

/// q's first seven and q̇'s first six from a given base_pose (a unit quaternion, finite) and base_twist.
void decode_given_base(const geometry_msgs::Pose& pose, const geometry_msgs::Twist& twist, Eigen::VectorXd& q,
                       Eigen::VectorXd& qd);

/// q's first seven and q̇'s first six: the request's base_pose and base_twist (zero when unset) when
/// base_pose is given, else the base state of `root_link` from `source` at `stamp` (its note, such
/// as a velocity taken as zero, appended to `notes`).
void decode_base(const std::string& root_link, const BaseStateSource& source, const geometry_msgs::Pose& pose,
                 const geometry_msgs::Twist& twist, const ros::Time& stamp, Eigen::VectorXd& q, Eigen::VectorXd& qd,
                 std::string& notes);

/// A fixed base's request: throws naming the first base field that is set.
void refuse_base_fields(const geometry_msgs::Pose& pose, const geometry_msgs::Twist& twist,
                        const geometry_msgs::Accel* acceleration);

}  // namespace spatial_dynamics
