// Integration test: the node keeps serving through faults — a garbage robot_description (then
// ~reload recovers), joint states that stop (stale-state limit), a joint-state publisher sending
// malformed messages (dropped, the previous state stays), and a tf frame that vanishes.
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "node_test_utils.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

class Faults : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(wait_for_services());
    model = model_from_parameter();
    for (int i = 1; i < model.nbodies(); ++i) names.push_back(model.joint_names[i]);
    joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10);
    for (int k = 0; k < 100 && joint_states.getNumSubscribers() == 0; ++k) ros::Duration(0.05).sleep();
  }

  void publish(const std::vector<std::string>& which, const std::vector<double>& q, const std::vector<double>& qd) {
    sensor_msgs::JointState msg;
    msg.header.stamp = ros::Time::now();
    msg.name = which;
    msg.position = q;
    msg.velocity = qd;
    joint_states.publish(msg);
    ros::Duration(0.1).sleep();  // delivered and merged
  }

  /// The gravity-plus-velocity torques the node computes from its latest joint states.
  spatial_dynamics::InverseDynamics::Response latest() {
    spatial_dynamics::InverseDynamics id;
    EXPECT_TRUE(ros::service::call(service("inverse_dynamics"), id));
    return id.response;
  }

  VectorXd expected(const VectorXd& q, const VectorXd& qd) {
    sd::Data<double> data(model);
    return sd::nonlinear_effects(model, data, q, qd);
  }

  ros::NodeHandle nh;
  ros::Publisher joint_states;
  sd::Model<double> model;
  std::vector<std::string> names;
  std::mt19937 rng{77};
};

}  // namespace

TEST_F(Faults, StaleJointStatesAreReportedWithTheirAge) {
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng);
  publish(names, to_std(q), to_std(qd));
  auto fresh = latest();
  ASSERT_TRUE(fresh.success) << fresh.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(fresh.effort), expected(q, qd)), 1e-12);
  ros::Duration(0.7).sleep();  // longer than ~max_state_age = 0.5 s
  auto stale = latest();
  EXPECT_FALSE(stale.success);
  EXPECT_TRUE(contains(stale.message, "max_state_age")) << stale.message;
  EXPECT_TRUE(contains(stale.message, "'" + names[0] + "'")) << stale.message;
  // Values given in the request do not depend on the stale state.
  spatial_dynamics::InverseDynamics full;
  full.request.position = to_std(q);
  full.request.velocity = to_std(qd);
  full = call("inverse_dynamics", full);
  EXPECT_TRUE(full.response.success) << full.response.message;
  publish(names, to_std(q), to_std(qd));
  EXPECT_TRUE(latest().success);
}

TEST_F(Faults, MalformedJointStatesAreDroppedAndThePreviousStateStays) {
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng);
  publish(names, to_std(q), to_std(qd));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> bad_q = to_std(q);
  bad_q.pop_back();
  publish(names, bad_q, to_std(qd));                                   // mismatched lengths
  std::vector<double> nan_q = to_std(q);
  nan_q[2] = nan;
  publish(names, nan_q, to_std(qd));                                   // NaN
  std::vector<std::string> twice = names;
  twice[1] = names[0];
  publish(twice, to_std(VectorXd(q.array() + 1.0)), to_std(qd));      // duplicate names
  auto res = latest();
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(res.effort), expected(q, qd)), 1e-12) << "the previous state must stay";

  // A name the model does not have drops the whole message (~unknown_joints: drop, the default).
  publish(names, to_std(q), to_std(qd));  // fresh again (max_state_age is 0.5 s here)
  std::vector<std::string> with_unknown = names;
  with_unknown.push_back("joint_of_another_robot");
  const VectorXd q2 = sd_test::random_configuration(model, rng);
  std::vector<double> q2_values = to_std(q2), qd_values = to_std(qd);
  q2_values.push_back(0.3);
  qd_values.push_back(0.0);
  publish(with_unknown, q2_values, qd_values);
  res = latest();
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(res.effort), expected(q, qd)), 1e-12) << "the previous state must stay";

  // The same joints without the unknown name are merged.
  publish(names, to_std(q2), to_std(qd));
  res = latest();
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(res.effort), expected(q2, qd)), 1e-12);
}

TEST_F(Faults, AVanishingTfFrameIsReportedAndTheNodeKeepsServing) {
  const VectorXd q = sd_test::random_configuration(model, rng), qd = VectorXd::Zero(model.nv);
  publish(names, to_std(q), to_std(qd));
  tf2_ros::TransformBroadcaster broadcaster;
  geometry_msgs::TransformStamped t;
  t.header.frame_id = model.body_names[0];
  t.child_frame_id = "handheld_sensor";
  t.transform.rotation.w = 1.0;
  t.transform.translation.x = 0.5;
  spatial_dynamics::TransformWrench srv;
  srv.request.wrench.header.frame_id = "handheld_sensor";
  srv.request.wrench.wrench.force.z = -10.0;
  srv.request.target_frame = model.frames.back().name;
  srv.request.position = to_std(q);  // the robot's configuration, independent of joint-state age
  for (int k = 0; k < 150; ++k) {  // broadcast until the node's tf listener has the frame
    t.header.stamp = ros::Time::now();
    broadcaster.sendTransform(t);
    ros::Duration(0.02).sleep();
    srv = call("transform_wrench", srv);
    if (srv.response.success) break;
  }
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  // The broadcaster stops: a lookup at a time after its last transform cannot be answered.
  ros::Duration(0.5).sleep();
  srv.request.wrench.header.stamp = ros::Time::now();
  srv = call("transform_wrench", srv);
  EXPECT_FALSE(srv.response.success);
  EXPECT_TRUE(contains(srv.response.message, "handheld_sensor")) << srv.response.message;
  // The node is still serving.
  publish(names, to_std(q), to_std(qd));
  EXPECT_TRUE(latest().success);
}

TEST_F(Faults, GarbageRobotDescriptionThenReloadRecovers) {
  std::string original;
  ASSERT_TRUE(ros::param::get("robot_description", original));
  ros::param::set("robot_description", std::string("garbage, not XML at all <<<"));
  std_srvs::Trigger reload;
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_FALSE(reload.response.success);
  EXPECT_TRUE(contains(reload.response.message, "malformed URDF")) << reload.response.message;
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng);
  publish(names, to_std(q), to_std(qd));
  auto res = latest();
  EXPECT_TRUE(res.success) << "the previous model keeps serving: " << res.message;
  ros::param::set("robot_description", original);
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_TRUE(reload.response.success) << reload.response.message;
  publish(names, to_std(q), to_std(qd));
  res = latest();
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(res.effort), expected(q, qd)), 1e-12);
}
