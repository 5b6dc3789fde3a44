// The ROS node (DESIGN.md, layer 5): reads robot_description, merges joint_states, serves
// inverse and forward dynamics, the mass matrix and wrench transforms, and publishes computed
// torques. Message ↔ vector translation only: the arithmetic is the library's.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "spatial_dynamics/ForwardDynamics.h"
#include "spatial_dynamics/InverseDynamics.h"
#include "spatial_dynamics/MassMatrix.h"
#include "spatial_dynamics/TransformWrench.h"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/ros/joint_request_decoder.hpp"
#include "spatial_dynamics/ros/joint_state_cache.hpp"

namespace spatial_dynamics {

/// One loaded robot: immutable model, its request decoder and its joint-state cache.
struct ServedModel {
  std::uint64_t version = 0;                 // unique per load; keys the per-thread workspaces
  std::shared_ptr<const Model<double>> model;
  std::unique_ptr<JointRequestDecoder> decoder;
  std::unique_ptr<JointStateCache> cache;
  std::string robot_name;
  std::string root_frame;                    // the URDF root link: the frame tf chains through
};

class DynamicsNode {
 public:
  DynamicsNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);

 private:
  struct Counters {
    std::atomic<long> calls{0};
    std::atomic<long> failures{0};
  };

  /// Builds a ServedModel from the parameters; throws with the reason.
  std::shared_ptr<const ServedModel> loadFromParameters() const;
  std::shared_ptr<const ServedModel> current() const;

  bool onInverseDynamics(InverseDynamics::Request& req, InverseDynamics::Response& res);
  bool onForwardDynamics(ForwardDynamics::Request& req, ForwardDynamics::Response& res);
  bool onMassMatrix(MassMatrix::Request& req, MassMatrix::Response& res);
  bool onTransformWrench(TransformWrench::Request& req, TransformWrench::Response& res);
  bool onReload(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  void onJointStates(const sensor_msgs::JointState::ConstPtr& msg);

  /// Runs `compute` with the current model and this thread's workspace; turns every error into
  /// success = false plus its message, and counts the call.
  template <class Response, class Compute>
  bool serve(Counters& counters, Response& res, Compute&& compute);

  /// ^{target}X_{source} for two frames, each a model frame (kinematics at q) or a tf2 frame.
  PluckerTransform<double> frameTransform(const ServedModel& served, const std::string& target,
                                          const std::string& source, const ros::Time& stamp,
                                          const Eigen::VectorXd* q) const;
  PluckerTransform<double> tfTransform(const std::string& target, const std::string& source,
                                       const ros::Time& stamp) const;

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_, private_nh_;
  bool publish_computed_torques_ = true;

  mutable std::mutex model_mutex_;
  std::shared_ptr<const ServedModel> served_;
  std::string load_error_;

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;

  ros::Publisher computed_torques_pub_;
  ros::Subscriber joint_states_sub_;
  std::vector<ros::ServiceServer> services_;

  Counters inverse_dynamics_, forward_dynamics_, mass_matrix_, transform_wrench_;
  std::atomic<long> joint_state_messages_{0}, joint_state_drops_{0}, torque_messages_{0};
  std::atomic<double> last_joint_state_time_{0.0};
  std::mutex warned_mutex_;
  std::set<std::string> warned_unknown_joints_;

  diagnostic_updater::Updater diagnostics_;
  ros::Timer diagnostics_timer_;
  long last_diag_joint_states_ = 0, last_diag_torques_ = 0;
  ros::WallTime last_diag_time_;
};

}  // namespace spatial_dynamics
