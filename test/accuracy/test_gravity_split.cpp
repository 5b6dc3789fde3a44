// The ABA's gravity split (algorithms/gravity_split.hpp) against the float128 reference: the
// joint forces it hands the passes, τ − τ_g(q), and the accelerations it reaches on the shared
// robots, which the anchors bound (Pinocchio's and RBDL's FD, max over their states).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "spatial_dynamics/reference/high_precision.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using sd_test::robot_path;

namespace {

using sd::Quad;

struct RobotCase {
  std::string file;
  bool floating;
  double aba_bound;  // the best anchor's FD error on that row (or the best comparator's)
};

struct State {
  Eigen::VectorXd q, qd, tau;
};

/// The benchmark's states: q uniform in (−π, π) (a unit quaternion for a free root), q̇, q̈ in
/// (−1, 1), τ = RNEA(q, q̇, q̈) in double.
std::vector<State> benchmark_states(const sd::Model<double>& model, int count) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  sd::Data<double> data(model);
  std::vector<State> states;
  for (int s = 0; s < count; ++s) {
    State st;
    st.q.resize(model.nq);
    for (int i = 1; i < model.nbodies(); ++i) {
      const auto& j = model.joints[i];
      if (j.type == sd::JointType::Free) {
        for (int k = 0; k < 3; ++k) st.q[j.idx_q + k] = u(rng);
        Eigen::Vector4d quat(u(rng), u(rng), u(rng), u(rng));
        st.q.segment<4>(j.idx_q + 3) = quat.normalized();
      } else {
        st.q[j.idx_q] = M_PI * u(rng);
      }
    }
    st.qd = Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); });
    const Eigen::VectorXd qdd = Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); });
    st.tau = sd::rnea(model, data, st.q, st.qd, qdd);
    states.push_back(st);
  }
  return states;
}

sd::Model<double> load(const RobotCase& c) {
  sd::ModelBuildOptions options;
  options.floating_base = c.floating;
  return sd::build_model_from_urdf_file(robot_path(c.file), options);
}

const std::vector<RobotCase>& cases() {
  static const std::vector<RobotCase> list = {
      {"panda.urdf", false, 3.9e-14},  {"ur5.urdf", false, 1.8e-14},  {"talos.urdf", false, 9.2e-14},
      {"solo12.urdf", true, 1.35e-13}, {"talos.urdf", true, 8.2e-13},
  };
  return list;
}

// τ − τ_g as the ABA forms it, against τ − τ_g(q) of the float128 RNEA: off by the rounding of the
// model's transforms and the final rounding only (2.3 ε of ‖τ_g‖ at worst when written).
TEST(GravitySplit, JointForcesLessGravityAgainstTheReference) {
  const double eps = std::numeric_limits<double>::epsilon();
  for (const RobotCase& c : cases()) {
    const sd::Model<double> model = load(c);
    const sd::Model<Quad> model_q = model.cast<Quad>();
    sd::Data<double> data(model);
    sd::Data<Quad> data_q(model_q);
    double worst = 0;
    for (const State& st : benchmark_states(model, 100)) {
      sd::aba(model, data, st.q, st.qd, st.tau);
      const sd::VectorX<Quad> gravity = sd::gravity_torques(model_q, data_q, sd::to_quad(st.q));
      const sd::VectorX<Quad> expected = sd::to_quad(st.tau) - gravity;
      const double error = static_cast<double>((sd::to_quad(data.tau_less_gravity) - expected).norm() / gravity.norm());
      worst = std::max(worst, error);
    }
    std::printf("%s (%s): worst ‖τ − τ_g error‖ / ‖τ_g‖ = %.2e (%.1f ε)\n", c.file.c_str(),
                c.floating ? "floating" : "fixed", worst, worst / eps);
    EXPECT_LE(worst, 4 * eps) << c.file;
  }
}

// Plain ABA over the benchmark's first 300 states within the anchors' FD errors. Without the split
// (gravity as the base acceleration) panda reached 8.0e-14, ur5 3.1e-14 and talos 1.1e-13 on these
// states in the portable build, and with it 2.4e-14, 1.0e-14 and 4.3e-14.
TEST(GravitySplit, AbaWithinTheAnchorsOnTheSharedRobots) {
  for (const RobotCase& c : cases()) {
    const sd::Model<double> model = load(c);
    const sd::Model<Quad> model_q = model.cast<Quad>();
    sd::Data<double> data(model);
    sd::Data<Quad> data_q(model_q);
    double worst = 0;
    for (const State& st : benchmark_states(model, 300)) {
      const sd::VectorX<Quad> reference = sd::aba(model_q, data_q, sd::to_quad(st.q), sd::to_quad(st.qd), sd::to_quad(st.tau));
      worst = std::max(worst, sd::relative_error_to(sd::aba(model, data, st.q, st.qd, st.tau), reference));
    }
    std::printf("%s (%s): worst ABA error %.2e (bound %.2e)\n", c.file.c_str(), c.floating ? "floating" : "fixed", worst,
                c.aba_bound);
    EXPECT_LE(worst, c.aba_bound) << c.file;
  }
}

}  // namespace
