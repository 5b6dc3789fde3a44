// Integration test: scenes configured by parameters serve their own services and topic and agree
// with the full model with the locked joints held still; moving a locked joint changes the
// answers; ~set_payload changes them by exactly the payload's effect; broken scenes name the
// culprit; a node with coupled mimic joints answers the coupled system.
#include <sensor_msgs/JointState.h>

#include <condition_variable>
#include <mutex>

#include "node_test_utils.hpp"
#include "spatial_dynamics/SetPayload.h"
#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/payload.hpp"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

const std::vector<std::string> kLeftArm = {"arm_left_1_joint", "arm_left_2_joint", "arm_left_3_joint",
                                           "arm_left_4_joint", "arm_left_5_joint", "arm_left_6_joint",
                                           "arm_left_7_joint"};

class Scenes : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(wait_for_services());
    ASSERT_TRUE(ros::service::waitForService("/dynamics/left_arm/inverse_dynamics", ros::Duration(10)));
    full = model_from_parameter();
    joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10);
    left_arm_torques = nh.subscribe("/dynamics/left_arm/computed_torques", 10, &Scenes::onTorques, this);
    for (int k = 0; k < 100 && (joint_states.getNumSubscribers() < 2 || left_arm_torques.getNumPublishers() == 0); ++k)
      ros::Duration(0.05).sleep();
  }

  /// Publishes a full joint state and waits for the left-arm scene's torques for it.
  sensor_msgs::JointState publish(const VectorXd& q, const VectorXd& qd) {
    sensor_msgs::JointState msg;
    msg.header.stamp = ros::Time(2000 + (++stamp_counter));
    for (int i = 1; i < full.nbodies(); ++i) msg.name.push_back(full.joint_names[i]);
    msg.position = to_std(q);
    msg.velocity = to_std(qd);
    joint_states.publish(msg);
    std::unique_lock<std::mutex> lock(mutex);
    const bool got = cv.wait_for(lock, std::chrono::seconds(5), [&] { return last.header.stamp == msg.header.stamp; });
    EXPECT_TRUE(got) << "no left_arm computed torques";
    return last;
  }

  void onTorques(const sensor_msgs::JointState& msg) {
    std::lock_guard<std::mutex> lock(mutex);
    last = msg;
    cv.notify_all();
  }

  /// The full model's torques for `kept` joints with every other joint held still at q.
  VectorXd held_still(const sd::Model<double>& model, const VectorXd& q, const VectorXd& qd_kept,
                      const VectorXd& qdd_kept, const std::vector<std::string>& kept) {
    sd::Data<double> data(model);
    VectorXd qd = VectorXd::Zero(model.nv), qdd = VectorXd::Zero(model.nv);
    for (std::size_t k = 0; k < kept.size(); ++k) {
      qd[model.joints[model.jointBody(kept[k])].idx_v] = qd_kept[k];
      qdd[model.joints[model.jointBody(kept[k])].idx_v] = qdd_kept[k];
    }
    const VectorXd tau = sd::rnea(model, data, q, qd, qdd);
    VectorXd out(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) out[k] = tau[model.joints[model.jointBody(kept[k])].idx_v];
    return out;
  }

  spatial_dynamics::InverseDynamics::Response arm_id(const VectorXd& q_arm, const VectorXd& qd_arm,
                                                     const VectorXd& qdd_arm) {
    spatial_dynamics::InverseDynamics id;
    id.request.name = kLeftArm;
    id.request.position = to_std(q_arm);
    id.request.velocity = to_std(qd_arm);
    id.request.acceleration = to_std(qdd_arm);
    EXPECT_TRUE(ros::service::call("/dynamics/left_arm/inverse_dynamics", id));
    EXPECT_TRUE(id.response.success) << id.response.message;
    return id.response;
  }

  VectorXd arm_part(const VectorXd& v) {
    VectorXd out(kLeftArm.size());
    for (std::size_t k = 0; k < kLeftArm.size(); ++k) out[k] = v[full.joints[full.jointBody(kLeftArm[k])].idx_v];
    return out;
  }

  ros::NodeHandle nh;
  ros::Publisher joint_states;
  ros::Subscriber left_arm_torques;
  std::mutex mutex;
  std::condition_variable cv;
  sensor_msgs::JointState last;
  sd::Model<double> full;
  std::mt19937 rng{31};
  static inline int stamp_counter = 0;
};

}  // namespace

TEST_F(Scenes, ASceneServesItsOwnServicesAndTopic) {
  const VectorXd q = sd_test::random_configuration(full, rng), qd = sd_test::random_vector(full.nv, rng);
  publish(q, qd);
  const sensor_msgs::JointState torques = publish(q, qd);  // after the relock to these positions
  EXPECT_EQ(torques.name, kLeftArm);
  EXPECT_LE(sd_test::relative_error(to_eigen(torques.effort),
                                    held_still(full, q, arm_part(qd), VectorXd::Zero(7), kLeftArm)),
            1e-12);
  const VectorXd q_arm = sd_test::random_vector(7, rng), qd_arm = sd_test::random_vector(7, rng),
                 qdd_arm = sd_test::random_vector(7, rng);
  VectorXd q_full = q;
  for (std::size_t k = 0; k < 7; ++k) q_full[full.joints[full.jointBody(kLeftArm[k])].idx_q] = q_arm[k];
  const auto res = arm_id(q_arm, qd_arm, qdd_arm);
  EXPECT_EQ(res.name, kLeftArm);
  EXPECT_LE(sd_test::relative_error(to_eigen(res.effort), held_still(full, q_full, qd_arm, qdd_arm, kLeftArm)), 1e-12);

  // The root/tip scene's mass matrix is the full one's block of the kept joints.
  spatial_dynamics::MassMatrix mm;
  ASSERT_TRUE(ros::service::call("/dynamics/torso_to_right/mass_matrix", mm));
  ASSERT_TRUE(mm.response.success) << mm.response.message;
  sd::Data<double> data(full);
  const Eigen::MatrixXd M = sd::crba(full, data, q);
  const int n = static_cast<int>(mm.response.name.size());
  EXPECT_EQ(n, 7);
  Eigen::MatrixXd block(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      block(a, b) = M(full.joints[full.jointBody(mm.response.name[a])].idx_v, full.joints[full.jointBody(mm.response.name[b])].idx_v);
  const Eigen::MatrixXd served = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      mm.response.mass_matrix.data(), n, n);
  EXPECT_LE(sd_test::relative_error(served, block), 1e-12);
}

TEST_F(Scenes, MovingALockedJointChangesTheAnswers) {
  VectorXd q = sd_test::random_configuration(full, rng);
  const VectorXd qd = VectorXd::Zero(full.nv);
  publish(q, qd);
  const VectorXd q_arm = arm_part(q), zero = VectorXd::Zero(7);
  const VectorXd before = to_eigen(arm_id(q_arm, zero, zero).effort);
  q[full.joints[full.jointBody("torso_2_joint")].idx_q] += 0.4;  // a locked joint of the arm scene
  q[full.joints[full.jointBody("torso_1_joint")].idx_q] -= 0.3;
  publish(q, qd);
  const VectorXd after = to_eigen(arm_id(q_arm, zero, zero).effort);
  EXPECT_GT((after - before).norm(), 1e-3) << "tilting the torso must change the arm's gravity torques";
  EXPECT_LE(sd_test::relative_error(after, held_still(full, q, zero, zero, kLeftArm)), 1e-12);
}

TEST_F(Scenes, SetPayloadChangesTheAnswersByExactlyThePayload) {
  const VectorXd q = sd_test::random_configuration(full, rng), qd = VectorXd::Zero(full.nv);
  publish(q, qd);
  const VectorXd q_arm = arm_part(q), zero = VectorXd::Zero(7);
  const VectorXd before = to_eigen(arm_id(q_arm, zero, zero).effort);

  spatial_dynamics::SetPayload set;
  set.request.frame = "arm_left_7_link";
  set.request.inertia.m = 1.5;
  set.request.inertia.com.x = 0.02;
  set.request.inertia.com.z = -0.1;
  set.request.inertia.ixx = 0.004;
  set.request.inertia.iyy = 0.005;
  set.request.inertia.izz = 0.003;
  set.request.inertia.ixy = 0.0002;
  ASSERT_TRUE(ros::service::call("/dynamics/set_payload", set));
  ASSERT_TRUE(set.response.success) << set.response.message;
  const VectorXd with = to_eigen(arm_id(q_arm, zero, zero).effort);

  sd::Payload payload;
  payload.mass = 1.5;
  payload.center_of_mass = Eigen::Vector3d(0.02, 0, -0.1);
  payload.inertia << 0.004, 0.0002, 0, 0.0002, 0.005, 0, 0, 0, 0.003;
  const sd::Model<double> loaded = sd::with_payloads(full, {{"arm_left_7_link", payload}});
  const VectorXd expected_change = held_still(loaded, q, zero, zero, kLeftArm) - held_still(full, q, zero, zero, kLeftArm);
  EXPECT_LE(sd_test::relative_error(VectorXd(with - before), expected_change), 1e-10);
  EXPECT_LE(sd_test::relative_error(with, held_still(loaded, q, zero, zero, kLeftArm)), 1e-12);

  // The main services see it too; removing it restores the answers.
  spatial_dynamics::MassMatrix mm;
  mm.request.position = to_std(q);
  ASSERT_TRUE(ros::service::call("/dynamics/mass_matrix", mm));
  sd::Data<double> data(loaded);
  EXPECT_LE(sd_test::relative_error(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
                                        mm.response.mass_matrix.data(), full.nv, full.nv),
                                    sd::crba(loaded, data, q)),
            1e-12);
  set.request.inertia = geometry_msgs::Inertia();
  ASSERT_TRUE(ros::service::call("/dynamics/set_payload", set));
  EXPECT_TRUE(set.response.success) << set.response.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(arm_id(q_arm, zero, zero).effort), before), 1e-14);

  set.request.frame = "no_such_link";
  set.request.inertia.m = 1.0;
  ASSERT_TRUE(ros::service::call("/dynamics/set_payload", set));
  EXPECT_FALSE(set.response.success);
  EXPECT_TRUE(contains(set.response.message, "'no_such_link'")) << set.response.message;
  set.request.frame = "arm_left_7_link";
  set.request.inertia.m = -2.0;
  ASSERT_TRUE(ros::service::call("/dynamics/set_payload", set));
  EXPECT_FALSE(set.response.success);
  EXPECT_TRUE(contains(set.response.message, "negative")) << set.response.message;
}

TEST_F(Scenes, BrokenScenesNameTheirCulprit) {
  spatial_dynamics::InverseDynamics id;
  ASSERT_TRUE(ros::service::call("/dynamics/broken/inverse_dynamics", id));
  EXPECT_FALSE(id.response.success);
  EXPECT_TRUE(contains(id.response.message, "'no_such_joint'")) << id.response.message;
  spatial_dynamics::MassMatrix mm;
  ASSERT_TRUE(ros::service::call("/dynamics/broken_link/mass_matrix", mm));
  EXPECT_FALSE(mm.response.success);
  EXPECT_TRUE(contains(mm.response.message, "'no_such_link'")) << mm.response.message;
}

TEST_F(Scenes, CoupledMimicJointsAnswerTheCoupledSystem) {
  ASSERT_TRUE(ros::service::waitForService("/dynamics_coupled/inverse_dynamics", ros::Duration(10)));
  const sd::Model<double> coupled = sd::couple_mimic_joints(full);
  sd::Data<double> data(coupled);
  const VectorXd q = sd_test::random_configuration(coupled, rng);
  const VectorXd qd = sd_test::random_vector(coupled.nv, rng), qdd = sd_test::random_vector(coupled.nv, rng);
  spatial_dynamics::InverseDynamics id;
  id.request.position = to_std(q);
  id.request.velocity = to_std(qd);
  id.request.acceleration = to_std(qdd);
  ASSERT_TRUE(ros::service::call("/dynamics_coupled/inverse_dynamics", id));
  ASSERT_TRUE(id.response.success) << id.response.message;
  EXPECT_EQ(static_cast<int>(id.response.name.size()), full.nv - 12);
  EXPECT_LE(sd_test::relative_error(to_eigen(id.response.effort), sd::rnea(coupled, data, q, qd, qdd)), 1e-12);
  spatial_dynamics::ForwardDynamics fd;
  fd.request.position = id.request.position;
  fd.request.velocity = id.request.velocity;
  fd.request.effort = id.response.effort;
  ASSERT_TRUE(ros::service::call("/dynamics_coupled/forward_dynamics", fd));
  ASSERT_TRUE(fd.response.success) << fd.response.message;
  EXPECT_LE(sd_test::relative_error(to_eigen(fd.response.acceleration), qdd), 1e-9);
}
