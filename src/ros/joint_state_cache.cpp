#include "spatial_dynamics/ros/joint_state_cache.hpp"

#include <chrono>
#include <cmath>
#include <unordered_set>

namespace spatial_dynamics {

double JointStateCache::steadyNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

JointStateCache::JointStateCache(std::vector<std::string> joint_names, double max_age_seconds,
                                 UnknownJoints unknown_joints)
    : names_(std::move(joint_names)), max_age_(max_age_seconds), unknown_joints_(unknown_joints) {
  for (int i = 0; i < static_cast<int>(names_.size()); ++i) index_[names_[i]] = i;
  const int n = static_cast<int>(names_.size());
  state_.position = Eigen::VectorXd::Zero(n);
  state_.velocity = Eigen::VectorXd::Zero(n);
  state_.position_known.assign(n, 0);
  state_.velocity_known.assign(n, 0);
  state_.received.assign(n, 0.0);
  state_.max_age = max_age_;
  state_.complete = n == 0;
}

std::string JointStateCache::update(const std::vector<std::string>& names, const std::vector<double>& positions,
                                    const std::vector<double>& velocities, std::vector<std::string>* unknown_names) {
  // Validate the whole message before touching the state.
  if (positions.size() != names.size())
    return "position has " + std::to_string(positions.size()) + " entries but name has " + std::to_string(names.size());
  if (!velocities.empty() && velocities.size() != names.size())
    return "velocity has " + std::to_string(velocities.size()) + " entries but name has " + std::to_string(names.size());
  std::unordered_set<std::string> seen;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (!seen.insert(names[k]).second) return "joint '" + names[k] + "' appears twice";
    if (!std::isfinite(positions[k])) return "position of joint '" + names[k] + "' is not finite";
    if (!velocities.empty() && !std::isfinite(velocities[k])) return "velocity of joint '" + names[k] + "' is not finite";
    if (unknown_joints_ == UnknownJoints::kDrop && index_.count(names[k]) == 0)
      return "joint '" + names[k] + "' is not a joint of the robot model";
  }
  const double now = steadyNow();
  std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto it = index_.find(names[k]);
    if (it == index_.end()) {
      if (unknown_names) unknown_names->push_back(names[k]);
      continue;
    }
    const int i = it->second;
    if (!state_.position_known[i]) {
      state_.position_known[i] = 1;
      ++known_positions_;
    }
    state_.position[i] = positions[k];
    state_.received[i] = now;
    if (!velocities.empty()) {
      state_.velocity[i] = velocities[k];
      state_.velocity_known[i] = 1;
    }
  }
  state_.complete = known_positions_ == static_cast<int>(names_.size());
  return {};
}

void JointStateCache::snapshot(Snapshot& out) const {
  std::lock_guard<std::mutex> lock(mutex_);
  out.position = state_.position;
  out.velocity = state_.velocity;
  out.position_known = state_.position_known;
  out.velocity_known = state_.velocity_known;
  out.received = state_.received;
  out.now = steadyNow();
  out.max_age = max_age_;
  out.complete = state_.complete;
}

bool JointStateCache::complete() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_.complete;
}

}  // namespace spatial_dynamics
