#include "spatial_dynamics/ros/service_endpoints.hpp"

#include <utility>

namespace spatial_dynamics {

ServiceEndpoints::ServiceEndpoints(ros::NodeHandle private_nh, ModelStore& store, const FrameLookup& frames,
                                   const BaseStateSource& base, ModelStore::SourceReader source)
    : private_nh_(std::move(private_nh)), store_(store), frames_(frames), base_(base), source_(std::move(source)) {
  Counters& wrench = counters_.emplace_back("transform_wrench");
  services_.push_back(private_nh_.advertiseService<TransformWrench::Request, TransformWrench::Response>(
      "transform_wrench", [this, &wrench](auto& req, auto& res) {
        return serve(0, wrench, res, [&](const ServedScene& scene, Workspace& ws) {
          compute_transform_wrench(scene, ws, frames_, req, res);
        });
      }));
  services_.push_back(private_nh_.advertiseService("reload", &ServiceEndpoints::onReload, this));
  services_.push_back(private_nh_.advertiseService("set_payload", &ServiceEndpoints::onSetPayload, this));
  services_.push_back(private_nh_.advertiseService("set_contacts", &ServiceEndpoints::onSetContacts, this));
  // The base state for the calls that need one.
  const auto with_base = [this](auto compute) {
    return [this, compute](const ServedScene& s, Workspace& ws, const auto& req, auto& res) { compute(s, base_, ws, req, res); };
  };
  for (std::size_t k = 0; k < store_.sceneCount(); ++k) {
    advertise<InverseDynamics>(k, "inverse_dynamics", with_base(compute_inverse_dynamics));
    advertise<InverseDynamicsTrajectory>(k, "inverse_dynamics_trajectory", compute_inverse_dynamics_trajectory);
    advertise<ForwardDynamics>(k, "forward_dynamics", with_base(compute_forward_dynamics));
    advertise<MassMatrix>(k, "mass_matrix", with_base(compute_mass_matrix));
  }
}

template <class Service, class Compute>
void ServiceEndpoints::advertise(std::size_t k, const std::string& name, Compute compute) {
  Counters& counters = counters_.emplace_back(store_.config().scenes[k].resolve(name));
  services_.push_back(private_nh_.advertiseService<typename Service::Request, typename Service::Response>(
      counters.service, [this, k, &counters, compute](auto& req, auto& res) {
        return serve(k, counters, res, [&](const ServedScene& s, Workspace& ws) { compute(s, ws, req, res); });
      }));
}

template <class Response, class Compute>
bool ServiceEndpoints::serve(std::size_t k, Counters& counters, Response& res, Compute&& compute) {
  ++counters.calls;
  res.success = false;
  res.message.clear();
  const std::shared_ptr<const ServedScene> served = store_.scene(k);
  if (!served) {
    res.message = "no robot model is loaded: " + store_.loadError();
  } else if (!served->model) {
    res.message = served->error;
  } else {
    try {
      const WorkspacePool::Lease workspace = served->workspaces.acquire(*served->model);
      compute(*served, *workspace);
      res.success = true;
    } catch (const std::exception& e) {
      res.message = e.what();
    }
  }
  if (!res.success) ++counters.failures;
  return true;  // the client always receives the body
}

bool ServiceEndpoints::onReload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  res.success = store_.reload(source_, res.message);
  if (res.success && reloaded_) reloaded_();
  if (res.success)
    ROS_INFO("dynamics: %s", res.message.c_str());
  else
    ROS_ERROR("dynamics: %s", res.message.c_str());
  return true;
}

bool ServiceEndpoints::onSetPayload(SetPayload::Request& req, SetPayload::Response& res) {
  const geometry_msgs::Inertia& in = req.inertia;
  Payload payload;
  payload.mass = in.m;
  payload.center_of_mass = Eigen::Vector3d(in.com.x, in.com.y, in.com.z);
  payload.inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  res.success = store_.setPayload(req.frame, payload, res.message);
  if (res.success) ROS_INFO("dynamics: %s", res.message.c_str());
  return true;
}

bool ServiceEndpoints::onSetContacts(SetContacts::Request& req, SetContacts::Response& res) {
  res.success = store_.setContacts(ContactSpec{req.frames, req.kinds, req.frictions}, res.message);
  if (res.success) ROS_INFO("dynamics: %s", res.message.c_str());
  return true;
}

void ServiceEndpoints::report(diagnostic_updater::DiagnosticStatusWrapper& status) const {
  for (const Counters& counters : counters_) {
    status.add(counters.service + " calls", static_cast<long>(counters.calls));
    status.add(counters.service + " failures", static_cast<long>(counters.failures));
  }
}

}  // namespace spatial_dynamics
