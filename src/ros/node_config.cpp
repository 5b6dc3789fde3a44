#include "spatial_dynamics/ros/node_config.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include <ros/console.h>
#include <ros/node_handle.h>
#include <ros/names.h>

namespace spatial_dynamics {
namespace {

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

/// The main scene, then each of ~scenes.
std::vector<SceneConfig> read_scenes(const ros::NodeHandle& private_nh) {
  std::vector<SceneConfig> configs(1);
  read_scene(private_nh, configs[0]);
  XmlRpc::XmlRpcValue scenes;
  if (!private_nh.getParam("scenes", scenes)) return configs;
  if (scenes.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    ROS_ERROR("dynamics: parameter %s must be a dictionary of scenes", private_nh.resolveName("scenes").c_str());
    return configs;
  }
  for (auto it = scenes.begin(); it != scenes.end(); ++it) {
    SceneConfig config;
    config.name = it->first;
    std::string why;
    if (!ros::names::validate(config.name, why)) {
      ROS_ERROR("dynamics: scene name '%s' is not a valid ROS name (%s); it is not served", config.name.c_str(), why.c_str());
      continue;
    }
    read_scene(ros::NodeHandle(private_nh, "scenes/" + config.name), config);
    configs.push_back(config);
  }
  return configs;
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

/// The first of the start-up parameters that is out of range, or "".
std::string check(const ros::NodeHandle& private_nh, const NodeConfig& config, const std::string& mimic_joints,
                  const std::string& unknown_joints) {
  const auto name = [&](const char* key) { return "parameter " + private_nh.resolveName(key); };
  if (mimic_joints != "independent" && mimic_joints != "coupled")
    return name("mimic_joints") + " must be 'independent' or 'coupled', not '" + mimic_joints + "'";
  if (unknown_joints != "drop" && unknown_joints != "ignore")
    return name("unknown_joints") + " must be 'drop' or 'ignore', not '" + unknown_joints + "'";
  if (!(config.max_state_age > 0.0)) return name("max_state_age") + " must be > 0 (seconds)";
  if (!(config.relock_tolerance >= 0.0)) return name("relock_tolerance") + " must be >= 0";
  if (config.world_frame.empty()) return name("world_frame") + " must name a tf frame";
  return "";
}

/// A number parameter's value (int or double), or false.
bool as_number(const XmlRpc::XmlRpcValue& value, double& out) {
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble) out = static_cast<double>(const_cast<XmlRpc::XmlRpcValue&>(value));
  else if (value.getType() == XmlRpc::XmlRpcValue::TypeInt) out = static_cast<int>(const_cast<XmlRpc::XmlRpcValue&>(value));
  else return false;
  return true;
}

/// ~contacts: a list of {frame: name, kind: point | surface, friction: μ (optional)}; throws naming
/// the entry that is malformed (the frames are checked against each model as it loads).
ContactSpec read_contacts(const ros::NodeHandle& private_nh) {
  ContactSpec spec;
  XmlRpc::XmlRpcValue value;
  if (!private_nh.getParam("contacts", value)) return spec;
  const std::string name = "parameter " + private_nh.resolveName("contacts");
  if (value.getType() != XmlRpc::XmlRpcValue::TypeArray)
    throw std::runtime_error(name + " must be a list of {frame: ..., kind: point|surface, friction: ...}");
  bool any_friction = false;
  for (int k = 0; k < value.size(); ++k) {
    XmlRpc::XmlRpcValue& entry = value[k];
    const std::string culprit = name + "[" + std::to_string(k) + "]";
    if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct || !entry.hasMember("frame") || !entry.hasMember("kind") ||
        entry["frame"].getType() != XmlRpc::XmlRpcValue::TypeString ||
        entry["kind"].getType() != XmlRpc::XmlRpcValue::TypeString)
      throw std::runtime_error(culprit + " must be {frame: <link>, kind: point|surface, friction: <mu, optional>}");
    for (auto it = entry.begin(); it != entry.end(); ++it)
      if (it->first != "frame" && it->first != "kind" && it->first != "friction")
        throw std::runtime_error(culprit + " has an unknown key '" + it->first + "' (frame, kind, friction)");
    spec.frames.push_back(static_cast<std::string>(entry["frame"]));
    spec.kinds.push_back(static_cast<std::string>(entry["kind"]));
    double mu = 0.0;
    if (entry.hasMember("friction")) {
      any_friction = true;
      if (!as_number(entry["friction"], mu) || !std::isfinite(mu) || mu < 0.0)
        throw std::runtime_error(culprit + ".friction must be a finite number >= 0");
    }
    spec.frictions.push_back(mu);
  }
  if (!any_friction) spec.frictions.clear();
  return spec;
}

/// `key` under `nh` as one number or a map name → number; throws naming it otherwise.
void read_number_or_map(const ros::NodeHandle& nh, const std::string& key, double& number,
                        std::map<std::string, double>& by_name) {
  XmlRpc::XmlRpcValue value;
  nh.getParam(key, value);
  const std::string culprit = "parameter " + nh.resolveName(key) + " must be a number or a map joint → number";
  if (as_number(value, number)) return;
  if (value.getType() != XmlRpc::XmlRpcValue::TypeStruct) throw std::runtime_error(culprit);
  for (auto it = value.begin(); it != value.end(); ++it) {
    double x = 0;
    if (!as_number(it->second, x)) throw std::runtime_error(culprit + " ('" + it->first + "' is not a number)");
    by_name[it->first] = x;
  }
}

}  // namespace

ExternalTorqueSettings read_external_torque_settings(const ros::NodeHandle& private_nh) {
  ExternalTorqueSettings settings;
  const ros::NodeHandle nh(private_nh, "external_torques");
  settings.parameter = nh.getNamespace();
  try {
    if (nh.hasParam("enabled") && !nh.getParam("enabled", settings.enabled))
      throw std::runtime_error("parameter " + nh.resolveName("enabled") + " must be true or false");
    if (nh.hasParam("gain")) read_number_or_map(nh, "gain", settings.gain, settings.joint_gains);
    if (nh.hasParam("collision_threshold")) {
      settings.detect_collisions = true;
      read_number_or_map(nh, "collision_threshold", settings.threshold, settings.joint_thresholds);
    }
    if (nh.hasParam("frames")) {
      settings.frames_given = true;
      settings.frames = read_names(nh, "frames");
    }
    if (nh.hasParam("max_gap")) {
      XmlRpc::XmlRpcValue value;
      nh.getParam("max_gap", value);
      if (!as_number(value, settings.max_gap))
        throw std::runtime_error("parameter " + nh.resolveName("max_gap") + " must be a number (s)");
    }
  } catch (const std::exception& e) {
    settings.error = e.what();
  }
  return settings;
}

NodeConfig read_node_config(const ros::NodeHandle& private_nh) {
  NodeConfig config;
  private_nh.param("publish_computed_torques", config.publish_computed_torques, config.publish_computed_torques);
  private_nh.param("publish_centroidal_state", config.publish_centroidal_state, config.publish_centroidal_state);
  private_nh.param("relock_tolerance", config.relock_tolerance, config.relock_tolerance);
  private_nh.param("max_state_age", config.max_state_age, config.max_state_age);
  private_nh.param("inline_joint_states", config.inline_joint_states, config.inline_joint_states);
  std::string mimic_joints = "independent", unknown_joints = "drop";
  private_nh.param<std::string>("mimic_joints", mimic_joints, mimic_joints);
  private_nh.param<std::string>("unknown_joints", unknown_joints, unknown_joints);
  config.coupled_mimic_joints = mimic_joints == "coupled";
  if (unknown_joints == "ignore") config.unknown_joints = JointStateCache::UnknownJoints::kIgnore;
  private_nh.param<std::string>("base_odometry", config.base_odometry, config.base_odometry);
  private_nh.param<std::string>("world_frame", config.world_frame, config.world_frame);
  config.scenes = read_scenes(private_nh);
  config.error = check(private_nh, config, mimic_joints, unknown_joints);
  try {
    config.contacts = read_contacts(private_nh);
  } catch (const std::exception& e) {
    if (config.error.empty()) config.error = e.what();
  }
  return config;
}

RobotSource read_robot_source(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh) {
  RobotSource source;
  if (!nh.getParam("robot_description", source.urdf))
    throw std::runtime_error("parameter " + nh.resolveName("robot_description") + " is not set");
  source.gravity = read_gravity(private_nh);
  source.actuators = read_actuator_settings(private_nh);
  std::string root_joint = "fixed";
  if (private_nh.hasParam("root_joint") && !private_nh.getParam("root_joint", root_joint)) root_joint = "(not a string)";
  if (root_joint != "fixed" && root_joint != "floating")
    throw std::runtime_error("parameter " + private_nh.resolveName("root_joint") + " must be 'fixed' or 'floating', not '" +
                             root_joint + "'");
  source.floating_base = root_joint == "floating";
  return source;
}

}  // namespace spatial_dynamics
