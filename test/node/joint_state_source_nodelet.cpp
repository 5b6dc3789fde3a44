// spatial_dynamics/JointStateSourceNodelet (tests only): joint_states for every joint of
// robot_description at ~rate Hz (default 100), positions and velocities on slow sines, published
// as shared pointers so that a subscriber in the same nodelet manager gets them without
// serialisation — the driver a dynamics nodelet would share a manager with.
#include <cmath>
#include <string>
#include <vector>

#include <boost/make_shared.hpp>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "spatial_dynamics/urdf/model_builder.hpp"

namespace spatial_dynamics {

class JointStateSourceNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    std::string urdf;
    if (!nh.getParam("robot_description", urdf)) {
      NODELET_ERROR("joint_state_source: robot_description is not set");
      return;
    }
    names_ = build_model_from_urdf_string(urdf).velocityNames();
    double rate = 100.0;
    getPrivateNodeHandle().param("rate", rate, rate);
    publisher_ = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
    start_ = ros::WallTime::now();
    timer_ = nh.createWallTimer(ros::WallDuration(1.0 / rate), &JointStateSourceNodelet::tick, this);
  }

  void tick(const ros::WallTimerEvent&) {
    const double t = (ros::WallTime::now() - start_).toSec();
    auto msg = boost::make_shared<sensor_msgs::JointState>();
    msg->header.stamp = ros::Time::now();
    msg->name = names_;
    for (std::size_t k = 0; k < names_.size(); ++k) {
      const double phase = 0.7 * t + static_cast<double>(k);
      msg->position.push_back(0.3 * std::sin(phase));
      msg->velocity.push_back(0.21 * std::cos(phase));
    }
    publisher_.publish(msg);  // a shared pointer: handed over as is within the manager
  }

  std::vector<std::string> names_;
  ros::Publisher publisher_;
  ros::WallTimer timer_;
  ros::WallTime start_;
};

}  // namespace spatial_dynamics

PLUGINLIB_EXPORT_CLASS(spatial_dynamics::JointStateSourceNodelet, nodelet::Nodelet)
