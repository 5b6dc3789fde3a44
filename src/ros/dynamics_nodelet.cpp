// spatial_dynamics/DynamicsNodelet: the dynamics node (dynamics_node.hpp) in a nodelet manager, so
// that a driver in the same manager hands it joint_states without serialisation. Its callbacks
// run on the manager's threads (the standalone node's ~service_threads is the manager's
// num_worker_threads here); joint_states keep their own inline queue and thread, as in the node.
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "spatial_dynamics/ros/dynamics_node.hpp"

namespace spatial_dynamics {

class DynamicsNodelet : public nodelet::Nodelet {
 private:
  void onInit() override { node_ = std::make_unique<DynamicsNode>(getMTNodeHandle(), getMTPrivateNodeHandle()); }

  std::unique_ptr<DynamicsNode> node_;
};

}  // namespace spatial_dynamics

PLUGINLIB_EXPORT_CLASS(spatial_dynamics::DynamicsNodelet, nodelet::Nodelet)
