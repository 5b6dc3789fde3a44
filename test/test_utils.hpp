// Helpers shared by the unit tests: robot paths, random states and norm-wise relative errors.
#pragma once

#include <cmath>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"
#include "test_paths.hpp"

namespace sd_test {

namespace sd = spatial_dynamics;

inline std::string robot_path(const std::string& file) { return std::string(robots_dir()) + "/" + file; }

/// The URDF text of a bundled robot.
inline std::string robot_text(const std::string& file) {
  std::ifstream in(robot_path(file));
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// `urdf` with `extra` (links and joints) added before </robot>.
inline std::string with_extra_elements(const std::string& urdf, const std::string& extra) {
  const std::size_t end = urdf.rfind("</robot>");
  return urdf.substr(0, end) + extra + urdf.substr(end);
}

/// Every robot of the shared set, by file name.
inline const std::vector<std::string>& robot_files() {
  static const std::vector<std::string> files = {"double_pendulum.urdf", "panda.urdf", "ur5.urdf", "solo12.urdf",
                                                 "talos.urdf"};
  return files;
}

/// ‖x − ref‖ / ‖ref‖ (absolute when ref is zero).
template <class A, class B>
double relative_error(const A& x, const B& ref) {
  const double denominator = ref.norm();
  const double difference = (x - ref).norm();
  return denominator > 0 ? difference / denominator : difference;
}

/// A random configuration: joints uniform within their limits (in [−π, π] where the URDF gives
/// none or an empty range, as the double pendulum's lower = upper = 0 does), a unit
/// quaternion for a free joint, a planar joint's translations in (−1, 1).
inline Eigen::VectorXd random_configuration(const sd::Model<double>& model, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q(model.nq);
  for (int i = 1; i < model.nbodies(); ++i) {
    const auto& j = model.joints[i];
    if (j.type == sd::JointType::Free) {
      for (int k = 0; k < 3; ++k) q[j.idx_q + k] = u(rng);
      Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
      quat.normalize();
      q.segment<4>(j.idx_q + 3) = quat;
    } else if (j.type == sd::JointType::Planar) {  // x, y in (−1, 1) m, yaw in (−π, π)
      q[j.idx_q] = u(rng);
      q[j.idx_q + 1] = u(rng);
      q[j.idx_q + 2] = M_PI * u(rng);
    } else if (std::isfinite(j.limits.position_lower) && std::isfinite(j.limits.position_upper) &&
               j.limits.position_upper > j.limits.position_lower) {  // an empty range (lower = upper = 0) means no limit
      const double mid = 0.5 * (j.limits.position_lower + j.limits.position_upper);
      const double half = 0.5 * (j.limits.position_upper - j.limits.position_lower);
      q[j.idx_q] = mid + half * u(rng);
    } else {
      q[j.idx_q] = M_PI * u(rng);
    }
  }
  return q;
}

inline Eigen::VectorXd random_vector(int n, std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int k = 0; k < n; ++k) v[k] = u(rng);
  return v;
}

}  // namespace sd_test
