// The tool the payload-identification tests put on the Panda's flange (test_payload_identification,
// node_payload_identification): about 2 kg, its centre of mass a few cm off the flange, principal
// moments 0.02–0.04 kg m² turned off the flange's axes; and the arm's joints.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "spatial_dynamics/reduction/payload.hpp"

namespace sd_test {

inline spatial_dynamics::Payload panda_tool() {
  spatial_dynamics::Payload p;
  p.mass = 2.1;
  p.center_of_mass = Eigen::Vector3d(0.012, -0.021, 0.085);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  p.inertia = R * Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal() * R.transpose();
  return p;
}

inline std::vector<std::string> panda_arm_joints() {
  std::vector<std::string> names;
  for (int k = 1; k <= 7; ++k) names.push_back("panda_joint" + std::to_string(k));
  return names;
}

}  // namespace sd_test
