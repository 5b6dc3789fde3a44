// The ROS node (doc/node.md): reads robot_description, merges joint_states, serves
// inverse and forward dynamics, the mass matrix and wrench transforms for the whole robot and for
// configured scenes (reduced models), manages payloads, and publishes computed torques.
// Message ↔ vector translation only: the arithmetic is the library's.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "spatial_dynamics/ForwardDynamics.h"
#include "spatial_dynamics/InverseDynamics.h"
#include "spatial_dynamics/InverseDynamicsTrajectory.h"
#include "spatial_dynamics/MassMatrix.h"
#include "spatial_dynamics/SetPayload.h"
#include "spatial_dynamics/TransformWrench.h"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/reduction/payload.hpp"
#include "spatial_dynamics/ros/inline_callback_queue.hpp"
#include "spatial_dynamics/ros/latency_recorder.hpp"
#include "spatial_dynamics/ros/served_model.hpp"
#include "spatial_dynamics/ros/service_handlers.hpp"

namespace spatial_dynamics {

/// A scene as the parameters configure it (fixed for the node's life).
struct SceneConfig {
  std::string name;                 // "" for the node's main services
  std::string parameter;            // where it was configured, for messages
  bool reduced = false;             // false: the whole robot
  std::vector<std::string> joints;  // kept joints, or
  std::string root_link;            // root link and tip links
  std::vector<std::string> tip_links;
  std::string error;                // a configuration error, reported by the scene's services
};

class DynamicsNode {
 public:
  DynamicsNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);
  /// Stops joint_states first, so that no callback runs while the members it uses are destroyed.
  ~DynamicsNode();
  DynamicsNode(const DynamicsNode&) = delete;
  DynamicsNode& operator=(const DynamicsNode&) = delete;

 private:
  struct Counters {
    std::atomic<long> calls{0};
    std::atomic<long> failures{0};
  };
  struct SceneEndpoints {
    std::vector<ros::ServiceServer> services;
    ros::Publisher computed_torques;
    Counters inverse_dynamics, inverse_dynamics_trajectory, forward_dynamics, mass_matrix;
  };

  std::shared_ptr<const ServedRobot> loadRobot(const std::map<std::string, Payload>& payloads) const;
  std::shared_ptr<const ServedRobot> withPayloads(const ServedRobot& robot,
                                                  const std::map<std::string, Payload>& payloads) const;
  std::shared_ptr<const ServedScene> buildScene(const std::shared_ptr<const ServedRobot>& robot,
                                                const SceneConfig& config) const;
  /// Replaces the robot and rebuilds every scene from it.
  void install(const std::shared_ptr<const ServedRobot>& robot);
  std::shared_ptr<const ServedScene> scene(std::size_t index) const;
  void readSceneConfigs();
  void advertiseScene(std::size_t index);

  bool onInverseDynamics(std::size_t scene, InverseDynamics::Request& req, InverseDynamics::Response& res);
  bool onInverseDynamicsTrajectory(std::size_t scene, InverseDynamicsTrajectory::Request& req,
                                   InverseDynamicsTrajectory::Response& res);
  bool onForwardDynamics(std::size_t scene, ForwardDynamics::Request& req, ForwardDynamics::Response& res);
  bool onMassMatrix(std::size_t scene, MassMatrix::Request& req, MassMatrix::Response& res);
  bool onTransformWrench(TransformWrench::Request& req, TransformWrench::Response& res);
  bool onReload(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSetPayload(SetPayload::Request& req, SetPayload::Response& res);
  void onJointStates(const ros::MessageEvent<sensor_msgs::JointState const>& event);

  /// Runs `compute` with a scene's model and this thread's workspace for it; turns every error
  /// into success = false plus its message, and counts the call.
  template <class Response, class Compute>
  bool serve(std::size_t scene, Counters& counters, Response& res, Compute&& compute);

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_, private_nh_;
  bool publish_computed_torques_ = true;
  bool coupled_mimic_joints_ = false;
  double relock_tolerance_ = 1e-6;
  double max_state_age_ = 1.0;
  JointStateCache::UnknownJoints unknown_joints_ = JointStateCache::UnknownJoints::kDrop;

  std::vector<SceneConfig> scene_configs_;    // [0]: the main services
  std::vector<SceneEndpoints> endpoints_;     // one per scene config

  mutable std::mutex model_mutex_;            // guards the pointers below, never a computation
  std::shared_ptr<const ServedRobot> robot_;
  std::vector<std::shared_ptr<const ServedScene>> scenes_;
  std::string load_error_;
  std::mutex payload_mutex_;                  // serialises ~set_payload and ~reload
  std::map<std::string, Payload> payloads_;

  /// Frames outside the robot model, from tf2: used for poses only (tf2's own wrench transform
  /// in ROS 1 drops the r × f moment).
  class TfFrames : public FrameLookup {
   public:
    explicit TfFrames(const tf2_ros::Buffer& buffer) : buffer_(buffer) {}
    bool hasFrame(const std::string& frame) const override;
    PluckerTransform<double> transform(const std::string& target, const std::string& source,
                                       const ros::Time& stamp) const override;

   private:
    const tf2_ros::Buffer& buffer_;
  };

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  TfFrames tf_frames_{tf_buffer_};

  // joint_states never wait behind service calls: by default (~inline_joint_states) each message
  // is handled at once in roscpp's receiving thread; otherwise, or when that is busy, by a thread of
  // their own, so that a burst of service calls never delays (or, through a full queue, drops) a
  // joint state and its computed torques.
  InlineCallbackQueue joint_state_queue_;
  ros::Subscriber joint_states_sub_;
  std::unique_ptr<ros::AsyncSpinner> joint_state_spinner_;
  std::vector<ros::ServiceServer> services_;
  Counters transform_wrench_;
  std::atomic<long> joint_state_messages_{0}, joint_state_drops_{0}, torque_messages_{0};
  // From a joint_states message's arrival (roscpp's receipt time) to its last ~computed_torques
  // message being handed to roscpp, in µs: the last 10 s at 1 kHz.
  LatencyRecorder torque_latency_us_{10000};
  std::atomic<double> last_joint_state_time_{0.0};
  std::mutex warned_mutex_;
  std::set<std::string> warned_unknown_joints_;

  diagnostic_updater::Updater diagnostics_;
  ros::Timer diagnostics_timer_;
  long last_diag_joint_states_ = 0, last_diag_torques_ = 0;
  ros::WallTime last_diag_time_;
};

}  // namespace spatial_dynamics
