// Integration test: several clients call the services concurrently while joint_states stream at
// 500 Hz. Every answer must be correct and none lost, and every joint_states message must get its
// computed torques.
#include <sensor_msgs/JointState.h>

#include <atomic>
#include <thread>

#include "node_test_utils.hpp"
#include "spatial_dynamics/CentroidalState.h"

using namespace sd_node_test;
using Eigen::VectorXd;

namespace {

constexpr int kClients = 4;
constexpr int kCallsPerClient = 500;
constexpr double kJointStateRate = 500.0;

struct ClientResult {
  int answered = 0;
  int correct = 0;
  double worst_error = 0;
  std::string first_problem;
};

/// One client: its own persistent connections, its own Data, a fixed sequence of random states.
void run_client(int id, const sd::Model<double>& model, ClientResult& result) {
  ros::NodeHandle nh;
  ros::ServiceClient id_client = nh.serviceClient<spatial_dynamics::InverseDynamics>(service("inverse_dynamics"), true);
  ros::ServiceClient fd_client = nh.serviceClient<spatial_dynamics::ForwardDynamics>(service("forward_dynamics"), true);
  ros::ServiceClient mm_client = nh.serviceClient<spatial_dynamics::MassMatrix>(service("mass_matrix"), true);
  sd::Data<double> data(model);
  std::mt19937 rng(100 + id);
  for (int call = 0; call < kCallsPerClient; ++call) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng);
    const VectorXd x = sd_test::random_vector(model.nv, rng);
    bool ok = false;
    double error = 1;
    std::string message;
    switch (call % 3) {
      case 0: {
        spatial_dynamics::InverseDynamics srv;
        srv.request.position = to_std(q);
        srv.request.velocity = to_std(qd);
        srv.request.acceleration = to_std(x);
        ok = id_client.call(srv) && srv.response.success;
        message = srv.response.message;
        if (ok) error = sd_test::relative_error(to_eigen(srv.response.effort), sd::rnea(model, data, q, qd, x));
        break;
      }
      case 1: {
        spatial_dynamics::ForwardDynamics srv;
        srv.request.position = to_std(q);
        srv.request.velocity = to_std(qd);
        srv.request.effort = to_std(x);
        ok = fd_client.call(srv) && srv.response.success;
        message = srv.response.message;
        if (ok) error = sd_test::relative_error(to_eigen(srv.response.acceleration), sd::aba(model, data, q, qd, x));
        break;
      }
      default: {
        spatial_dynamics::MassMatrix srv;
        srv.request.position = to_std(q);
        ok = mm_client.call(srv) && srv.response.success;
        message = srv.response.message;
        if (ok) {
          const Eigen::MatrixXd M = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
              srv.response.mass_matrix.data(), model.nv, model.nv);
          error = sd_test::relative_error(M, sd::crba(model, data, q));
        }
      }
    }
    if (ok) ++result.answered;
    if (ok && error <= 1e-12) ++result.correct;
    result.worst_error = std::max(result.worst_error, error);
    if ((!ok || error > 1e-12) && result.first_problem.empty())
      result.first_problem = "call " + std::to_string(call) + ": " + (ok ? "error " + std::to_string(error) : message);
  }
}

}  // namespace

TEST(Concurrency, ClientsAndJointStatesAtOnce) {
  ASSERT_TRUE(wait_for_services());
  const sd::Model<double> model = model_from_parameter();
  ros::NodeHandle nh;
  std::atomic<long> torques_received{0};
  ros::Subscriber torques = nh.subscribe<sensor_msgs::JointState>(
      "/dynamics/computed_torques", 10000, [&](const sensor_msgs::JointState::ConstPtr&) { ++torques_received; });
  // ~centroidal_state: one per joint_states message, none when ~publish_centroidal_state is false.
  const bool centroidal_expected = ros::param::param("/dynamics/publish_centroidal_state", true);
  std::atomic<long> centroidal_received{0};
  ros::Subscriber centroidal = nh.subscribe<sd::CentroidalState>(
      "/dynamics/centroidal_state", 10000, [&](const sd::CentroidalState::ConstPtr&) { ++centroidal_received; });
  ros::Publisher joint_states = nh.advertise<sensor_msgs::JointState>("/joint_states", 10000);
  for (int k = 0; k < 100 && (joint_states.getNumSubscribers() == 0 || torques.getNumPublishers() == 0 ||
                              centroidal.getNumPublishers() == 0);
       ++k)
    ros::Duration(0.05).sleep();

  std::atomic<bool> clients_done{false};
  long published = 0;
  std::thread streamer([&] {
    std::mt19937 rng(1);
    ros::WallRate rate(kJointStateRate);
    while (!clients_done) {
      sensor_msgs::JointState msg;
      msg.header.stamp = ros::Time::now();
      for (int i = 1; i < model.nbodies(); ++i) msg.name.push_back(model.joint_names[i]);
      msg.position = to_std(sd_test::random_configuration(model, rng));
      msg.velocity = to_std(sd_test::random_vector(model.nv, rng));
      joint_states.publish(msg);
      ++published;
      rate.sleep();
    }
  });

  std::vector<ClientResult> results(kClients);
  std::vector<std::thread> clients;
  const ros::WallTime start = ros::WallTime::now();
  for (int c = 0; c < kClients; ++c) clients.emplace_back(run_client, c, std::cref(model), std::ref(results[c]));
  for (auto& t : clients) t.join();
  const double seconds = (ros::WallTime::now() - start).toSec();
  clients_done = true;
  streamer.join();
  for (int k = 0; k < 100 && (torques_received < published || (centroidal_expected && centroidal_received < published)); ++k)
    ros::Duration(0.05).sleep();

  for (int c = 0; c < kClients; ++c) {
    EXPECT_EQ(results[c].answered, kCallsPerClient) << "client " << c << ": " << results[c].first_problem;
    EXPECT_EQ(results[c].correct, kCallsPerClient) << "client " << c << ": " << results[c].first_problem;
  }
  EXPECT_EQ(torques_received.load(), published);
  EXPECT_EQ(centroidal_received.load(), centroidal_expected ? published : 0L) << "~publish_centroidal_state " << centroidal_expected;
  std::printf("[concurrency] %d clients x %d calls in %.2f s (%.0f calls/s); joint_states published %ld, computed "
              "torques received %ld, centroidal states %ld\n",
              kClients, kCallsPerClient, seconds, kClients * kCallsPerClient / seconds, published,
              torques_received.load(), centroidal_received.load());
}
