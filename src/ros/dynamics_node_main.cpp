// dynamics_node: see include/spatial_dynamics/ros/dynamics_node.hpp and the README.
#include <ros/ros.h>

#include "spatial_dynamics/ros/dynamics_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "dynamics");
  ros::NodeHandle nh, private_nh("~");
  spatial_dynamics::DynamicsNode node(nh, private_nh);
  int threads = 4;
  private_nh.param("service_threads", threads, threads);
  ros::AsyncSpinner spinner(std::max(1, threads));
  spinner.start();
  ros::waitForShutdown();
  return 0;
}
