// The momentum observer and the wrench estimate (estimation/) on a simulated robot: the library's
// own forward dynamics (forward_dynamics_actuated, RK4 at 1 kHz) under a PD controller with gravity
// compensation that tracks random sums of sines, whose torque is the measured effort. Checked
// against the ideal response ṙ = K (τ_ext − r), integrated exactly for a τ_ext linear between
// samples:
//  - a constant wrench F on the tool frame from t = 5 s (20 s): r̂ within 1 % of max |Jᵀ F| of the
//    ideal response, and the wrench estimated at the tool within 1 % (force and moment each) of
//    the least-squares wrench of the ideal response;
//  - the same with Gaussian effort noise σ = 0.05 N·m: r̂ within 0.3 N·m of the ideal response;
//  - 60 s of free motion with that noise: no joint over a 1 N·m threshold;
//  - a 5 N·m external torque step at one joint: over the threshold within 20 ms, not before;
// on the UR5 and the Panda, and on the Panda with damping and Coulomb friction in the actuator
// model. And the observer's refusals: a bad gain, a non-finite input, a bad time step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "observer_simulation.hpp"
#include "spatial_dynamics/estimation/external_wrench.hpp"

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

namespace {

constexpr double kThreshold = 1.0;
using sd_test::kDt;
using sd_test::kGain;
using sd_test::Disturbance;
using sd_test::Robot;
using sd_test::Trajectory;
using sd_test::max_abs;
using sd_test::max_difference;
using sd_test::robots;
using sd_test::simulate;
using sd_test::tool_wrench;

}  // namespace

TEST(MomentumObserver, FollowsTheIdealResponseToAToolWrench) {
  for (const Robot& r : robots()) {
    const Trajectory run = simulate(r, tool_wrench(), 20.0, 0.0, 1);
    const double scale = max_abs(run.ideal), error = max_difference(run);
    // The wrench at the tool from r̂ and from the ideal response, after the wrench is on.
    sd::Data<double> data(r.model);
    const int tool = r.model.frameIndex(r.tool);
    double force_scale = 0, moment_scale = 0, force_error = 0, moment_error = 0;
    int min_rank = 6;
    for (std::size_t k = 0; k < run.t.size(); ++k) {
      if (run.t[k] < 5.0) continue;
      const sd::ExternalWrench<double> ideal = sd::external_wrench(r.model, data, run.q[k], tool, run.ideal[k]);
      const sd::ExternalWrench<double> estimate = sd::external_wrench(r.model, data, run.q[k], tool, run.estimate[k]);
      min_rank = std::min(min_rank, estimate.rank);
      force_scale = std::max(force_scale, ideal.wrench.linear.norm());
      moment_scale = std::max(moment_scale, ideal.wrench.angular.norm());
      force_error = std::max(force_error, (estimate.wrench.linear - ideal.wrench.linear).norm());
      moment_error = std::max(moment_error, (estimate.wrench.angular - ideal.wrench.angular).norm());
    }
    std::printf("[observer] %-34s max|JᵀF| %6.3f N m, |r̂ − ideal| %8.2g N m; wrench: force %6.3f N err %8.2g, "
                "moment %6.3f N m err %8.2g\n",
                r.name.c_str(), scale, error, force_scale, force_error, moment_scale, moment_error);
    EXPECT_GT(scale, 1.0) << r.name;
    EXPECT_LE(error, 0.01 * scale) << r.name;
    EXPECT_EQ(min_rank, 6) << r.name;
    EXPECT_LE(force_error, 0.01 * force_scale) << r.name;
    EXPECT_LE(moment_error, 0.01 * moment_scale) << r.name;
    // Before the wrench, no disturbance: the ideal response is zero and r̂ stays near it.
    EXPECT_EQ(run.ideal[4000].norm(), 0.0) << r.name;
  }
}

TEST(MomentumObserver, WithEffortNoiseStaysWithin0_3NmOfTheIdealResponse) {
  for (const Robot& r : robots()) {
    const Trajectory run = simulate(r, tool_wrench(), 20.0, 0.05, 2);
    const double error = max_difference(run);
    std::printf("[observer] %-34s noise σ 0.05 N m: |r̂ − ideal| %6.3f N m\n", r.name.c_str(), error);
    EXPECT_LE(error, 0.3) << r.name;
  }
}

TEST(MomentumObserver, NoCollisionIn60sOfFreeMotionWithNoise) {
  for (const Robot& r : robots()) {
    const Trajectory run = simulate(r, Disturbance(), 60.0, 0.05, 3);
    const double largest = max_abs(run.estimate);
    std::printf("[observer] %-34s 60 s free motion, noise σ 0.05 N m: max |r̂| %6.3f N m\n", r.name.c_str(), largest);
    EXPECT_LT(largest, kThreshold) << r.name;
  }
}

TEST(MomentumObserver, FlagsA5NmStepWithin20ms) {
  for (const Robot& r : robots()) {
    Disturbance d;
    d.step_joint = 2;
    d.step = 5.0;
    d.step_from = 3.0;
    const Trajectory run = simulate(r, d, 4.0, 0.05, 4);
    double flagged_at = -1;
    for (std::size_t k = 0; k < run.t.size() && flagged_at < 0; ++k)
      if (run.estimate[k].cwiseAbs().maxCoeff() > kThreshold) flagged_at = run.t[k];
    std::printf("[observer] %-34s 5 N m step at 3 s flagged at %.3f s\n", r.name.c_str(), flagged_at);
    EXPECT_GE(flagged_at, 3.0) << r.name;
    EXPECT_LE(flagged_at, 3.020) << r.name;
  }
}

TEST(MomentumObserver, TareMakesTheCurrentEstimateTheZero) {
  // The wrench on from 5 s, tared at 10 s: from then on r̂ follows the ideal response less its
  // value at 10 s (Jᵀ F changes as the arm moves), starting from zero.
  const Robot r = robots()[1];
  const Trajectory run = simulate(r, tool_wrench(), 15.0, 0.0, 6, 10.0);
  const double scale = max_abs(run.ideal), error = max_difference(run);
  std::printf("[observer] %-34s tared at 10 s: |r̂ − (ideal − tared)| %8.2g N m (max |ideal − tared| %6.3f)\n",
              r.name.c_str(), error, scale);
  EXPECT_EQ(run.estimate[10000].norm(), 0.0);
  EXPECT_GT(run.estimate[9999].norm(), 1.0);
  EXPECT_LE(error, 0.01 * scale);
}

TEST(MomentumObserver, RefusesBadGainInputAndTimeStep) {
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("ur5.urdf"));
  const int n = model.nv;
  VectorXd gain = VectorXd::Constant(n, kGain);
  gain[2] = 0.0;
  try {
    sd::MomentumObserver<double> bad(model, gain);
    ADD_FAILURE() << "a zero gain was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'elbow_joint'"), std::string::npos) << e.what();
  }
  gain[2] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(sd::MomentumObserver<double>(model, gain), std::invalid_argument);
  sd::MomentumObserver<double> observer(model, VectorXd::Constant(n, kGain));
  const VectorXd q = VectorXd::Constant(n, 0.3), qd = VectorXd::Constant(n, 0.2), tau = VectorXd::Constant(n, 1.0);
  observer.update(q, qd, tau, kDt);
  VectorXd bad_tau = tau;
  bad_tau[4] = std::nan("");
  try {
    observer.update(q, qd, bad_tau, kDt);
    ADD_FAILURE() << "a NaN effort was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("measured effort of 'wrist_2_joint'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(observer.update(q, qd, tau, 0.0), std::invalid_argument);
  EXPECT_THROW(observer.update(q, qd, tau, -kDt), std::invalid_argument);
  EXPECT_THROW(observer.update(q, VectorXd::Zero(n + 1), tau, kDt), std::invalid_argument);
  // Refused samples leave it as it was: the same sample twice more gives the response to a
  // constant momentum, and reset() starts again from zero.
  const VectorXd first = observer.update(q, qd, tau, kDt);
  EXPECT_TRUE(first.allFinite());
  observer.reset();
  EXPECT_FALSE(observer.started());
  EXPECT_EQ(observer.update(q, qd, tau, kDt).norm(), 0.0);
}

TEST(ExternalWrench, RecoversAWrenchAndReportsRank) {
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf"));
  sd::Data<double> data(model);
  std::mt19937 rng(5);
  const int tool = model.frameIndex("panda_hand");
  for (int trial = 0; trial < 20; ++trial) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const sd::ForceVector<double> F(sd::Vector6<double>(sd_test::random_vector(6, rng, 10.0)));
    const VectorXd r = sd::frame_jacobian(model, data, q, tool, sd::ReferenceFrame::Local).transpose() * F.toVector();
    const sd::ExternalWrench<double> w = sd::external_wrench(model, data, q, tool, r);
    EXPECT_EQ(w.rank, 6);
    EXPECT_TRUE(w.determined());
    EXPECT_LE(sd_test::relative_error(w.wrench.toVector(), F.toVector()), 1e-10) << "condition " << w.condition;
    EXPECT_LE(w.residual, 1e-10 * r.norm());
  }
  // The double pendulum's tip is moved by two joints: rank 2, the minimum-norm wrench that
  // explains r exactly, not a blown-up one.
  const sd::Model<double> pendulum = sd::build_model_from_urdf_file(sd_test::robot_path("double_pendulum.urdf"));
  sd::Data<double> pd(pendulum);
  const int tip = pendulum.frameIndex(pendulum.body_names.back());
  const VectorXd q = VectorXd::Constant(pendulum.nq, 0.4), r = VectorXd::Constant(pendulum.nv, 2.0);
  const sd::ExternalWrench<double> w = sd::external_wrench(pendulum, pd, q, tip, r);
  EXPECT_EQ(w.rank, 2);
  EXPECT_FALSE(w.determined());
  const VectorXd explained = sd::frame_jacobian(pendulum, pd, q, tip, sd::ReferenceFrame::Local).transpose() * w.wrench.toVector();
  EXPECT_LE((explained - r).norm(), 1e-12);
  EXPECT_LE(w.wrench.toVector().norm(), 10 * r.norm());
  EXPECT_THROW(sd::external_wrench(pendulum, pd, q, 99, r), std::out_of_range);
}
