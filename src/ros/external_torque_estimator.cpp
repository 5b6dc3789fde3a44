#include "spatial_dynamics/ros/external_torque_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace spatial_dynamics {
namespace {

/// A gain or threshold: positive and finite, or an error naming `parameter`.
double checked(double value, const std::string& parameter, const char* unit) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw std::invalid_argument("parameter " + parameter + " must be a positive, finite number (" + unit + "), not " +
                                std::to_string(value));
  return value;
}

/// Per coordinate: `value` for every joint, or the map's entries (joints not named: `fallback`).
Eigen::VectorXd per_joint(const std::vector<std::string>& joints, double value, const std::map<std::string, double>& by_joint,
                          double fallback, const std::string& parameter, const char* unit) {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(joints.size()), fallback);
  if (by_joint.empty()) {
    out.setConstant(checked(value, parameter, unit));
    return out;
  }
  for (const auto& entry : by_joint) {
    const auto it = std::find(joints.begin(), joints.end(), entry.first);
    if (it == joints.end())
      throw std::invalid_argument("parameter " + parameter + " names joint '" + entry.first +
                                  "', which this model does not have as a moving joint");
    out[it - joints.begin()] = checked(entry.second, parameter + "/" + entry.first, unit);
  }
  return out;
}

}  // namespace

ExternalTorqueEstimator::ExternalTorqueEstimator(std::shared_ptr<const Model<double>> model,
                                                 const ExternalTorqueSettings& settings,
                                                 const std::vector<std::string>& leaf_links,
                                                 std::vector<std::string> locked_joints,
                                                 const std::map<std::string, double>& tare)
    : model_(std::move(model)),
      joint_names_(model_->velocityNames()),
      locked_joints_(std::move(locked_joints)),
      thresholds_(Eigen::VectorXd::Constant(model_->nv, std::numeric_limits<double>::infinity())),
      max_gap_(checked(settings.max_gap, settings.parameter + "/max_gap", "s")),
      observer_(*model_, per_joint(joint_names_, settings.gain, settings.joint_gains, 50.0, settings.parameter + "/gain", "1/s")),
      data_(*model_) {
  if (settings.detect_collisions)
    thresholds_ = per_joint(joint_names_, settings.threshold, settings.joint_thresholds,
                            std::numeric_limits<double>::infinity(), settings.parameter + "/collision_threshold", "N m or N");
  if (settings.frames_given) {
    for (const std::string& frame : settings.frames) {
      if (!model_->hasFrame(frame))
        throw std::invalid_argument("parameter " + settings.parameter + "/frames names frame '" + frame +
                                    "', which this model does not have");
      frame_names_.push_back(frame);
    }
  } else {  // the URDF's leaf links that this model has and moves
    for (const std::string& link : leaf_links)
      if (model_->hasFrame(link) && model_->frames[model_->frameIndex(link)].body > 0) frame_names_.push_back(link);
  }
  for (const std::string& frame : frame_names_) frames_.push_back(model_->frameIndex(frame));
  if (!tare.empty()) {
    Eigen::VectorXd offset = Eigen::VectorXd::Zero(model_->nv);
    for (int k = 0; k < model_->nv; ++k) {
      const auto it = tare.find(joint_names_[k]);
      if (it != tare.end()) offset[k] = it->second;
    }
    observer_.set_effort_offset(offset);
  }
  estimate_.wrenches.resize(frames_.size());
}

const ExternalTorqueEstimator::Estimate& ExternalTorqueEstimator::update(double stamp, const Eigen::VectorXd& q,
                                                                         const Eigen::VectorXd& qd,
                                                                         const Eigen::VectorXd& effort) {
  for (const Eigen::VectorXd* values : {&q, &qd, &effort})
    for (int k = 0; k < model_->nv; ++k)
      if (!std::isfinite((*values)[k]))
        throw std::invalid_argument(std::string(values == &q ? "position" : values == &qd ? "velocity" : "effort") +
                                    " of joint '" + joint_names_[k] + "' is not finite");
  if (has_stamp_ && stamp == last_stamp_)
    throw std::invalid_argument("its stamp is the previous sample's (" + std::to_string(stamp) + " s)");
  estimate_.restarted = false;
  estimate_.restart_reason.clear();
  char reason[128] = "";
  if (!has_stamp_)
    std::snprintf(reason, sizeof reason, "first sample");
  else if (stamp < last_stamp_)
    std::snprintf(reason, sizeof reason, "the stamp went back by %.6f s", last_stamp_ - stamp);
  else if (stamp - last_stamp_ > max_gap_)
    std::snprintf(reason, sizeof reason, "a gap of %.3f s between joint states (max_gap %.3f s)", stamp - last_stamp_,
                  max_gap_);
  if (reason[0] != '\0') {
    observer_.reset();
    estimate_.restarted = true;
    estimate_.restart_reason = reason;
    if (has_stamp_) ++restarts_;
  }
  const double dt = has_stamp_ && !estimate_.restarted ? stamp - last_stamp_ : 1.0;
  estimate_.torques = &observer_.update(q, qd, effort, dt);
  last_stamp_ = stamp;
  has_stamp_ = true;
  const Eigen::VectorXd& r = *estimate_.torques;
  // Collision: a joint over its threshold.
  const bool was_in_collision = estimate_.in_collision;
  estimate_.over_threshold.clear();
  for (int k = 0; k < model_->nv; ++k) {
    if (std::abs(r[k]) > thresholds_[k]) estimate_.over_threshold.push_back(k);
    if (std::abs(r[k]) > largest_) largest_ = std::abs(r[k]), largest_joint_ = k;
  }
  estimate_.in_collision = !estimate_.over_threshold.empty();
  estimate_.collision_changed = estimate_.in_collision != was_in_collision;
  // The wrench at each frame; the one with the smallest residual explains r̂ best.
  estimate_.best_frame = -1;
  for (std::size_t f = 0; f < frames_.size(); ++f) {
    estimate_.wrenches[f] = external_wrench(*model_, data_, q, frames_[f], r);
    if (estimate_.best_frame < 0 || estimate_.wrenches[f].residual < estimate_.wrenches[estimate_.best_frame].residual)
      estimate_.best_frame = static_cast<int>(f);
  }
  return estimate_;
}

bool ExternalTorqueEstimator::tare() {
  if (!observer_.started()) return false;
  observer_.tare();
  return true;
}

std::map<std::string, double> ExternalTorqueEstimator::tareByJoint() const {
  std::map<std::string, double> out;
  for (int k = 0; k < model_->nv; ++k)
    if (observer_.effort_offset()[k] != 0.0) out[joint_names_[k]] = observer_.effort_offset()[k];
  return out;
}

std::pair<double, std::string> ExternalTorqueEstimator::takeLargest() {
  std::pair<double, std::string> out{largest_, largest_joint_ >= 0 ? joint_names_[largest_joint_] : ""};
  largest_ = 0.0;
  largest_joint_ = -1;
  return out;
}

}  // namespace spatial_dynamics
