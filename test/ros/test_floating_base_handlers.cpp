// The service handlers on a floating Solo12 with an actuator model, without a master: the robot
// loaded by ModelStore as the node loads it (~root_joint floating, ~contacts on the four feet,
// ~actuator_model parameters), the handlers called as the node calls them. With contacts the
// actuator terms enter as in a fixed-base robot: inverse dynamics adds armature · q̈ + τ_a(q̇) to the
// joints and leaves λ alone (the base's rows carry no actuator), forward dynamics inverts it, and the
// mass matrix gains the armature on the joints' diagonal. ~set_contacts' refusals leave the contacts.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/ros/model_store.hpp"
#include "spatial_dynamics/ros/service_handlers.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::VectorXd;

namespace {

/// The base at a pose of its own, moving.
class MovingBase : public sd::BaseStateSource {
 public:
  void state(const std::string&, const ros::Time&, sd::BaseState& out) const override {
    out.position = Eigen::Vector3d(0.2, 0.1, 0.35);
    out.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -2, 3).normalized()));
    out.twist << 0.2, -0.1, 0.3, 0.5, -0.2, 0.1;
    out.world_frame = "odom";
  }
};

class FloatingBaseHandlers : public ::testing::Test {
 protected:
  void SetUp() override {
    sd::NodeConfig config;
    config.scenes.resize(1);
    config.contacts = {{"FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"}, {"point", "point", "point", "point"}, {}};
    store = std::make_unique<sd::ModelStore>(config);
    store->load([] {
      std::ifstream file(sd_test::robot_path("solo12.urdf"));
      sd::RobotSource source;
      source.urdf.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
      source.floating_base = true;
      source.actuators.model = sd::ActuatorModel::Parameters;
      for (const char* joint : {"FL_HFE", "FL_KFE", "HR_HAA"}) {
        source.actuators.actuators[joint]["armature"] = 0.04;
        source.actuators.actuators[joint]["damping"] = 0.3;
        source.actuators.actuators[joint]["friction"] = 0.2;
      }
      return source;
    });
    scene = store->scene(0);
    ASSERT_TRUE(scene && scene->model) << (scene ? scene->error : "no scene");
    names = scene->decoder->jointNames();
    std::mt19937 rng(5);
    q = sd_test::random_vector(12, rng, 0.5);
    qd = sd_test::random_vector(12, rng);
    qdd = sd_test::random_vector(12, rng);
  }

  sd::InverseDynamics::Request idRequest(bool rigid_body_only) const {
    sd::InverseDynamics::Request r;
    r.name = names;
    r.position.assign(q.data(), q.data() + 12);
    r.velocity.assign(qd.data(), qd.data() + 12);
    r.acceleration.assign(qdd.data(), qdd.data() + 12);
    r.base_acceleration.angular.x = 0.3;
    r.base_acceleration.linear.z = -0.5;
    r.rigid_body_only = rigid_body_only;
    return r;
  }

  std::unique_ptr<sd::ModelStore> store;
  std::shared_ptr<const sd::ServedScene> scene;
  MovingBase base;
  std::vector<std::string> names;
  VectorXd q, qd, qdd;
};

VectorXd to_vector(const std::vector<double>& v) { return Eigen::Map<const VectorXd>(v.data(), v.size()); }

VectorXd stacked_forces(const std::vector<geometry_msgs::WrenchStamped>& wrenches) {
  VectorXd out(3 * wrenches.size());
  for (std::size_t k = 0; k < wrenches.size(); ++k)
    out.segment<3>(3 * k) << wrenches[k].wrench.force.x, wrenches[k].wrench.force.y, wrenches[k].wrench.force.z;
  return out;
}

}  // namespace

TEST_F(FloatingBaseHandlers, ActuatorTermsLoadTheJointsNotTheContacts) {
  const sd::WorkspacePool::Lease ws = scene->workspaces.acquire(*scene->model);
  sd::InverseDynamics::Response actuated, rigid;
  sd::compute_inverse_dynamics(*scene, base, *ws, idRequest(false), actuated);
  sd::compute_inverse_dynamics(*scene, base, *ws, idRequest(true), rigid);
  ASSERT_EQ(actuated.contact_wrenches.size(), 4u);
  EXPECT_LT(sd_test::relative_error(stacked_forces(actuated.contact_wrenches), stacked_forces(rigid.contact_wrenches)), 1e-13);
  // τ − τ_rigid = armature ⊙ q̈ + damping ⊙ q̇ + friction ⊙ ramp(q̇ / friction_velocity), joint by joint.
  const sd::Model<double>& model = *scene->model;
  VectorXd expected = VectorXd::Zero(12);
  for (int k = 0; k < 12; ++k) {
    const int v = 6 + k;
    const double ramp = std::clamp(qd[k] / model.friction_velocity[v], -1.0, 1.0);
    expected[k] = model.armature[v] * qdd[k] + model.damping[v] * qd[k] + model.friction[v] * ramp;
  }
  EXPECT_GT(expected.cwiseAbs().maxCoeff(), 0.1) << "the actuators are set";
  const VectorXd difference = to_vector(actuated.effort) - to_vector(rigid.effort);
  EXPECT_LT((difference - expected).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((to_vector(actuated.actuator_effort) - expected).cwiseAbs().maxCoeff(), 1e-12);
}

// One foot held as a surface: six contact rows that span the base's six, so that inverse dynamics' λ
// (fixed by the base's rows) is forward dynamics' (with four feet, or two point feet, which cannot
// push a moment about the line through them, inverse dynamics takes the minimum-norm one of many).
TEST_F(FloatingBaseHandlers, ForwardDynamicsInvertsInverseDynamicsWithContactsAndActuators) {
  const sd::WorkspacePool::Lease ws = scene->workspaces.acquire(*scene->model);
  sd::ForwardDynamics::Request fd;
  fd.contact_frames = {"FL_FOOT"};
  fd.contact_kinds = {"surface"};
  fd.name = names;
  fd.position.assign(q.data(), q.data() + 12);
  fd.velocity.assign(qd.data(), qd.data() + 12);
  fd.effort = {1.0, -2.0, 0.5, 3.0, 0.0, -1.0, 2.0, 1.5, -0.5, 0.2, 0.0, 1.0};
  sd::ForwardDynamics::Response accelerations;
  sd::compute_forward_dynamics(*scene, base, *ws, fd, accelerations);
  sd::InverseDynamics::Request id = idRequest(false);
  id.acceleration = accelerations.acceleration;
  id.base_acceleration = accelerations.base_acceleration;
  id.contact_frames = fd.contact_frames;
  id.contact_kinds = fd.contact_kinds;
  sd::InverseDynamics::Response effort;
  sd::compute_inverse_dynamics(*scene, base, *ws, id, effort);
  EXPECT_LT(sd_test::relative_error(to_vector(effort.effort), to_vector(fd.effort)), 1e-10);
  const auto wrench = [](const geometry_msgs::WrenchStamped& w) {
    return (VectorXd(6) << w.wrench.torque.x, w.wrench.torque.y, w.wrench.torque.z, w.wrench.force.x, w.wrench.force.y,
            w.wrench.force.z)
        .finished();
  };
  ASSERT_EQ(effort.contact_wrenches.size(), 1u);
  EXPECT_LT(sd_test::relative_error(wrench(effort.contact_wrenches[0]), wrench(accelerations.contact_wrenches[0])), 1e-10);
  const geometry_msgs::Wrench& b = effort.base_wrench;
  EXPECT_LT(std::abs(b.force.x) + std::abs(b.force.y) + std::abs(b.force.z) + std::abs(b.torque.x) + std::abs(b.torque.y) +
                std::abs(b.torque.z),
            1e-9);
}

TEST_F(FloatingBaseHandlers, MassMatrixGainsTheArmatureOnTheJointsDiagonal) {
  const sd::WorkspacePool::Lease ws = scene->workspaces.acquire(*scene->model);
  sd::MassMatrix::Request request;
  request.name = names;
  request.position.assign(q.data(), q.data() + 12);
  sd::MassMatrix::Response actuated, rigid;
  sd::compute_mass_matrix(*scene, base, *ws, request, actuated);
  request.rigid_body_only = true;
  sd::compute_mass_matrix(*scene, base, *ws, request, rigid);
  ASSERT_EQ(actuated.name.size(), 18u);
  EXPECT_EQ(actuated.name[0], "root_joint/wx");
  const Eigen::Map<const Eigen::Matrix<double, 18, 18, Eigen::RowMajor>> M(actuated.mass_matrix.data()),
      M_rigid(rigid.mass_matrix.data());
  Eigen::Matrix<double, 18, 18> expected = Eigen::Matrix<double, 18, 18>::Zero();
  for (int v = 6; v < 18; ++v) expected(v, v) = scene->model->armature[v];
  EXPECT_LT((M - M_rigid - expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST_F(FloatingBaseHandlers, SetContactsRefusesAndKeepsTheContacts) {
  std::string message;
  EXPECT_FALSE(store->setContacts({{"FL_FOOT", "nowhere"}, {"point", "point"}, {}}, message));
  EXPECT_NE(message.find("unknown frame 'nowhere'"), std::string::npos) << message;
  EXPECT_FALSE(store->setContacts({{"FL_FOOT"}, {"edge"}, {}}, message));
  EXPECT_NE(message.find("unknown kind 'edge'"), std::string::npos) << message;
  EXPECT_EQ(store->scene(0)->contacts.size(), 4u);
  EXPECT_TRUE(store->setContacts({{"FL_FOOT", "HR_FOOT"}, {"point", "point"}, {0.5, 0.5}}, message)) << message;
  EXPECT_EQ(store->scene(0)->contacts.size(), 2u);
  EXPECT_EQ(store->robot()->contacts.frames, (std::vector<std::string>{"FL_FOOT", "HR_FOOT"}));
}
