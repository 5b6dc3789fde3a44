#include "spatial_dynamics/ros/payload_identification_handlers.hpp"

#include <cmath>
#include <stdexcept>

#include "spatial_dynamics/estimation/excitation_trajectory.hpp"
#include "spatial_dynamics/ros/trajectory_differences.hpp"

namespace spatial_dynamics {

namespace {

/// A field of point k: empty, or one value per name.
void check_point_field(const std::string& field, std::size_t k, const std::vector<double>& values, std::size_t names,
                       bool required) {
  if (values.empty() && !required) return;
  if (values.size() != names)
    throw std::invalid_argument("samples: point " + std::to_string(k) + " has " + std::to_string(values.size()) + " " +
                                field + " for " + std::to_string(names) + " joints in joint_names");
}

}  // namespace

PayloadSamples decode_payload_samples(const PayloadIdentificationInput& input, const trajectory_msgs::JointTrajectory& trajectory,
                                      std::vector<int>& measured) {
  const Model<double>& model = input.model;
  const JointRequestDecoder& decoder = input.decoder;
  if (model.nq != model.nv) throw std::invalid_argument("payload identification needs a model whose joints each have one coordinate");
  const std::vector<std::string>& model_joints = decoder.jointNames();
  std::vector<std::string> names = trajectory.joint_names;
  if (names.empty()) names = model_joints;
  // the columns kept: joints of the model, not mimic joints it couples to their master
  std::vector<std::size_t> columns;
  std::vector<std::string> kept;
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (model.hasJoint(names[c]) && model.joints[model.jointBody(names[c])].coupled) continue;
    columns.push_back(c);
    kept.push_back(names[c]);
  }
  if (kept.empty()) throw std::invalid_argument("samples: joint_names has no joint of the model with a coordinate of its own");
  std::vector<int> indices;
  const std::string error = decoder.resolve(kept, indices);
  if (!error.empty()) throw std::invalid_argument("samples: " + error);
  measured = indices;

  const std::size_t n = trajectory.points.size();
  if (n < 2) throw std::invalid_argument("samples: " + std::to_string(n) + " points; at least two are needed");
  const bool differentiate = trajectory.points[0].accelerations.empty();
  std::vector<double> t(n);
  for (std::size_t k = 0; k < n; ++k) {
    const trajectory_msgs::JointTrajectoryPoint& p = trajectory.points[k];
    check_point_field("positions", k, p.positions, names.size(), true);
    check_point_field("velocities", k, p.velocities, names.size(), true);
    check_point_field("effort", k, p.effort, names.size(), true);
    if (p.accelerations.empty() != differentiate)
      throw std::invalid_argument("samples: point " + std::to_string(k) + (differentiate ? " has" : " lacks") +
                                  " accelerations, which must be given in every point or in none");
    check_point_field("accelerations", k, p.accelerations, names.size(), false);
    t[k] = p.time_from_start.toSec();
    if (!std::isfinite(t[k]) || (k > 0 && !(t[k] > t[k - 1])))
      throw std::invalid_argument("samples: time_from_start of point " + std::to_string(k) + " does not increase");
  }

  const int nv = model.nv;
  PayloadSamples s{Eigen::MatrixXd(nv, n), Eigen::MatrixXd::Zero(nv, n), Eigen::MatrixXd::Zero(nv, n), Eigen::MatrixXd::Zero(nv, n)};
  Eigen::VectorXd held;  // the joints left out: their latest positions (the named ones overwritten below)
  const std::string missing = decoder.decode("positions", kept, indices, std::vector<double>(kept.size(), 0.0),
                                             JointRequestDecoder::Default::LatestPosition, input.state, held);
  if (!missing.empty()) throw std::invalid_argument("samples: " + missing);
  for (std::size_t k = 0; k < n; ++k) {
    const trajectory_msgs::JointTrajectoryPoint& p = trajectory.points[k];
    s.position.col(k) = held;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::size_t from = columns[c];
      const int to = indices[c];
      const double values[4] = {p.positions[from], p.velocities[from], differentiate ? 0.0 : p.accelerations[from], p.effort[from]};
      const char* fields[4] = {"positions", "velocities", "accelerations", "effort"};
      for (int f = 0; f < 4; ++f)
        if (!std::isfinite(values[f]))
          throw std::invalid_argument(std::string("samples: ") + fields[f] + " of joint '" + names[from] + "' in point " +
                                      std::to_string(k) + " is not finite");
      s.position(to, k) = values[0];
      s.velocity(to, k) = values[1];
      s.acceleration(to, k) = values[2];
      s.effort(to, k) = values[3];
    }
  }
  if (differentiate)  // q̈ = d q̇ / dt (second order inside, one-sided at the ends)
    for (std::size_t k = 0; k < n; ++k) {
      const DifferenceWeights w = difference_weights(t, k);
      s.acceleration.col(k).setZero();
      for (std::size_t m = 0; m < w.count; ++m) s.acceleration.col(k) += w.first[m] * s.velocity.col(w.start + m);
    }
  return s;
}

void compute_identify_payload(const PayloadIdentificationInput& input, const std::string& frame,
                              const trajectory_msgs::JointTrajectory& samples, bool identify_friction,
                              IdentifyPayload::Response& res) {
  if (!input.model.hasFrame(frame)) throw std::invalid_argument("frame: unknown frame '" + frame + "' (not a link of the robot model)");
  PayloadIdentificationOptions options;
  options.identify_friction = identify_friction;
  options.prior = input.prior;
  const PayloadSamples decoded = decode_payload_samples(input, samples, options.measured);
  Data<double> data(input.model);
  const PayloadIdentification r = identify_payload(input.model, data, frame, decoded, options);
  auto to_message = [](const Payload& p, geometry_msgs::Inertia& m) {
    m.m = p.mass;
    m.com.x = p.center_of_mass.x(), m.com.y = p.center_of_mass.y(), m.com.z = p.center_of_mass.z();
    m.ixx = p.inertia(0, 0), m.ixy = p.inertia(0, 1), m.ixz = p.inertia(0, 2);
    m.iyy = p.inertia(1, 1), m.iyz = p.inertia(1, 2), m.izz = p.inertia(2, 2);
  };
  to_message(r.payload, res.inertia);
  to_message(r.stddev, res.stddev);
  res.unidentifiable = r.unidentifiable;
  res.condition_number = r.condition_number;
  const std::vector<std::string>& joints = input.decoder.jointNames();
  res.name.clear();
  for (int k : options.measured) res.name.push_back(joints[k]);
  res.residual_rms.assign(r.residual_rms.data(), r.residual_rms.data() + r.residual_rms.size());
  res.damping.assign(r.damping.data(), r.damping.data() + r.damping.size());
  res.friction.assign(r.friction.data(), r.friction.data() + r.friction.size());
}

void compute_excitation_trajectory(const PayloadIdentificationInput& input, const ExcitationTrajectory::Request& req,
                                   ExcitationTrajectory::Response& res) {
  const Model<double>& model = input.model;
  ExcitationOptions options;
  options.speed_scale = req.speed_scale;
  options.max_acceleration = req.max_acceleration;
  options.sample_period = 0.01;
  options.rest_position = Eigen::VectorXd::Zero(model.nq);
  std::vector<int> none_indices;
  Eigen::VectorXd latest;
  if (input.decoder.decode("positions", {}, none_indices, {}, JointRequestDecoder::Default::LatestPosition, input.state,
                           latest).empty() && latest.size() == model.nq)
    options.rest_position = latest;  // the other joints where they are now
  const Excitation e = excitation_trajectory(model, req.joints, req.duration, options);
  trajectory_msgs::JointTrajectory& t = res.trajectory;
  t.joint_names = e.joints;
  t.points.resize(e.time.size());
  for (Eigen::Index k = 0; k < e.time.size(); ++k) {
    trajectory_msgs::JointTrajectoryPoint& p = t.points[k];
    p.time_from_start = ros::Duration(e.time[k]);
    p.positions.assign(e.position.col(k).data(), e.position.col(k).data() + e.position.rows());
    p.velocities.assign(e.velocity.col(k).data(), e.velocity.col(k).data() + e.velocity.rows());
    p.accelerations.assign(e.acceleration.col(k).data(), e.acceleration.col(k).data() + e.acceleration.rows());
  }
  res.condition_number = e.condition_number;
}

}  // namespace spatial_dynamics
