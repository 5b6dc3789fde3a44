// ~inverse_dynamics_trajectory: τ_k = ID(q_k, q̇_k, q̈_k) at every point k of a JointTrajectory,
// all points through the batched RNEA (rnea_batch.hpp), with each joint's peak |τ| and the first
// point where it exceeds the URDF effort limit. Missing velocities and accelerations come from
// finite differences of the positions over time_from_start (trajectory_differences.hpp); joints the
// trajectory does not name stay at their latest joint_states position, still (q̇ = q̈ = 0).
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include "spatial_dynamics/algorithms/actuator_dynamics.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/ros/service_handlers.hpp"
#include "spatial_dynamics/ros/trajectory_differences.hpp"

namespace spatial_dynamics {
namespace {

std::string point(std::size_t k) { return "point " + std::to_string(k) + ": "; }

/// A point's array: `width` entries (none is allowed when `optional`), every one finite.
void check_point_array(std::size_t k, const char* field, const std::vector<double>& values, bool optional,
                       const std::vector<std::string>& columns, bool by_name) {
  if (values.empty() && optional) return;
  if (values.size() != columns.size())
    throw std::runtime_error(point(k) + field + " has " + std::to_string(values.size()) + " entries but " +
                             (by_name ? "joint_names has " + std::to_string(columns.size())
                                      : "the model has " + std::to_string(columns.size()) +
                                            " joints (joint_names is empty)"));
  for (std::size_t j = 0; j < values.size(); ++j)
    if (!std::isfinite(values[j]))
      throw std::runtime_error(point(k) + field + " of joint '" + columns[j] + "' is not finite");
}

/// The URDF effort limit; +inf ("no limit") when the URDF gives none or one that is not positive
/// (a <limit> written only for its required attributes has effort="0").
double effort_limit(const Model<double>& model, const std::string& joint) {
  const double limit = model.joints[model.jointBody(joint)].limits.effort;
  return limit > 0 ? limit : std::numeric_limits<double>::infinity();
}

/// "velocities of 5 of 8 points": what the differences supplied, for the message.
std::string differences_note(std::size_t velocities, std::size_t accelerations, std::size_t count) {
  std::string what;
  if (velocities > 0) what = "velocities of " + std::to_string(velocities) + " of " + std::to_string(count) + " points";
  if (accelerations > 0)
    what += (what.empty() ? "" : " and ") + std::string("accelerations of ") + std::to_string(accelerations) + " of " +
            std::to_string(count) + " points";
  if (count == 2)
    return what + " by finite differences over time_from_start: the slope between the two points (one-sided)";
  return what +
         " by finite differences of the positions over time_from_start: central differences inside (the quadratic "
         "through the point and its neighbours), one-sided at the first and last point (the quadratic through the "
         "first or last three points)";
}

}  // namespace

void compute_inverse_dynamics_trajectory(const ServedScene& scene, Workspace& ws,
                                         const InverseDynamicsTrajectory::Request& req,
                                         InverseDynamicsTrajectory::Response& res) {
  if (scene.model->floating_base)
    throw std::runtime_error("inverse_dynamics_trajectory serves fixed-base robots (~root_joint is floating): call "
                             "inverse_dynamics at each point with its base state");
  const JointRequestDecoder& decoder = *scene.decoder;
  const Model<double>& model = model_for(scene, req.rigid_body_only);
  const trajectory_msgs::JointTrajectory& trajectory = req.trajectory;
  const std::vector<std::string>& names = trajectory.joint_names;
  const std::string error = decoder.resolve(names, ws.indices);  // unknown or repeated joint
  if (!error.empty()) throw std::runtime_error("joint_names: " + error);
  const bool by_name = !names.empty();
  const std::vector<std::string>& columns = by_name ? names : decoder.jointNames();  // the points' order
  const int n = static_cast<int>(decoder.jointNames().size());
  const std::size_t count = trajectory.points.size();
  auto row = [&](std::size_t m) { return by_name ? ws.indices[m] : static_cast<int>(m); };

  // Every point is checked before anything is computed.
  std::size_t missing_velocities = 0, missing_accelerations = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const trajectory_msgs::JointTrajectoryPoint& p = trajectory.points[k];
    check_point_array(k, "positions", p.positions, false, columns, by_name);
    check_point_array(k, "velocities", p.velocities, true, columns, by_name);
    check_point_array(k, "accelerations", p.accelerations, true, columns, by_name);
    missing_velocities += p.velocities.empty();
    missing_accelerations += p.accelerations.empty();
  }
  std::vector<double> t(count);
  for (std::size_t k = 0; k < count; ++k) t[k] = trajectory.points[k].time_from_start.toSec();
  if (missing_velocities + missing_accelerations > 0) {
    const std::string why = " (needed for the velocities or accelerations the points leave out, by finite differences)";
    // A line through two points gives velocities; accelerations need a quadratic, three points.
    using Need = std::tuple<std::size_t, const char*, std::size_t>;  // missing, what, points needed
    for (const auto& [missing, what, needed] :
         {Need{missing_velocities, "velocities", 2}, Need{missing_accelerations, "accelerations", 3}})
      if (missing > 0 && count < needed)
        throw std::runtime_error("the trajectory has " + std::to_string(count) + " point(s); " + what +
                                 " by finite differences need at least " + std::to_string(needed) +
                                 " points; give them in the points");
    for (std::size_t k = 1; k < count; ++k)
      if (!(t[k] > t[k - 1]))
        throw std::runtime_error(point(k) + "time_from_start " + std::to_string(t[k]) +
                                 " s is not after the previous point's " + std::to_string(t[k - 1]) +
                                 " s; it must increase strictly" + why);
  }

  // Joints the trajectory leaves out: the latest joint state's position, held still.
  std::string notes;
  ws.q.setZero(n);
  if (count > 0 && static_cast<int>(columns.size()) < n) {
    scene.robot->cache->snapshot(ws.state);
    const std::string held_error = decoder.decode("position", names, ws.indices, trajectory.points[0].positions,
                                                  JointRequestDecoder::Default::LatestPosition, ws.state, ws.q);
    if (!held_error.empty()) throw std::runtime_error(held_error);
    std::vector<char> named(n, 0);
    for (std::size_t m = 0; m < columns.size(); ++m) named[row(m)] = 1;
    std::string held;
    for (int i = 0; i < n; ++i)
      if (!named[i]) held += (held.empty() ? "'" : ", '") + decoder.jointNames()[i] + "'";
    append_message(notes, "joint(s) " + held + " not in the trajectory: held at their latest joint_states position");
  }

  // The states, one column per point.
  Eigen::MatrixXd& q = ws.trajectory_q;
  Eigen::MatrixXd& qd = ws.trajectory_qd;
  Eigen::MatrixXd& qdd = ws.trajectory_qdd;
  q.resize(n, static_cast<Eigen::Index>(count));
  qd.setZero(n, static_cast<Eigen::Index>(count));
  qdd.setZero(n, static_cast<Eigen::Index>(count));
  ws.trajectory_tau.resize(n, static_cast<Eigen::Index>(count));
  for (std::size_t k = 0; k < count; ++k) {
    q.col(k) = ws.q;
    for (std::size_t m = 0; m < columns.size(); ++m) q(row(m), k) = trajectory.points[k].positions[m];
  }
  for (std::size_t k = 0; k < count; ++k) {
    const trajectory_msgs::JointTrajectoryPoint& p = trajectory.points[k];
    const bool differentiate = p.velocities.empty() || p.accelerations.empty();
    const DifferenceWeights w = differentiate ? difference_weights(t, k) : DifferenceWeights{};
    for (std::size_t m = 0; m < columns.size(); ++m) {
      const int i = row(m);
      if (!p.velocities.empty()) {
        qd(i, k) = p.velocities[m];
      } else {
        for (std::size_t s = 0; s < w.count; ++s) qd(i, k) += w.first[s] * q(i, w.start + s);  // q̇_k ≈ Σ w'_s q_s
      }
      if (!p.accelerations.empty()) {
        qdd(i, k) = p.accelerations[m];
      } else {
        for (std::size_t s = 0; s < w.count; ++s) qdd(i, k) += w.second[s] * q(i, w.start + s);  // q̈_k ≈ Σ w''q_s
      }
    }
  }
  if (missing_velocities + missing_accelerations > 0)
    append_message(notes, differences_note(missing_velocities, missing_accelerations, count));

  try {
    rnea_batch(model, ws.batch, q, qd, qdd, ws.trajectory_tau);  // with armature ⊙ q̈
    if (with_actuators(scene, req.rigid_body_only))                 // and the damping and friction forces
      for (std::size_t k = 0; k < count; ++k) ws.trajectory_tau.col(k) += actuator_forces(model, ws.data, qd.col(k));
  } catch (const std::exception& e) {  // "state k: …" is point k
    std::string message = e.what();
    if (message.rfind("state ", 0) == 0) message.replace(0, 6, "point ");
    throw std::runtime_error(message);
  }
  const Eigen::MatrixXd& tau = ws.trajectory_tau;

  res.name = decoder.jointNames();
  res.points.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    trajectory_msgs::JointTrajectoryPoint& out = res.points[k];
    out.positions.assign(q.col(k).data(), q.col(k).data() + n);
    out.velocities.assign(qd.col(k).data(), qd.col(k).data() + n);
    out.accelerations.assign(qdd.col(k).data(), qdd.col(k).data() + n);
    out.effort.assign(tau.col(k).data(), tau.col(k).data() + n);
    out.time_from_start = trajectory.points[k].time_from_start;
  }
  res.peak_effort.assign(n, 0.0);
  res.effort_limit.resize(n);
  res.first_violation.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    res.effort_limit[i] = effort_limit(model, res.name[i]);
    for (std::size_t k = 0; k < count; ++k) {
      const double magnitude = std::abs(tau(i, k));
      res.peak_effort[i] = std::max(res.peak_effort[i], magnitude);
      if (magnitude > res.effort_limit[i] && res.first_violation[i] < 0) res.first_violation[i] = static_cast<int>(k);
    }
  }

  // Positions outside their limits are computed anyway and reported, as by the other services.
  std::size_t outside = 0;
  std::string first_warning;
  for (std::size_t k = 0; k < count; ++k) {
    const std::string warning = decoder.limitWarnings(q.col(k));
    if (warning.empty()) continue;
    if (outside++ == 0) first_warning = point(k) + warning;
  }
  if (outside > 1) first_warning += " (" + std::to_string(outside) + " points have positions outside the limits)";
  append_message(notes, first_warning);
  if (count == 0) append_message(notes, "the trajectory has no points");
  res.message = notes;
}

}  // namespace spatial_dynamics
