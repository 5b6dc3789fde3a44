// The node's per-scene external-torque estimate (ros/external_torque_estimator.hpp), without ROS:
// its parameters checked against the model (each refusal names the parameter), the default frames,
// restarts on a gap and on a stamp going back, skipped samples, the collision state, the tare and
// its carry-over to a rebuilt model; its r̂ is the library observer's on the same samples.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "observer_simulation.hpp"
#include "spatial_dynamics/ros/external_torque_estimator.hpp"

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

namespace {

std::shared_ptr<const sd::Model<double>> panda() {
  return std::make_shared<const sd::Model<double>>(sd::build_model_from_urdf_file(sd_test::robot_path("panda.urdf")));
}

const std::vector<std::string> kLeaves = {"panda_leftfinger", "panda_rightfinger", "panda_hand_tcp", "no_such_link"};

std::string refusal(const sd::ExternalTorqueSettings& settings) {
  try {
    sd::ExternalTorqueEstimator estimator(panda(), settings, kLeaves, {});
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ExternalTorqueEstimator, RefusesBadParametersNamingThem) {
  sd::ExternalTorqueSettings s;
  s.parameter = "/dynamics/external_torques";
  s.gain = -1.0;
  EXPECT_NE(refusal(s).find("/dynamics/external_torques/gain must be a positive"), std::string::npos) << refusal(s);
  s.gain = std::numeric_limits<double>::infinity();
  EXPECT_NE(refusal(s).find("/dynamics/external_torques/gain"), std::string::npos);
  s.gain = 50;
  s.joint_gains = {{"panda_joint9", 10.0}};
  EXPECT_NE(refusal(s).find("names joint 'panda_joint9'"), std::string::npos) << refusal(s);
  s.joint_gains = {{"panda_joint2", 0.0}};
  EXPECT_NE(refusal(s).find("/dynamics/external_torques/gain/panda_joint2"), std::string::npos) << refusal(s);
  s.joint_gains.clear();
  s.detect_collisions = true;
  s.threshold = 0.0;
  EXPECT_NE(refusal(s).find("/dynamics/external_torques/collision_threshold"), std::string::npos) << refusal(s);
  s.threshold = 1.0;
  s.frames_given = true;
  s.frames = {"panda_hand", "gripper_tip"};
  EXPECT_NE(refusal(s).find("frames names frame 'gripper_tip'"), std::string::npos) << refusal(s);
  s.frames = {"panda_hand"};
  s.max_gap = 0.0;
  EXPECT_NE(refusal(s).find("/dynamics/external_torques/max_gap"), std::string::npos) << refusal(s);
  s.max_gap = 0.1;
  EXPECT_EQ(refusal(s), "");
}

TEST(ExternalTorqueEstimator, DefaultFramesAreTheLeafLinksTheModelMoves) {
  sd::ExternalTorqueEstimator estimator(panda(), sd::ExternalTorqueSettings(), kLeaves, {});
  EXPECT_EQ(estimator.frames(), (std::vector<std::string>{"panda_leftfinger", "panda_rightfinger", "panda_hand_tcp"}));
}

TEST(ExternalTorqueEstimator, MatchesTheLibraryObserverRestartsSkipsAndTares) {
  const sd_test::Robot robot = sd_test::robots()[1];  // panda
  sd_test::Disturbance d = sd_test::tool_wrench();
  d.wrench_from = 1.0;
  d.wrench_until = 2.0;
  const sd_test::Trajectory run = sd_test::simulate(robot, d, 3.0, 0.0, 7);
  sd::ExternalTorqueSettings s;
  s.detect_collisions = true;
  s.threshold = 1.0;
  s.frames_given = true;
  s.frames = {"panda_link4", "panda_hand"};
  auto model = std::make_shared<const sd::Model<double>>(robot.model);
  sd::ExternalTorqueEstimator estimator(model, s, {}, {});
  int changes = 0, first_collision = -1;
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    const auto& e = estimator.update(100.0 + run.t[k], run.q[k], run.qd[k], run.effort[k]);
    ASSERT_LE((*e.torques - run.estimate[k]).cwiseAbs().maxCoeff(), 1e-9) << "sample " << k;
    EXPECT_EQ(e.restarted, k == 0);
    if (e.collision_changed) {
      ++changes;
      if (e.in_collision && first_collision < 0) {
        first_collision = static_cast<int>(k);
        EXPECT_EQ(estimator.frames()[e.best_frame], "panda_hand");  // the wrench is at the hand
        EXPECT_FALSE(e.over_threshold.empty());
      }
    }
  }
  EXPECT_GE(first_collision, 1000);  // on with the wrench, within 20 ms
  EXPECT_LE(first_collision, 1020);
  EXPECT_EQ(changes, 2);             // and off again after it
  // A non-finite effort or the same stamp again: skipped, the observer as it was.
  VectorXd bad = run.effort.back();
  bad[3] = std::nan("");
  try {
    estimator.update(200.0, run.q.back(), run.qd.back(), bad);
    ADD_FAILURE() << "a NaN effort was estimated";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("effort of joint 'panda_joint4'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(estimator.update(100.0 + run.t.back(), run.q.back(), run.qd.back(), run.effort.back()), std::invalid_argument);
  EXPECT_EQ(estimator.restarts(), 0);
  // A stamp going back, and a gap over max_gap: restarts, saying why.
  const auto& back = estimator.update(100.0, run.q.back(), run.qd.back(), run.effort.back());
  EXPECT_TRUE(back.restarted);
  EXPECT_NE(back.restart_reason.find("went back"), std::string::npos) << back.restart_reason;
  const auto& gap = estimator.update(100.5, run.q.back(), run.qd.back(), run.effort.back());
  EXPECT_TRUE(gap.restarted);
  EXPECT_NE(gap.restart_reason.find("a gap of 0.500 s"), std::string::npos) << gap.restart_reason;
  EXPECT_EQ(estimator.restarts(), 2);
  // The tare: the arm held still with its gravity torques plus 3 N m at joint 2 that the model
  // does not explain (r̂ → −3 there); the current r̂ becomes the zero, and a rebuilt model's
  // estimator keeps it.
  sd::Data<double> data(*model);
  const VectorXd q = run.q.back(), still = VectorXd::Zero(model->nv);
  VectorXd effort = sd::gravity_torques(*model, data, q);
  effort[1] += 3.0;
  for (int k = 1; k <= 300; ++k) estimator.update(100.5 + 1e-3 * k, q, still, effort);
  const auto& before = estimator.update(100.801, q, still, effort);
  EXPECT_NEAR((*before.torques)[1], -3.0, 1e-3);
  ASSERT_TRUE(estimator.tare());
  const auto& after = estimator.update(100.802, q, still, effort);
  EXPECT_LE(after.torques->cwiseAbs().maxCoeff(), 1e-5);  // what was still settling (e^{−K t} ≈ 3e-7 · 3)
  EXPECT_NEAR(estimator.tareByJoint().at("panda_joint2"), -3.0, 1e-3);
  sd::ExternalTorqueEstimator rebuilt(model, s, {}, {}, estimator.tareByJoint());
  for (int k = 0; k <= 300; ++k) rebuilt.update(200.0 + 1e-3 * k, q, still, effort);
  EXPECT_LE(rebuilt.update(200.301, q, still, effort).torques->cwiseAbs().maxCoeff(), 1e-3);
}
