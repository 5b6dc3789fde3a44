// The node's services (doc/node.md): per scene inverse_dynamics, inverse_dynamics_trajectory,
// forward_dynamics and mass_matrix; transform_wrench, reload, set_payload and set_contacts. Each call runs a
// ROS-free handler (service_handlers.hpp) on its scene's current snapshot with a workspace leased
// from the scene's pool; an error becomes success = false with its message, and the client always
// receives the body. Calls and failures are counted for diagnostics.
#pragma once

#include <atomic>
#include <cstddef>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "spatial_dynamics/SetContacts.h"
#include "spatial_dynamics/SetPayload.h"
#include "spatial_dynamics/ros/base_state.hpp"
#include "spatial_dynamics/ros/model_store.hpp"
#include "spatial_dynamics/ros/service_handlers.hpp"

namespace spatial_dynamics {

class ServiceEndpoints {
 public:
  /// Advertises every service under `private_nh`; `frames` resolves frames outside the robot, `base`
  /// gives a floating base's state and `source` reads what ~reload loads.
  ServiceEndpoints(ros::NodeHandle private_nh, ModelStore& store, const FrameLookup& frames,
                   const BaseStateSource& base, ModelStore::SourceReader source);

  /// Calls and failures of each service.
  void report(diagnostic_updater::DiagnosticStatusWrapper& status) const;
  /// `listener` runs after each successful ~reload (set before the first call can arrive).
  void onReloaded(std::function<void()> listener) { reloaded_ = std::move(listener); }

 private:
  struct Counters {
    std::string service;  // its name below the node, for diagnostics
    std::atomic<long> calls{0};
    std::atomic<long> failures{0};
    explicit Counters(std::string name) : service(std::move(name)) {}
  };

  /// Runs `compute` on scene k's snapshot and a leased workspace, counting the call.
  template <class Response, class Compute>
  bool serve(std::size_t k, Counters& counters, Response& res, Compute&& compute);
  /// Advertises a scene service computed by `compute(scene, workspace, req, res)`.
  template <class Service, class Compute>
  void advertise(std::size_t k, const std::string& name, Compute compute);

  bool onReload(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSetPayload(SetPayload::Request& req, SetPayload::Response& res);
  bool onSetContacts(SetContacts::Request& req, SetContacts::Response& res);

  ros::NodeHandle private_nh_;
  ModelStore& store_;
  const FrameLookup& frames_;
  const BaseStateSource& base_;
  ModelStore::SourceReader source_;
  std::function<void()> reloaded_;
  std::deque<Counters> counters_;  // stable addresses: the callbacks hold them
  std::vector<ros::ServiceServer> services_;
};

}  // namespace spatial_dynamics
