#include "spatial_dynamics/ros/dynamics_node.hpp"

#include <stdexcept>

namespace spatial_dynamics {

DynamicsNode::DynamicsNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh)
    : nh_(nh),
      private_nh_(private_nh),
      tf_listener_(tf_buffer_),
      read_source_([this] { return read_robot_source(nh_, private_nh_); }),
      store_(read_node_config(private_nh_)),
      base_state_(nh_, tf_buffer_, store_.config().base_odometry, store_.config().world_frame,
                  store_.config().max_state_age),
      services_(private_nh_, loadedAtStartUp(), tf_frames_, base_state_, read_source_),
      external_torques_(private_nh_, store_),
      payload_identification_(private_nh_, store_, recorder_),
      joint_states_(nh_, private_nh_, store_, base_state_, external_torques_, recorder_),
      diagnostics_(nh_, private_nh_, store_, services_, joint_states_, external_torques_, payload_identification_,
                   base_state_) {
  services_.onReloaded([this] { external_torques_.reconfigure(); });
}

ModelStore& DynamicsNode::loadedAtStartUp() {
  ROS_INFO("dynamics: simd backend %s", simd_backend_or_error().c_str());
  try {
    if (!store_.config().error.empty()) throw std::runtime_error(store_.config().error);
    store_.load(read_source_);
    const std::shared_ptr<const ServedRobot> robot = store_.robot();
    ROS_INFO("dynamics: serving '%s' with %d joints, %s base, actuator model %s", robot->robot_name.c_str(),
             static_cast<int>(robot->cache->jointNames().size()), robot->floating_base ? "floating" : "fixed",
             to_string(robot->actuator_model));
  } catch (const std::exception& e) {
    store_.setLoadError(e.what());
    ROS_ERROR("dynamics: no robot model: %s", e.what());
  }
  for (std::size_t k = 0; k < store_.sceneCount(); ++k) {
    const SceneConfig& config = store_.config().scenes[k];
    const std::shared_ptr<const ServedScene> scene = store_.scene(k);
    if (!config.error.empty())
      ROS_ERROR("dynamics: %s", config.error.c_str());
    else if (scene && !scene->error.empty())
      ROS_ERROR("dynamics: %s", scene->error.c_str());
  }
  return store_;
}

}  // namespace spatial_dynamics
