// Integration test: joints with several coordinates through the node. A UR5 on a planar cart is
// served by the coordinates' names (`cart_joint/x`, `/y`, `/yaw`): inverse dynamics, forward
// dynamics and the mass matrix equal the library's on the same URDF, and joint_states by those
// names feed the defaults. A floating joint inside the tree (7 position, 6 velocity coordinates)
// is refused, naming the joint, while the node keeps serving after a reload.
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include <random>

#include "node_test_utils.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

constexpr double kTolerance = 1e-12;

using sd_test::robot_text;
using sd_test::with_extra_elements;

const char* const kCartLink =
    "<link name=\"cart\"><inertial><origin xyz=\"0.05 0 0.1\"/><mass value=\"30\"/>"
    "<inertia ixx=\"1.2\" ixy=\"0\" ixz=\"0.05\" iyy=\"1.5\" iyz=\"0\" izz=\"2\"/></inertial></link>\n";

/// floor —planar (normal z)→ cart —fixed→ the UR5's root link (world).
std::string ur5_on_cart() {
  return with_extra_elements(robot_text("ur5.urdf"),
                    std::string("<link name=\"floor\"/>\n") + kCartLink +
                        "<joint name=\"cart_joint\" type=\"planar\"><parent link=\"floor\"/><child link=\"cart\"/>"
                        "<axis xyz=\"0 0 1\"/></joint>\n"
                        "<joint name=\"cart_mount\" type=\"fixed\"><parent link=\"cart\"/><child link=\"world\"/>"
                        "<origin xyz=\"0.1 0 0.3\"/></joint>\n");
}

/// The UR5 holding an object on a floating joint.
std::string ur5_with_floating_object() {
  return with_extra_elements(robot_text("ur5.urdf"),
                    std::string(kCartLink) +
                        "<joint name=\"object_joint\" type=\"floating\"><parent link=\"wrist_3_link\"/>"
                        "<child link=\"cart\"/></joint>\n");
}

std_srvs::Trigger reload_with(const std::string& urdf) {
  ros::param::set("robot_description", urdf);
  return reload();
}

class NodeTreeJoints : public ServedNodeTest {};

}  // namespace

TEST_F(NodeTreeJoints, APlanarJointIsServedByItsCoordinatesNames) {
  const std::string urdf = ur5_on_cart();
  const std_srvs::Trigger reload = reload_with(urdf);
  ASSERT_TRUE(reload.response.success) << reload.response.message;
  const sd::Model<double> model = sd::build_model_from_urdf_string(urdf);
  const std::vector<std::string> names = model.velocityNames();
  ASSERT_EQ(names[0], "cart_joint/x");
  ASSERT_EQ(names[2], "cart_joint/yaw");
  sd::Data<double> data(model);
  std::mt19937 rng(7);
  for (int s = 0; s < 5; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng),
                   qdd = sd_test::random_vector(model.nv, rng);
    // By name, in reverse order: the node maps each coordinate by its name.
    spatial_dynamics::InverseDynamics id;
    for (int k = model.nv - 1; k >= 0; --k) {
      id.request.name.push_back(names[k]);
      id.request.position.push_back(q[k]);
      id.request.velocity.push_back(qd[k]);
      id.request.acceleration.push_back(qdd[k]);
    }
    id = call("inverse_dynamics", id);
    ASSERT_TRUE(id.response.success) << id.response.message;
    EXPECT_EQ(id.response.name, names);
    const VectorXd tau = sd::rnea(model, data, q, qd, qdd);
    EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), tau), kTolerance);

    spatial_dynamics::ForwardDynamics fd = call_forward_dynamics(q, qd, tau);
    ASSERT_TRUE(fd.response.success) << fd.response.message;
    EXPECT_LE(sd_test::relative_error(to_eigen(fd.response.acceleration), qdd), 1e-10);  // FD(ID(q̈)) = q̈

    spatial_dynamics::MassMatrix mm;
    mm.request.position = to_std(q);
    mm = call("mass_matrix", mm);
    ASSERT_TRUE(mm.response.success) << mm.response.message;
    EXPECT_EQ(mm.response.name, names);
    const Eigen::MatrixXd M = sd::crba(model, data, q);
    const Eigen::MatrixXd served = Eigen::Map<const Eigen::MatrixXd>(mm.response.mass_matrix.data(), model.nv, model.nv);
    EXPECT_LE(sd_test::relative_error(served, M), kTolerance);
  }

  // The joint itself is no coordinate: a request must name x, y or yaw.
  spatial_dynamics::InverseDynamics bad;
  bad.request.name = {"cart_joint"};
  bad.request.position = {0.1};
  bad = call("inverse_dynamics", bad);
  EXPECT_FALSE(bad.response.success);
  EXPECT_TRUE(contains(bad.response.message, "'cart_joint'")) << bad.response.message;

  // joint_states by the coordinates' names give the defaults of a request without positions.
  ros::NodeHandle nh;
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10, true);
  sensor_msgs::JointState msg;
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng);
  msg.header.stamp = ros::Time::now();
  msg.name = names;
  msg.position = to_std(q);
  msg.velocity = to_std(qd);
  const VectorXd expected = sd::nonlinear_effects(model, data, q, qd);
  spatial_dynamics::InverseDynamics latest;
  for (int k = 0; k < 100; ++k) {  // until the node has the message
    msg.header.stamp = ros::Time::now();
    states.publish(msg);
    ros::Duration(0.05).sleep();
    latest = call("inverse_dynamics", spatial_dynamics::InverseDynamics());
    if (latest.response.success && sd_test::relative_error(to_eigen(latest.response.effort), expected) <= kTolerance) break;
  }
  ASSERT_TRUE(latest.response.success) << latest.response.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(latest.response.effort), expected), kTolerance);
}

TEST_F(NodeTreeJoints, AFloatingJointInsideTheTreeIsRefusedNamingItAndTheNodeKeepsServing) {
  const std_srvs::Trigger reload = reload_with(ur5_with_floating_object());
  EXPECT_TRUE(contains(reload.response.message, "'object_joint'")) << reload.response.message;
  spatial_dynamics::InverseDynamics id = call("inverse_dynamics", spatial_dynamics::InverseDynamics());
  EXPECT_FALSE(id.response.success);
  EXPECT_TRUE(contains(id.response.message, "'object_joint'")) << id.response.message;
  EXPECT_TRUE(contains(id.response.message, "7 position and 6 velocity coordinates")) << id.response.message;

  const std_srvs::Trigger back = reload_with(robot_text("ur5.urdf"));
  EXPECT_TRUE(back.response.success) << back.response.message;
  spatial_dynamics::MassMatrix mm;
  mm.request.position = std::vector<double>(6, 0.1);
  mm = call("mass_matrix", mm);
  EXPECT_TRUE(mm.response.success) << mm.response.message;
}
