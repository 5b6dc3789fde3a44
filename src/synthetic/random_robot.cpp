#include "spatial_dynamics/synthetic/random_robot.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

namespace spatial_dynamics {
namespace synthetic {
namespace {

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

std::string triple(const Eigen::Vector3d& v) { return number(v.x()) + " " + number(v.y()) + " " + number(v.z()); }

double uniform(std::mt19937& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  Eigen::Quaterniond q(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  return q.normalized().toRotationMatrix();
}

}  // namespace

Eigen::Vector3d random_unit_vector(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  for (;;) {
    const Eigen::Vector3d v(n(rng), n(rng), n(rng));
    if (v.norm() > 1e-3) return v.normalized();
  }
}

Eigen::Matrix3d box_inertia(double m, double a, double b, double c, const Eigen::Matrix3d& R) {
  const Eigen::Vector3d d(b * b + c * c, a * a + c * c, a * a + b * b);  // I_xx = m (b² + c²) / 12, …
  return R * (m / 12.0 * d).asDiagonal() * R.transpose();
}

Link random_link(int parent, std::mt19937& rng, const RandomOptions& o) {
  Link l;
  l.parent = parent;
  l.joint_xyz = uniform(rng, o.offset_min, o.offset_max) * random_unit_vector(rng);
  l.joint_rpy = Eigen::Vector3d(uniform(rng, -M_PI, M_PI), uniform(rng, -M_PI / 2, M_PI / 2), uniform(rng, -M_PI, M_PI));
  l.axis = random_unit_vector(rng);
  l.mass = o.log_uniform_mass ? std::exp(uniform(rng, std::log(o.mass_min), std::log(o.mass_max)))
                              : uniform(rng, o.mass_min, o.mass_max);
  l.com = Eigen::Vector3d(uniform(rng, -o.com_max, o.com_max), uniform(rng, -o.com_max, o.com_max),
                          uniform(rng, -o.com_max, o.com_max));
  l.inertia = box_inertia(l.mass, uniform(rng, o.box_min, o.box_max), uniform(rng, o.box_min, o.box_max),
                          uniform(rng, o.box_min, o.box_max), random_rotation(rng));
  return l;
}

std::vector<Link> random_chain(int n, std::mt19937& rng, const RandomOptions& options) {
  std::vector<Link> links(1);
  links[0].mass = 1.0;
  links[0].inertia = box_inertia(1.0, 0.1, 0.1, 0.1, Eigen::Matrix3d::Identity());
  for (int i = 1; i <= n; ++i) links.push_back(random_link(i - 1, rng, options));
  return links;
}

std::vector<Link> random_tree(int n, std::mt19937& rng, const RandomOptions& options) {
  std::vector<Link> links(1);
  links[0].mass = 1.0;
  links[0].inertia = box_inertia(1.0, 0.1, 0.1, 0.1, Eigen::Matrix3d::Identity());
  for (int i = 1; i <= n; ++i) links.push_back(random_link(std::uniform_int_distribution<int>(0, i - 1)(rng), rng, options));
  return links;
}

std::string to_urdf(const std::string& robot_name, const std::vector<Link>& links) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<robot name=\"" << robot_name << "\">\n";
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Link& l = links[i];
    if (i > 0 && (l.parent < 0 || l.parent >= static_cast<int>(i)))
      throw std::invalid_argument("link " + std::to_string(i) + ": parent " + std::to_string(l.parent) +
                                  " is not an earlier link");
    s << "  <link name=\"link" << i << "\">";
    if (l.mass > 0.0) {
      const Eigen::Matrix3d& I = l.inertia;
      s << "\n    <inertial><origin xyz=\"" << triple(l.com) << "\" rpy=\"0 0 0\"/><mass value=\"" << number(l.mass)
        << "\"/>\n      <inertia ixx=\"" << number(I(0, 0)) << "\" ixy=\"" << number(I(0, 1)) << "\" ixz=\""
        << number(I(0, 2)) << "\" iyy=\"" << number(I(1, 1)) << "\" iyz=\"" << number(I(1, 2)) << "\" izz=\""
        << number(I(2, 2)) << "\"/></inertial>\n  ";
    }
    s << "</link>\n";
  }
  for (std::size_t i = 1; i < links.size(); ++i) {
    const Link& l = links[i];
    s << "  <joint name=\"joint" << i << "\" type=\"continuous\"><parent link=\"link" << l.parent
      << "\"/><child link=\"link" << i << "\"/>\n    <origin xyz=\"" << triple(l.joint_xyz) << "\" rpy=\""
      << triple(l.joint_rpy) << "\"/><axis xyz=\"" << triple(l.axis) << "\"/></joint>\n";
  }
  s << "</robot>\n";
  return s.str();
}

}  // namespace synthetic
}  // namespace spatial_dynamics
