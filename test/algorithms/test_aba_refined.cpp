// Forward dynamics with iterative refinement (aba_refined) against the float128 reference
// (reference/forward_dynamics.hpp, the ABA on 6×6 matrices): on every shared robot, fixed and
// floating base, it reaches the double rounding level, and with the float128 escalation it does
// so on states whose long double residual cannot (tiny q̈ against large forces) and on an
// ill-conditioned random chain; with long double and with double-double residuals; a float model
// refines too; a massless leaf still fails naming the joint. The long double sin and cos are
// checked against float128.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/reference/forward_dynamics.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

namespace {

/// Max relative errors of aba_refined with one wide type, alone and with the float128 escalation.
struct Refined {
  double error = 0, escalated = 0;
  int max_iterations = 0;  // wide corrections
  int escalations = 0;     // calls that went on with float128 residuals
};

struct Errors {
  double plain = 0;    // aba
  double kappa = 0;    // largest condition number of M met
  Refined long_double, double_double;
};

template <class W>
void refine_and_measure(const sd::Model<double>& model, sd::Data<double>& data, sd::RefinementWorkspace<double, W>& ws,
                        sd::RefinementWorkspace<double, sd::Quad>& fine, const VectorXd& q, const VectorXd& qd,
                        const VectorXd& tau, const sd::VectorX<sd::Quad>& reference, Refined& r) {
  r.error = std::max(r.error, sd::relative_error_to(sd::aba_refined(model, data, ws, q, qd, tau), reference));
  r.max_iterations = std::max(r.max_iterations, ws.iterations);
  r.escalated = std::max(r.escalated, sd::relative_error_to(sd::aba_refined(model, data, ws, fine, q, qd, tau), reference));
  r.escalations += fine.iterations > 0;
}

/// Max relative errors of aba and aba_refined (long double and double-double residuals) over
/// `states` random states (q̇ ∈ U(−1, 1), q̈ ∈ U(−s, s) for s = qdd_scale, τ = RNEA(q, q̇, q̈) in
/// double), against the reference ABA in float128 on the same (exactly converted) inputs.
Errors measure(const sd::Model<double>& model, int states, unsigned seed, double qdd_scale = 1.0) {
  sd::Data<double> data(model);
  sd::RefinementWorkspace<double, long double> ws_long_double(model);
  sd::RefinementWorkspace<double, sd::DoubleDouble> ws_double_double(model);
  sd::RefinementWorkspace<double, sd::Quad> fine(model);
  const sd::Model<sd::Quad> reference_model = model.cast<sd::Quad>();
  std::mt19937 rng(seed);
  Errors e;
  for (int s = 0; s < states; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd tau = sd::rnea(model, data, q, qd, sd_test::random_vector(model.nv, rng, qdd_scale));
    const sd::VectorX<sd::Quad> reference =
        sd::reference::forward_dynamics(reference_model, sd::to_quad(q), sd::to_quad(qd), sd::to_quad(tau));
    e.plain = std::max(e.plain, sd::relative_error_to(sd::aba(model, data, q, qd, tau), reference));
    refine_and_measure(model, data, ws_long_double, fine, q, qd, tau, reference, e.long_double);
    refine_and_measure(model, data, ws_double_double, fine, q, qd, tau, reference, e.double_double);
    const Eigen::VectorXd lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(sd::crba(model, data, q), Eigen::EigenvaluesOnly).eigenvalues();
    e.kappa = std::max(e.kappa, lambda.maxCoeff() / lambda.minCoeff());
  }
  return e;
}

void print(const char* label, const Errors& e) {
  std::printf("[%s] plain ABA %.3g, kappa %.2g\n", label, e.plain, e.kappa);
  for (const auto& [name, r] : {std::pair<const char*, const Refined&>{"long double", e.long_double},
                                std::pair<const char*, const Refined&>{"double-double", e.double_double}})
    std::printf("    %-13s residual: refined %.3g (%d corrections at most), with float128 %.3g (%d escalated)\n",
                name, r.error, r.max_iterations, r.escalated, r.escalations);
}

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kEpsWide = std::numeric_limits<long double>::epsilon();

}  // namespace

class RefinedRobot : public ::testing::TestWithParam<std::tuple<std::string, bool>> {};

TEST_P(RefinedRobot, ReachesDoubleRoundingLevel) {
  const auto& [file, floating] = GetParam();
  sd::ModelBuildOptions options;
  options.floating_base = floating;
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(file), options);
  const Errors e = measure(model, 100, 11);
  print((file + (floating ? " floating" : "")).c_str(), e);
  // The result is rounded once from the converged wide iterate (≤ ε/2 per entry; 4ε allows for
  // entries of very different size in the norm), and the iteration converges to what the wide
  // residual resolves: κ(M)·ε_W relative, ε_W = ε_ld (5e4 · 1.1e-19 for the floating double
  // pendulum) or 2^-72 for double-double (its sines and cosines).
  for (const auto& [r, eps_wide] : {std::pair<const Refined&, double>{e.long_double, kEpsWide},
                                    std::pair<const Refined&, double>{e.double_double, 0x1p-72}}) {
    EXPECT_LE(r.error, 4 * kEps + e.kappa * eps_wide) << file;
    EXPECT_LE(r.error, e.plain) << file;
    EXPECT_LE(r.escalated, r.error) << file;
    EXPECT_GE(r.max_iterations, 1) << file;
  }
}

INSTANTIATE_TEST_SUITE_P(SharedRobots, RefinedRobot,
                         ::testing::Combine(::testing::ValuesIn(sd_test::robot_files()), ::testing::Bool()),
                         [](const auto& info) {
                           const std::string& f = std::get<0>(info.param);
                           return f.substr(0, f.find('.')) + (std::get<1>(info.param) ? "_floating" : "_fixed");
                         });

TEST(RefinedChain, WinsAtLeastTwoDigitsOnAnIllConditionedChainAndFloat128ReachesRounding) {
  std::mt19937 rng(200);
  const sd::Model<double> model =
      sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(200, rng)));
  const Errors e = measure(model, 10, 12);
  print("200-body chain", e);
  // The limit of the long double residual is about κ ε_ld = κ ε / 2048: at least a factor 100
  // below plain ABA's κ ε-sized error. That limit is above ε (κ ≈ 1e6 here), so every call goes
  // on with float128 residuals (ε_F = 1.9e-34), whose limit is far below double rounding. The
  // double-double residual's limit, κ·2.1e-22, is below ε: it reaches rounding by itself.
  EXPECT_LE(e.long_double.error, 1e-2 * e.plain);
  EXPECT_EQ(e.long_double.escalations, 10);
  EXPECT_LE(e.double_double.error, 4 * kEps);
  for (const Refined& r : {e.long_double, e.double_double}) {
    EXPECT_GE(r.max_iterations, 1);
    EXPECT_LE(r.escalated, 4 * kEps);
  }
}

TEST(RefinedEscalation, ReachesRoundingWhereTheLongDoubleResidualCannot) {
  // Accelerations 1e-3 times smaller than the forces that balance them (τ ≈ h(q, q̇)): plain ABA's
  // relative error grows a thousandfold, and the long double residual's limit passes ε.
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("double_pendulum.urdf"));
  const Errors e = measure(model, 200, 14, 1e-3);
  print("double pendulum, q̈ ∈ U(−1e-3, 1e-3)", e);
  EXPECT_GT(e.long_double.error, 4 * kEps);  // the case the escalation is for
  EXPECT_GE(e.long_double.escalations, 100);
  EXPECT_LE(e.double_double.error, 4 * kEps);  // finer: this case is within its reach
  for (const Refined& r : {e.long_double, e.double_double}) EXPECT_LE(r.escalated, 4 * kEps);
}

TEST(WideSinCos, MatchesFloat128) {
  // Reduction boundaries (multiples of π/4 and π/2 and their neighbours), both signs, up to the
  // 1e5 range of the Cody–Waite reduction, and beyond it (where glibc's sinl and cosl take over).
  std::vector<long double> xs;
  for (int k = -400; k <= 400; ++k) {
    const double x = k * M_PI / 4;
    xs.push_back(x);
    xs.push_back(std::nextafter(x, 1e300));
    xs.push_back(std::nextafter(x, -1e300));
  }
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> wide(-1e5, 1e5), narrow(-10, 10);
  for (int k = 0; k < 2000; ++k) {
    xs.push_back(wide(rng));
    xs.push_back(narrow(rng));
  }
  for (long double x : {1e-300L, -3e-8L, 99999.99L, 1e5L, 1.0000001e5L, -7e6L}) xs.push_back(x);
  double worst = 0;
  for (long double x : xs) {
    long double s, c;
    sd::detail::sin_cos_wide(x, s, c);
    const sd::Quad xq(x);
    worst = std::max({worst, static_cast<double>(abs(sd::Quad(s) - sin(xq))),
                      static_cast<double>(abs(sd::Quad(c) - cos(xq)))});
  }
  std::printf("[sin_cos_wide] max absolute error %.3g over %zu arguments\n", worst, xs.size());
  EXPECT_LE(worst, 2 * kEpsWide);
}

TEST(RefinedFloat, RefinesAFloatModelToFloatRounding) {
  const sd::Model<double> model_d = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  const sd::Model<float> model = model_d.cast<float>();
  sd::Data<float> data(model);
  sd::RefinementWorkspace<float> ws(model);
  const sd::Model<sd::Quad> reference_model = model.cast<sd::Quad>();
  std::mt19937 rng(13);
  double plain = 0, refined = 0;
  for (int s = 0; s < 50; ++s) {
    const Eigen::VectorXf q = sd_test::random_configuration(model_d, rng).cast<float>();
    const Eigen::VectorXf qd = sd_test::random_vector(model.nv, rng).cast<float>();
    const Eigen::VectorXf tau = sd::rnea(model, data, q, qd, Eigen::VectorXf(sd_test::random_vector(model.nv, rng).cast<float>()));
    const sd::VectorX<sd::Quad> reference =
        sd::reference::forward_dynamics(reference_model, sd::to_quad(q), sd::to_quad(qd), sd::to_quad(tau));
    plain = std::max(plain, sd::relative_error_to(sd::aba(model, data, q, qd, tau), reference));
    refined = std::max(refined, sd::relative_error_to(sd::aba_refined(model, data, ws, q, qd, tau), reference));
  }
  std::printf("[panda, float] plain ABA %.3g, refined %.3g\n", plain, refined);
  EXPECT_LE(refined, 4 * std::numeric_limits<float>::epsilon());
  EXPECT_LT(refined, plain);
}

TEST(RefinedMasslessLeaf, FailsNamingTheJointAsAbaDoes) {
  std::mt19937 rng(4);
  std::vector<sd::synthetic::Link> links = sd::synthetic::random_chain(3, rng);
  links.back().mass = 0.0;  // a massless leaf on its own revolute joint
  const sd::Model<double> model = sd::build_model_from_urdf_string(sd::synthetic::to_urdf("leaf", links));
  sd::Data<double> data(model);
  sd::RefinementWorkspace<double> ws(model);
  const VectorXd zero = VectorXd::Zero(model.nv);
  try {
    sd::aba_refined(model, data, ws, zero, zero, zero);
    FAIL() << "forward dynamics of a massless leaf must fail";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("'joint3'"), std::string::npos) << e.what();
  }
}
