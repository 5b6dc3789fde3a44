// The yardstick of the node-overhead measurement (scripts/run_node_overhead.sh): a node serving
// ~inverse_dynamics with the dynamics node's message type that computes nothing. Its answer has
// the same size as the real one (success, an empty message, the request's names and one effort
// per position), so the two round trips differ only by what the dynamics node does.
#include <ros/ros.h>

#include "spatial_dynamics/InverseDynamics.h"

namespace {

bool answer(spatial_dynamics::InverseDynamics::Request& req, spatial_dynamics::InverseDynamics::Response& res) {
  res.success = true;
  res.name = req.name;
  res.effort.assign(req.position.size(), 0.0);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "empty_service");
  ros::NodeHandle private_nh("~");
  ros::ServiceServer server = private_nh.advertiseService("inverse_dynamics", &answer);
  // As many serving threads as the dynamics node's default ~service_threads.
  ros::AsyncSpinner spinner(4);
  spinner.start();
  ros::waitForShutdown();
  return 0;
}
