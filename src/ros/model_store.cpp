#include "spatial_dynamics/ros/model_store.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reduction/reduce_model.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

#include <urdf_parser/urdf_parser.h>

namespace spatial_dynamics {

std::shared_ptr<const ServedRobot> ModelStore::loadRobot(const RobotSource& source,
                                                         const std::map<std::string, Payload>& payloads) const {
  ModelBuildOptions options;
  options.gravity = source.gravity;
  options.floating_base = source.floating_base;
  auto robot = std::make_shared<ServedRobot>();
  Model<double> bare = build_model_from_urdf_string(source.urdf, options);
  ContactSet<double>(bare, contacts_.frames, contacts_.kinds, contacts_.frictions);  // throws naming a bad contact
  apply_actuator_settings(source.actuators, config_.coupled_mimic_joints, bare);
  robot->actuator_model = source.actuators.model;
  robot->bare = std::make_shared<const Model<double>>(std::move(bare));
  robot->full = std::make_shared<const Model<double>>(with_payloads(*robot->bare, payloads));
  // One joint state per coordinate: a joint's name, or <joint>/x, /y, /yaw of a planar joint; a
  // floating base's six come from its base state instead.
  std::vector<std::string> joint_names = robot->bare->velocityNames();
  if (source.floating_base) joint_names.erase(joint_names.begin(), joint_names.begin() + 6);
  robot->cache = std::make_shared<JointStateCache>(joint_names, config_.max_state_age, config_.unknown_joints);
  robot->robot_name = robot->bare->name;
  robot->floating_base = source.floating_base;
  robot->root_frame = robot->bare->body_names[source.floating_base ? 1 : 0];
  robot->contacts = contacts_;
  if (const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(source.urdf))
    for (const auto& link : urdf->links_)
      if (link.second->child_links.empty()) robot->leaf_links.push_back(link.first);
  return robot;
}

std::shared_ptr<const ServedRobot> ModelStore::withPayloads(const ServedRobot& robot,
                                                            const std::map<std::string, Payload>& payloads) const {
  auto loaded = std::make_shared<ServedRobot>(robot);
  loaded->full = std::make_shared<const Model<double>>(with_payloads(*robot.bare, payloads));
  return loaded;
}

bool ModelStore::setContacts(const ContactSpec& contacts, std::string& message) {
  std::lock_guard<std::mutex> serialise(payload_mutex_);
  const std::shared_ptr<const ServedRobot> served = robot();
  if (!served) {
    message = "no robot model is loaded: " + loadError();
    return false;
  }
  try {
    const ContactSet<double> set(*served->full, contacts.frames, contacts.kinds, contacts.frictions);
    auto changed = std::make_shared<ServedRobot>(*served);
    changed->contacts = contacts;
    install(changed);
    message = std::to_string(set.size()) + " contact(s) set";
    for (std::size_t k = 0; k < set.size(); ++k)
      message += (k ? ", '" : ": '") + contacts.frames[k] + "' (" + contact_kind_name(set.contacts[k].kind) + ")";
  } catch (const std::exception& e) {
    message = std::string("contacts not set: ") + e.what() + " (the previous contacts stay)";
    return false;
  }
  contacts_ = contacts;
  return true;
}

std::shared_ptr<const ServedScene> ModelStore::buildScene(const std::shared_ptr<const ServedRobot>& robot,
                                                          const SceneConfig& config) const {
  auto scene = std::make_shared<ServedScene>();
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
      if (config_.coupled_mimic_joints)  // a mimic joint follows a kept master
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
    if (config_.coupled_mimic_joints) model = couple_mimic_joints(model);
    scene->model = std::make_shared<const Model<double>>(std::move(model));
    scene->rigid_model = scene->model;
    if (robot->actuator_model != ActuatorModel::RigidBody) {  // for rigid_body_only
      Model<double> rigid = *scene->model;
      rigid.reset_actuator_terms();
      rigid.finalize();
      scene->rigid_model = std::make_shared<const Model<double>>(std::move(rigid));
    }
    scene->decoder = std::make_unique<JointRequestDecoder>(*scene->model, robot->cache->jointNames());
    try {
      const ContactSpec& c = robot->contacts;
      scene->contacts = ContactSet<double>(*scene->model, c.frames, c.kinds, c.frictions);
    } catch (const std::exception& e) {
      scene->contacts_error = who + ": the node's contacts do not resolve on its model: " + e.what();
    }
  } catch (const std::exception& e) {
    scene->model.reset();
    scene->rigid_model.reset();
    scene->error = who + " (" + config.parameter + "): " + e.what();
  }
  return scene;
}

void ModelStore::install(const std::shared_ptr<const ServedRobot>& robot) {
  std::vector<std::shared_ptr<const ServedScene>> scenes;
  for (const SceneConfig& config : config_.scenes) scenes.push_back(buildScene(robot, config));
  std::lock_guard<std::mutex> lock(mutex_);
  robot_ = robot;
  scenes_ = std::move(scenes);
  load_error_.clear();
}

void ModelStore::load(const SourceReader& source) {
  std::lock_guard<std::mutex> serialise(payload_mutex_);
  install(loadRobot(source(), payloads_));
}

void ModelStore::setLoadError(const std::string& error) {
  std::lock_guard<std::mutex> lock(mutex_);
  load_error_ = error;
}

bool ModelStore::reload(const SourceReader& source, std::string& message) {
  std::lock_guard<std::mutex> serialise(payload_mutex_);
  const std::shared_ptr<const ServedRobot> previous = robot();
  std::shared_ptr<const ServedRobot> loaded;
  try {
    loaded = loadRobot(source(), payloads_);
  } catch (const std::exception& e) {
    message = std::string("reload failed: ") + e.what() +
              (previous ? " (the previous model is still served)" : " (no model is served)");
    if (!previous) setLoadError(e.what());
    return false;
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
  message = "loaded '" + loaded->robot_name + "' with " + std::to_string(loaded->bare->nv) + " joints";
  for (std::size_t k = 0; k < sceneCount(); ++k) {
    const auto s = scene(k);
    if (s && !s->error.empty()) message += "; but " + s->error;
  }
  return true;
}

std::map<std::string, Payload> ModelStore::payloads() {
  std::lock_guard<std::mutex> serialise(payload_mutex_);
  return payloads_;
}

bool ModelStore::setPayload(const std::string& frame, const Payload& payload, std::string& message) {
  std::lock_guard<std::mutex> serialise(payload_mutex_);
  const std::shared_ptr<const ServedRobot> served = robot();
  if (!served) {
    message = "no robot model is loaded: " + loadError();
    return false;
  }
  if (!served->bare->hasFrame(frame)) {
    message = "unknown frame '" + frame + "' (not a link of the robot model)";
    return false;
  }
  std::map<std::string, Payload> payloads = payloads_;
  if (payload.mass == 0.0) {
    message = payloads.erase(frame) ? "payload removed from '" + frame + "'" : "no payload on '" + frame + "' to remove";
  } else {
    payloads[frame] = payload;
    message = "payload of " + std::to_string(payload.mass) + " kg attached to '" + frame + "'";
  }
  try {
    install(withPayloads(*served, payloads));
  } catch (const std::exception& e) {
    message = e.what();
    return false;
  }
  payloads_ = std::move(payloads);
  return true;
}

std::shared_ptr<const ServedRobot> ModelStore::robot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return robot_;
}

std::shared_ptr<const ServedScene> ModelStore::scene(std::size_t k) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return k < scenes_.size() ? scenes_[k] : nullptr;
}

std::string ModelStore::loadError() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return load_error_;
}

std::shared_ptr<const ServedScene> ModelStore::followLockedJoints(std::size_t k, std::shared_ptr<const ServedScene> served,
                                                                  const std::shared_ptr<const ServedRobot>& robot,
                                                                  std::string& moved) {
  moved.clear();
  if (served->locks.empty()) return served;
  {
    const WorkspacePool::Lease ws = served->workspaces.acquire(*served->model);
    robot->cache->snapshot(ws->state);
    for (const auto& [index, position] : served->locks)
      if (ws->state.position_known[index] && std::abs(ws->state.position[index] - position) > config_.relock_tolerance) {
        moved = "locked joint '" + robot->cache->jointNames()[index] + "' moved by " +
                std::to_string(ws->state.position[index] - position);
        break;
      }
  }
  if (moved.empty()) return served;
  std::shared_ptr<const ServedScene> rebuilt = buildScene(robot, config_.scenes[k]);
  std::lock_guard<std::mutex> lock(mutex_);
  if (scenes_[k] == served) scenes_[k] = rebuilt;  // unless a reload or payload change came first
  return rebuilt;
}

}  // namespace spatial_dynamics
