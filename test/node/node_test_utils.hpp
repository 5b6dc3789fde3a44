// Helpers for the rostest integration tests: the same model the node serves, built by the test
// from the same parameter, and small conversions.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <string>
#include <vector>

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

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace sd_node_test
