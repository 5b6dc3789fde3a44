// Helpers for the rostest integration tests: the same model the node serves, built by the test
// from the same parameter, and small conversions.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include "spatial_dynamics/ForwardDynamics.h"
#include "spatial_dynamics/InverseDynamics.h"
#include "spatial_dynamics/MassMatrix.h"
#include "spatial_dynamics/TransformWrench.h"
#include "test_utils.hpp"

namespace sd_node_test {

namespace sd = spatial_dynamics;

inline sd::Model<double> model_from_parameter() {
  std::string urdf;
  if (!ros::param::get("robot_description", urdf)) throw std::runtime_error("robot_description is not set");
  return sd::build_model_from_urdf_string(urdf);
}

inline std::vector<double> to_std(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

inline Eigen::VectorXd to_eigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

inline std::string service(const std::string& name) { return "/dynamics/" + name; }

inline bool wait_for_services(double seconds = 30.0) {
  for (const char* name : {"inverse_dynamics", "forward_dynamics", "mass_matrix", "transform_wrench", "reload"})
    if (!ros::service::waitForService(service(name), ros::Duration(seconds))) return false;
  return true;
}

/// Calls a service; fails the test when the call itself does not go through.
template <class Srv>
Srv call(const std::string& name, Srv srv) {
  EXPECT_TRUE(ros::service::call(service(name), srv)) << "call of " << name << " did not go through";
  return srv;
}

/// Every message of a topic, in arrival order.
template <class Message>
class Collector {
 public:
  Collector(ros::NodeHandle& nh, const std::string& topic) : sub_(nh.subscribe(topic, 10000, &Collector::on, this)) {}

  /// Waits for `count` messages; those received by then.
  std::vector<Message> waitForCount(std::size_t count, double seconds) {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return received_.size() >= count; });
    return received_;
  }
  /// Waits for the message stamped `stamp`.
  bool waitFor(const ros::Time& stamp, Message& out, double seconds = 5.0) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto stamped = [&](const Message& m) { return m.header.stamp == stamp; };
    const bool found = cv_.wait_for(lock, std::chrono::duration<double>(seconds),
                                    [&] { return std::any_of(received_.begin(), received_.end(), stamped); });
    if (found) out = *std::find_if(received_.begin(), received_.end(), stamped);
    return found;
  }
  std::vector<Message> all() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_.size();
  }
  bool connected() const { return sub_.getNumPublishers() > 0; }

 private:
  void on(const Message& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    received_.push_back(msg);
    cv_.notify_all();
  }
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<Message> received_;
};

/// Records the ~computed_torques messages of `topic`.
class TorqueListener : public Collector<sensor_msgs::JointState> {
 public:
  explicit TorqueListener(ros::NodeHandle& nh, const std::string& topic = "/dynamics/computed_torques")
      : Collector(nh, topic) {}
};

/// ~reload, the call expected to go through.
inline std_srvs::Trigger reload() {
  std_srvs::Trigger trigger;
  EXPECT_TRUE(ros::service::call(service("reload"), trigger)) << "call of reload did not go through";
  return trigger;
}

/// The fixture of a checker that needs the node's services up.
class ServedNodeTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { ASSERT_TRUE(wait_for_services()) << "the node's services did not appear"; }
  ros::NodeHandle nh;
};

/// ~inverse_dynamics at (q, q̇, q̈), every coordinate in the model's order.
inline spatial_dynamics::InverseDynamics call_inverse_dynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                                               const Eigen::VectorXd& qdd) {
  spatial_dynamics::InverseDynamics srv;
  srv.request.position = to_std(q);
  srv.request.velocity = to_std(qd);
  srv.request.acceleration = to_std(qdd);
  return call("inverse_dynamics", srv);
}

/// ~forward_dynamics at (q, q̇, τ), every coordinate in the model's order.
inline spatial_dynamics::ForwardDynamics call_forward_dynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                                               const Eigen::VectorXd& tau) {
  spatial_dynamics::ForwardDynamics srv;
  srv.request.position = to_std(q);
  srv.request.velocity = to_std(qd);
  srv.request.effort = to_std(tau);
  return call("forward_dynamics", srv);
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace sd_node_test
