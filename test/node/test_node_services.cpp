// Integration test: the node's services, computed-torque stream, joint_states merge, reload and
// wrench transforms, checked against the library called directly in this process.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <condition_variable>
#include <mutex>
#include <numeric>

#include "node_test_utils.hpp"
#include "spatial_dynamics/CentroidalState.h"
#include "spatial_dynamics/algorithms/centroidal.hpp"
#include "spatial_dynamics/simd_backend.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

constexpr double kTolerance = 1e-12;

class NodeServices : public ServedNodeTest {
 protected:

  void SetUp() override {
    model = model_from_parameter();
    names.clear();
    for (int i = 1; i < model.nbodies(); ++i) names.push_back(model.joint_names[i]);
    joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 100);
    for (int k = 0; k < 100 && (joint_states.getNumSubscribers() == 0 || !listener.connected()); ++k)
      ros::Duration(0.05).sleep();
  }

  /// Publishes the given joints and waits until the node has answered with computed torques
  /// (which it does once every joint is known).
  sensor_msgs::JointState publish(const std::vector<std::string>& which, const VectorXd& q, const VectorXd& qd,
                                  bool expect_torques = true) {
    sensor_msgs::JointState msg;
    msg.header.stamp = ros::Time(1000 + (++stamp_counter_));
    for (const std::string& name : which) {
      const int i = model.joints[model.jointBody(name)].idx_v;
      msg.name.push_back(name);
      msg.position.push_back(q[i]);
      msg.velocity.push_back(qd[i]);
    }
    joint_states.publish(msg);
    sensor_msgs::JointState torques;
    if (expect_torques) {
      EXPECT_TRUE(listener.waitFor(msg.header.stamp, torques)) << "no computed torques for stamp";
    }
    return torques;
  }

  TorqueListener listener{nh};
  ros::Publisher joint_states;
  sd::Model<double> model;
  std::vector<std::string> names;
  std::mt19937 rng{42};
  static inline int stamp_counter_ = 0;
};

}  // namespace

TEST_F(NodeServices, InverseForwardDynamicsAndMassMatrixMatchTheLibrary) {
  sd::Data<double> data(model);
  for (int s = 0; s < 20; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd qdd = sd_test::random_vector(model.nv, rng);

    spatial_dynamics::InverseDynamics id = call_inverse_dynamics(q, qd, qdd);
    ASSERT_TRUE(id.response.success) << id.response.message;
    EXPECT_EQ(id.response.name, names);
    const VectorXd tau = sd::rnea(model, data, q, qd, qdd);
    EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), tau), kTolerance);

    spatial_dynamics::ForwardDynamics fd = call_forward_dynamics(q, qd, tau);
    ASSERT_TRUE(fd.response.success) << fd.response.message;
    EXPECT_LE(sd_test::relative_error(to_eigen(fd.response.acceleration), VectorXd(sd::aba(model, data, q, qd, tau))),
              kTolerance);

    spatial_dynamics::MassMatrix mm;
    mm.request.position = to_std(q);
    mm = call("mass_matrix", mm);
    ASSERT_TRUE(mm.response.success) << mm.response.message;
    ASSERT_EQ(mm.response.mass_matrix.size(), static_cast<std::size_t>(model.nv * model.nv));
    const Eigen::MatrixXd M = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        mm.response.mass_matrix.data(), model.nv, model.nv);
    EXPECT_LE(sd_test::relative_error(M, sd::crba(model, data, q)), kTolerance);
  }
}

TEST_F(NodeServices, NamedArraysInAnyOrderAndLeftOutJointsFromJointStates) {
  sd::Data<double> data(model);
  const VectorXd q_state = sd_test::random_configuration(model, rng);
  const VectorXd qd_state = sd_test::random_vector(model.nv, rng);
  publish(names, q_state, qd_state);

  // Name every other joint, in reverse order; the rest come from joint_states.
  std::vector<std::string> named;
  for (int i = model.nv - 1; i >= 0; i -= 2) named.push_back(names[i]);
  VectorXd q = q_state, qd = qd_state, qdd = VectorXd::Zero(model.nv);
  spatial_dynamics::InverseDynamics id;
  id.request.name = named;
  for (const std::string& name : named) {
    const int i = model.joints[model.jointBody(name)].idx_v;
    q[i] += 0.1;
    qd[i] = 0.3;
    qdd[i] = -0.7;
    id.request.position.push_back(q[i]);
    id.request.velocity.push_back(qd[i]);
    id.request.acceleration.push_back(qdd[i]);
  }
  id = call("inverse_dynamics", id);
  ASSERT_TRUE(id.response.success) << id.response.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), sd::rnea(model, data, q, qd, qdd)), kTolerance);

  // Everything left out: the latest joint states, zero acceleration.
  spatial_dynamics::InverseDynamics latest;
  latest = call("inverse_dynamics", latest);
  ASSERT_TRUE(latest.response.success) << latest.response.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(latest.response.effort),
                                    sd::nonlinear_effects(model, data, q_state, qd_state)),
            kTolerance);
}

// External wrenches given in link frames enter as −Jᵀ w (J: the frame's local Jacobian).
TEST_F(NodeServices, ExternalWrenchesMatchJacobianTranspose) {
  sd::Data<double> data(model);
  const VectorXd q = sd_test::random_configuration(model, rng);
  const VectorXd qd = sd_test::random_vector(model.nv, rng);
  const VectorXd qdd = sd_test::random_vector(model.nv, rng);
  VectorXd expected = sd::rnea(model, data, q, qd, qdd);
  spatial_dynamics::InverseDynamics id;
  id.request.position = to_std(q);
  id.request.velocity = to_std(qd);
  id.request.acceleration = to_std(qdd);
  for (int frame : {static_cast<int>(model.frames.size()) - 1, static_cast<int>(model.frames.size()) / 2}) {
    geometry_msgs::WrenchStamped w;
    w.header.frame_id = model.frames[frame].name;
    const Eigen::Matrix<double, 6, 1> f = sd_test::random_vector(6, rng, 5.0);
    w.wrench.torque.x = f[0]; w.wrench.torque.y = f[1]; w.wrench.torque.z = f[2];
    w.wrench.force.x = f[3]; w.wrench.force.y = f[4]; w.wrench.force.z = f[5];
    id.request.external_wrenches.push_back(w);
    expected -= sd::frame_jacobian(model, data, q, frame, sd::ReferenceFrame::Local).transpose() * f;
  }
  id = call("inverse_dynamics", id);
  ASSERT_TRUE(id.response.success) << id.response.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), expected), kTolerance);
}

TEST_F(NodeServices, ComputedTorquesStreamForEveryJointStatesMessage) {
  sd::Data<double> data(model);
  for (int s = 0; s < 10; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const sensor_msgs::JointState torques = publish(names, q, qd);
    EXPECT_EQ(torques.name, names);
    EXPECT_LE(sd_test::relative_error(to_eigen(torques.position), q), 0.0);
    EXPECT_LE(sd_test::relative_error(to_eigen(torques.velocity), qd), 0.0);
    EXPECT_LE(sd_test::relative_error(to_eigen(torques.effort), sd::nonlinear_effects(model, data, q, qd)), kTolerance);
  }
}

// A fixed base's ~centroidal_state, one per joint_states message with its stamp, in the root link's
// frame: the library's centre of mass, its velocity and the angular momentum about it; the linear
// momentum m ċ.
TEST_F(NodeServices, CentroidalStateOfAFixedBaseIsInTheRootLinkFrame) {
  Collector<sd::CentroidalState> centroidal{nh, "/dynamics/centroidal_state"};
  for (int k = 0; k < 100 && !centroidal.connected(); ++k) ros::Duration(0.05).sleep();
  sd::Data<double> data(model);
  double mass = 0;
  for (int i = 1; i < model.nbodies(); ++i) mass += model.inertia[i].mass;
  const auto vec = [](const geometry_msgs::Vector3& v) { return Eigen::Vector3d(v.x, v.y, v.z); };
  for (int s = 0; s < 3; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    publish(names, q, qd);
    sd::CentroidalState c;
    ASSERT_TRUE(centroidal.waitFor(ros::Time(1000 + stamp_counter_), c)) << "no centroidal state for the stamp";
    EXPECT_EQ(c.header.frame_id, model.body_names[0]);
    const Eigen::Vector3d com(c.center_of_mass.x, c.center_of_mass.y, c.center_of_mass.z);
    EXPECT_LE(sd_test::relative_error(com, sd::center_of_mass(model, data, q)), kTolerance);
    const Eigen::Vector3d c_dot = sd::center_of_mass_velocity(model, data, q, qd);
    EXPECT_LE(sd_test::relative_error(vec(c.center_of_mass_velocity), c_dot), kTolerance);
    EXPECT_LE(sd_test::relative_error(vec(c.linear_momentum), Eigen::Vector3d(mass * c_dot)), kTolerance);
    const sd::ForceVector<double> h = sd::centroidal_momentum(model, data, q, qd);
    EXPECT_LE(sd_test::relative_error(vec(c.angular_momentum), Eigen::Vector3d(h.angular.eigen())), kTolerance);
  }
}

// Two messages, each with part of the joints in its own order, merge by name.
TEST_F(NodeServices, PartialJointStatesMerge) {
  sd::Data<double> data(model);
  const VectorXd q = sd_test::random_configuration(model, rng);
  const VectorXd qd = sd_test::random_vector(model.nv, rng);
  std::vector<std::string> first, second;
  for (int i = 0; i < model.nv; ++i) (i % 2 ? first : second).push_back(names[i]);
  std::reverse(second.begin(), second.end());
  publish(first, q, qd, false);
  const sensor_msgs::JointState torques = publish(second, q, qd);
  EXPECT_LE(sd_test::relative_error(to_eigen(torques.position), q), 0.0);
  EXPECT_LE(sd_test::relative_error(to_eigen(torques.effort), sd::nonlinear_effects(model, data, q, qd)), kTolerance);
}

namespace {

/// f_T = R f_S and n_T = R n_S + p × (R f_S) for the pose (R, p) of S in T: a wrench moved with
/// 3-D vectors, independently of the library's Plücker transforms.
Eigen::Matrix<double, 6, 1> moved_wrench(const Eigen::Matrix3d& R, const Eigen::Vector3d& p,
                                         const Eigen::Matrix<double, 6, 1>& w) {
  const Eigen::Vector3d f = R * w.tail<3>();
  Eigen::Matrix<double, 6, 1> out;
  out << R * w.head<3>() + p.cross(f), f;
  return out;
}

Eigen::Matrix<double, 6, 1> to_vector(const geometry_msgs::Wrench& w) {
  Eigen::Matrix<double, 6, 1> v;
  v << w.torque.x, w.torque.y, w.torque.z, w.force.x, w.force.y, w.force.z;
  return v;
}

geometry_msgs::Wrench to_wrench(const Eigen::Matrix<double, 6, 1>& v) {
  geometry_msgs::Wrench w;
  w.torque.x = v[0]; w.torque.y = v[1]; w.torque.z = v[2];
  w.force.x = v[3]; w.force.y = v[4]; w.force.z = v[5];
  return w;
}

/// Pose of model frame `name` in the base frame at q: (R, p).
std::pair<Eigen::Matrix3d, Eigen::Vector3d> pose(const sd::Model<double>& model, sd::Data<double>& data,
                                                 const VectorXd& q, const std::string& name) {
  sd::forward_kinematics(model, data, q);
  const auto& X = data.X_frame_base[model.frameIndex(name)];
  return {X.rotation(), X.translation()};
}

}  // namespace

TEST_F(NodeServices, TransformWrenchBetweenRobotLinks) {
  sd::Data<double> data(model);
  const std::string source = model.frames.back().name, target = model.frames[1].name;
  for (int s = 0; s < 10; ++s) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const Eigen::Matrix<double, 6, 1> w = sd_test::random_vector(6, rng, 10.0);
    spatial_dynamics::TransformWrench srv;
    srv.request.wrench.header.frame_id = source;
    srv.request.wrench.wrench = to_wrench(w);
    srv.request.target_frame = target;
    srv.request.name = names;
    srv.request.position = to_std(q);
    srv = call("transform_wrench", srv);
    ASSERT_TRUE(srv.response.success) << srv.response.message;
    EXPECT_EQ(srv.response.wrench.header.frame_id, target);
    const auto [R_s, p_s] = pose(model, data, q, source);
    const auto [R_t, p_t] = pose(model, data, q, target);
    // Pose of the source in the target: R = R_tᵀ R_s, p = R_tᵀ (p_s − p_t).
    const Eigen::Matrix<double, 6, 1> expected = moved_wrench(R_t.transpose() * R_s, R_t.transpose() * (p_s - p_t), w);
    EXPECT_LE(sd_test::relative_error(to_vector(srv.response.wrench.wrench), expected), kTolerance);
  }
}

// A frame published only on tf (a sensor mount fixed to the robot's root link) against robot
// links, in both directions, and two tf-only frames.
TEST_F(NodeServices, TransformWrenchThroughTf) {
  sd::Data<double> data(model);
  tf2_ros::StaticTransformBroadcaster broadcaster;
  const Eigen::Matrix3d R_mount = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d p_mount(0.4, -0.2, 0.9);
  const std::string root = model.body_names[0];
  std::vector<geometry_msgs::TransformStamped> statics(2);
  for (auto& t : statics) t.header.stamp = ros::Time::now();
  statics[0].header.frame_id = root;
  statics[0].child_frame_id = "sensor_mount";
  const Eigen::Quaterniond quat(R_mount);
  statics[0].transform.rotation.w = quat.w(); statics[0].transform.rotation.x = quat.x();
  statics[0].transform.rotation.y = quat.y(); statics[0].transform.rotation.z = quat.z();
  statics[0].transform.translation.x = p_mount.x(); statics[0].transform.translation.y = p_mount.y();
  statics[0].transform.translation.z = p_mount.z();
  statics[1].header.frame_id = "sensor_mount";
  statics[1].child_frame_id = "sensor_tip";
  statics[1].transform.rotation.w = 1.0;
  statics[1].transform.translation.z = 0.25;
  broadcaster.sendTransform(statics);

  const VectorXd q = sd_test::random_configuration(model, rng);
  const std::string link = model.frames.back().name;
  const auto [R_link, p_link] = pose(model, data, q, link);  // in the root link's frame
  const Eigen::Matrix<double, 6, 1> w = sd_test::random_vector(6, rng, 10.0);

  auto transform = [&](const std::string& source, const std::string& target) {
    spatial_dynamics::TransformWrench srv;
    srv.request.wrench.header.frame_id = source;
    srv.request.wrench.wrench = to_wrench(w);
    srv.request.target_frame = target;
    srv.request.name = names;
    srv.request.position = to_std(q);
    for (int attempt = 0; attempt < 50; ++attempt) {  // the static transform needs a moment to arrive
      srv = call("transform_wrench", srv);
      if (srv.response.success) break;
      ros::Duration(0.1).sleep();
    }
    EXPECT_TRUE(srv.response.success) << srv.response.message;
    return to_vector(srv.response.wrench.wrench);
  };
  // link → sensor_mount: pose of the link in the mount = (R_mᵀ R_l, R_mᵀ (p_l − p_m)).
  EXPECT_LE(sd_test::relative_error(transform(link, "sensor_mount"),
                                    moved_wrench(R_mount.transpose() * R_link, R_mount.transpose() * (p_link - p_mount), w)),
            kTolerance);
  // sensor_mount → link.
  EXPECT_LE(sd_test::relative_error(transform("sensor_mount", link),
                                    moved_wrench(R_link.transpose() * R_mount, R_link.transpose() * (p_mount - p_link), w)),
            kTolerance);
  // tf-only to tf-only: sensor_tip sits 0.25 m along the mount's z axis.
  EXPECT_LE(sd_test::relative_error(transform("sensor_tip", "sensor_mount"),
                                    moved_wrench(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0.25), w)),
            kTolerance);
}

// Reload picks up a changed robot_description; a broken one leaves the previous model served.
// Runs last in this file: it changes the served model and then restores it.
TEST_F(NodeServices, ZReloadPicksUpANewRobotDescription) {
  std::string original;
  ASSERT_TRUE(ros::param::get("robot_description", original));
  std::ifstream other_file(sd_test::robot_path("double_pendulum.urdf"));
  const std::string other((std::istreambuf_iterator<char>(other_file)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(other.empty());

  ros::param::set("robot_description", other);
  std_srvs::Trigger reload;
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_TRUE(reload.response.success) << reload.response.message;
  spatial_dynamics::MassMatrix mm;
  mm.request.position = {0.1, 0.2};
  mm = call("mass_matrix", mm);
  EXPECT_TRUE(mm.response.success) << mm.response.message;
  const sd::Model<double> pendulum = sd::build_model_from_urdf_string(other);
  EXPECT_EQ(mm.response.name, std::vector<std::string>({pendulum.joint_names[1], pendulum.joint_names[2]}));

  ros::param::set("robot_description", std::string("<robot name='broken'><link name='a'>"));
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_FALSE(reload.response.success);
  EXPECT_TRUE(contains(reload.response.message, "malformed URDF")) << reload.response.message;
  mm = call("mass_matrix", mm);
  EXPECT_TRUE(mm.response.success) << "the previous model must still be served: " << mm.response.message;

  ros::param::set("robot_description", original);
  ASSERT_TRUE(ros::service::call(service("reload"), reload));
  EXPECT_TRUE(reload.response.success) << reload.response.message;
  spatial_dynamics::MassMatrix back;
  back.request.position = std::vector<double>(model.nv, 0.0);
  back = call("mass_matrix", back);
  EXPECT_EQ(back.response.name, names);
}

TEST_F(NodeServices, DiagnosticsShowTheSimdBackend) {
  // The node runs the same compiled library as this process, chosen from the same CPU and
  // environment: its diagnostics name that build, which is the AVX2 one where the CPU has it.
  std::mutex mutex;
  std::string shown;
  ros::Subscriber sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
        for (const auto& status : msg->status)
          for (const auto& kv : status.values)
            if (kv.key == "simd backend") {
              std::lock_guard<std::mutex> lock(mutex);
              shown = kv.value;
            }
      });
  for (int k = 0; k < 200; ++k) {  // published once a second
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (!shown.empty()) break;
    }
    ros::Duration(0.05).sleep();
  }
  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_EQ(shown, sd::simd_backend());
  const char* forced = std::getenv("SPATIAL_DYNAMICS_SIMD");
  if ((forced == nullptr || *forced == '\0') && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    EXPECT_EQ(shown, "avx2_fma");
  }
}
