// Forward dynamics with iterative refinement (aba_refined) against the float128 reference: on
// every shared robot, fixed and floating base, it reaches the double rounding level; on an
// ill-conditioned random chain it wins at least two digits over plain ABA; a float model refines
// too; a massless leaf still fails naming the joint.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdio>

#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

namespace {

struct Errors {
  double plain = 0, refined = 0;
  double kappa = 0;  // largest condition number of M met
  int max_iterations = 0;
};

/// Max relative errors of aba and aba_refined over `states` random states (q̇, q̈ ∈ U(−1, 1),
/// τ = RNEA(q, q̇, q̈) in double), against ABA in float128 on the same (exactly converted) inputs.
Errors measure(const sd::Model<double>& model, int states, unsigned seed) {
  sd::Data<double> data(model);
  sd::RefinementWorkspace<double> ws(model);
  const sd::Model<sd::Quad> reference_model = model.cast<sd::Quad>();
  sd::Data<sd::Quad> reference_data(reference_model);
  std::mt19937 rng(seed);
  Errors e;
  for (int s = 0; s < states; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd tau = sd::rnea(model, data, q, qd, sd_test::random_vector(model.nv, rng));
    const sd::VectorX<sd::Quad> reference =
        sd::aba(reference_model, reference_data, sd::to_quad(q), sd::to_quad(qd), sd::to_quad(tau));
    e.plain = std::max(e.plain, sd::relative_error_to(sd::aba(model, data, q, qd, tau), reference));
    e.refined = std::max(e.refined, sd::relative_error_to(sd::aba_refined(model, data, ws, q, qd, tau), reference));
    e.max_iterations = std::max(e.max_iterations, ws.iterations);
    const Eigen::VectorXd lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(sd::crba(model, data, q), Eigen::EigenvaluesOnly).eigenvalues();
    e.kappa = std::max(e.kappa, lambda.maxCoeff() / lambda.minCoeff());
  }
  return e;
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
  const Errors e = measure(model, 50, 11);
  std::printf("[%s%s] plain ABA %.3g, refined %.3g (%d corrections at most, kappa %.2g)\n", file.c_str(),
              floating ? " floating" : "", e.plain, e.refined, e.max_iterations, e.kappa);
  // The result is rounded once from the converged wide iterate (≤ ε/2 per entry; 4ε allows for
  // entries of very different size in the norm), and the iteration converges to what the long
  // double residual resolves: κ(M)·ε_ld relative (5e4 · 1.1e-19 for the floating double pendulum).
  EXPECT_LE(e.refined, 4 * kEps + e.kappa * kEpsWide) << file;
  EXPECT_LE(e.refined, e.plain) << file;
  EXPECT_GE(e.max_iterations, 1) << file;
}

INSTANTIATE_TEST_SUITE_P(SharedRobots, RefinedRobot,
                         ::testing::Combine(::testing::ValuesIn(sd_test::robot_files()), ::testing::Bool()),
                         [](const auto& info) {
                           const std::string& f = std::get<0>(info.param);
                           return f.substr(0, f.find('.')) + (std::get<1>(info.param) ? "_floating" : "_fixed");
                         });

TEST(RefinedChain, WinsAtLeastTwoDigitsOnAnIllConditionedChain) {
  std::mt19937 rng(200);
  const sd::Model<double> model =
      sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(200, rng)));
  const Errors e = measure(model, 10, 12);
  std::printf("[200-body chain] plain ABA %.3g, refined %.3g (%d corrections at most)\n", e.plain, e.refined,
              e.max_iterations);
  // Each correction gains about κ ε (≈ 1e-6 here); the limit is the long double residual,
  // about κ ε_ld = κ ε / 2048: at least a factor 100 below plain ABA's κ ε-sized error.
  EXPECT_LE(e.refined, 1e-2 * e.plain);
  EXPECT_GE(e.max_iterations, 2);
}

TEST(RefinedFloat, RefinesAFloatModelToFloatRounding) {
  const sd::Model<double> model_d = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  const sd::Model<float> model = model_d.cast<float>();
  sd::Data<float> data(model);
  sd::RefinementWorkspace<float> ws(model);
  const sd::Model<sd::Quad> reference_model = model.cast<sd::Quad>();
  sd::Data<sd::Quad> reference_data(reference_model);
  std::mt19937 rng(13);
  double plain = 0, refined = 0;
  for (int s = 0; s < 50; ++s) {
    const Eigen::VectorXf q = sd_test::random_configuration(model_d, rng).cast<float>();
    const Eigen::VectorXf qd = sd_test::random_vector(model.nv, rng).cast<float>();
    const Eigen::VectorXf tau = sd::rnea(model, data, q, qd, Eigen::VectorXf(sd_test::random_vector(model.nv, rng).cast<float>()));
    const sd::VectorX<sd::Quad> reference = sd::aba(reference_model, reference_data, sd::to_quad(q), sd::to_quad(qd), sd::to_quad(tau));
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
