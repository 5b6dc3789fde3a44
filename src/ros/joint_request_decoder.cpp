#include "spatial_dynamics/ros/joint_request_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace spatial_dynamics {

JointRequestDecoder::JointRequestDecoder(const Model<double>& model, const std::vector<std::string>& state_joint_names) {
  for (int i = 1; i < model.nbodies(); ++i) {
    const Joint<double>& j = model.joints[i];
    if (j.coupled) continue;  // follows its master: no coordinate of its own
    if (model.floating_base && i == 1) continue;  // the base's coordinates come with the base's state
    if (j.nq != j.nv)
      throw std::invalid_argument("joint '" + model.joint_names[i] + "': a free joint has " + std::to_string(j.nq) +
                                  " position and " + std::to_string(j.nv) +
                                  " velocity coordinates, which the services do not serve (the library does)");
    // One coordinate per name: the joint's own, or <joint>/x, /y, /yaw of a planar joint.
    for (const std::string& name : visit_joint(j, [&](auto joint) { return joint.velocity_names(model.joint_names[i]); })) {
      const auto it = std::find(state_joint_names.begin(), state_joint_names.end(), name);
      if (it == state_joint_names.end()) throw std::invalid_argument("joint '" + name + "' is not among the joint states");
      index_[name] = static_cast<int>(names_.size());
      names_.push_back(name);
      state_index_.push_back(static_cast<int>(it - state_joint_names.begin()));
      lower_.push_back(j.nv == 1 ? j.limits.position_lower : -std::numeric_limits<double>::infinity());
      upper_.push_back(j.nv == 1 ? j.limits.position_upper : std::numeric_limits<double>::infinity());
    }
  }
}

std::string JointRequestDecoder::resolve(const std::vector<std::string>& names, std::vector<int>& indices) const {
  indices.assign(names.size(), -1);
  std::vector<char> seen(names_.size(), 0);
  for (std::size_t k = 0; k < names.size(); ++k) {
    const auto it = index_.find(names[k]);
    if (it == index_.end()) return "unknown joint '" + names[k] + "'";
    if (seen[it->second]) return "joint '" + names[k] + "' is named twice";
    seen[it->second] = 1;
    indices[k] = it->second;
  }
  return {};
}

std::string JointRequestDecoder::decode(const std::string& field, const std::vector<std::string>& names,
                                        const std::vector<int>& indices, const std::vector<double>& values,
                                        Default fallback, const JointStateCache::Snapshot& state,
                                        Eigen::VectorXd& out) const {
  const int n = static_cast<int>(names_.size());
  out.resize(n);
  const bool by_name = !names.empty();
  if (!values.empty()) {
    const std::size_t expected = by_name ? names.size() : names_.size();
    if (values.size() != expected)
      return field + " has " + std::to_string(values.size()) + " entries but " +
             (by_name ? "name has " + std::to_string(names.size())
                      : "the model has " + std::to_string(n) + " joints (name is empty)");
    for (std::size_t k = 0; k < values.size(); ++k)
      if (!std::isfinite(values[k]))
        return field + " of joint '" + (by_name ? names[k] : names_[k]) + "' is not finite";
    if (!by_name) {
      out = Eigen::Map<const Eigen::VectorXd>(values.data(), n);
      return {};
    }
  }
  // Defaults for the joints the request leaves out, then the named values on top.
  std::vector<char> given(n, 0);
  if (!values.empty())
    for (std::size_t k = 0; k < values.size(); ++k) given[indices[k]] = 1;
  for (int i = 0; i < n; ++i) {
    if (given[i]) continue;
    switch (fallback) {
      case Default::Zero: out[i] = 0.0; break;
      case Default::LatestVelocity:
      case Default::LatestPosition: {
        const int s = state_index_[i];
        if (state.position_known.empty() || !state.position_known[s])
          return "no joint state yet for joint '" + names_[i] + "' (" + field + " not given in the request)";
        const double age = state.now - state.received[s];
        if (age > state.max_age) {
          std::ostringstream why;
          why << "the joint state of joint '" << names_[i] << "' is " << age << " s old, older than max_state_age ("
              << state.max_age << " s); give the " << field << " in the request or publish joint_states";
          return why.str();
        }
        out[i] = fallback == Default::LatestPosition ? state.position[s] : state.velocity[s];
        break;
      }
    }
  }
  for (std::size_t k = 0; k < values.size(); ++k) out[indices[k]] = values[k];
  return {};
}

std::string JointRequestDecoder::limitWarnings(const Eigen::VectorXd& full_q) const {
  const auto q = full_q.tail(names_.size());  // after a floating base's coordinates
  std::string warnings;  // stays empty (no formatting, no allocation) when every joint is in range
  for (int i = 0; i < static_cast<int>(names_.size()); ++i) {
    const bool has_range = upper_[i] > lower_[i];  // URDF's lower = upper = 0 means "not given"
    if (has_range && (q[i] < lower_[i] || q[i] > upper_[i])) {
      std::ostringstream warning;
      warning << "warning: joint '" << names_[i] << "' position " << q[i] << " is outside its limits [" << lower_[i]
              << ", " << upper_[i] << "]";
      if (!warnings.empty()) warnings += "; ";
      warnings += warning.str();
    }
  }
  return warnings;
}

}  // namespace spatial_dynamics
