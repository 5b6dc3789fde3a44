// The models the node serves: the robot (loaded, with its payloads) and one model per configured
// scene, as one immutable snapshot swapped whole (served_model.hpp), so that a call in progress
// keeps the snapshot it started with. Loading, ~reload, ~set_payload, ~set_contacts and the rebuild of a scene
// whose locked joint has moved all go through here. No ROS here: the node reads the parameters
// (node_config.hpp), logs and answers.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "spatial_dynamics/reduction/payload.hpp"
#include "spatial_dynamics/ros/node_config.hpp"
#include "spatial_dynamics/ros/served_model.hpp"

namespace spatial_dynamics {

class ModelStore {
 public:
  explicit ModelStore(NodeConfig config) : config_(std::move(config)), contacts_(config_.contacts) {}

  const NodeConfig& config() const { return config_; }
  std::size_t sceneCount() const { return config_.scenes.size(); }

  /// What a robot is built from, read when it is (re)loaded (read_robot_source); throws naming
  /// the parameter that is missing or malformed.
  using SourceReader = std::function<RobotSource()>;

  /// The robot from `source` with the payloads attached so far, and every scene built from it,
  /// swapped in. Throws (naming the culprit) when the robot does not load; what was served stays.
  void load(const SourceReader& source);
  /// Why no model is served (a start-up load that failed), for every answer until one loads.
  void setLoadError(const std::string& error);

  /// ~reload: load() from `source`, the joint states of joints that keep their names carried over.
  /// The message says what was loaded, or why not and what is still served.
  bool reload(const SourceReader& source, std::string& message);
  /// ~set_payload: `payload` attached to `frame` (a link of the robot), or the frame's payload
  /// removed where payload.mass is 0. The message says what was done or why not.
  bool setPayload(const std::string& frame, const Payload& payload, std::string& message);

  /// ~set_contacts: the robot's contacts for every scene from now on (reloads keep them). The
  /// message says what was set, or names the frame, kind or coefficient refused.
  bool setContacts(const ContactSpec& contacts, std::string& message);

  /// The payloads attached now, by frame.
  std::map<std::string, Payload> payloads();

  std::shared_ptr<const ServedRobot> robot() const;
  /// Scene k (0: the main services); null before a robot has loaded.
  std::shared_ptr<const ServedScene> scene(std::size_t k) const;
  std::string loadError() const;

  /// Scene k as joint_states leave it: `served`, or a rebuild of it when a joint it locks has moved
  /// further than ~relock_tolerance (served from now on unless a reload or a payload change
  /// replaced the scene first). `moved` then says which joint moved and by how much.
  std::shared_ptr<const ServedScene> followLockedJoints(std::size_t k, std::shared_ptr<const ServedScene> served,
                                                        const std::shared_ptr<const ServedRobot>& robot,
                                                        std::string& moved);

 private:
  std::shared_ptr<const ServedRobot> loadRobot(const RobotSource& source, const std::map<std::string, Payload>& payloads) const;
  std::shared_ptr<const ServedRobot> withPayloads(const ServedRobot& robot,
                                                  const std::map<std::string, Payload>& payloads) const;
  std::shared_ptr<const ServedScene> buildScene(const std::shared_ptr<const ServedRobot>& robot,
                                                const SceneConfig& config) const;
  /// Replaces the robot and rebuilds every scene from it.
  void install(const std::shared_ptr<const ServedRobot>& robot);

  const NodeConfig config_;
  mutable std::mutex mutex_;  // guards the pointers below, never a computation
  std::shared_ptr<const ServedRobot> robot_;
  std::vector<std::shared_ptr<const ServedScene>> scenes_;
  std::string load_error_;
  std::mutex payload_mutex_;  // serialises ~set_payload and ~reload
  std::map<std::string, Payload> payloads_;
  ContactSpec contacts_;  // ~contacts, then the last ~set_contacts (guarded by payload_mutex_)
};

}  // namespace spatial_dynamics
