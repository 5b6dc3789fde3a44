#include "spatial_dynamics/ros/dynamics_node.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <ros/names.h>
#include <tf2/exceptions.h>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/simd_backend.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace spatial_dynamics {
namespace {

std::atomic<std::uint64_t> next_scene_version{1};

Eigen::Vector3d read_gravity(const ros::NodeHandle& private_nh) {
  if (!private_nh.hasParam("gravity")) return Eigen::Vector3d(0.0, 0.0, -9.81);
  XmlRpc::XmlRpcValue value;
  private_nh.getParam("gravity", value);
  const std::string culprit = "parameter " + private_nh.resolveName("gravity") + " must be a list of 3 finite numbers";
  if (value.getType() != XmlRpc::XmlRpcValue::TypeArray || value.size() != 3) throw std::runtime_error(culprit);
  Eigen::Vector3d g;
  for (int k = 0; k < 3; ++k) {
    if (value[k].getType() == XmlRpc::XmlRpcValue::TypeDouble) g[k] = static_cast<double>(value[k]);
    else if (value[k].getType() == XmlRpc::XmlRpcValue::TypeInt) g[k] = static_cast<int>(value[k]);
    else throw std::runtime_error(culprit);
    if (!std::isfinite(g[k])) throw std::runtime_error(culprit);
  }
  return g;
}

/// A list-of-strings parameter; throws naming it when it has another type.
std::vector<std::string> read_names(const ros::NodeHandle& nh, const std::string& key) {
  std::vector<std::string> names;
  if (!nh.getParam(key, names))
    throw std::runtime_error("parameter " + nh.resolveName(key) + " must be a list of names");
  return names;
}

/// Reads `joints` or `root_link` + `tip_links` under `nh` into `config`.
void read_scene(const ros::NodeHandle& nh, SceneConfig& config) {
  config.parameter = nh.getNamespace();
  try {
    const bool by_joints = nh.hasParam("joints"), by_root = nh.hasParam("root_link") || nh.hasParam("tip_links");
    if (by_joints && by_root)
      throw std::runtime_error("give either " + nh.resolveName("joints") + " or " + nh.resolveName("root_link") +
                               " with " + nh.resolveName("tip_links") + ", not both");
    if (by_joints) {
      config.reduced = true;
      config.joints = read_names(nh, "joints");
    } else if (by_root) {
      config.reduced = true;
      if (!nh.getParam("root_link", config.root_link))
        throw std::runtime_error("parameter " + nh.resolveName("root_link") + " must be a link name");
      config.tip_links = read_names(nh, "tip_links");
    } else if (!config.name.empty()) {
      throw std::runtime_error("scene '" + config.name + "' needs " + nh.resolveName("joints") + " or " +
                               nh.resolveName("root_link") + " and " + nh.resolveName("tip_links"));
    }
  } catch (const std::exception& e) {
    config.error = e.what();
  }
}

/// ~actuator_model and ~actuators (actuator_parameters.hpp); throws naming a bad ~actuator_model.
ActuatorSettings read_actuator_settings(const ros::NodeHandle& private_nh) {
  ActuatorSettings settings;
  if (private_nh.hasParam("actuator_model")) {
    std::string value;
    if (!private_nh.getParam("actuator_model", value))
      throw std::runtime_error("parameter " + private_nh.resolveName("actuator_model") +
                               " must be 'rigid_body', 'urdf' or 'parameters'");
    settings.model = parse_actuator_model(value, private_nh.resolveName("actuator_model"));
  }
  settings.actuators_parameter = private_nh.resolveName("actuators");
  if (private_nh.hasParam("actuators")) private_nh.getParam("actuators", settings.actuators);
  if (settings.model == ActuatorModel::RigidBody && settings.actuators.valid())
    ROS_WARN("dynamics: %s is set but %s is 'rigid_body': the answers include no actuator terms",
             settings.actuators_parameter.c_str(), private_nh.resolveName("actuator_model").c_str());
  return settings;
}

/// The build of the compiled algorithms this process runs (simd_backend.hpp), or why there is none
/// (a bad SPATIAL_DYNAMICS_SIMD, which every algorithm call then reports as well).
std::string simd_backend_or_error() {
  try {
    return simd_backend();
  } catch (const std::exception& e) {
    return std::string("none: ") + e.what();
  }
}

}  // namespace

DynamicsNode::DynamicsNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh)
    : nh_(nh), private_nh_(private_nh), tf_listener_(tf_buffer_), diagnostics_(nh, private_nh) {
  ROS_INFO("dynamics: simd backend %s", simd_backend_or_error().c_str());
  private_nh_.param("publish_computed_torques", publish_computed_torques_, true);
  private_nh_.param("relock_tolerance", relock_tolerance_, 1e-6);
  private_nh_.param("max_state_age", max_state_age_, 1.0);
  std::string mimic_joints = "independent";
  private_nh_.param<std::string>("mimic_joints", mimic_joints, mimic_joints);
  coupled_mimic_joints_ = mimic_joints == "coupled";
  std::string unknown_joints = "drop";
  private_nh_.param<std::string>("unknown_joints", unknown_joints, unknown_joints);
  if (unknown_joints == "ignore") unknown_joints_ = JointStateCache::UnknownJoints::kIgnore;
  readSceneConfigs();
  try {
    if (mimic_joints != "independent" && mimic_joints != "coupled")
      throw std::runtime_error("parameter " + private_nh_.resolveName("mimic_joints") +
                               " must be 'independent' or 'coupled', not '" + mimic_joints + "'");
    if (unknown_joints != "drop" && unknown_joints != "ignore")
      throw std::runtime_error("parameter " + private_nh_.resolveName("unknown_joints") +
                               " must be 'drop' or 'ignore', not '" + unknown_joints + "'");
    if (!(max_state_age_ > 0.0))
      throw std::runtime_error("parameter " + private_nh_.resolveName("max_state_age") + " must be > 0 (seconds)");
    if (!(relock_tolerance_ >= 0.0))
      throw std::runtime_error("parameter " + private_nh_.resolveName("relock_tolerance") + " must be >= 0");
    install(loadRobot({}));
    ROS_INFO("dynamics: serving '%s' with %d joints, actuator model %s", robot_->robot_name.c_str(), robot_->bare->nv,
             to_string(robot_->actuator_model));
  } catch (const std::exception& e) {
    load_error_ = e.what();
    scenes_.assign(scene_configs_.size(), nullptr);
    ROS_ERROR("dynamics: no robot model: %s", load_error_.c_str());
  }
  for (std::size_t k = 0; k < scene_configs_.size(); ++k) {
    if (!scene_configs_[k].error.empty())
      ROS_ERROR("dynamics: %s", scene_configs_[k].error.c_str());
    else if (scenes_[k] && !scenes_[k]->error.empty())
      ROS_ERROR("dynamics: %s", scenes_[k]->error.c_str());
  }
  endpoints_ = std::vector<SceneEndpoints>(scene_configs_.size());
  for (std::size_t k = 0; k < scene_configs_.size(); ++k) advertiseScene(k);
  bool inline_joint_states = true;
  private_nh_.param("inline_joint_states", inline_joint_states, inline_joint_states);
  ros::NodeHandle state_nh(nh_);
  if (inline_joint_states)
    state_nh.setCallbackQueue(&joint_state_queue_);
  else
    state_nh.setCallbackQueue(&joint_state_queue_.fallback());
  joint_states_sub_ = state_nh.subscribe("joint_states", 1000, &DynamicsNode::onJointStates, this,
                                         ros::TransportHints().tcpNoDelay());
  joint_state_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &joint_state_queue_.fallback());
  joint_state_spinner_->start();
  services_.push_back(private_nh_.advertiseService("transform_wrench", &DynamicsNode::onTransformWrench, this));
  services_.push_back(private_nh_.advertiseService("reload", &DynamicsNode::onReload, this));
  services_.push_back(private_nh_.advertiseService("set_payload", &DynamicsNode::onSetPayload, this));

  diagnostics_.setHardwareID("none");
  diagnostics_.add("Dynamics", this, &DynamicsNode::diagnose);
  last_diag_time_ = ros::WallTime::now();
  diagnostics_timer_ = private_nh_.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { diagnostics_.update(); });
}

DynamicsNode::~DynamicsNode() {
  // Unsubscribing waits for a callback running in roscpp's receiving thread; then the fallback
  // thread stops. Only then may the members the callback uses go.
  joint_states_sub_.shutdown();
  if (joint_state_spinner_) joint_state_spinner_->stop();
}

void DynamicsNode::readSceneConfigs() {
  SceneConfig main;
  read_scene(private_nh_, main);
  scene_configs_.push_back(main);
  XmlRpc::XmlRpcValue scenes;
  if (!private_nh_.getParam("scenes", scenes)) return;
  if (scenes.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    SceneConfig bad;
    bad.name = "scenes";
    bad.error = "parameter " + private_nh_.resolveName("scenes") + " must be a dictionary of scenes";
    ROS_ERROR("dynamics: %s", bad.error.c_str());
    return;
  }
  for (auto it = scenes.begin(); it != scenes.end(); ++it) {
    SceneConfig config;
    config.name = it->first;
    std::string why;
    if (!ros::names::validate(config.name, why)) {
      ROS_ERROR("dynamics: scene name '%s' is not a valid ROS name (%s); it is not served", config.name.c_str(), why.c_str());
      continue;
    }
    read_scene(ros::NodeHandle(private_nh_, "scenes/" + config.name), config);
    scene_configs_.push_back(config);
  }
}

void DynamicsNode::advertiseScene(std::size_t k) {
  const std::string prefix = scene_configs_[k].name.empty() ? "" : scene_configs_[k].name + "/";
  SceneEndpoints& e = endpoints_[k];
  e.services.push_back(private_nh_.advertiseService<InverseDynamics::Request, InverseDynamics::Response>(
      prefix + "inverse_dynamics", [this, k](auto& req, auto& res) { return onInverseDynamics(k, req, res); }));
  e.services.push_back(private_nh_.advertiseService<InverseDynamicsTrajectory::Request, InverseDynamicsTrajectory::Response>(
      prefix + "inverse_dynamics_trajectory",
      [this, k](auto& req, auto& res) { return onInverseDynamicsTrajectory(k, req, res); }));
  e.services.push_back(private_nh_.advertiseService<ForwardDynamics::Request, ForwardDynamics::Response>(
      prefix + "forward_dynamics", [this, k](auto& req, auto& res) { return onForwardDynamics(k, req, res); }));
  e.services.push_back(private_nh_.advertiseService<MassMatrix::Request, MassMatrix::Response>(
      prefix + "mass_matrix", [this, k](auto& req, auto& res) { return onMassMatrix(k, req, res); }));
  e.computed_torques = private_nh_.advertise<sensor_msgs::JointState>(prefix + "computed_torques", 1000);
}

std::shared_ptr<const ServedRobot> DynamicsNode::loadRobot(const std::map<std::string, Payload>& payloads) const {
  std::string urdf;
  if (!nh_.getParam("robot_description", urdf))
    throw std::runtime_error("parameter " + nh_.resolveName("robot_description") + " is not set");
  ModelBuildOptions options;
  options.gravity = read_gravity(private_nh_);
  auto robot = std::make_shared<ServedRobot>();
  const ActuatorSettings actuators = read_actuator_settings(private_nh_);
  Model<double> bare = build_model_from_urdf_string(urdf, options);
  apply_actuator_settings(actuators, coupled_mimic_joints_, bare);
  robot->actuator_model = actuators.model;
  robot->bare = std::make_shared<const Model<double>>(std::move(bare));
  robot->full = std::make_shared<const Model<double>>(with_payloads(*robot->bare, payloads));
  // One joint state per coordinate: a joint's name, or <joint>/x, /y, /yaw of a planar joint.
  robot->cache = std::make_shared<JointStateCache>(robot->bare->velocityNames(), max_state_age_, unknown_joints_);
  robot->robot_name = robot->bare->name;
  robot->root_frame = robot->bare->body_names[0];
  return robot;
}

std::shared_ptr<const ServedRobot> DynamicsNode::withPayloads(const ServedRobot& robot,
                                                              const std::map<std::string, Payload>& payloads) const {
  auto loaded = std::make_shared<ServedRobot>(robot);
  loaded->full = std::make_shared<const Model<double>>(with_payloads(*robot.bare, payloads));
  return loaded;
}

std::shared_ptr<const ServedScene> DynamicsNode::buildScene(const std::shared_ptr<const ServedRobot>& robot,
                                                            const SceneConfig& config) const {
  auto scene = std::make_shared<ServedScene>();
  scene->version = next_scene_version++;
  scene->robot = robot;
  const std::string who = config.name.empty() ? "the robot" : "scene '" + config.name + "'";
  if (!config.error.empty()) {
    scene->error = config.error;
    return scene;
  }
  try {
    const Model<double>& full = *robot->full;
    Model<double> model;
    if (!config.reduced) {
      model = full;
    } else {
      Scene spec = config.root_link.empty()
                       ? Scene{config.joints, {}}
                       : scene_from_root_and_tips(full, RootTipScene{config.root_link, config.tip_links, {}});
      std::set<std::string> kept(spec.kept_joints.begin(), spec.kept_joints.end());
      if (coupled_mimic_joints_)  // a mimic joint follows a kept master
        for (int i = 1; i < full.nbodies(); ++i)
          if (full.joints[i].mimic.active() && kept.count(full.joint_names[full.joints[i].mimic.master_body]))
            kept.insert(full.joint_names[i]);
      spec.kept_joints.assign(kept.begin(), kept.end());
      for (const std::string& name : spec.kept_joints)
        if (!full.hasJoint(name)) throw SceneError("unknown joint '" + name + "' in the joints to keep");
      JointStateCache::Snapshot state;
      robot->cache->snapshot(state);
      const std::vector<std::string>& names = robot->cache->jointNames();
      for (std::size_t i = 0; i < names.size(); ++i) {
        // Kept, or a coordinate of a planar joint, which a scene keeps (reduce_model.hpp).
        if (kept.count(names[i]) || !full.hasJoint(names[i])) continue;
        const double position = state.position_known[i] ? state.position[i] : 0.0;  // latest joint state, else 0
        spec.locked_positions[names[i]] = position;
        scene->locks.emplace_back(static_cast<int>(i), position);
      }
      model = reduce_model(full, spec);
    }
    if (coupled_mimic_joints_) model = couple_mimic_joints(model);
    scene->model = std::make_shared<const Model<double>>(std::move(model));
    scene->rigid_model = scene->model;
    if (robot->actuator_model != ActuatorModel::RigidBody) {  // for rigid_body_only
      Model<double> rigid = *scene->model;
      rigid.reset_actuator_terms();
      rigid.finalize();
      scene->rigid_model = std::make_shared<const Model<double>>(std::move(rigid));
    }
    scene->decoder = std::make_unique<JointRequestDecoder>(*scene->model, robot->cache->jointNames());
  } catch (const std::exception& e) {
    scene->model.reset();
    scene->rigid_model.reset();
    scene->error = who + " (" + config.parameter + "): " + e.what();
  }
  return scene;
}

void DynamicsNode::install(const std::shared_ptr<const ServedRobot>& robot) {
  std::vector<std::shared_ptr<const ServedScene>> scenes;
  for (const SceneConfig& config : scene_configs_) scenes.push_back(buildScene(robot, config));
  std::lock_guard<std::mutex> lock(model_mutex_);
  robot_ = robot;
  scenes_ = std::move(scenes);
  load_error_.clear();
}

std::shared_ptr<const ServedScene> DynamicsNode::scene(std::size_t index) const {
  std::lock_guard<std::mutex> lock(model_mutex_);
  return index < scenes_.size() ? scenes_[index] : nullptr;
}

template <class Response, class Compute>
bool DynamicsNode::serve(std::size_t index, Counters& counters, Response& res, Compute&& compute) {
  ++counters.calls;
  res.success = false;
  res.message.clear();
  const std::shared_ptr<const ServedScene> served = scene(index);
  if (!served) {
    std::lock_guard<std::mutex> lock(model_mutex_);
    res.message = "no robot model is loaded: " + load_error_;
  } else if (!served->model) {
    res.message = served->error;
  } else {
    try {
      compute(*served, workspace_for(index, *served));
      res.success = true;
    } catch (const std::exception& e) {
      res.message = e.what();
    }
  }
  if (!res.success) ++counters.failures;
  return true;  // the client always receives the body
}







bool DynamicsNode::onInverseDynamics(std::size_t k, InverseDynamics::Request& req, InverseDynamics::Response& res) {
  return serve(k, endpoints_[k].inverse_dynamics, res,
               [&](const ServedScene& scene, Workspace& ws) { compute_inverse_dynamics(scene, ws, req, res); });
}

bool DynamicsNode::onInverseDynamicsTrajectory(std::size_t k, InverseDynamicsTrajectory::Request& req,
                                               InverseDynamicsTrajectory::Response& res) {
  return serve(k, endpoints_[k].inverse_dynamics_trajectory, res, [&](const ServedScene& scene, Workspace& ws) {
    compute_inverse_dynamics_trajectory(scene, ws, req, res);
  });
}

bool DynamicsNode::onForwardDynamics(std::size_t k, ForwardDynamics::Request& req, ForwardDynamics::Response& res) {
  return serve(k, endpoints_[k].forward_dynamics, res,
               [&](const ServedScene& scene, Workspace& ws) { compute_forward_dynamics(scene, ws, req, res); });
}

bool DynamicsNode::onMassMatrix(std::size_t k, MassMatrix::Request& req, MassMatrix::Response& res) {
  return serve(k, endpoints_[k].mass_matrix, res,
               [&](const ServedScene& scene, Workspace& ws) { compute_mass_matrix(scene, ws, req, res); });
}

bool DynamicsNode::onTransformWrench(TransformWrench::Request& req, TransformWrench::Response& res) {
  return serve(0, transform_wrench_, res, [&](const ServedScene& scene, Workspace& ws) {
    compute_transform_wrench(scene, ws, tf_frames_, req, res);
  });
}

bool DynamicsNode::TfFrames::hasFrame(const std::string& frame) const { return buffer_._frameExists(frame); }

PluckerTransform<double> DynamicsNode::TfFrames::transform(const std::string& target, const std::string& source,
                                                           const ros::Time& stamp) const {
  geometry_msgs::TransformStamped t;
  try {
    t = buffer_.lookupTransform(target, source, stamp, ros::Duration(0.1));
  } catch (const tf2::TransformException& e) {
    throw std::runtime_error("tf2 cannot transform from '" + source + "' to '" + target + "': " + e.what());
  }
  // t is the pose of `source` in `target`; FromPose gives ^{source}X_{target}.
  const Eigen::Quaterniond rotation(t.transform.rotation.w, t.transform.rotation.x, t.transform.rotation.y,
                                    t.transform.rotation.z);
  const Eigen::Vector3d translation(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z);
  return PluckerTransform<double>::FromPose(rotation.normalized().toRotationMatrix(), translation).inverse();
}

bool DynamicsNode::onReload(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  std::lock_guard<std::mutex> serialise(payload_mutex_);
  std::shared_ptr<const ServedRobot> loaded;
  std::shared_ptr<const ServedRobot> previous;
  {
    std::lock_guard<std::mutex> lock(model_mutex_);
    previous = robot_;
  }
  try {
    loaded = loadRobot(payloads_);
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("reload failed: ") + e.what() +
                  (previous ? " (the previous model is still served)" : " (no model is served)");
    ROS_ERROR("dynamics: %s", res.message.c_str());
    if (!previous) {
      std::lock_guard<std::mutex> lock(model_mutex_);
      load_error_ = e.what();
    }
    return true;
  }
  // Carry the joint states of joints that keep their names over to the new model.
  if (previous) {
    JointStateCache::Snapshot old;
    previous->cache->snapshot(old);
    const std::vector<std::string>& names = previous->cache->jointNames();
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!old.position_known[i]) continue;
      std::vector<double> velocity;
      if (old.velocity_known[i]) velocity.push_back(old.velocity[i]);
      loaded->cache->update({names[i]}, {old.position[i]}, velocity);
    }
  }
  install(loaded);
  res.success = true;
  res.message = "loaded '" + loaded->robot_name + "' with " + std::to_string(loaded->bare->nv) + " joints";
  for (std::size_t k = 0; k < scene_configs_.size(); ++k) {
    const auto s = scene(k);
    if (s && !s->error.empty()) append_message(res.message, "but " + s->error);
  }
  ROS_INFO("dynamics: %s", res.message.c_str());
  return true;
}

bool DynamicsNode::onSetPayload(SetPayload::Request& req, SetPayload::Response& res) {
  std::lock_guard<std::mutex> serialise(payload_mutex_);
  res.success = false;
  std::shared_ptr<const ServedRobot> robot;
  {
    std::lock_guard<std::mutex> lock(model_mutex_);
    robot = robot_;
    if (!robot) {
      res.message = "no robot model is loaded: " + load_error_;
      return true;
    }
  }
  if (!robot->bare->hasFrame(req.frame)) {
    res.message = "unknown frame '" + req.frame + "' (not a link of the robot model)";
    return true;
  }
  std::map<std::string, Payload> payloads = payloads_;
  const geometry_msgs::Inertia& in = req.inertia;
  if (in.m == 0.0) {
    res.message = payloads.erase(req.frame) ? "payload removed from '" + req.frame + "'"
                                            : "no payload on '" + req.frame + "' to remove";
  } else {
    Payload payload;
    payload.mass = in.m;
    payload.center_of_mass = Eigen::Vector3d(in.com.x, in.com.y, in.com.z);
    payload.inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    payloads[req.frame] = payload;
    res.message = "payload of " + std::to_string(in.m) + " kg attached to '" + req.frame + "'";
  }
  try {
    install(withPayloads(*robot, payloads));
  } catch (const std::exception& e) {
    res.message = e.what();
    return true;
  }
  payloads_ = std::move(payloads);
  res.success = true;
  ROS_INFO("dynamics: %s", res.message.c_str());
  return true;
}

void DynamicsNode::onJointStates(const ros::MessageEvent<sensor_msgs::JointState const>& event) {
  const sensor_msgs::JointState::ConstPtr& msg = event.getConstMessage();
  ++joint_state_messages_;
  last_joint_state_time_ = ros::WallTime::now().toSec();
  std::shared_ptr<const ServedRobot> robot;
  {
    std::lock_guard<std::mutex> lock(model_mutex_);
    robot = robot_;
  }
  if (!robot) return;
  std::vector<std::string> unknown;
  const std::string error = robot->cache->update(msg->name, msg->position, msg->velocity, &unknown);
  if (!error.empty()) {
    ++joint_state_drops_;
    ROS_WARN_THROTTLE(5.0, "dynamics: joint_states message dropped: %s", error.c_str());
    return;
  }
  if (!unknown.empty()) {
    std::lock_guard<std::mutex> lock(warned_mutex_);
    for (const std::string& name : unknown)
      if (warned_unknown_joints_.insert(name).second)
        ROS_WARN("dynamics: joint_states names joint '%s', which the robot model does not have; it is "
                 "ignored (~unknown_joints: ignore)",
                 name.c_str());
  }
  bool published = false;
  for (std::size_t k = 0; k < scene_configs_.size(); ++k) {
    std::shared_ptr<const ServedScene> served = scene(k);
    if (!served || !served->model || served->robot != robot) continue;
    // Locked joints follow joint_states: rebuild the scene when one has moved.
    if (!served->locks.empty()) {
      Workspace& ws = workspace_for(k, *served);
      robot->cache->snapshot(ws.state);
      for (const auto& [index, position] : served->locks) {
        if (ws.state.position_known[index] && std::abs(ws.state.position[index] - position) > relock_tolerance_) {
          const std::string what = scene_configs_[k].name.empty() ? "the main scene" : "scene '" + scene_configs_[k].name + "'";
          ROS_DEBUG("dynamics: locked joint '%s' moved by %g; rebuilding %s", robot->cache->jointNames()[index].c_str(),
                    ws.state.position[index] - position, what.c_str());
          std::shared_ptr<const ServedScene> rebuilt = buildScene(robot, scene_configs_[k]);
          std::lock_guard<std::mutex> lock(model_mutex_);
          if (scenes_[k] == served) scenes_[k] = rebuilt;  // unless a reload or payload change came first
          served = rebuilt;
          break;
        }
      }
    }
    if (!publish_computed_torques_ || !served->model || endpoints_.size() <= k) continue;
    try {
      sensor_msgs::JointState out;
      if (!compute_latest_torques(*served, workspace_for(k, *served), out.position, out.velocity, out.effort)) continue;
      out.header = msg->header;
      out.name = served->decoder->jointNames();
      endpoints_[k].computed_torques.publish(out);
      ++torque_messages_;
      published = true;
    } catch (const std::exception& e) {
      ROS_WARN_THROTTLE(5.0, "dynamics: no computed torques for this joint state: %s", e.what());
    }
  }
  if (published) torque_latency_us_.record((ros::Time::now() - event.getReceiptTime()).toSec() * 1e6);
}

void DynamicsNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const ros::WallTime now = ros::WallTime::now();
  const double elapsed = std::max(1e-9, (now - last_diag_time_).toSec());
  const long joint_states = joint_state_messages_, torques = torque_messages_;
  status.add("simd backend", simd_backend_or_error());
  status.add("joint_states rate [Hz]", (joint_states - last_diag_joint_states_) / elapsed);
  status.add("computed_torques rate [Hz]", (torques - last_diag_torques_) / elapsed);
  last_diag_joint_states_ = joint_states;
  last_diag_torques_ = torques;
  last_diag_time_ = now;
  const double last = last_joint_state_time_;
  status.add("joint_states age [s]", last > 0 ? now.toSec() - last : -1.0);
  status.add("joint_states dropped", static_cast<long>(joint_state_drops_));
  const LatencyRecorder::Summary latency = torque_latency_us_.summary();
  status.add("computed_torques latency window [messages]", latency.count);
  status.add("computed_torques latency p50 [us]", latency.p50);
  status.add("computed_torques latency p99 [us]", latency.p99);
  status.add("computed_torques latency max [us]", latency.max);
  status.add("transform_wrench calls", static_cast<long>(transform_wrench_.calls));
  status.add("transform_wrench failures", static_cast<long>(transform_wrench_.failures));
  std::string scene_errors;
  for (std::size_t k = 0; k < endpoints_.size(); ++k) {
    const std::string prefix = scene_configs_[k].name.empty() ? "" : scene_configs_[k].name + "/";
    for (const auto& [name, counters] : {std::pair<const char*, const Counters*>{"inverse_dynamics", &endpoints_[k].inverse_dynamics},
                                         {"inverse_dynamics_trajectory", &endpoints_[k].inverse_dynamics_trajectory},
                                         {"forward_dynamics", &endpoints_[k].forward_dynamics},
                                         {"mass_matrix", &endpoints_[k].mass_matrix}}) {
      status.add(prefix + name + " calls", static_cast<long>(counters->calls));
      status.add(prefix + name + " failures", static_cast<long>(counters->failures));
    }
    const auto s = scene(k);
    if (s && !s->error.empty()) append_message(scene_errors, s->error);
  }
  std::shared_ptr<const ServedRobot> robot;
  {
    std::lock_guard<std::mutex> lock(model_mutex_);
    robot = robot_;
    if (!robot) {
      status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no robot model: " + load_error_);
      return;
    }
  }
  diagnostics_.setHardwareID(robot->robot_name);
  status.add("joints", robot->bare->nv);
  status.add("actuator model", to_string(robot->actuator_model));
  if (!scene_errors.empty())
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, scene_errors);
  else if (!robot->cache->complete())
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "model loaded; waiting for joint_states of every joint");
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "model loaded; joint states complete");
}

}  // namespace spatial_dynamics
