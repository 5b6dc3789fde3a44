// A user of spatial_dynamics in another package: loads the installed Panda URDF (found through
// ros::package::getPath), checks sd::rnea against a second computation of the same torques, then
// calls the node's ~inverse_dynamics through the generated service headers and checks that its
// answers equal sd::rnea.
//   check_inverse_dynamics [NODE]   (NODE: the dynamics node's name, default /dynamics)
// Prints one line per check ("PASS ..." or "FAIL ..."); the exit status is non-zero when any failed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include <ros/package.h>
#include <ros/ros.h>

#include "spatial_dynamics/InverseDynamics.h"
#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace sd = spatial_dynamics;

namespace {

// Both computations are double; 1e-12 relative to the torques' size (at least 1 N m).
constexpr double kTolerance = 1e-12;

struct State {
  Eigen::VectorXd q, qd, qdd;
};

int failures = 0;

void report(bool ok, const std::string& what, double error, double bound) {
  std::printf("%s %s: max error %.3g (bound %.3g)\n", ok ? "PASS" : "FAIL", what.c_str(), error, bound);
  if (!ok) ++failures;
}

/// Reproducible states inside the joint limits, at moderate velocities and accelerations.
std::vector<State> states(const sd::Model<double>& model, int count) {
  std::mt19937 random(20240611);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fraction(0.05, 0.95);
  std::vector<State> result;
  for (int k = 0; k < count; ++k) {
    State s{Eigen::VectorXd::Zero(model.nq), Eigen::VectorXd::Zero(model.nv), Eigen::VectorXd::Zero(model.nv)};
    for (int i = 1; i < model.nbodies(); ++i) {
      const auto& joint = model.joints[i];
      const auto& lim = joint.limits;
      const bool bounded = std::isfinite(lim.position_lower) && std::isfinite(lim.position_upper);
      s.q[joint.idx_q] = bounded ? lim.position_lower + fraction(random) * (lim.position_upper - lim.position_lower)
                                 : unit(random);
      s.qd[joint.idx_v] = unit(random);
      s.qdd[joint.idx_v] = 2.0 * unit(random);
    }
    result.push_back(s);
  }
  return result;
}

double scale(const Eigen::VectorXd& tau) { return std::max(1.0, tau.lpNorm<Eigen::Infinity>()); }

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "dynamics_user_check", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  const std::string node = argc > 1 ? argv[1] : "/dynamics";
  try {
    const std::string package = ros::package::getPath("spatial_dynamics");
    if (package.empty()) {
      std::printf("FAIL the package spatial_dynamics is not found (ROS_PACKAGE_PATH)\n");
      return 1;
    }
    const std::string urdf = package + "/urdf/panda.urdf";
    const sd::Model<double> model = sd::build_model_from_urdf_file(urdf);
    sd::Data<double> data(model);
    std::printf("model %s: nq = %d, nv = %d, simd backend %s\n", urdf.c_str(), model.nq, model.nv, sd::simd_backend());
    const std::vector<State> samples = states(model, 20);

    // 1. The library against itself: RNEA = M(q) qdd + C(q, qd) qd + g(q) (CRBA and the bias
    //    forces), and ID(FD(tau)) = tau (ABA, then RNEA).
    double error_split = 0.0, error_round_trip = 0.0;
    for (const State& s : samples) {
      const Eigen::VectorXd tau = sd::rnea(model, data, s.q, s.qd, s.qdd);
      const Eigen::MatrixXd mass = sd::crba(model, data, s.q);
      const Eigen::VectorXd bias = sd::nonlinear_effects(model, data, s.q, s.qd);
      error_split = std::max(error_split, (tau - (mass * s.qdd + bias)).lpNorm<Eigen::Infinity>() / scale(tau));
      const Eigen::VectorXd qdd = sd::aba(model, data, s.q, s.qd, tau);
      const Eigen::VectorXd tau_back = sd::rnea(model, data, s.q, s.qd, qdd);
      error_round_trip = std::max(error_round_trip, (tau_back - tau).lpNorm<Eigen::Infinity>() / scale(tau));
    }
    report(error_split <= kTolerance, "sd::rnea = sd::crba * qdd + sd::nonlinear_effects (20 states)", error_split,
           kTolerance);
    report(error_round_trip <= kTolerance, "sd::rnea(sd::aba(tau)) = tau (20 states)", error_round_trip, kTolerance);

    // 2. The node against the library.
    const std::string service = ros::names::resolve(node) + "/inverse_dynamics";
    if (!ros::service::waitForService(service, ros::Duration(30.0))) {
      std::printf("FAIL the service %s is not there after 30 s\n", service.c_str());
      return 1;
    }
    double error_node = 0.0;
    bool answered = true;
    for (const State& s : samples) {
      spatial_dynamics::InverseDynamics call;
      for (int i = 1; i < model.nbodies(); ++i) {
        const auto& joint = model.joints[i];
        call.request.name.push_back(model.joint_names[i]);
        call.request.position.push_back(s.q[joint.idx_q]);
        call.request.velocity.push_back(s.qd[joint.idx_v]);
        call.request.acceleration.push_back(s.qdd[joint.idx_v]);
      }
      if (!ros::service::call(service, call) || !call.response.success ||
          call.response.name.size() != call.response.effort.size()) {
        std::printf("FAIL %s: no answer or an error: '%s'\n", service.c_str(), call.response.message.c_str());
        answered = false;
        break;
      }
      const Eigen::VectorXd& tau = sd::rnea(model, data, s.q, s.qd, s.qdd);
      if (static_cast<int>(call.response.name.size()) != model.nv) {
        std::printf("FAIL %s answered %zu joints, the model has %d\n", service.c_str(), call.response.name.size(),
                    model.nv);
        answered = false;
        break;
      }
      for (std::size_t k = 0; k < call.response.name.size(); ++k) {
        const int i = model.jointBody(call.response.name[k]);
        error_node = std::max(error_node, std::abs(call.response.effort[k] - tau[model.joints[i].idx_v]) / scale(tau));
      }
    }
    if (answered)
      report(error_node <= kTolerance, service + " = sd::rnea (20 states)", error_node, kTolerance);
    else
      ++failures;
  } catch (const std::exception& e) {
    std::printf("FAIL error: %s\n", e.what());
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
