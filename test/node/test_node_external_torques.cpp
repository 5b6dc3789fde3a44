// Integration test: external torques, wrenches and collisions through the node (doc/node.md,
// External torques). A simulated Panda (observer_simulation.hpp: the library's forward dynamics,
// RK4 at 1 kHz, a wrench at panda_hand from 1 s to 2.5 s) is published as joint_states at 1 kHz,
// by joint name, with its measured effort; the node's ~external_torques must equal the library's
// observer on the same samples (1e-9) and so the ideal response (1 % of max |Jᵀ F|),
// ~external_wrench/panda_hand the library's wrench fit, ~collision change at the samples where
// the library's estimate crosses the threshold; ~tare_external_torques; and every bad input named
// in diagnostics. node_external_torques_bad_parameters.test: a node started with a bad parameter
// serves everything else, and a ~reload with good ones starts the estimate.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/WrenchStamped.h>

#include <chrono>
#include <limits>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "node_test_utils.hpp"
#include "observer_simulation.hpp"
#include "spatial_dynamics/CollisionState.h"
#include "spatial_dynamics/estimation/external_wrench.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

/// The node's diagnostics: waits until the value of `key` contains `part`; returns the last value seen.
class Diagnostics {
 public:
  explicit Diagnostics(ros::NodeHandle& nh)
      : sub_(nh.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10, [this](const auto& msg) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& status : msg->status) {
            if (status.level == diagnostic_msgs::DiagnosticStatus::ERROR) summary_ = status.message;
            for (const auto& kv : status.values) values_[kv.key] = kv.value;
          }
        })) {}
  std::string waitFor(const std::string& key, const std::string& part, double seconds = 5.0) {
    for (double waited = 0; waited < seconds; waited += 0.05) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (contains(values_[key], part)) return values_[key];
      }
      ros::Duration(0.05).sleep();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    return values_[key];
  }
  /// Waits until the value of `key` is exactly `value`; returns the last value seen.
  std::string waitForExactly(const std::string& key, const std::string& value, double seconds = 5.0) {
    for (double waited = 0; waited < seconds; waited += 0.05) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (values_[key] == value) return value;
      }
      ros::Duration(0.05).sleep();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    return values_[key];
  }
  std::string summary() {
    std::lock_guard<std::mutex> lock(mutex_);
    return summary_;
  }

 private:
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::map<std::string, std::string> values_;
  std::string summary_;
};

constexpr double kStart = 1000.0;  // stamp of the first sample [s]

class NodeExternalTorques : public ServedNodeTest {
 protected:
  void SetUp() override {
    names = robot.model.velocityNames();
    joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10000);
    for (int k = 0; k < 100 && (joint_states.getNumSubscribers() == 0 || !torques.connected()); ++k)
      ros::Duration(0.05).sleep();
  }

  sensor_msgs::JointState sample(double stamp, const VectorXd& q, const VectorXd& qd, const VectorXd& effort) const {
    sensor_msgs::JointState msg;
    msg.header.stamp = ros::Time(stamp);
    msg.name = names;
    msg.position = to_std(q);
    msg.velocity = to_std(qd);
    msg.effort = to_std(effort);
    return msg;
  }

  /// Publishes `messages` at 1 kHz.
  void stream(const std::vector<sensor_msgs::JointState>& messages) {
    auto next = std::chrono::steady_clock::now();
    for (const sensor_msgs::JointState& msg : messages) {
      std::this_thread::sleep_until(next);
      joint_states.publish(msg);
      next += std::chrono::microseconds(1000);
    }
  }

  sd_test::Robot robot = sd_test::robot("panda.urdf", "panda_hand", false);
  std::vector<std::string> names;
  ros::Publisher joint_states;
  Collector<sensor_msgs::JointState> torques{nh, "/dynamics/external_torques"};
  Collector<geometry_msgs::WrenchStamped> wrenches{nh, "/dynamics/external_wrench/panda_hand"};
  Collector<spatial_dynamics::CollisionState> collisions{nh, "/dynamics/collision"};
};

}  // namespace

TEST_F(NodeExternalTorques, AStreamAt1kHzGivesTheLibrarysEstimateWrenchAndCollisions) {
  sd_test::Disturbance d = sd_test::tool_wrench();
  d.wrench_from = 1.0;
  d.wrench_until = 2.5;
  const sd_test::Trajectory run = sd_test::simulate(robot, d, 3.0, 0.0, 11);
  std::vector<sensor_msgs::JointState> messages;
  for (std::size_t k = 0; k < run.t.size(); ++k) messages.push_back(sample(kStart + run.t[k], run.q[k], run.qd[k], run.effort[k]));
  stream(messages);
  const auto received = torques.waitForCount(messages.size(), 20.0);
  ASSERT_EQ(received.size(), messages.size()) << "an estimate per joint_states message";
  const double scale = sd_test::max_abs(run.ideal);
  double to_library = 0, to_ideal = 0;
  for (std::size_t k = 0; k < received.size(); ++k) {
    ASSERT_EQ(received[k].header.stamp, messages[k].header.stamp) << k;
    ASSERT_EQ(received[k].name, names);
    const VectorXd r = to_eigen(received[k].effort);
    to_library = std::max(to_library, (r - run.estimate[k]).cwiseAbs().maxCoeff());
    to_ideal = std::max(to_ideal, (r - run.ideal[k]).cwiseAbs().maxCoeff());
  }
  std::printf("[node] max |Jᵀ F| %.3f N m; |r̂ − library| %.2g, |r̂ − ideal| %.2g N m\n", scale, to_library, to_ideal);
  EXPECT_LE(to_library, 1e-9);
  EXPECT_LE(to_ideal, 0.01 * scale);
  // The wrench at panda_hand: the library's fit of the same r̂; near F once settled (t = 2.4 s).
  const auto wrench_msgs = wrenches.waitForCount(messages.size(), 5.0);
  ASSERT_EQ(wrench_msgs.size(), messages.size());
  sd::Data<double> data(robot.model);
  const int hand = robot.model.frameIndex("panda_hand");
  for (std::size_t k : {std::size_t(1500), std::size_t(2400)}) {
    EXPECT_EQ(wrench_msgs[k].header.frame_id, "panda_hand");
    const sd::ExternalWrench<double> fit = sd::external_wrench(robot.model, data, run.q[k], hand, run.estimate[k]);
    const auto& w = wrench_msgs[k].wrench;
    const VectorXd got = (VectorXd(6) << w.torque.x, w.torque.y, w.torque.z, w.force.x, w.force.y, w.force.z).finished();
    EXPECT_EQ(wrench_msgs[k].header.stamp, messages[k].header.stamp);
    EXPECT_LE((got - fit.wrench.toVector()).norm(), 1e-9 * fit.wrench.toVector().norm())
        << k << ": " << got.transpose() << " vs " << fit.wrench.toVector().transpose() << " r̂ " << to_eigen(received[k].effort).transpose() << " vs " << run.estimate[k].transpose();
    if (k == 2400) {
      EXPECT_LE((got.tail<3>() - d.wrench.linear.eigen()).norm(), 0.02 * d.wrench.linear.norm()) << got.transpose();
      EXPECT_LE((got.head<3>() - d.wrench.angular.eigen()).norm(), 0.02 * d.wrench.angular.norm()) << got.transpose();
    }
  }
  // ~collision (threshold 1 N m): the first sample, then on and off where the library's r̂ crosses.
  std::vector<std::size_t> changes;
  bool in = false;
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    const bool over = run.estimate[k].cwiseAbs().maxCoeff() > 1.0;
    if (over != in) changes.push_back(k), in = over;
  }
  ASSERT_EQ(changes.size(), 2u);
  const auto states = collisions.waitForCount(3, 5.0);
  ASSERT_EQ(states.size(), 3u);
  EXPECT_FALSE(states[0].in_collision);
  EXPECT_EQ(states[0].header.stamp, messages[0].header.stamp);
  EXPECT_TRUE(states[1].in_collision);
  EXPECT_EQ(states[1].header.stamp, messages[changes[0]].header.stamp);
  EXPECT_LE(run.t[changes[0]], 1.020);
  EXPECT_EQ(states[1].frame, "panda_hand");  // of panda_hand and panda_link4, the hand explains r̂
  EXPECT_FALSE(states[1].name.empty());
  EXPECT_EQ(states[1].name.size(), states[1].external_effort.size());
  EXPECT_FALSE(states[2].in_collision);
  EXPECT_EQ(states[2].header.stamp, messages[changes[1]].header.stamp);
  EXPECT_TRUE(states[2].name.empty());
}

TEST_F(NodeExternalTorques, TareMakesTheCurrentEstimateTheZero) {
  // The arm held still with its gravity torques and 3 N m at panda_joint2 the model does not
  // explain: r̂ → −3 there; after the tare, zero.
  sd::Data<double> data(robot.model);
  VectorXd q = VectorXd::Zero(robot.model.nq);
  q[3] = -1.5, q[5] = 1.5;
  const VectorXd still = VectorXd::Zero(robot.model.nv);
  VectorXd effort = sd::gravity_torques(robot.model, data, q);
  effort[1] += 3.0;
  std::vector<sensor_msgs::JointState> messages;
  for (int k = 0; k < 300; ++k) messages.push_back(sample(2000.0 + 1e-3 * k, q, still, effort));
  const std::size_t before = torques.all().size();
  stream(messages);
  auto received = torques.waitForCount(before + messages.size(), 10.0);
  ASSERT_EQ(received.size(), before + messages.size());
  EXPECT_NEAR(received.back().effort[1], -3.0, 0.01);
  std_srvs::Trigger tare;
  ASSERT_TRUE(ros::service::call(service("tare_external_torques"), tare));
  EXPECT_TRUE(tare.response.success) << tare.response.message;
  messages.clear();
  for (int k = 0; k < 100; ++k) messages.push_back(sample(2000.3 + 1e-3 * k, q, still, effort));
  stream(messages);
  received = torques.waitForCount(before + 400, 10.0);
  ASSERT_EQ(received.size(), before + 400);
  EXPECT_LE(to_eigen(received.back().effort).cwiseAbs().maxCoeff(), 1e-6);
}

TEST_F(NodeExternalTorques, BadInputIsNamedInDiagnostics) {
  Diagnostics diagnostics(nh);
  sd::Data<double> data(robot.model);
  const VectorXd q = VectorXd::Constant(robot.model.nq, 0.1), still = VectorXd::Zero(robot.model.nv);
  const VectorXd effort = sd::gravity_torques(robot.model, data, q);
  // No effort at all, then none for panda_joint3: no estimate, the joints named.
  sensor_msgs::JointState msg = sample(3000.0, q, still, effort);
  msg.effort.clear();
  joint_states.publish(msg);
  EXPECT_TRUE(contains(diagnostics.waitFor("external torques: joints without measured effort", "panda_joint1"),
                       "panda_joint7"));
  msg = sample(3000.001, q, still, effort);
  const int j3 = 2;
  msg.name.erase(msg.name.begin() + j3);
  msg.position.erase(msg.position.begin() + j3);
  msg.velocity.erase(msg.velocity.begin() + j3);
  msg.effort.erase(msg.effort.begin() + j3);
  joint_states.publish(msg);
  EXPECT_EQ(diagnostics.waitForExactly("external torques: joints without measured effort", "panda_joint3"), "panda_joint3");
  // A non-finite effort: skipped, counted, named.
  const std::size_t before = torques.all().size();
  joint_states.publish(sample(3000.002, q, still, effort));
  msg = sample(3000.003, q, still, effort);
  msg.effort[4] = std::nan("");
  joint_states.publish(msg);
  EXPECT_TRUE(contains(diagnostics.waitFor("external torques: last skipped", "panda_joint5"), "not finite"));
  msg = sample(3000.0035, q, still, effort);  // a non-finite velocity: the message is dropped, and counted here
  msg.velocity[1] = std::numeric_limits<double>::infinity();
  joint_states.publish(msg);
  EXPECT_TRUE(contains(diagnostics.waitFor("external torques: last skipped", "dropped"), "panda_joint2"));
  // A stamp going back, and a gap over max_gap (0.1 s): restarts, said.
  joint_states.publish(sample(2999.0, q, still, effort));
  EXPECT_TRUE(contains(diagnostics.waitFor("external torques: last restart", "went back"), "went back"));
  joint_states.publish(sample(2999.5, q, still, effort));
  EXPECT_TRUE(contains(diagnostics.waitFor("external torques: last restart", "a gap of 0.500 s"), "a gap"));
  const auto received = torques.waitForCount(before + 3, 5.0);
  EXPECT_EQ(received.size(), before + 3);  // the good sample and the two restarts; not the skipped one
  EXPECT_TRUE(diagnostics.summary().empty()) << diagnostics.summary();
}

// node_external_torques_bad_parameters.test: started with ~external_torques/gain = -1.
TEST_F(NodeExternalTorques, ABadParameterLeavesItOffNamedAndEverythingElseServed) {
  Diagnostics diagnostics(nh);
  EXPECT_TRUE(contains(diagnostics.waitFor("external torques", "/dynamics/external_torques/gain"), "positive"));
  EXPECT_TRUE(contains(diagnostics.summary(), "/dynamics/external_torques/gain")) << diagnostics.summary();
  const VectorXd q = VectorXd::Zero(robot.model.nq);
  joint_states.publish(sample(4000.0, q, q, q));
  const spatial_dynamics::InverseDynamics id = call_inverse_dynamics(q, q, q);
  EXPECT_TRUE(id.response.success) << id.response.message;
  std_srvs::Trigger tare;
  ASSERT_TRUE(ros::service::call(service("tare_external_torques"), tare));
  EXPECT_FALSE(tare.response.success);
  // An unknown frame on ~reload: refused, named; then good parameters start it.
  ros::param::set("/dynamics/external_torques/gain", 40.0);
  ros::param::set("/dynamics/external_torques/frames", std::vector<std::string>{"panda_hand", "no_such_frame"});
  EXPECT_TRUE(reload().response.success);
  EXPECT_TRUE(contains(diagnostics.waitFor("external torques", "no_such_frame"), "frames"));
  ros::param::set("/dynamics/external_torques/frames", std::vector<std::string>{"panda_hand"});
  EXPECT_TRUE(reload().response.success);
  joint_states.publish(sample(4000.001, q, q, q));
  EXPECT_EQ(diagnostics.waitFor("external torques", "estimating"), "estimating");
  EXPECT_GE(torques.waitForCount(1, 5.0).size(), 1u);
}
