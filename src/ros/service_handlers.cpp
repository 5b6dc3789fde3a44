#include "spatial_dynamics/ros/service_handlers.hpp"

#include <algorithm>
#include <stdexcept>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/ros/base_request_decoder.hpp"
#include "spatial_dynamics/ros/contact_answers.hpp"

namespace spatial_dynamics {
namespace {

/// Throws std::runtime_error(message) when `error` is not empty.
void check(const std::string& error) {
  if (!error.empty()) throw std::runtime_error(error);
}

/// One joint array of a request into the joints' coordinates of `out` (size `size`): its last n,
/// after a floating base's (all of it for a fixed base).
void decode_joint_array(const ServedScene& scene, Workspace& ws, const std::string& field,
                        const std::vector<std::string>& names, const std::vector<double>& values,
                        JointRequestDecoder::Default fallback, Eigen::VectorXd& out, int size) {
  check(scene.decoder->decode(field, names, ws.indices, values, fallback, ws.state, ws.joint_values));
  out.resize(size);
  out.tail(ws.joint_values.size()) = ws.joint_values;
  if (size > ws.joint_values.size()) out.head(size - ws.joint_values.size()).setZero();
}

/// The joint order and positions of a request, decoded into ws.indices and ws.q; a floating base at
/// the identity pose (its coordinates are then the root link's).
void decode_positions(const ServedScene& scene, Workspace& ws, const std::vector<std::string>& names,
                      const std::vector<double>& positions) {
  check(scene.decoder->resolve(names, ws.indices));
  scene.robot->cache->snapshot(ws.state);
  decode_joint_array(scene, ws, "position", names, positions, JointRequestDecoder::Default::LatestPosition, ws.q,
                     scene.model->nq);
  if (scene.model->floating_base) ws.q.head<7>() << 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0;
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
/// ws.x, a floating base's pose and twist (the request's, or the base state's, whose note goes to
/// `notes`), and the external wrenches in ws.f_ext. Returns whether any wrench was given.
template <class Request>
bool decode_dynamics_request(const ServedScene& scene, const BaseStateSource& base, Workspace& ws, const Request& req,
                             const std::string& field, const std::vector<double>& values, std::string& notes) {
  const Model<double>& model = *scene.model;
  decode_positions(scene, ws, req.name, req.position);
  decode_joint_array(scene, ws, "velocity", req.name, req.velocity, JointRequestDecoder::Default::LatestVelocity, ws.qd,
                     model.nv);
  decode_joint_array(scene, ws, field, req.name, values, JointRequestDecoder::Default::Zero, ws.x, model.nv);
  if (model.floating_base)
    decode_base(scene.robot->root_frame, base, req.base_pose, req.base_twist, ros::Time(0), ws.q, ws.qd, notes);
  else
    refuse_base_fields(req.base_pose, req.base_twist, nullptr);
  return decode_wrenches(model, req.external_wrenches, ws.f_ext);
}

/// The joints' part of a full vector (after a floating base's six).
template <class Vector>
void copy_joints(const Vector& v, std::size_t joints, std::vector<double>& out) {
  out.assign(v.data() + (v.size() - joints), v.data() + v.size());
}

/// A floating base's six rows of `v` as a wrench message (zero for a fixed base).
geometry_msgs::Wrench base_rows(const Model<double>& model, const Eigen::VectorXd& v) {
  return to_wrench_message(model.floating_base ? Eigen::Matrix<double, 6, 1>(v.head<6>())
                                               : Eigen::Matrix<double, 6, 1>::Zero());
}

/// Refuses forward dynamics of a floating base whose root link has no mass (M is then singular).
void check_root_mass(const Model<double>& model) {
  if (model.floating_base && !(model.inertia[1].mass > 0.0))
    throw std::runtime_error("the root link '" + model.body_names[1] +
                             "' has no mass: a floating base (~root_joint floating) needs one for forward dynamics");
}

/// The contacts of a request (contact_answers.hpp).
template <class Request>
const ContactSet<double>& request_contacts(const ServedScene& scene, Workspace& ws, const Model<double>& model,
                                           const Request& req) {
  return contacts_for_call(scene, ws, model, req.contact_frames, req.contact_kinds, req.contact_frictions,
                           req.ignore_contacts);
}

/// ws.q and ws.qd of the latest joint states and, for a floating base, its state at `stamp` (its
/// pose; its twist too unless `base_at_rest`), for the topics; false while the joint states are
/// incomplete.
bool decode_latest_state(const ServedScene& scene, const BaseStateSource& base, Workspace& ws, const ros::Time& stamp,
                         bool base_at_rest, BaseState& state) {
  scene.robot->cache->snapshot(ws.state);
  if (!ws.state.complete) return false;
  const Model<double>& model = *scene.model;
  ws.indices.clear();
  decode_joint_array(scene, ws, "position", {}, {}, JointRequestDecoder::Default::LatestPosition, ws.q, model.nq);
  decode_joint_array(scene, ws, "velocity", {}, {}, JointRequestDecoder::Default::LatestVelocity, ws.qd, model.nv);
  if (model.floating_base) {
    base.state(scene.robot->root_frame, stamp, state);
    set_base_coordinates(state, ws.q, ws.qd);
    if (base_at_rest) ws.qd.head<6>().setZero();
  }
  return true;
}

/// The contact answers: each contact's wrench, and the contacts that pull or slip.
template <class Response>
void answer_contacts(const Model<double>& model, const ContactSet<double>& contacts, const ContactData<double>& cd,
                     Response& res) {
  contact_wrench_messages(model, contacts, cd.lambda, ros::Time(), res.contact_wrenches);
  check_contact_wrenches(model, contacts, cd.lambda, res.contact_violations, res.message);
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

void compute_inverse_dynamics(const ServedScene& scene, const BaseStateSource& base, Workspace& ws,
                              const InverseDynamics::Request& req, InverseDynamics::Response& res) {
  std::string notes;
  const bool with_wrenches = decode_dynamics_request(scene, base, ws, req, "acceleration", req.acceleration, notes);
  const Model<double>& model = model_for(scene, req.rigid_body_only);
  if (model.floating_base)
    ws.x.head<6>() = angular_linear(req.base_acceleration, "base_acceleration");
  else
    refuse_base_fields({}, {}, &req.base_acceleration);
  Data<double>& data = ws.data;
  const bool actuated = with_actuators(scene, req.rigid_body_only);
  const ContactSet<double>& contacts = request_contacts(scene, ws, model, req);
  const Eigen::VectorXd* tau = nullptr;
  if (!contacts.empty()) {
    ContactData<double>& cd = ws.contactData(model, contacts);
    if (with_wrenches)
      inverse_dynamics_with_contacts(model, data, contacts, cd, ws.q, ws.qd, ws.x, ws.f_ext);
    else
      inverse_dynamics_with_contacts(model, data, contacts, cd, ws.q, ws.qd, ws.x);
    if (actuated) cd.tau += actuator_forces(model, data, ws.qd);  // damping and friction (armature is in M)
    tau = &cd.tau;
    answer_contacts(model, contacts, cd, res);
    const double left = cd.tau.head(model.floating_base ? 6 : 0).norm();
    if (model.floating_base && left > 1e-9 * (left + cd.lambda.norm()))
      append_message(res.message, "the contacts cannot balance the base: base_wrench is the wrench left over");
  } else {
    tau = &(actuated ? (with_wrenches ? inverse_dynamics_actuated(model, data, ws.q, ws.qd, ws.x, ws.f_ext)
                                      : inverse_dynamics_actuated(model, data, ws.q, ws.qd, ws.x))
                     : (with_wrenches ? rnea(model, data, ws.q, ws.qd, ws.x, ws.f_ext) : rnea(model, data, ws.q, ws.qd, ws.x)));
  }
  check_finite(*tau, "effort");
  const std::size_t joints = scene.decoder->jointNames().size();
  res.name = scene.decoder->jointNames();
  copy_joints(*tau, joints, res.effort);
  res.base_wrench = base_rows(model, *tau);
  if (actuated) copy_joints(actuator_effort(model, data, ws.qd, ws.x), joints, res.actuator_effort);
  append_message(res.message, notes);
  append_message(res.message, request_notes(scene, ws, req.velocity));
}

void compute_forward_dynamics(const ServedScene& scene, const BaseStateSource& base, Workspace& ws,
                              const ForwardDynamics::Request& req, ForwardDynamics::Response& res) {
  std::string notes;
  const bool with_wrenches = decode_dynamics_request(scene, base, ws, req, "effort", req.effort, notes);
  const Model<double>& model = model_for(scene, req.rigid_body_only);
  check_root_mass(model);
  Data<double>& data = ws.data;
  const bool actuated = with_actuators(scene, req.rigid_body_only);
  const ContactSet<double>& contacts = request_contacts(scene, ws, model, req);
  const Eigen::VectorXd* qdd = nullptr;
  if (!contacts.empty()) {
    ContactData<double>& cd = ws.contactData(model, contacts);
    if (actuated) ws.x -= actuator_forces(model, data, ws.qd);  // τ − τ_a(q̇) for the rigid body and rotors
    qdd = &(with_wrenches ? forward_dynamics_with_contacts(model, data, contacts, cd, ws.q, ws.qd, ws.x, ws.f_ext)
                          : forward_dynamics_with_contacts(model, data, contacts, cd, ws.q, ws.qd, ws.x));
    answer_contacts(model, contacts, cd, res);
  } else {
    qdd = &(actuated ? (with_wrenches ? forward_dynamics_actuated(model, data, ws.q, ws.qd, ws.x, ws.f_ext)
                                      : forward_dynamics_actuated(model, data, ws.q, ws.qd, ws.x))
                     : (with_wrenches ? forward_dynamics(model, data, ws.q, ws.qd, ws.x, ws.f_ext)
                                      : forward_dynamics(model, data, ws.q, ws.qd, ws.x)));
  }
  check_finite(*qdd, "acceleration");
  res.name = scene.decoder->jointNames();
  copy_joints(*qdd, res.name.size(), res.acceleration);
  if (model.floating_base) {
    res.base_acceleration.angular.x = (*qdd)[0];
    res.base_acceleration.angular.y = (*qdd)[1];
    res.base_acceleration.angular.z = (*qdd)[2];
    res.base_acceleration.linear.x = (*qdd)[3];
    res.base_acceleration.linear.y = (*qdd)[4];
    res.base_acceleration.linear.z = (*qdd)[5];
  }
  append_message(res.message, notes);
  append_message(res.message, request_notes(scene, ws, req.velocity));
}

void compute_mass_matrix(const ServedScene& scene, const BaseStateSource&, Workspace& ws,
                         const MassMatrix::Request& req, MassMatrix::Response& res) {
  decode_positions(scene, ws, req.name, req.position);
  const Model<double>& model = model_for(scene, req.rigid_body_only);
  if (model.floating_base) {  // M does not depend on the base's state: the request's is checked only
    ws.qd.resize(model.nv);
    if (base_pose_given(req.base_pose)) decode_given_base(req.base_pose, req.base_twist, ws.q, ws.qd);
    angular_linear(req.base_twist, "base_twist");
    angular_linear(req.base_acceleration, "base_acceleration");
  } else {
    refuse_base_fields(req.base_pose, req.base_twist, &req.base_acceleration);
  }
  request_contacts(scene, ws, model, req);  // checked: M does not depend on them
  const Eigen::MatrixXd& M = crba(model, ws.data, ws.q);  // with armature
  check_finite(M, "mass matrix");
  res.name.clear();
  if (model.floating_base) {
    const std::vector<std::string> names = model.velocityNames();
    res.name.assign(names.begin(), names.begin() + 6);
  }
  res.name.insert(res.name.end(), scene.decoder->jointNames().begin(), scene.decoder->jointNames().end());
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

bool compute_latest_torques(const ServedScene& scene, const BaseStateSource& base, Workspace& ws, const ros::Time& stamp,
                            sensor_msgs::JointState& torques, std::vector<geometry_msgs::WrenchStamped>& wrenches) {
  wrenches.clear();
  BaseState state;
  if (!decode_latest_state(scene, base, ws, stamp, true, state)) return false;
  const Model<double>& model = *scene.model;
  const JointRequestDecoder& decoder = *scene.decoder;
  const bool actuated = with_actuators(scene, false);
  const Eigen::VectorXd* tau = nullptr;
  if (!model.floating_base) {
    tau = &(actuated ? inverse_dynamics_actuated(model, ws.data, ws.q, ws.qd, ws.data.zero_v)
                     : nonlinear_effects(model, ws.data, ws.q, ws.qd));  // ID(q, q̇, 0)
  } else {  // the base at rest at its latest pose
    if (!scene.contacts_error.empty()) throw std::runtime_error(scene.contacts_error);
    if (scene.contacts.empty()) {
      tau = &(actuated ? inverse_dynamics_actuated(model, ws.data, ws.q, ws.qd, ws.data.zero_v)
                       : nonlinear_effects(model, ws.data, ws.q, ws.qd));
    } else {
      ContactData<double>& cd = ws.contactData(model, scene.contacts);
      inverse_dynamics_with_contacts(model, ws.data, scene.contacts, cd, ws.q, ws.qd, ws.data.zero_v);
      if (actuated) cd.tau += actuator_forces(model, ws.data, ws.qd);
      tau = &cd.tau;
      contact_wrench_messages(model, scene.contacts, cd.lambda, stamp, wrenches);
    }
  }
  check_finite(*tau, "computed torque");
  const std::size_t joints = decoder.jointNames().size();
  copy_joints(ws.q, joints, torques.position);
  copy_joints(ws.qd, joints, torques.velocity);
  copy_joints(*tau, joints, torques.effort);
  torques.name = decoder.jointNames();
  return true;
}

bool compute_centroidal_state(const ServedScene& scene, const BaseStateSource& base, Workspace& ws,
                              const ros::Time& stamp, CentroidalState& out) {
  BaseState state;
  if (!decode_latest_state(scene, base, ws, stamp, false, state)) return false;
  const Model<double>& model = *scene.model;
  out.header.frame_id = model.floating_base ? state.world_frame : scene.robot->root_frame;
  const Eigen::Vector3d c = center_of_mass(model, ws.data, ws.q);
  const Eigen::Vector3d c_dot = center_of_mass_velocity(model, ws.data, ws.q, ws.qd);
  const ForceVector<double> h = centroidal_momentum(model, ws.data, ws.q, ws.qd);  // about c, base axes
  if (!c.allFinite() || !c_dot.allFinite() || !h.toVector().allFinite())
    throw std::runtime_error("the centroidal state is not finite");
  out.header.stamp = stamp;
  out.center_of_mass.x = c.x();
  out.center_of_mass.y = c.y();
  out.center_of_mass.z = c.z();
  out.center_of_mass_velocity.x = c_dot.x();
  out.center_of_mass_velocity.y = c_dot.y();
  out.center_of_mass_velocity.z = c_dot.z();
  out.linear_momentum.x = h.linear.x();
  out.linear_momentum.y = h.linear.y();
  out.linear_momentum.z = h.linear.z();
  out.angular_momentum.x = h.angular.x();
  out.angular_momentum.y = h.angular.y();
  out.angular_momentum.z = h.angular.z();
  return true;
}

}  // namespace spatial_dynamics
