// Synthetic robots for accuracy tests and benchmarks, written as URDF text so that every library
// loads the same file: serial chains and branched trees with random unit axes, joint offsets of
// 5–15 cm with random roll-pitch-yaw, masses in a given range (uniform or log-uniform), random
// centres of mass, and full inertia tensors of random boxes in random orientations.
#pragma once

#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace spatial_dynamics {
namespace synthetic {

/// One link and the revolute joint that attaches it to its parent (the root link has none).
struct Link {
  int parent = -1;                                    // index into the link list; -1 for the root
  Eigen::Vector3d joint_xyz = Eigen::Vector3d::Zero();  // joint origin in the parent link frame
  Eigen::Vector3d joint_rpy = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();    // unit axis in the joint frame
  double mass = 0.0;                                  // 0 writes no <inertial> (a massless link)
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      // centre of mass in the link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centre of mass, link axes
};

struct RandomOptions {
  double mass_min = 0.5, mass_max = 2.0;
  bool log_uniform_mass = false;        // masses log-uniform in [mass_min, mass_max]
  double offset_min = 0.05, offset_max = 0.15;  // joint offset lengths [m]
  double box_min = 0.02, box_max = 0.2;         // box side lengths [m] (inertias scale with mass)
  double com_max = 0.05;                        // |centre of mass coordinate| bound [m]
};

/// A random unit vector, uniform on the sphere.
Eigen::Vector3d random_unit_vector(std::mt19937& rng);

/// Inertia about the centre of a uniform box of mass m and sides a, b, c, rotated by R: R diag Rᵀ.
Eigen::Matrix3d box_inertia(double m, double a, double b, double c, const Eigen::Matrix3d& R);

/// A random link (joint offset, axis, mass, centre of mass, rotated box inertia) below `parent`.
Link random_link(int parent, std::mt19937& rng, const RandomOptions& options = {});

/// A root link plus n links, each the child of the previous one.
std::vector<Link> random_chain(int n, std::mt19937& rng, const RandomOptions& options = {});

/// A root link plus n links, each the child of a random earlier link (a branched tree).
std::vector<Link> random_tree(int n, std::mt19937& rng, const RandomOptions& options = {});

/// URDF text: links "link0".."linkN", revolute joints "joint1".."jointN" (continuous, no limits).
/// Numbers are written with 17 significant digits, so every loader reads exactly these doubles.
std::string to_urdf(const std::string& robot_name, const std::vector<Link>& links);

}  // namespace synthetic
}  // namespace spatial_dynamics
