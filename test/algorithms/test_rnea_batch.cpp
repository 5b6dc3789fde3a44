// The batched RNEA against the one-state rnea, state by state: every shared robot (fixed and
// floating base), random general axes and prismatic joints, coupled mimic joints, block
// remainders and N = 0, 1; no allocation per call; errors that name the state.
#include <gtest/gtest.h>

#include <limits>

#include "allocation_counter.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "synthetic_robots.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kTolerance = 1e-13;

/// N random states as columns: q within limits (unit quaternions), q̇, q̈ ∈ U(−2, 2).
struct Trajectory {
  MatrixXd q, qd, qdd;
  Trajectory(const sd::Model<double>& model, int n, std::mt19937& rng)
      : q(model.nq, n), qd(model.nv, n), qdd(model.nv, n) {
    for (int k = 0; k < n; ++k) {
      q.col(k) = sd_test::random_configuration(model, rng);
      qd.col(k) = sd_test::random_vector(model.nv, rng, 2.0);
      qdd.col(k) = sd_test::random_vector(model.nv, rng, 2.0);
    }
  }
};

/// max over states of ‖τ_batch − τ_rnea‖∞ / ‖τ_rnea‖∞, with rnea called on each column.
double worst_relative_difference(const sd::Model<double>& model, const Trajectory& t, const MatrixXd& tau) {
  sd::Data<double> data(model);
  double worst = 0;
  for (Eigen::Index k = 0; k < t.q.cols(); ++k) {
    const VectorXd expected = sd::rnea(model, data, t.q.col(k), t.qd.col(k), t.qdd.col(k));
    const double scale = expected.lpNorm<Eigen::Infinity>();
    worst = std::max(worst, (tau.col(k) - expected).lpNorm<Eigen::Infinity>() / (scale > 0 ? scale : 1.0));
  }
  return worst;
}

/// Runs the batch with L lanes on N states for several N around the block size and checks every
/// state against rnea; the result is written into the middle of a wider matrix whose other
/// columns must stay untouched.
template <int L>
void expect_matches_rnea(const sd::Model<double>& model, std::mt19937& rng, const std::string& what) {
  sd::BatchData<double, L> batch(model);
  for (int n : {0, 1, L - 1, L, L + 1, 2 * L + 3, 37}) {
    if (n < 0) continue;
    const Trajectory t(model, n, rng);
    MatrixXd wide = MatrixXd::Constant(model.nv, n + 2, -7.0);
    auto tau = wide.middleCols(1, n);
    sd::rnea_batch(model, batch, t.q, t.qd, t.qdd, tau);
    EXPECT_LE(worst_relative_difference(model, t, tau), kTolerance) << what << ", " << L << " lanes, N = " << n;
    EXPECT_TRUE((wide.col(0).array() == -7.0).all() && (wide.col(n + 1).array() == -7.0).all())
        << what << ": columns outside the result were written";
  }
}

template <int L>
void expect_matches_rnea_on_robots(bool floating, std::mt19937& rng) {
  for (const std::string& file : sd_test::robot_files()) {
    sd::ModelBuildOptions options;
    options.floating_base = floating;
    const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
    expect_matches_rnea<L>(model, rng, file + (floating ? " (floating)" : " (fixed)"));
  }
}

}  // namespace

class RneaBatchOnRobots : public ::testing::TestWithParam<bool> {};

TEST_P(RneaBatchOnRobots, EveryStateEqualsOneStateRnea) {
  std::mt19937 rng(GetParam() ? 11 : 12);
  expect_matches_rnea_on_robots<sd::kDefaultBatchLanes<double>>(GetParam(), rng);
  expect_matches_rnea_on_robots<1>(GetParam(), rng);
  expect_matches_rnea_on_robots<3>(GetParam(), rng);
  expect_matches_rnea_on_robots<8>(GetParam(), rng);
}

INSTANTIATE_TEST_SUITE_P(Base, RneaBatchOnRobots, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Floating" : "Fixed"; });

TEST(RneaBatch, GeneralAxesAndPrismaticJointsEqualOneStateRnea) {
  // Random unit axes (the general-axis path) on a chain and a tree; the synthetic mobile
  // manipulator has axis-aligned and general prismatic joints and a mimic finger.
  std::mt19937 rng(5);
  const sd::Model<double> chain = sd::build_model_from_urdf_string(
      sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(12, rng)));
  const sd::Model<double> tree = sd::build_model_from_urdf_string(
      sd::synthetic::to_urdf("tree", sd::synthetic::random_tree(20, rng)));
  const sd::Model<double> manipulator = sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf(3));
  int general_revolute = 0, general_prismatic = 0;
  for (const auto* model : {&chain, &tree, &manipulator})
    for (int i = 1; i < model->nbodies(); ++i)
      if (model->joints[i].axis_kind == sd::AxisKind::General)
        (model->joints[i].type == sd::JointType::Revolute ? general_revolute : general_prismatic)++;
  ASSERT_GT(general_revolute, 0);
  ASSERT_GT(general_prismatic, 0);
  expect_matches_rnea<4>(chain, rng, "random chain");
  expect_matches_rnea<4>(tree, rng, "random tree");
  expect_matches_rnea<4>(manipulator, rng, "mobile manipulator");
}

TEST(RneaBatch, CoupledMimicJointsEqualOneStateRnea) {
  std::mt19937 rng(6);
  for (const std::string file : {"panda.urdf", "talos.urdf"}) {
    const sd::Model<double> coupled = sd::couple_mimic_joints(sd::build_model_from_urdf_file(sd_test::robot_path(file)));
    ASSERT_TRUE(coupled.has_coupled_joints) << file;
    expect_matches_rnea<4>(coupled, rng, file + " (coupled mimic joints)");
  }
}

TEST(RneaBatch, CallsDoNotAllocate) {
  std::mt19937 rng(7);
  for (const std::string& file : sd_test::robot_files()) {
    for (bool floating : {false, true}) {
      sd::ModelBuildOptions options;
      options.floating_base = floating;
      const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
      const sd::Model<double> coupled = sd::couple_mimic_joints(model);
      for (const auto* m : {&model, &coupled}) {
        sd::BatchData<double> batch(*m);
        const Trajectory t(*m, 11, rng);
        MatrixXd tau(m->nv, 11);
        const long before_sanity = bench::allocation_count();  // the counter works
        ::operator delete(::operator new(64));
        ASSERT_EQ(bench::allocation_count() - before_sanity, 1);
        const long before = bench::allocation_count();
        sd::rnea_batch(*m, batch, t.q, t.qd, t.qdd, tau);
        auto first_three = tau.leftCols(3);
        sd::rnea_batch(*m, batch, t.q.leftCols(3), t.qd.leftCols(3), t.qdd.leftCols(3), first_three);
        EXPECT_EQ(bench::allocation_count() - before, 0) << file << (floating ? " (floating)" : " (fixed)")
                                             << (m == &coupled ? ", coupled" : "");
      }
    }
  }
}

TEST(RneaBatch, ErrorsNameTheStateAndTheArgument) {
  sd::ModelBuildOptions options;
  options.floating_base = true;
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("ur5.urdf"), options);
  sd::BatchData<double> batch(model);
  std::mt19937 rng(8);
  Trajectory t(model, 6, rng);
  MatrixXd tau(model.nv, 6);
  auto message_of = [&](const MatrixXd& q, const MatrixXd& qd, const MatrixXd& qdd, MatrixXd& out) -> std::string {
    try {
      sd::rnea_batch(model, batch, q, qd, qdd, out);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "(no error)";
  };
  // Shapes.
  EXPECT_EQ(message_of(t.q.topRows(model.nq - 1), t.qd, t.qdd, tau), "q (rows) has 12 entries; the model expects 13");
  EXPECT_EQ(message_of(t.q, t.qd.leftCols(5), t.qdd, tau), "velocity has 5 columns (states); q has 6");
  MatrixXd short_tau(model.nv, 4);
  EXPECT_EQ(message_of(t.q, t.qd, t.qdd, short_tau), "tau has 4 columns (states); q has 6");
  // A non-unit quaternion in state 5 (the partial second block).
  Trajectory bad = t;
  bad.q(6, 5) += 0.1;
  EXPECT_THROW(sd::rnea_batch(model, batch, bad.q, bad.qd, bad.qdd, tau), std::invalid_argument);
  EXPECT_EQ(message_of(bad.q, bad.qd, bad.qdd, tau),
            "state 5: joint 'root_joint': the quaternion (q[3..6]) is not of unit norm");
  // A non-finite input in state 2: the joint force is not finite, naming the state.
  bad = t;
  bad.qdd(model.nv - 1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(sd::rnea_batch(model, batch, bad.q, bad.qd, bad.qdd, tau), std::domain_error);
  const std::string nan_message = message_of(bad.q, bad.qd, bad.qdd, tau);
  EXPECT_EQ(nan_message.rfind("state 2: inverse dynamics: the joint force for '", 0), 0u) << nan_message;
  // A workspace of another model.
  sd::BatchData<double> other(sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf")));
  EXPECT_THROW(sd::rnea_batch(model, other, t.q, t.qd, t.qdd, tau), std::invalid_argument);
}

TEST(RneaBatch, LaneSineAndCosineAgreeWithTheCLibrary) {
  // The reduced polynomial evaluation against std::sin and std::cos: random angles over the joint
  // range and far beyond it, angles next to multiples of π/2 (the reduction's hard cases), and the
  // huge or non-finite angles that take the C library itself.
  std::mt19937 rng(9);
  std::vector<double> angles;
  for (double scale : {1.0, 4.0, 100.0, 1e5}) {
    std::uniform_real_distribution<double> u(-scale, scale);
    for (int k = 0; k < 2000; ++k) angles.push_back(u(rng));
  }
  for (int k = -40000; k <= 40000; k += 7)
    for (double eps : {0.0, 1e-12, -3e-9}) angles.push_back(k * (M_PI / 2) + eps);
  for (double x : {0.0, -0.0, 1e-300, 1e6, -3e15, std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::quiet_NaN()})
    angles.push_back(x);
  angles.resize((angles.size() + 1) / 2 * 2, 0.5);
  double worst = 0;
  for (std::size_t k = 0; k < angles.size(); k += 2) {
    sd::Lanes<double, 2> x, s, c;
    x.set(0, angles[k]);
    x.set(1, angles[k + 1]);
    sd::sincos_lanes(x, s, c);
    for (int l = 0; l < 2; ++l) {
      const double a = x[l];
      if (!std::isfinite(a)) {
        EXPECT_TRUE(std::isnan(s[l]) && std::isnan(c[l])) << a;
        continue;
      }
      worst = std::max({worst, std::abs(s[l] - std::sin(a)), std::abs(c[l] - std::cos(a))});
    }
  }
  EXPECT_LE(worst, 4.5e-16);  // two units in the last place of a number below 1
}
