// Loads a URDF (default: the package's urdf/panda.urdf, found through roslib) and prints its
// gravity torques g(q) at the zero configuration and at a second one (the Panda's "ready" pose, or
// mid-range of every joint's limits for other robots).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <ros/package.h>

#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace sd = spatial_dynamics;

namespace {

Eigen::VectorXd second_configuration(const sd::Model<double>& model) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq);
  const char* panda_ready[][2] = {{"panda_joint2", "-0.785398163397448"}, {"panda_joint4", "-2.35619449019234"},
                                  {"panda_joint6", "1.5707963267949"}, {"panda_joint7", "0.785398163397448"}};
  bool is_panda = model.hasJoint("panda_joint7");
  for (int i = 1; i < model.nbodies(); ++i) {
    const auto& lim = model.joints[i].limits;
    if (!is_panda && std::isfinite(lim.position_lower) && std::isfinite(lim.position_upper))
      q[model.joints[i].idx_q] = 0.5 * (lim.position_lower + lim.position_upper) + 0.25 * (lim.position_upper - lim.position_lower);
  }
  if (is_panda)
    for (const auto& entry : panda_ready) q[model.joints[model.jointBody(entry[0])].idx_q] = std::stod(entry[1]);
  return q;
}

void print(const sd::Model<double>& model, sd::Data<double>& data, const char* label, const Eigen::VectorXd& q) {
  const Eigen::VectorXd& tau = sd::gravity_torques(model, data, q);
  std::printf("\n%s\n  %-24s %14s %14s\n", label, "joint", "position", "torque [N m|N]");
  for (int i = 1; i < model.nbodies(); ++i) {
    const auto& j = model.joints[i];
    const double shown = std::abs(tau[j.idx_v]) < 5e-7 ? 0.0 : tau[j.idx_v];  // what %.6f shows, without "-0.000000"
    std::printf("  %-24s %14.6f %14.6f\n", model.joint_names[i].c_str(), q[j.idx_q], shown);
  }
}

/// The bundled Panda: urdf/panda.urdf in the package's share directory (the source tree in the
/// devel space), as ROS_PACKAGE_PATH has it; empty, after an error message, when the package is not found.
std::string default_urdf() {
  const std::string package = ros::package::getPath("spatial_dynamics");
  if (package.empty()) {
    const char* package_path = std::getenv("ROS_PACKAGE_PATH");
    std::fprintf(stderr,
                 "error: no URDF given, and the default, urdf/panda.urdf of the package spatial_dynamics, cannot be found:\n"
                 "  the package spatial_dynamics is not on ROS_PACKAGE_PATH (%s).\n"
                 "  Source the setup.bash of the workspace it is built or installed in, or give a URDF: "
                 "print_gravity_torques URDF\n",
                 package_path != nullptr && *package_path != '\0' ? package_path : "unset");
    return std::string();
  }
  return package + "/urdf/panda.urdf";
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : default_urdf();
  if (path.empty()) return 1;
  try {
    const sd::Model<double> model = sd::build_model_from_urdf_file(path);
    sd::Data<double> data(model);
    std::printf("model: %s\n  %d moving bodies, %d frames, nq = %d, nv = %d, gravity = (%g, %g, %g) m/s^2\n", path.c_str(),
                model.nbodies() - 1, static_cast<int>(model.frames.size()), model.nq, model.nv, model.gravity.x(),
                model.gravity.y(), model.gravity.z());
    print(model, data, "gravity torques at q = 0", Eigen::VectorXd::Zero(model.nq));
    print(model, data, "gravity torques at the second configuration", second_configuration(model));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
