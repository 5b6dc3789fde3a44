// The ABA's gravity split (algorithms/gravity_split.hpp) against the float128 reference
// (reference/: RNEA and ABA on 6×6 matrices): the joint forces it hands the passes, τ − τ_g(q),
// and the accelerations it reaches on the shared robots, which the anchors bound
// (Pinocchio's and RBDL's FD, max over their states).
#include <gtest/gtest.h>

#include <cstdio>

#include "random_states.hpp"  // bench/: the benchmark's states
#include "spatial_dynamics/reference/forward_dynamics.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/reference/inverse_dynamics.hpp"
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

/// A case's model in double and float128, the double workspace and the benchmark's states.
struct Loaded {
  explicit Loaded(const RobotCase& c, int states)
      : model(sd::build_model_from_urdf_file(robot_path(c.file), options(c))),
        model_q(model.cast<Quad>()),
        data(model),
        pool(bench::random_states(model, states, 12345)) {}
  static sd::ModelBuildOptions options(const RobotCase& c) {
    sd::ModelBuildOptions o;
    o.floating_base = c.floating;
    return o;
  }
  sd::Model<double> model;
  sd::Model<Quad> model_q;
  sd::Data<double> data;
  std::vector<bench::State> pool;
};

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
    Loaded l(c, 100);
    double worst = 0;
    for (const bench::State& st : l.pool) {
      sd::aba(l.model, l.data, st.q, st.qd, st.tau);
      const sd::VectorX<Quad> gravity = sd::reference::gravity_torques(l.model_q, sd::to_quad(st.q));
      const sd::VectorX<Quad> expected = sd::to_quad(st.tau) - gravity;
      const double error = static_cast<double>((sd::to_quad(l.data.tau_less_gravity) - expected).norm() / gravity.norm());
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
    Loaded l(c, 300);
    double worst = 0;
    for (const bench::State& st : l.pool) {
      const sd::VectorX<Quad> reference =
          sd::reference::forward_dynamics(l.model_q, sd::to_quad(st.q), sd::to_quad(st.qd), sd::to_quad(st.tau));
      worst = std::max(worst, sd::relative_error_to(sd::aba(l.model, l.data, st.q, st.qd, st.tau), reference));
    }
    std::printf("%s (%s): worst ABA error %.2e (bound %.2e)\n", c.file.c_str(), c.floating ? "floating" : "fixed", worst,
                c.aba_bound);
    EXPECT_LE(worst, c.aba_bound) << c.file;
  }
}

}  // namespace
