// Integration test: a node started with a broken robot_description stays up, answers every
// service with the reason, and serves once ~reload finds a good model; a bad ~gravity is refused
// on reload while the previous model keeps being served, as is a ~root_joint that is neither
// fixed nor floating; a floating root link without mass is named by forward dynamics.
#include <std_srvs/Trigger.h>

#include <fstream>

#include "node_test_utils.hpp"

using namespace sd_node_test;

TEST(BadModel, ServicesAnswerWhyUntilAGoodModelIsReloaded) {
  ASSERT_TRUE(wait_for_services());
  spatial_dynamics::MassMatrix mm;
  mm.request.position = std::vector<double>(9, 0.0);
  mm = call("mass_matrix", mm);
  EXPECT_FALSE(mm.response.success);
  EXPECT_TRUE(contains(mm.response.message, "no robot model")) << mm.response.message;
  EXPECT_TRUE(contains(mm.response.message, "malformed URDF")) << mm.response.message;
  spatial_dynamics::InverseDynamics id = call("inverse_dynamics", spatial_dynamics::InverseDynamics());
  EXPECT_FALSE(id.response.success);
  EXPECT_TRUE(contains(id.response.message, "no robot model")) << id.response.message;

  std::ifstream file(sd_test::robot_path("panda.urdf"));
  const std::string panda((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  ros::param::set("robot_description", panda);
  std_srvs::Trigger reload;
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_TRUE(reload.response.success) << reload.response.message;
  mm = call("mass_matrix", mm);
  EXPECT_TRUE(mm.response.success) << mm.response.message;

  // A gravity parameter that is not three numbers is refused, naming the parameter.
  ros::param::set("/dynamics/gravity", std::vector<double>{0.0, -9.81});
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_FALSE(reload.response.success);
  EXPECT_TRUE(contains(reload.response.message, "/dynamics/gravity")) << reload.response.message;

  // A valid one takes effect: gravity torques on the moon.
  ros::param::set("/dynamics/gravity", std::vector<double>{0.0, 0.0, -1.62});
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_TRUE(reload.response.success) << reload.response.message;
  sd::ModelBuildOptions moon;
  moon.gravity = Eigen::Vector3d(0.0, 0.0, -1.62);
  const sd::Model<double> model = sd::build_model_from_urdf_string(panda, moon);
  sd::Data<double> data(model);
  std::mt19937 rng(9);
  const Eigen::VectorXd q = sd_test::random_configuration(model, rng);
  spatial_dynamics::InverseDynamics gravity;
  gravity.request.position = to_std(q);
  gravity.request.velocity = std::vector<double>(model.nv, 0.0);
  gravity = call("inverse_dynamics", gravity);
  ASSERT_TRUE(gravity.response.success) << gravity.response.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(gravity.response.effort), sd::gravity_torques(model, data, q)), 1e-12);
}

// ~root_joint other than fixed or floating is refused, naming it; a floating base whose root link
// has no mass is refused for forward dynamics, naming the link.
TEST(BadModel, RootJointIsFixedOrFloatingAndAFloatingRootNeedsMass) {
  ASSERT_TRUE(wait_for_services());
  std_srvs::Trigger reload;
  ros::param::set("/dynamics/root_joint", std::string("sideways"));
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_FALSE(reload.response.success);
  EXPECT_TRUE(contains(reload.response.message, "/dynamics/root_joint")) << reload.response.message;
  EXPECT_TRUE(contains(reload.response.message, "sideways")) << reload.response.message;

  const std::string massless_root =
      "<robot name='massless_root'><link name='base'/>"
      "<link name='arm'><inertial><origin xyz='0 0 0.2'/><mass value='1.5'/>"
      "<inertia ixx='0.02' ixy='0' ixz='0' iyy='0.02' iyz='0' izz='0.01'/></inertial></link>"
      "<joint name='shoulder' type='revolute'><parent link='base'/><child link='arm'/><axis xyz='0 1 0'/>"
      "<limit lower='-3' upper='3' effort='10' velocity='2'/></joint></robot>";
  ros::param::set("robot_description", massless_root);
  ros::param::set("/dynamics/root_joint", std::string("floating"));
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  ASSERT_TRUE(reload.response.success) << reload.response.message;
  spatial_dynamics::ForwardDynamics fd;
  fd.request.name = {"shoulder"};
  fd.request.position = {0.3};
  fd.request.velocity = {0.0};
  fd.request.effort = {1.0};
  fd.request.base_pose.orientation.w = 1.0;
  fd = call("forward_dynamics", fd);
  EXPECT_FALSE(fd.response.success);
  EXPECT_TRUE(contains(fd.response.message, "root link 'base' has no mass")) << fd.response.message;
  // Inverse dynamics needs no inverse of M: it answers, the base wrench included.
  spatial_dynamics::InverseDynamics id;
  id.request.name = {"shoulder"};
  id.request.position = {0.3};
  id.request.velocity = {0.0};
  id.request.base_pose.orientation.w = 1.0;
  id = call("inverse_dynamics", id);
  EXPECT_TRUE(id.response.success) << id.response.message;
  EXPECT_NEAR(id.response.base_wrench.force.z, 1.5 * 1.62, 1e-12);  // its weight on the moon (~gravity above)
  ros::param::set("/dynamics/root_joint", std::string("fixed"));
}
