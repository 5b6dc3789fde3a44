#include "spatial_dynamics/ros/base_request_decoder.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace spatial_dynamics {
namespace {

template <class Message>
Eigen::Matrix<double, 6, 1> stacked(const Message& m, const std::string& field) {
  Eigen::Matrix<double, 6, 1> x;
  x << m.angular.x, m.angular.y, m.angular.z, m.linear.x, m.linear.y, m.linear.z;
  if (!x.allFinite()) throw std::runtime_error(field + " is not finite");
  return x;
}

}  // namespace

bool base_pose_given(const geometry_msgs::Pose& pose) {
  const geometry_msgs::Quaternion& o = pose.orientation;
  return o.x != 0.0 || o.y != 0.0 || o.z != 0.0 || o.w != 0.0;
}

Eigen::Matrix<double, 6, 1> angular_linear(const geometry_msgs::Twist& twist, const std::string& field) {
  return stacked(twist, field);
}

Eigen::Matrix<double, 6, 1> angular_linear(const geometry_msgs::Accel& acceleration, const std::string& field) {
  return stacked(acceleration, field);
}

void set_base_coordinates(const BaseState& state, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  q.head<3>() = state.position;
  q.segment<4>(3) = state.orientation.coeffs();  // (x y z w)
  qd.head<6>() = state.twist;
}

void decode_given_base(const geometry_msgs::Pose& pose, const geometry_msgs::Twist& twist, Eigen::VectorXd& q,
                       Eigen::VectorXd& qd) {
  const geometry_msgs::Point& p = pose.position;
  const geometry_msgs::Quaternion& o = pose.orientation;
  q.head<7>() << p.x, p.y, p.z, o.x, o.y, o.z, o.w;
  if (!q.head<7>().allFinite()) throw std::runtime_error("base_pose is not finite");
  const double norm = q.segment<4>(3).norm();
  if (std::abs(norm - 1.0) > 1e-6) {
    std::ostringstream why;
    why << "base_pose.orientation is not a unit quaternion (norm " << norm << ")";
    throw std::runtime_error(why.str());
  }
  qd.head<6>() = angular_linear(twist, "base_twist");
}

void decode_base(const std::string& root_link, const BaseStateSource& source, const geometry_msgs::Pose& pose,
                 const geometry_msgs::Twist& twist, const ros::Time& stamp, Eigen::VectorXd& q, Eigen::VectorXd& qd,
                 std::string& notes) {
  if (base_pose_given(pose)) {
    decode_given_base(pose, twist, q, qd);
    return;
  }
  BaseState state;
  source.state(root_link, stamp, state);
  set_base_coordinates(state, q, qd);
  if (!state.note.empty()) notes += (notes.empty() ? "" : "; ") + state.note;
}

void refuse_base_fields(const geometry_msgs::Pose& pose, const geometry_msgs::Twist& twist,
                        const geometry_msgs::Accel* acceleration) {
  const std::string fixed = " is set but the robot's base is fixed (~root_joint: fixed)";
  const geometry_msgs::Point& p = pose.position;
  if (base_pose_given(pose) || p.x != 0.0 || p.y != 0.0 || p.z != 0.0) throw std::runtime_error("base_pose" + fixed);
  if (!angular_linear(twist, "base_twist").isZero(0.0)) throw std::runtime_error("base_twist" + fixed);
  if (acceleration && !angular_linear(*acceleration, "base_acceleration").isZero(0.0))
    throw std::runtime_error("base_acceleration" + fixed);
}

}  // namespace spatial_dynamics
