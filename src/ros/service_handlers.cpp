#include "spatial_dynamics/ros/service_handlers.hpp"

#include <algorithm>
#include <stdexcept>

#include "spatial_dynamics/algorithms.hpp"

namespace spatial_dynamics {
namespace {

/// Throws std::runtime_error(message) when `error` is not empty.
void check(const std::string& error) {
  if (!error.empty()) throw std::runtime_error(error);
}

template <class Vector>
void copy_to(const Vector& v, std::vector<double>& out) {
  out.assign(v.data(), v.data() + v.size());
}

/// The joint order and positions of a request, decoded into ws.indices and ws.q.
void decode_positions(const ServedScene& scene, Workspace& ws, const std::vector<std::string>& names,
                      const std::vector<double>& positions) {
  check(scene.decoder->resolve(names, ws.indices));
  scene.robot->cache->snapshot(ws.state);
  check(scene.decoder->decode("position", names, ws.indices, positions, JointRequestDecoder::Default::LatestPosition,
                              ws.state, ws.q));
}

ForceVector<double> to_force(const geometry_msgs::Wrench& w) {
  return {Eigen::Vector3d(w.torque.x, w.torque.y, w.torque.z), Eigen::Vector3d(w.force.x, w.force.y, w.force.z)};
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
    const ForceVector<double> f = to_force(wrenches[k].wrench);
    if (!f.toVector().allFinite()) throw std::runtime_error(field + " (frame '" + frame_name + "') is not finite");
    const Frame<double>& frame = model.frames[model.frameIndex(frame_name)];
    f_ext[frame.body] += frame.X_frame_body.applyInverse(f);
  }
  return !wrenches.empty();
}

/// ws.q, ws.qd, the third joint array (`field`: acceleration or effort, zero when left out) in
/// ws.x, and the external wrenches in ws.f_ext. Returns whether any wrench was given.
template <class Request>
bool decode_dynamics_request(const ServedScene& scene, Workspace& ws, const Request& req, const std::string& field,
                             const std::vector<double>& values) {
  decode_positions(scene, ws, req.name, req.position);
  check(scene.decoder->decode("velocity", req.name, ws.indices, req.velocity,
                              JointRequestDecoder::Default::LatestVelocity, ws.state, ws.qd));
  check(scene.decoder->decode(field, req.name, ws.indices, values, JointRequestDecoder::Default::Zero, ws.state, ws.x));
  return decode_wrenches(*scene.model, req.external_wrenches, ws.f_ext);
}

/// Warnings for a successful answer: positions outside limits, velocities taken as zero.
std::string request_notes(const ServedScene& scene, const Workspace& ws, const std::vector<double>& velocity) {
  std::string notes = scene.decoder->limitWarnings(ws.q);
  if (!velocity.empty()) return notes;
  std::string missing;
  for (std::size_t i = 0; i < scene.decoder->jointNames().size(); ++i)
    if (!ws.state.velocity_known[scene.decoder->stateIndex(static_cast<int>(i))])
      missing += (missing.empty() ? "'" : ", '") + scene.decoder->jointNames()[i] + "'";
  if (!missing.empty()) append_message(notes, "note: no velocity received on joint_states for joint(s) " + missing + "; zero used");
  return notes;
}

/// Results must be finite: a non-finite one is reported, never returned.
template <class Vector>
void check_finite(const Vector& v, const char* what) {
  if (!v.allFinite())
    throw std::runtime_error(std::string("the ") + what +
                             " is not finite (the inputs are finite: a model or input too extreme for double precision)");
}

/// ^{target}X_{source} for two frames, each a model frame (kinematics at ws.q) or a looked-up one.
PluckerTransform<double> frame_transform(const ServedScene& scene, Workspace& ws, const FrameLookup& frames,
                                         const std::string& target, const std::string& source, const ros::Time& stamp) {
  const Model<double>& model = *scene.model;
  const bool source_in_model = model.hasFrame(source), target_in_model = model.hasFrame(target);
  for (const std::string* frame : {&source, &target})
    if (!model.hasFrame(*frame) && !frames.hasFrame(*frame))
      throw std::runtime_error("frame '" + *frame + "' is known neither to the robot model nor to tf2");
  if (!source_in_model && !target_in_model) return frames.transform(target, source, stamp);
  forward_kinematics(model, ws.data, ws.q);
  // ^FX_0 of a model frame; the base coordinates are those of the root link's frame.
  auto from_base = [&](const std::string& name) { return ws.data.X_frame_base[model.frameIndex(name)]; };
  if (source_in_model && target_in_model) return from_base(target) * from_base(source).inverse();
  // One robot frame and one outside frame: chain through the robot's root link.
  const std::string& root = scene.robot->root_frame;
  if (!frames.hasFrame(root))
    throw std::runtime_error("frame '" + (source_in_model ? target : source) + "' is on tf2 but the robot's root link '" +
                             root + "' is not, so the two cannot be chained");
  if (source_in_model) return frames.transform(target, root, stamp) * from_base(source).inverse();
  return from_base(target) * frames.transform(root, source, stamp);
}

}  // namespace

void append_message(std::string& message, const std::string& more) {
  if (more.empty()) return;
  if (!message.empty()) message += "; ";
  message += more;
}

void compute_inverse_dynamics(const ServedScene& scene, Workspace& ws, const InverseDynamics::Request& req,
                              InverseDynamics::Response& res) {
  const bool with_wrenches = decode_dynamics_request(scene, ws, req, "acceleration", req.acceleration);
  const Model<double>& model = model_for(scene, req.rigid_body_only);
  Data<double>& data = ws.data;
  const bool actuated = with_actuators(scene, req.rigid_body_only);
  const Eigen::VectorXd& tau =
      actuated ? (with_wrenches ? inverse_dynamics_actuated(model, data, ws.q, ws.qd, ws.x, ws.f_ext)
                                : inverse_dynamics_actuated(model, data, ws.q, ws.qd, ws.x))
               : (with_wrenches ? rnea(model, data, ws.q, ws.qd, ws.x, ws.f_ext) : rnea(model, data, ws.q, ws.qd, ws.x));
  check_finite(tau, "effort");
  res.name = scene.decoder->jointNames();
  copy_to(tau, res.effort);
  if (actuated) copy_to(actuator_effort(model, data, ws.qd, ws.x), res.actuator_effort);
  res.message = request_notes(scene, ws, req.velocity);
}

void compute_forward_dynamics(const ServedScene& scene, Workspace& ws, const ForwardDynamics::Request& req,
                              ForwardDynamics::Response& res) {
  const bool with_wrenches = decode_dynamics_request(scene, ws, req, "effort", req.effort);
  const Model<double>& model = model_for(scene, req.rigid_body_only);
  Data<double>& data = ws.data;
  const Eigen::VectorXd& qdd =
      with_actuators(scene, req.rigid_body_only)
          ? (with_wrenches ? forward_dynamics_actuated(model, data, ws.q, ws.qd, ws.x, ws.f_ext)
                           : forward_dynamics_actuated(model, data, ws.q, ws.qd, ws.x))
          : (with_wrenches ? forward_dynamics(model, data, ws.q, ws.qd, ws.x, ws.f_ext)
                           : forward_dynamics(model, data, ws.q, ws.qd, ws.x));
  check_finite(qdd, "acceleration");
  res.name = scene.decoder->jointNames();
  copy_to(qdd, res.acceleration);
  res.message = request_notes(scene, ws, req.velocity);
}

void compute_mass_matrix(const ServedScene& scene, Workspace& ws, const MassMatrix::Request& req,
                         MassMatrix::Response& res) {
  decode_positions(scene, ws, req.name, req.position);
  const Eigen::MatrixXd& M = crba(model_for(scene, req.rigid_body_only), ws.data, ws.q);  // with armature
  check_finite(M, "mass matrix");
  res.name = scene.decoder->jointNames();
  res.mass_matrix.resize(M.size());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(res.mass_matrix.data(), M.rows(),
                                                                                    M.cols()) = M;
  res.message = scene.decoder->limitWarnings(ws.q);
}

void compute_transform_wrench(const ServedScene& scene, Workspace& ws, const FrameLookup& frames,
                              const TransformWrench::Request& req, TransformWrench::Response& res) {
  const std::string& source = req.wrench.header.frame_id;
  if (source.empty()) throw std::runtime_error("wrench.header.frame_id is empty");
  if (req.target_frame.empty()) throw std::runtime_error("target_frame is empty");
  const ForceVector<double> f = to_force(req.wrench.wrench);
  if (!f.toVector().allFinite()) throw std::runtime_error("wrench (frame '" + source + "') is not finite");
  const bool uses_model = scene.model->hasFrame(source) || scene.model->hasFrame(req.target_frame);
  if (uses_model) decode_positions(scene, ws, req.name, req.position);
  const ForceVector<double> f_target =
      frame_transform(scene, ws, frames, req.target_frame, source, req.wrench.header.stamp).apply(f);  // X* f (eq. 12)
  check_finite(f_target.toVector(), "transformed wrench");
  res.wrench.header.stamp = req.wrench.header.stamp;
  res.wrench.header.frame_id = req.target_frame;
  res.wrench.wrench.torque.x = f_target.angular.x();
  res.wrench.wrench.torque.y = f_target.angular.y();
  res.wrench.wrench.torque.z = f_target.angular.z();
  res.wrench.wrench.force.x = f_target.linear.x();
  res.wrench.wrench.force.y = f_target.linear.y();
  res.wrench.wrench.force.z = f_target.linear.z();
  if (uses_model) res.message = scene.decoder->limitWarnings(ws.q);
}

bool compute_latest_torques(const ServedScene& scene, Workspace& ws, std::vector<double>& position,
                            std::vector<double>& velocity, std::vector<double>& effort) {
  scene.robot->cache->snapshot(ws.state);
  if (!ws.state.complete) return false;
  const JointRequestDecoder& decoder = *scene.decoder;
  check(decoder.decode("position", {}, {}, {}, JointRequestDecoder::Default::LatestPosition, ws.state, ws.q));
  check(decoder.decode("velocity", {}, {}, {}, JointRequestDecoder::Default::LatestVelocity, ws.state, ws.qd));
  const Eigen::VectorXd& tau = with_actuators(scene, false)
                                   ? inverse_dynamics_actuated(*scene.model, ws.data, ws.q, ws.qd, ws.data.zero_v)
                                   : nonlinear_effects(*scene.model, ws.data, ws.q, ws.qd);  // ID(q, q̇, 0)
  check_finite(tau, "computed torque");
  copy_to(ws.q, position);
  copy_to(ws.qd, velocity);
  copy_to(tau, effort);
  return true;
}

}  // namespace spatial_dynamics
