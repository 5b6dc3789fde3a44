// The one main() of the rostest checkers: gtest and ROS initialised (rostest names the node after
// the test), a spinner for the subscriptions' callbacks, then every test of the checker.
#include <gtest/gtest.h>
#include <ros/ros.h>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_test");
  ros::NodeHandle nh;  // keeps the node up while the tests come and go
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
