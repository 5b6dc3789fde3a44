#include "spatial_dynamics/ros/dynamics_node.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <tf2/exceptions.h>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace spatial_dynamics {
namespace {

/// Per-thread buffers, rebuilt when the served model changes (Data is allocated once per model).
struct Workspace {
  std::uint64_t version = 0;
  std::unique_ptr<Data<double>> data;
  JointStateCache::Snapshot state;
  std::vector<int> indices;
  Eigen::VectorXd q, qd, x;
  std::vector<ForceVector<double>> f_ext;
};

Workspace& workspace_for(const ServedModel& served) {
  thread_local Workspace ws;
  if (ws.version != served.version) {
    ws.data = std::make_unique<Data<double>>(*served.model);
    ws.f_ext.assign(served.model->nbodies(), ForceVector<double>::Zero());
    ws.version = served.version;
  }
  return ws;
}

std::atomic<std::uint64_t> next_model_version{1};

/// Throws std::runtime_error(message) when `error` is not empty.
void check(const std::string& error) {
  if (!error.empty()) throw std::runtime_error(error);
}

void append(std::string& message, const std::string& more) {
  if (more.empty()) return;
  if (!message.empty()) message += "; ";
  message += more;
}

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

/// The joint order and positions of a request, decoded into ws.indices and ws.q.
void decode_positions(const ServedModel& served, Workspace& ws, const std::vector<std::string>& names,
                      const std::vector<double>& positions) {
  check(served.decoder->resolve(names, ws.indices));
  served.cache->snapshot(ws.state);
  check(served.decoder->decode("position", names, ws.indices, positions, JointRequestDecoder::Default::LatestPosition,
                               ws.state, ws.q));
}

/// Positions and velocities of a request, decoded into ws.q and ws.qd.
template <class Request>
void decode_state(const ServedModel& served, Workspace& ws, const Request& req) {
  decode_positions(served, ws, req.name, req.position);
  check(served.decoder->decode("velocity", req.name, ws.indices, req.velocity,
                               JointRequestDecoder::Default::LatestVelocity, ws.state, ws.qd));
}

/// External wrenches → forces on bodies (body coordinates): f_B = ^FX_Bᵀ f_F for a wrench given
/// in frame F about its origin (X* of eq. 12, inverted). Returns whether any wrench was given.
bool decode_wrenches(const Model<double>& model, const std::vector<geometry_msgs::WrenchStamped>& wrenches,
                     std::vector<ForceVector<double>>& f_ext) {
  std::fill(f_ext.begin(), f_ext.end(), ForceVector<double>::Zero());
  for (std::size_t k = 0; k < wrenches.size(); ++k) {
    const std::string field = "external_wrenches[" + std::to_string(k) + "]";
    const std::string& frame_name = wrenches[k].header.frame_id;
    if (!model.hasFrame(frame_name))
      throw std::runtime_error(field + ": unknown frame '" + frame_name + "' (not a link of the robot model)");
    const geometry_msgs::Wrench& w = wrenches[k].wrench;
    const ForceVector<double> f(Eigen::Vector3d(w.torque.x, w.torque.y, w.torque.z),
                                Eigen::Vector3d(w.force.x, w.force.y, w.force.z));
    if (!f.toVector().allFinite()) throw std::runtime_error(field + " (frame '" + frame_name + "') is not finite");
    const Frame<double>& frame = model.frames[model.frameIndex(frame_name)];
    f_ext[frame.body] += frame.X_frame_body.applyInverse(f);
  }
  return !wrenches.empty();
}

/// ws.q, ws.qd, the third joint array (`field`: acceleration or effort, zero when left out) in
/// ws.x, and the external wrenches in ws.f_ext. Returns whether any wrench was given.
template <class Request>
bool decode_dynamics_request(const ServedModel& served, Workspace& ws, const Request& req, const std::string& field,
                             const std::vector<double>& values) {
  decode_state(served, ws, req);
  check(served.decoder->decode(field, req.name, ws.indices, values, JointRequestDecoder::Default::Zero, ws.state, ws.x));
  return decode_wrenches(*served.model, req.external_wrenches, ws.f_ext);
}

/// Warnings for a successful answer: positions outside limits, velocities taken as zero.
std::string request_notes(const ServedModel& served, const Workspace& ws, const std::vector<double>& velocity) {
  std::string notes = served.decoder->limitWarnings(ws.q);
  if (!velocity.empty()) return notes;
  std::string missing;
  for (std::size_t i = 0; i < ws.state.velocity_known.size(); ++i)
    if (!ws.state.velocity_known[i]) missing += (missing.empty() ? "'" : ", '") + served.decoder->jointNames()[i] + "'";
  if (!missing.empty()) append(notes, "note: no velocity received on joint_states for joint(s) " + missing + "; zero used");
  return notes;
}

}  // namespace

DynamicsNode::DynamicsNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh)
    : nh_(nh), private_nh_(private_nh), tf_listener_(tf_buffer_), diagnostics_(nh, private_nh) {
  private_nh_.param("publish_computed_torques", publish_computed_torques_, true);
  try {
    served_ = loadFromParameters();
    ROS_INFO("dynamics: serving '%s' with %d joints", served_->robot_name.c_str(), served_->model->nv);
  } catch (const std::exception& e) {
    load_error_ = e.what();
    ROS_ERROR("dynamics: no robot model: %s", load_error_.c_str());
  }
  computed_torques_pub_ = private_nh_.advertise<sensor_msgs::JointState>("computed_torques", 10);
  joint_states_sub_ = nh_.subscribe("joint_states", 100, &DynamicsNode::onJointStates, this,
                                    ros::TransportHints().tcpNoDelay());
  services_.push_back(private_nh_.advertiseService("inverse_dynamics", &DynamicsNode::onInverseDynamics, this));
  services_.push_back(private_nh_.advertiseService("forward_dynamics", &DynamicsNode::onForwardDynamics, this));
  services_.push_back(private_nh_.advertiseService("mass_matrix", &DynamicsNode::onMassMatrix, this));
  services_.push_back(private_nh_.advertiseService("transform_wrench", &DynamicsNode::onTransformWrench, this));
  services_.push_back(private_nh_.advertiseService("reload", &DynamicsNode::onReload, this));

  diagnostics_.setHardwareID("none");
  diagnostics_.add("Dynamics", this, &DynamicsNode::diagnose);
  last_diag_time_ = ros::WallTime::now();
  diagnostics_timer_ = private_nh_.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { diagnostics_.update(); });
}

std::shared_ptr<const ServedModel> DynamicsNode::loadFromParameters() const {
  std::string urdf;
  if (!nh_.getParam("robot_description", urdf))
    throw std::runtime_error("parameter " + nh_.resolveName("robot_description") + " is not set");
  ModelBuildOptions options;
  options.gravity = read_gravity(private_nh_);
  auto served = std::make_shared<ServedModel>();
  served->model = std::make_shared<const Model<double>>(build_model_from_urdf_string(urdf, options));
  served->decoder = std::make_unique<JointRequestDecoder>(*served->model);
  served->cache = std::make_unique<JointStateCache>(served->decoder->jointNames());
  served->root_frame = served->model->body_names[0];
  served->robot_name = served->model->name;
  served->version = next_model_version++;
  return served;
}

std::shared_ptr<const ServedModel> DynamicsNode::current() const {
  std::lock_guard<std::mutex> lock(model_mutex_);
  return served_;
}

template <class Response, class Compute>
bool DynamicsNode::serve(Counters& counters, Response& res, Compute&& compute) {
  ++counters.calls;
  res.success = false;
  const std::shared_ptr<const ServedModel> served = current();
  if (!served) {
    std::lock_guard<std::mutex> lock(model_mutex_);
    res.message = "no robot model is loaded: " + load_error_;
  } else {
    try {
      res.message.clear();
      compute(*served, workspace_for(*served));
      res.success = true;
    } catch (const std::exception& e) {
      res.message = e.what();
    }
  }
  if (!res.success) ++counters.failures;
  return true;  // the client always receives the body
}

bool DynamicsNode::onInverseDynamics(InverseDynamics::Request& req, InverseDynamics::Response& res) {
  return serve(inverse_dynamics_, res, [&](const ServedModel& served, Workspace& ws) {
    const bool with_wrenches = decode_dynamics_request(served, ws, req, "acceleration", req.acceleration);
    const Model<double>& model = *served.model;
    const Eigen::VectorXd& tau = with_wrenches ? rnea(model, *ws.data, ws.q, ws.qd, ws.x, ws.f_ext)
                                               : rnea(model, *ws.data, ws.q, ws.qd, ws.x);
    res.name = served.decoder->jointNames();
    res.effort.assign(tau.data(), tau.data() + tau.size());
    res.message = request_notes(served, ws, req.velocity);
  });
}

bool DynamicsNode::onForwardDynamics(ForwardDynamics::Request& req, ForwardDynamics::Response& res) {
  return serve(forward_dynamics_, res, [&](const ServedModel& served, Workspace& ws) {
    const bool with_wrenches = decode_dynamics_request(served, ws, req, "effort", req.effort);
    const Model<double>& model = *served.model;
    const Eigen::VectorXd& qdd = with_wrenches ? aba(model, *ws.data, ws.q, ws.qd, ws.x, ws.f_ext)
                                               : aba(model, *ws.data, ws.q, ws.qd, ws.x);
    res.name = served.decoder->jointNames();
    res.acceleration.assign(qdd.data(), qdd.data() + qdd.size());
    res.message = request_notes(served, ws, req.velocity);
  });
}

bool DynamicsNode::onMassMatrix(MassMatrix::Request& req, MassMatrix::Response& res) {
  return serve(mass_matrix_, res, [&](const ServedModel& served, Workspace& ws) {
    decode_positions(served, ws, req.name, req.position);
    const Eigen::MatrixXd& M = crba(*served.model, *ws.data, ws.q);
    res.name = served.decoder->jointNames();
    res.mass_matrix.resize(M.size());
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(res.mass_matrix.data(), M.rows(),
                                                                                      M.cols()) = M;
    append(res.message, served.decoder->limitWarnings(ws.q));
  });
}

bool DynamicsNode::onTransformWrench(TransformWrench::Request& req, TransformWrench::Response& res) {
  return serve(transform_wrench_, res, [&](const ServedModel& served, Workspace& ws) {
    const std::string& source = req.wrench.header.frame_id;
    if (source.empty()) throw std::runtime_error("wrench.header.frame_id is empty");
    if (req.target_frame.empty()) throw std::runtime_error("target_frame is empty");
    const geometry_msgs::Wrench& w = req.wrench.wrench;
    const ForceVector<double> f(Eigen::Vector3d(w.torque.x, w.torque.y, w.torque.z),
                                Eigen::Vector3d(w.force.x, w.force.y, w.force.z));
    if (!f.toVector().allFinite()) throw std::runtime_error("wrench (frame '" + source + "') is not finite");
    const bool uses_model = served.model->hasFrame(source) || served.model->hasFrame(req.target_frame);
    if (uses_model) decode_positions(served, ws, req.name, req.position);
    const PluckerTransform<double> X = frameTransform(served, req.target_frame, source, req.wrench.header.stamp,
                                                      uses_model ? &ws.q : nullptr);
    const ForceVector<double> f_target = X.apply(f);  // X* f (eq. 12): the moment gains r × f
    res.wrench.header.stamp = req.wrench.header.stamp;
    res.wrench.header.frame_id = req.target_frame;
    res.wrench.wrench.torque.x = f_target.angular.x();
    res.wrench.wrench.torque.y = f_target.angular.y();
    res.wrench.wrench.torque.z = f_target.angular.z();
    res.wrench.wrench.force.x = f_target.linear.x();
    res.wrench.wrench.force.y = f_target.linear.y();
    res.wrench.wrench.force.z = f_target.linear.z();
    if (uses_model) append(res.message, served.decoder->limitWarnings(ws.q));
  });
}

PluckerTransform<double> DynamicsNode::frameTransform(const ServedModel& served, const std::string& target,
                                                      const std::string& source, const ros::Time& stamp,
                                                      const Eigen::VectorXd* q) const {
  const Model<double>& model = *served.model;
  const bool source_in_model = model.hasFrame(source), target_in_model = model.hasFrame(target);
  if (!source_in_model && !target_in_model) return tfTransform(target, source, stamp);
  Data<double>& data = *workspace_for(served).data;
  forward_kinematics(model, data, *q);
  // ^FX_0 of a model frame; the base coordinates are those of the root link's frame.
  auto from_base = [&](const std::string& name) { return data.X_frame_base[model.frameIndex(name)]; };
  if (source_in_model && target_in_model) return from_base(target) * from_base(source).inverse();
  // One robot frame and one tf frame: chain through the robot's root link, which tf must know.
  const std::string& tf_frame = source_in_model ? target : source;
  if (!tf_buffer_._frameExists(tf_frame))
    throw std::runtime_error("frame '" + tf_frame + "' is known neither to the robot model nor to tf2");
  if (!tf_buffer_._frameExists(served.root_frame))
    throw std::runtime_error("frame '" + tf_frame + "' is on tf2 but the robot's root link '" + served.root_frame +
                             "' is not, so the two cannot be chained");
  if (source_in_model) return tfTransform(target, served.root_frame, stamp) * from_base(source).inverse();
  return from_base(target) * tfTransform(served.root_frame, source, stamp);
}

PluckerTransform<double> DynamicsNode::tfTransform(const std::string& target, const std::string& source,
                                                   const ros::Time& stamp) const {
  for (const std::string* frame : {&source, &target})
    if (!tf_buffer_._frameExists(*frame))
      throw std::runtime_error("frame '" + *frame + "' is known neither to the robot model nor to tf2");
  geometry_msgs::TransformStamped t;
  try {
    t = tf_buffer_.lookupTransform(target, source, stamp, ros::Duration(0.1));
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
  std::shared_ptr<const ServedModel> loaded;
  try {
    loaded = loadFromParameters();
  } catch (const std::exception& e) {
    res.success = false;
    const bool has_previous = current() != nullptr;
    res.message = std::string("reload failed: ") + e.what() +
                  (has_previous ? " (the previous model is still served)" : " (no model is served)");
    ROS_ERROR("dynamics: %s", res.message.c_str());
    if (!has_previous) {
      std::lock_guard<std::mutex> lock(model_mutex_);
      load_error_ = e.what();
    }
    return true;
  }
  // Carry the joint states of joints that keep their names over to the new model.
  if (const std::shared_ptr<const ServedModel> previous = current()) {
    JointStateCache::Snapshot old;
    previous->cache->snapshot(old);
    const std::vector<std::string>& names = previous->decoder->jointNames();
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!old.position_known[i]) continue;
      std::vector<double> velocity;
      if (old.velocity_known[i]) velocity.push_back(old.velocity[i]);
      loaded->cache->update({names[i]}, {old.position[i]}, velocity);
    }
  }
  {
    std::lock_guard<std::mutex> lock(model_mutex_);
    served_ = loaded;
    load_error_.clear();
  }
  res.success = true;
  res.message = "loaded '" + loaded->robot_name + "' with " + std::to_string(loaded->model->nv) + " joints";
  ROS_INFO("dynamics: %s", res.message.c_str());
  return true;
}

void DynamicsNode::onJointStates(const sensor_msgs::JointState::ConstPtr& msg) {
  ++joint_state_messages_;
  last_joint_state_time_ = ros::WallTime::now().toSec();
  const std::shared_ptr<const ServedModel> served = current();
  if (!served) return;
  std::vector<std::string> unknown;
  const std::string error = served->cache->update(msg->name, msg->position, msg->velocity, &unknown);
  if (!error.empty()) {
    ++joint_state_drops_;
    ROS_WARN_THROTTLE(5.0, "dynamics: joint_states message dropped: %s", error.c_str());
    return;
  }
  if (!unknown.empty()) {
    std::lock_guard<std::mutex> lock(warned_mutex_);
    for (const std::string& name : unknown)
      if (warned_unknown_joints_.insert(name).second)
        ROS_WARN("dynamics: joint_states names joint '%s', which the robot model does not have; it is ignored",
                 name.c_str());
  }
  if (!publish_computed_torques_) return;
  Workspace& ws = workspace_for(*served);
  served->cache->snapshot(ws.state);
  if (!ws.state.complete) return;
  const Eigen::VectorXd& tau = nonlinear_effects(*served->model, *ws.data, ws.state.position, ws.state.velocity);
  sensor_msgs::JointState out;
  out.header = msg->header;
  out.name = served->decoder->jointNames();
  out.position.assign(ws.state.position.data(), ws.state.position.data() + ws.state.position.size());
  out.velocity.assign(ws.state.velocity.data(), ws.state.velocity.data() + ws.state.velocity.size());
  out.effort.assign(tau.data(), tau.data() + tau.size());
  computed_torques_pub_.publish(out);
  ++torque_messages_;
}

void DynamicsNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const ros::WallTime now = ros::WallTime::now();
  const double elapsed = std::max(1e-9, (now - last_diag_time_).toSec());
  const long joint_states = joint_state_messages_, torques = torque_messages_;
  status.add("joint_states rate [Hz]", (joint_states - last_diag_joint_states_) / elapsed);
  status.add("computed_torques rate [Hz]", (torques - last_diag_torques_) / elapsed);
  last_diag_joint_states_ = joint_states;
  last_diag_torques_ = torques;
  last_diag_time_ = now;
  const double last = last_joint_state_time_;
  status.add("joint_states age [s]", last > 0 ? now.toSec() - last : -1.0);
  status.add("joint_states dropped", static_cast<long>(joint_state_drops_));
  for (const auto& [name, counters] : {std::pair<const char*, Counters*>{"inverse_dynamics", &inverse_dynamics_},
                                       {"forward_dynamics", &forward_dynamics_},
                                       {"mass_matrix", &mass_matrix_},
                                       {"transform_wrench", &transform_wrench_}}) {
    status.add(std::string(name) + " calls", static_cast<long>(counters->calls));
    status.add(std::string(name) + " failures", static_cast<long>(counters->failures));
  }
  const std::shared_ptr<const ServedModel> served = current();
  if (!served) {
    std::lock_guard<std::mutex> lock(model_mutex_);
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no robot model: " + load_error_);
    return;
  }
  diagnostics_.setHardwareID(served->robot_name);
  status.add("joints", served->model->nv);
  if (!served->cache->complete())
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "model loaded; waiting for joint_states of every joint");
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "model loaded; joint states complete");
}

}  // namespace spatial_dynamics
