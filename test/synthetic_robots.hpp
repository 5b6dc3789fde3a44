// Synthetic URDFs for tests: a mobile manipulator (wheeled base, torso, two 7-DoF arms with
// grippers, 20 fixed sensor links) with random but physically valid inertias.
#pragma once

#include <random>
#include <sstream>
#include <string>

namespace sd_test {

class UrdfWriter {
 public:
  explicit UrdfWriter(unsigned seed) : rng_(seed) {}

  std::string link(const std::string& name, double mass) {
    std::ostringstream s;
    s.precision(17);
    s << "<link name='" << name << "'>";
    if (mass > 0) {
      const double a = uniform(0.02, 0.2), b = uniform(0.02, 0.2), c = uniform(0.02, 0.2);
      s << "<inertial><origin xyz='" << uniform(-0.05, 0.05) << " " << uniform(-0.05, 0.05) << " "
        << uniform(-0.05, 0.05) << "' rpy='" << uniform(-3, 3) << " " << uniform(-1.5, 1.5) << " " << uniform(-3, 3)
        << "'/><mass value='" << mass << "'/><inertia ixx='" << mass / 12 * (b * b + c * c) << "' ixy='0' ixz='0' iyy='"
        << mass / 12 * (a * a + c * c) << "' iyz='0' izz='" << mass / 12 * (a * a + b * b) << "'/></inertial>";
    }
    s << "</link>";
    return s.str();
  }

  std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                    const std::string& child, const std::string& axis, const std::string& extra = "") {
    std::ostringstream s;
    s.precision(17);
    s << "<joint name='" << name << "' type='" << type << "'><parent link='" << parent << "'/><child link='" << child
      << "'/><origin xyz='" << uniform(-0.15, 0.15) << " " << uniform(-0.15, 0.15) << " " << uniform(0.05, 0.15)
      << "' rpy='" << uniform(-1, 1) << " " << uniform(-1, 1) << " " << uniform(-1, 1) << "'/>";
    if (type != "fixed") s << "<axis xyz='" << axis << "'/>";
    if (type == "revolute" || type == "prismatic")
      s << "<limit lower='-2' upper='2' effort='100' velocity='3'/>";
    s << extra << "</joint>";
    return s.str();
  }

  std::string random_axis() {
    switch (std::uniform_int_distribution<int>(0, 3)(rng_)) {
      case 0: return "1 0 0";
      case 1: return "0 1 0";
      case 2: return "0 0 1";
      default: {
        std::ostringstream s;
        s.precision(17);
        s << uniform(-1, 1) << " " << uniform(-1, 1) << " " << uniform(-1, 1);
        return s.str();
      }
    }
  }

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

 private:
  std::mt19937 rng_;
};

/// base (two wheels) + torso (lift, pan) + two 7-DoF arms + two-finger grippers (the second
/// finger mimics the first) + 20 fixed sensor links spread over the robot.
inline std::string mobile_manipulator_urdf(unsigned seed = 1) {
  UrdfWriter w(seed);
  std::string links, joints;
  std::vector<std::string> all_links = {"base_link"};
  links += w.link("base_link", 40.0);
  for (const char* side : {"left", "right"}) {
    const std::string wheel = std::string("wheel_") + side + "_link";
    links += w.link(wheel, 2.0);
    joints += w.joint(std::string("wheel_") + side + "_joint", "continuous", "base_link", wheel, "0 1 0");
    all_links.push_back(wheel);
  }
  links += w.link("torso_lift_link", 10.0) + w.link("torso_link", 8.0);
  joints += w.joint("torso_lift_joint", "prismatic", "base_link", "torso_lift_link", "0 0 1");
  joints += w.joint("torso_pan_joint", "revolute", "torso_lift_link", "torso_link", "0 0 1");
  all_links.insert(all_links.end(), {"torso_lift_link", "torso_link"});
  for (const std::string side : {"left", "right"}) {
    std::string parent = "torso_link";
    for (int k = 1; k <= 7; ++k) {
      const std::string link = "arm_" + side + "_" + std::to_string(k) + "_link";
      links += w.link(link, w.uniform(0.5, 3.0));
      joints += w.joint("arm_" + side + "_" + std::to_string(k) + "_joint", "revolute", parent, link, w.random_axis());
      all_links.push_back(link);
      parent = link;
    }
    const std::string hand = "gripper_" + side + "_link";
    links += w.link(hand, 0.8);
    joints += w.joint("gripper_" + side + "_mount", "fixed", parent, hand, "");
    all_links.push_back(hand);
    for (int f = 1; f <= 2; ++f) {
      const std::string finger = "gripper_" + side + "_finger_" + std::to_string(f) + "_link";
      links += w.link(finger, 0.05);
      const std::string mimic =
          f == 2 ? "<mimic joint='gripper_" + side + "_finger_1_joint' multiplier='-1' offset='0'/>" : "";
      joints += w.joint("gripper_" + side + "_finger_" + std::to_string(f) + "_joint", "prismatic", hand, finger,
                        f == 1 ? "0 1 0" : "0 -1 0", mimic);
      all_links.push_back(finger);
    }
  }
  for (int k = 0; k < 20; ++k) {
    const std::string sensor = "sensor_" + std::to_string(k) + "_link";
    const std::string parent = all_links[(k * 7) % all_links.size()];
    links += w.link(sensor, k % 3 == 0 ? 0.0 : w.uniform(0.01, 0.3));
    joints += w.joint("sensor_" + std::to_string(k) + "_mount", "fixed", parent, sensor, "");
  }
  return "<robot name='mobile_manipulator'>" + links + joints + "</robot>";
}

}  // namespace sd_test
