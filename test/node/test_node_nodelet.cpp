// The dynamics node as a nodelet (spatial_dynamics/DynamicsNodelet, launch/dynamics_nodelet.launch)
// in one manager with a joint-state source nodelet: ~computed_torques follow the source's
// joint_states, each equal to the library's ID(q, q̇, 0) at the state it reports, and a service
// call is answered as by the standalone node.
#include <random>
#include <vector>

#include "node_test_utils.hpp"
#include "spatial_dynamics/algorithms.hpp"

using namespace sd_node_test;

namespace {

/// q (or q̇) in the model's coordinate order from a message's names and values.
Eigen::VectorXd by_name(const sd::Model<double>& model, const std::vector<std::string>& names,
                        const std::vector<double>& values) {
  const std::vector<std::string> order = model.velocityNames();
  Eigen::VectorXd out(model.nv);
  for (int k = 0; k < model.nv; ++k) {
    const auto it = std::find(names.begin(), names.end(), order[k]);
    if (it == names.end()) throw std::runtime_error("joint '" + order[k] + "' is not in the message");
    out[k] = values[static_cast<std::size_t>(it - names.begin())];
  }
  return out;
}

}  // namespace

TEST(Nodelet, ComputedTorquesFollowTheSourceNodelet) {
  const sd::Model<double> model = model_from_parameter();
  sd::Data<double> data(model);
  ros::NodeHandle nh;
  TorqueListener listener(nh);
  const std::vector<sensor_msgs::JointState> torques = listener.waitForCount(20, 30.0);
  ASSERT_GE(torques.size(), 20u) << "the dynamics nodelet published too few computed torques";
  double worst = 0;
  for (const sensor_msgs::JointState& m : torques) {
    ASSERT_EQ(m.position.size(), static_cast<std::size_t>(model.nv));
    const Eigen::VectorXd q = by_name(model, m.name, m.position), qd = by_name(model, m.name, m.velocity);
    const Eigen::VectorXd expected = sd::nonlinear_effects(model, data, q, qd);  // ID(q, q̇, 0)
    const Eigen::VectorXd effort = by_name(model, m.name, m.effort);
    worst = std::max(worst, (effort - expected).norm() / expected.norm());
    EXPECT_GT(q.norm(), 0.0) << "the source's states did not reach the nodelet";
  }
  EXPECT_LE(worst, 1e-12);
  EXPECT_LT(torques.front().header.stamp, torques.back().header.stamp) << "the states did not move on";
}

TEST(Nodelet, AnswersInverseDynamics) {
  ASSERT_TRUE(wait_for_services());
  const sd::Model<double> model = model_from_parameter();
  sd::Data<double> data(model);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  Eigen::VectorXd q(model.nv), qd(model.nv), qdd(model.nv);
  for (int k = 0; k < model.nv; ++k) {
    q[k] = uniform(rng);
    qd[k] = uniform(rng);
    qdd[k] = uniform(rng);
  }
  sd::InverseDynamics srv;
  srv.request.name = model.velocityNames();
  srv.request.position = to_std(q);
  srv.request.velocity = to_std(qd);
  srv.request.acceleration = to_std(qdd);
  srv = call("inverse_dynamics", srv);
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  const Eigen::VectorXd expected = sd::rnea(model, data, q, qd, qdd);
  EXPECT_LE((to_eigen(srv.response.effort) - expected).norm() / expected.norm(), 1e-12);
}
