// Integration test: actuator dynamics through the node. The node runs the Panda with
// ~actuator_model `urdf` (the URDF's <dynamics damping>) and the ~actuators of
// launch/example_actuators.yaml; this checker builds the same model from the same parameters with
// its own reading of them, and checks every service and ~computed_torques against the library:
// with the terms, and with rigid_body_only as the rigid-body functions give them. A trajectory whose
// rigid-body peak is under a joint's effort limit and whose actuated peak is over it is flagged at
// the right point. Each bad parameter is refused at ~reload, naming it, while the previous model is
// served; a node started with one answers success: false naming it until a good ~reload.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <random>

#include "node_test_utils.hpp"
#include "spatial_dynamics/InverseDynamicsTrajectory.h"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

constexpr double kTolerance = 1e-12;

/// The model the node should serve: the URDF's damping, then each ~actuators entry's values
/// (armature, or rotor_inertia · gear_ratio²), read here from the parameter server.
sd::Model<double> actuated_model() {
  sd::Model<double> model = model_from_parameter();
  XmlRpc::XmlRpcValue actuators;
  if (!ros::param::get("/dynamics/actuators", actuators)) throw std::runtime_error("/dynamics/actuators is not set");
  for (auto& [joint, entry] : actuators) {
    const int k = model.joints[model.jointBody(joint)].idx_v;
    auto value = [&](const char* key) { return static_cast<double>(entry[key]); };
    if (entry.hasMember("armature")) model.armature[k] = value("armature");
    if (entry.hasMember("rotor_inertia"))
      model.armature[k] = value("rotor_inertia") * std::pow(static_cast<int>(entry["gear_ratio"]), 2);
    if (entry.hasMember("damping")) model.damping[k] = value("damping");
    if (entry.hasMember("friction")) model.friction[k] = value("friction");
    if (entry.hasMember("friction_velocity")) model.friction_velocity[k] = value("friction_velocity");
  }
  model.finalize();
  return model;
}

/// The same robot without actuator terms.
sd::Model<double> rigid_model() {
  sd::Model<double> model = model_from_parameter();
  model.reset_actuator_terms();
  model.finalize();
  return model;
}

class NodeActuators : public ServedNodeTest {};

}  // namespace

TEST_F(NodeActuators, EveryServiceCarriesTheTermsAndRigidBodyOnlyGivesTheRigidBodyAnswers) {
  const sd::Model<double> model = actuated_model(), rigid = rigid_model();
  ASSERT_TRUE(model.has_armature);
  ASSERT_GT(*std::max_element(model.damping.begin(), model.damping.end()), 0.0);  // the URDF's
  ASSERT_GT(*std::max_element(model.friction.begin(), model.friction.end()), 0.0);  // the parameters'
  sd::Data<double> data(model), rigid_data(rigid);
  std::mt19937 rng(19);
  for (int s = 0; s < 5; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng),
                   qdd = sd_test::random_vector(model.nv, rng), tau = sd_test::random_vector(model.nv, rng, 10.0);
    for (const bool rigid_body_only : {false, true}) {
      const sd::Model<double>& expected_model = rigid_body_only ? rigid : model;
      sd::Data<double>& d = rigid_body_only ? rigid_data : data;
      spatial_dynamics::InverseDynamics id;
      id.request.position = to_std(q);
      id.request.velocity = to_std(qd);
      id.request.acceleration = to_std(qdd);
      id.request.rigid_body_only = rigid_body_only;
      id = call("inverse_dynamics", id);
      ASSERT_TRUE(id.response.success) << id.response.message;
      const VectorXd expected_tau = sd::inverse_dynamics_actuated(expected_model, d, q, qd, qdd);
      EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), expected_tau), kTolerance);
      if (rigid_body_only) {
        EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), sd::rnea(rigid, d, q, qd, qdd)), kTolerance);
        EXPECT_TRUE(id.response.actuator_effort.empty());
      } else {
        EXPECT_LE(sd_test::relative_error(to_eigen(id.response.actuator_effort), sd::actuator_effort(model, d, qd, qdd)),
                  kTolerance);
        EXPECT_GT((expected_tau - sd::rnea(rigid, rigid_data, q, qd, qdd)).norm(), 1e-3);  // the terms matter
      }

      spatial_dynamics::ForwardDynamics fd;
      fd.request.position = to_std(q);
      fd.request.velocity = to_std(qd);
      fd.request.effort = to_std(tau);
      fd.request.rigid_body_only = rigid_body_only;
      fd = call("forward_dynamics", fd);
      ASSERT_TRUE(fd.response.success) << fd.response.message;
      EXPECT_LE(sd_test::relative_error(to_eigen(fd.response.acceleration),
                                        sd::forward_dynamics_actuated(expected_model, d, q, qd, tau)),
                1e-10);

      spatial_dynamics::MassMatrix mm;
      mm.request.position = to_std(q);
      mm.request.rigid_body_only = rigid_body_only;
      mm = call("mass_matrix", mm);
      ASSERT_TRUE(mm.response.success) << mm.response.message;
      const Eigen::MatrixXd M = sd::crba(expected_model, d, q);
      EXPECT_LE(sd_test::relative_error(Eigen::Map<const Eigen::MatrixXd>(mm.response.mass_matrix.data(), model.nv, model.nv), M),
                kTolerance);
    }
  }
}

TEST_F(NodeActuators, ComputedTorquesCarryTheTerms) {
  const sd::Model<double> model = actuated_model();
  sd::Data<double> data(model);
  std::mt19937 rng(20);
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng, 0.5);
  VectorXd expected = sd::nonlinear_effects(model, data, q, qd);  // ID(q, q̇, 0), with the actuators' forces
  expected += sd::actuator_forces(model, data, qd);
  std::mutex mutex;
  std::vector<double> received;
  ros::Subscriber sub = nh.subscribe<sensor_msgs::JointState>(
      "/dynamics/computed_torques", 10, [&](const sensor_msgs::JointState::ConstPtr& msg) {
        std::lock_guard<std::mutex> lock(mutex);
        received = msg->effort;
      });
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10, true);
  sensor_msgs::JointState msg;
  msg.name = model.velocityNames();
  msg.position = to_std(q);
  msg.velocity = to_std(qd);
  double error = 1.0;
  for (int k = 0; k < 100 && error > kTolerance; ++k) {
    msg.header.stamp = ros::Time::now();
    states.publish(msg);
    ros::Duration(0.05).sleep();
    std::lock_guard<std::mutex> lock(mutex);
    if (static_cast<int>(received.size()) == model.nv) error = sd_test::relative_error(to_eigen(received), expected);
  }
  EXPECT_LE(error, kTolerance);
}

TEST_F(NodeActuators, ATrajectoryOverTheLimitOnlyWithTheTermsIsFlaggedAtTheRightPoint) {
  // panda_joint7 (effort limit 12 N m) turns ever faster while the arm holds still elsewhere: its
  // rigid-body torque stays small, its friction and the damping set below grow past the limit.
  ros::param::set("/dynamics/actuators/panda_joint7/damping", 4.0);
  ASSERT_TRUE(reload().response.success);
  const sd::Model<double> model = actuated_model(), rigid = rigid_model();
  sd::Data<double> data(model), rigid_data(rigid);
  const int joint = model.joints[model.jointBody("panda_joint7")].idx_v;
  const double limit = model.joints[model.jointBody("panda_joint7")].limits.effort;
  spatial_dynamics::InverseDynamicsTrajectory traj;
  traj.request.trajectory.joint_names = model.velocityNames();
  VectorXd q = VectorXd::Zero(model.nv), qd = VectorXd::Zero(model.nv), qdd = VectorXd::Zero(model.nv);
  q[model.joints[model.jointBody("panda_joint4")].idx_v] = -1.5;
  int expected_violation = -1;
  double rigid_peak = 0;
  for (int k = 0; k < 10; ++k) {
    qd[joint] = 0.5 * k;  // rad/s
    qdd[joint] = 0.5;
    trajectory_msgs::JointTrajectoryPoint p;
    p.positions = to_std(q);
    p.velocities = to_std(qd);
    p.accelerations = to_std(qdd);
    p.time_from_start = ros::Duration(0.1 * k);
    traj.request.trajectory.points.push_back(p);
    rigid_peak = std::max(rigid_peak, std::abs(sd::rnea(rigid, rigid_data, q, qd, qdd)[joint]));
    if (expected_violation < 0 && std::abs(sd::inverse_dynamics_actuated(model, data, q, qd, qdd)[joint]) > limit)
      expected_violation = k;
  }
  ASSERT_LT(rigid_peak, limit);
  ASSERT_GT(expected_violation, 0);
  for (const bool rigid_body_only : {false, true}) {
    traj.request.rigid_body_only = rigid_body_only;
    spatial_dynamics::InverseDynamicsTrajectory answer = call("inverse_dynamics_trajectory", traj);
    ASSERT_TRUE(answer.response.success) << answer.response.message;
    EXPECT_EQ(answer.response.first_violation[joint], rigid_body_only ? -1 : expected_violation);
    EXPECT_NEAR(answer.response.peak_effort[joint],
                rigid_body_only ? rigid_peak
                                : std::abs(sd::inverse_dynamics_actuated(model, data, q, qd, qdd)[joint]),
                1e-9);
  }
  ros::param::del("/dynamics/actuators/panda_joint7/damping");
  ASSERT_TRUE(reload().response.success);
}

TEST_F(NodeActuators, EachBadParameterIsRefusedNamingItAndThePreviousModelIsServed) {
  struct Bad {
    std::string parameter;
    XmlRpc::XmlRpcValue value;
    std::string named;  // what the message must contain
  };
  std::vector<Bad> cases = {
      {"/dynamics/actuators/panda_joint2/armature", -0.5, "/dynamics/actuators/panda_joint2/armature"},
      {"/dynamics/actuators/panda_joint2/damping", "fast", "/dynamics/actuators/panda_joint2/damping"},
      {"/dynamics/actuators/panda_joint2/friction_velocity", 0.0, "/dynamics/actuators/panda_joint2/friction_velocity"},
      {"/dynamics/actuators/panda_joint2/stiffness", 1.0, "/dynamics/actuators/panda_joint2/stiffness"},
      {"/dynamics/actuators/panda_joint2/gear_ratio", 50.0, "/dynamics/actuators/panda_joint2"},
      {"/dynamics/actuators/no_such_joint/armature", 0.1, "/dynamics/actuators/no_such_joint"},
      {"/dynamics/actuator_model", "motors", "/dynamics/actuator_model"},
  };
  const sd::Model<double> model = actuated_model();
  sd::Data<double> data(model);
  std::mt19937 rng(21);
  const VectorXd q = sd_test::random_configuration(model, rng), qd = sd_test::random_vector(model.nv, rng),
                 qdd = sd_test::random_vector(model.nv, rng);
  for (Bad& bad : cases) {
    XmlRpc::XmlRpcValue saved;
    const bool had = ros::param::get(bad.parameter, saved);
    ros::param::set(bad.parameter, bad.value);
    const std_srvs::Trigger refused = reload();
    EXPECT_FALSE(refused.response.success) << bad.parameter;
    EXPECT_TRUE(contains(refused.response.message, bad.named)) << refused.response.message;
    if (had) ros::param::set(bad.parameter, saved);
    else ros::param::del(bad.parameter);
    if (bad.parameter == "/dynamics/actuators/no_such_joint/armature") ros::param::del("/dynamics/actuators/no_such_joint");
    // The previous model, with its terms, is still served.
    spatial_dynamics::InverseDynamics id = call_inverse_dynamics(q, qd, qdd);
    ASSERT_TRUE(id.response.success) << id.response.message;
    EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), sd::inverse_dynamics_actuated(model, data, q, qd, qdd)),
              kTolerance);
  }
  ASSERT_TRUE(reload().response.success);
}

// node_actuators_bad_start.test: the node starts with ~actuators/panda_joint3/friction = -1.
TEST_F(NodeActuators, ABadParameterAtStartIsAnsweredNamingItUntilAGoodReload) {
  spatial_dynamics::InverseDynamics id = call("inverse_dynamics", spatial_dynamics::InverseDynamics());
  EXPECT_FALSE(id.response.success);
  EXPECT_TRUE(contains(id.response.message, "/dynamics/actuators/panda_joint3/friction")) << id.response.message;
  spatial_dynamics::MassMatrix mm = call("mass_matrix", spatial_dynamics::MassMatrix());
  EXPECT_FALSE(mm.response.success);
  EXPECT_TRUE(contains(mm.response.message, "/dynamics/actuators/panda_joint3/friction")) << mm.response.message;
  // The diagnostics say it too.
  std::mutex mutex;
  std::string summary;
  ros::Subscriber sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
        for (const auto& status : msg->status) {
          std::lock_guard<std::mutex> lock(mutex);
          if (status.level == diagnostic_msgs::DiagnosticStatus::ERROR) summary = status.message;
        }
      });
  for (int k = 0; k < 200; ++k) {  // published once a second
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (!summary.empty()) break;
    }
    ros::Duration(0.05).sleep();
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_TRUE(contains(summary, "/dynamics/actuators/panda_joint3/friction")) << summary;
  }
  ros::param::set("/dynamics/actuators/panda_joint3/friction", 0.3);
  const std_srvs::Trigger good = reload();
  EXPECT_TRUE(good.response.success) << good.response.message;
  mm.request.position.assign(model_from_parameter().nq, 0.0);
  mm = call("mass_matrix", mm);
  EXPECT_TRUE(mm.response.success) << mm.response.message;
}
