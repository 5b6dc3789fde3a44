// Integration test: payload identification through the node (doc/payload_identification.md). The
// node serves the Panda; the test asks ~excitation_trajectory for the arm's joints, simulates the arm
// carrying a 2.1 kg tool on panda_link8 along it (the library's inverse dynamics) and
//  - gives the samples to ~identify_payload with apply: the identified tool equals the simulated one
//    (exact efforts: 1e-6) and ~inverse_dynamics then equals the simulation with the tool;
//  - publishes them as joint_states at 200 Hz while ~identify_payload records (record_seconds):
//    the node keeps serving ~inverse_dynamics meanwhile, refuses a second recording by name, and the
//    recorded identification (accelerations by differences of the velocities) matches within 1 %;
//  - refuses every bad input by name and attaches nothing.
#include <atomic>
#include <thread>

#include "node_test_utils.hpp"
#include "panda_tool.hpp"
#include "spatial_dynamics/ExcitationTrajectory.h"
#include "spatial_dynamics/IdentifyPayload.h"
#include "spatial_dynamics/SetPayload.h"
#include "spatial_dynamics/reduction/payload.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

const char* const kFrame = "panda_link8";

spatial_dynamics::ExcitationTrajectory excitation(double duration) {
  spatial_dynamics::ExcitationTrajectory srv;
  srv.request.joints = sd_test::panda_arm_joints();
  srv.request.duration = duration;
  srv.request.speed_scale = 0.5;
  return call("excitation_trajectory", srv);
}

/// The trajectory's points with the efforts of `truth` (the fingers at 0, at rest).
trajectory_msgs::JointTrajectory with_efforts(const sd::Model<double>& truth, trajectory_msgs::JointTrajectory t) {
  sd::Data<double> data(truth);
  for (trajectory_msgs::JointTrajectoryPoint& p : t.points) {
    VectorXd q = VectorXd::Zero(truth.nq), qd = VectorXd::Zero(truth.nv), qdd = VectorXd::Zero(truth.nv);
    for (std::size_t j = 0; j < t.joint_names.size(); ++j) {
      const int k = truth.joints[truth.jointBody(t.joint_names[j])].idx_v;
      q[k] = p.positions[j], qd[k] = p.velocities[j], qdd[k] = p.accelerations[j];
    }
    const VectorXd tau = sd::rnea(truth, data, q, qd, qdd);
    p.effort.clear();
    for (const std::string& name : t.joint_names) p.effort.push_back(tau[truth.joints[truth.jointBody(name)].idx_v]);
  }
  return t;
}

spatial_dynamics::IdentifyPayload identify(const trajectory_msgs::JointTrajectory& samples, bool apply) {
  spatial_dynamics::IdentifyPayload srv;
  srv.request.frame = kFrame;
  srv.request.samples = samples;
  srv.request.apply = apply;
  return call("identify_payload", srv);
}

double tool_error(const geometry_msgs::Inertia& m) {
  const sd::Payload t = sd_test::panda_tool();
  return std::max({std::abs(m.m - t.mass) / t.mass, (Eigen::Vector3d(m.com.x, m.com.y, m.com.z) - t.center_of_mass).norm() / 0.1,
                   std::abs(m.ixx - t.inertia(0, 0)) / 0.04, std::abs(m.ixy - t.inertia(0, 1)) / 0.04,
                   std::abs(m.iyz - t.inertia(1, 2)) / 0.04, std::abs(m.izz - t.inertia(2, 2)) / 0.04});
}

/// Removes any payload on kFrame.
void detach() {
  spatial_dynamics::SetPayload srv;
  srv.request.frame = kFrame;
  EXPECT_TRUE(call("set_payload", srv).response.success);
}

/// ~inverse_dynamics at a fixed state against the library on `expected_model`.
double inverse_dynamics_error(const sd::Model<double>& expected_model) {
  VectorXd q(9), qd(9), qdd(9);
  q << 0.3, -0.4, 0.2, -1.9, 0.1, 1.6, 0.5, 0.01, 0.01;
  qd << 0.5, -0.3, 0.2, 0.4, -0.6, 0.3, 0.9, 0, 0;
  qdd << 1.0, -0.5, 0.7, 0.3, -1.2, 0.8, 2.0, 0, 0;
  const spatial_dynamics::InverseDynamics srv = call_inverse_dynamics(q, qd, qdd);
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  sd::Data<double> data(expected_model);
  const VectorXd expected = sd::rnea(expected_model, data, q, qd, qdd);
  return (to_eigen(srv.response.effort) - expected).norm() / expected.norm();
}

class PayloadIdentificationNode : public ServedNodeTest {
 protected:
  static void SetUpTestSuite() {
    ServedNodeTest::SetUpTestSuite();
    ASSERT_TRUE(ros::service::waitForService(service("identify_payload"), ros::Duration(30)));
    // the gripper's own publisher, at 20 Hz throughout: the fingers at 0, which samples of the arm
    // leave out (and which must be fresher than ~max_state_age)
    gripper_running_ = true;
    gripper_ = std::thread([] {
      ros::NodeHandle nh;
      ros::Publisher gripper = nh.advertise<sensor_msgs::JointState>("/joint_states", 10);
      sensor_msgs::JointState fingers;
      fingers.name = {"panda_finger_joint1", "panda_finger_joint2"};
      fingers.position = {0.0, 0.0};
      fingers.velocity = {0.0, 0.0};
      while (gripper_running_) {
        fingers.header.stamp = ros::Time::now();
        gripper.publish(fingers);
        ros::WallDuration(0.05).sleep();
      }
    });
    ros::WallDuration(1.0).sleep();
  }
  static void TearDownTestSuite() {
    gripper_running_ = false;
    if (gripper_.joinable()) gripper_.join();
  }
  static std::atomic<bool> gripper_running_;
  static std::thread gripper_;
};

std::atomic<bool> PayloadIdentificationNode::gripper_running_{false};
std::thread PayloadIdentificationNode::gripper_;

}  // namespace

TEST_F(PayloadIdentificationNode, ExcitationTrajectoryIsAtRestAndWithinLimits) {
  const spatial_dynamics::ExcitationTrajectory srv = excitation(20.0);
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const trajectory_msgs::JointTrajectory& t = srv.response.trajectory;
  ASSERT_EQ(t.points.size(), 2001u);
  EXPECT_EQ(t.joint_names, sd_test::panda_arm_joints());
  EXPECT_NEAR(t.points[1].time_from_start.toSec(), 0.01, 1e-9);
  const sd::Model<double> model = model_from_parameter();
  for (std::size_t j = 0; j < 7; ++j) {
    const sd::JointLimits<double>& limits = model.joints[model.jointBody(t.joint_names[j])].limits;
    for (const auto& p : t.points) {
      ASSERT_LE(std::abs(p.velocities[j]), 0.5 * limits.velocity);
      ASSERT_GE(p.positions[j], limits.position_lower);
      ASSERT_LE(p.positions[j], limits.position_upper);
    }
    EXPECT_LE(std::abs(t.points.front().velocities[j]), 1e-12);
    EXPECT_LE(std::abs(t.points.back().velocities[j]), 1e-12);
  }
  EXPECT_GT(srv.response.condition_number, 1.0);
}

TEST_F(PayloadIdentificationNode, SamplesGivenIdentifyAndApplyTheTool) {
  const sd::Model<double> model = model_from_parameter();
  const sd::Model<double> truth = sd::with_payloads(model, {{kFrame, sd_test::panda_tool()}});
  const spatial_dynamics::ExcitationTrajectory trajectory = excitation(20.0);
  ASSERT_TRUE(trajectory.response.success) << trajectory.response.message;
  const spatial_dynamics::IdentifyPayload srv = identify(with_efforts(truth, trajectory.response.trajectory), true);
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_TRUE(contains(srv.response.message, "attached")) << srv.response.message;
  EXPECT_LE(tool_error(srv.response.inertia), 1e-6) << srv.response.message;
  EXPECT_TRUE(srv.response.unidentifiable.empty());
  EXPECT_EQ(srv.response.name, sd_test::panda_arm_joints());
  EXPECT_LE(inverse_dynamics_error(truth), 1e-6);
  detach();
  EXPECT_LE(inverse_dynamics_error(model), 1e-12);
}

TEST_F(PayloadIdentificationNode, RecordedFromJointStatesWhileServing) {
  const sd::Model<double> model = model_from_parameter();
  const sd::Model<double> truth = sd::with_payloads(model, {{kFrame, sd_test::panda_tool()}});
  const spatial_dynamics::ExcitationTrajectory trajectory = excitation(10.0);
  ASSERT_TRUE(trajectory.response.success) << trajectory.response.message;
  const trajectory_msgs::JointTrajectory samples = with_efforts(truth, trajectory.response.trajectory);
  ros::Publisher pub = nh.advertise<sensor_msgs::JointState>("/joint_states", 1000);
  for (int k = 0; k < 50 && pub.getNumSubscribers() == 0; ++k) ros::Duration(0.1).sleep();

  spatial_dynamics::IdentifyPayload recorded;
  recorded.request.frame = kFrame;
  recorded.request.record_seconds = 4.0;
  std::thread recorder([&] { recorded = call("identify_payload", recorded); });
  ros::Duration(0.3).sleep();
  // a second recording is refused, and the other services keep serving
  spatial_dynamics::IdentifyPayload second;
  second.request.frame = kFrame;
  second.request.record_seconds = 1.0;
  second = call("identify_payload", second);
  EXPECT_FALSE(second.response.success);
  EXPECT_TRUE(contains(second.response.message, "already in progress")) << second.response.message;
  EXPECT_LE(inverse_dynamics_error(model), 1e-12);
  // joint_states at 100 Hz along the first 3.5 s (the trajectory's points every 10 ms), stamped as sampled
  const ros::Time start = ros::Time::now();
  for (std::size_t k = 0; k < 350; ++k) {
    const trajectory_msgs::JointTrajectoryPoint& p = samples.points[k];
    sensor_msgs::JointState msg;
    msg.header.stamp = start + p.time_from_start;
    msg.name = samples.joint_names;
    msg.position = p.positions;
    msg.velocity = p.velocities;
    msg.effort = p.effort;
    pub.publish(msg);
    ros::WallDuration(0.009).sleep();
  }
  recorder.join();
  ASSERT_TRUE(recorded.response.success) << recorded.response.message;
  EXPECT_TRUE(contains(recorded.response.message, "recorded")) << recorded.response.message;
  std::printf("[node] recorded identification: %s, relative error %.3g\n", recorded.response.message.c_str(),
              tool_error(recorded.response.inertia));
  EXPECT_LE(tool_error(recorded.response.inertia), 0.01);
  EXPECT_LE(inverse_dynamics_error(model), 1e-12);  // not applied
}

TEST_F(PayloadIdentificationNode, BadInputRefusedByNameAndNothingAttached) {
  const sd::Model<double> model = model_from_parameter();
  const sd::Model<double> truth = sd::with_payloads(model, {{kFrame, sd_test::panda_tool()}});
  const spatial_dynamics::ExcitationTrajectory trajectory = excitation(2.0);
  ASSERT_TRUE(trajectory.response.success) << trajectory.response.message;
  const trajectory_msgs::JointTrajectory good = with_efforts(truth, trajectory.response.trajectory);
  auto refused = [&](spatial_dynamics::IdentifyPayload srv, const std::string& needle) {
    srv.request.apply = true;
    srv = call("identify_payload", srv);
    EXPECT_FALSE(srv.response.success) << needle;
    EXPECT_TRUE(contains(srv.response.message, needle)) << srv.response.message;
  };
  spatial_dynamics::IdentifyPayload srv;
  srv.request.frame = kFrame;
  srv.request.samples = good;
  srv.request.frame = "no_such_link";
  refused(srv, "'no_such_link'");
  srv.request.frame = kFrame;
  srv.request.samples.points[5].effort.pop_back();
  refused(srv, "point 5 has 6 effort");
  srv.request.samples = good;
  for (auto& p : srv.request.samples.points) p.effort.clear();
  refused(srv, "effort");
  srv.request.samples = good;
  srv.request.samples.points[7].velocities[2] = std::numeric_limits<double>::quiet_NaN();
  refused(srv, "velocities of joint 'panda_joint3' in point 7 is not finite");
  srv.request.samples = good;
  srv.request.samples.joint_names = {"panda_joint7"};
  srv.request.samples.points.resize(3);
  for (auto& p : srv.request.samples.points) p.positions.resize(1), p.velocities.resize(1), p.accelerations.resize(1), p.effort.resize(1);
  refused(srv, "fewer than the 10 parameters");
  srv.request.samples = good;
  srv.request.record_seconds = 1.0;
  refused(srv, "not both");
  srv.request.samples = trajectory_msgs::JointTrajectory();
  srv.request.record_seconds = 0.0;
  refused(srv, "record_seconds");
  srv.request.record_seconds = 601.0;
  refused(srv, "record_seconds");
  // joint_states without effort while recording
  ros::Publisher pub = nh.advertise<sensor_msgs::JointState>("/joint_states", 100);
  for (int k = 0; k < 50 && pub.getNumSubscribers() == 0; ++k) ros::Duration(0.1).sleep();
  std::atomic<bool> publishing{true};
  std::thread publisher([&] {
    while (publishing) {
      sensor_msgs::JointState msg;
      msg.header.stamp = ros::Time::now();
      msg.name = sd_test::panda_arm_joints();
      msg.position.assign(7, 0.1);
      msg.velocity.assign(7, 0.0);
      pub.publish(msg);
      ros::WallDuration(0.01).sleep();
    }
  });
  srv.request.record_seconds = 0.5;
  refused(srv, "without velocity or effort");
  publishing = false;
  publisher.join();
  EXPECT_LE(inverse_dynamics_error(model), 1e-12);  // nothing attached

  auto trajectory_refused = [&](spatial_dynamics::ExcitationTrajectory t, const std::string& needle) {
    t = call("excitation_trajectory", t);
    EXPECT_FALSE(t.response.success) << needle;
    EXPECT_TRUE(contains(t.response.message, needle)) << t.response.message;
  };
  spatial_dynamics::ExcitationTrajectory t;
  t.request.joints = {"panda_joint1", "panda_joint42"};
  t.request.duration = 10;
  t.request.speed_scale = 0.5;
  trajectory_refused(t, "'panda_joint42'");
  t.request.joints = {"panda_joint1"};
  t.request.speed_scale = 0;
  trajectory_refused(t, "speed_scale");
  t.request.speed_scale = 0.5;
  t.request.duration = -1;
  trajectory_refused(t, "duration");
  t.request.duration = 10;
  t.request.max_acceleration = -2;
  trajectory_refused(t, "max_acceleration");
}
