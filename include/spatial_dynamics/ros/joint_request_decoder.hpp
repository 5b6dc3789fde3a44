// Turns the joint arrays of a service request into full vectors in the model's joint order.
// Arrays follow the request's `name` when it is non-empty, else the model's order (and then must
// have the model's length); an empty array means "left out". Joints left out take the latest
// joint state (position, velocity) or zero (acceleration, effort). Every error names the field
// and the joint. The model may be a reduced one: its joints are looked up by name in the cache of
// the full robot's joint states. ROS-free: it takes plain vectors, so it is tested without a master.
#pragma once

#include <Eigen/Core>
#include <string>
#include <unordered_map>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/ros/joint_state_cache.hpp"

namespace spatial_dynamics {

class JointRequestDecoder {
 public:
  /// What a joint left out of a request takes.
  enum class Default { LatestPosition, LatestVelocity, Zero };

  /// The coordinates of `model`'s joints (one per joint with a coordinate of its own; a floating
  /// base's free root joint is not one of them: its coordinates lead q and q̇, and the joints' are the
  /// last jointNames().size()), and where each joint sits in the joint-state cache's order.
  JointRequestDecoder(const Model<double>& model, const std::vector<std::string>& state_joint_names);

  /// Maps request names to joint indices; fails on an unknown or repeated name.
  std::string resolve(const std::vector<std::string>& names, std::vector<int>& indices) const;

  /// Fills `out` (model order) from `values`. `indices` come from resolve(names).
  std::string decode(const std::string& field, const std::vector<std::string>& names, const std::vector<int>& indices,
                     const std::vector<double>& values, Default fallback, const JointStateCache::Snapshot& state,
                     Eigen::VectorXd& out) const;

  /// "joint 'x' position 1.2 is outside its limits [a, b]" for every such joint ("" if none), of
  /// the joints' coordinates (q's last jointNames().size());
  /// an empty range (URDF lower = upper, e.g. both left at 0) counts as no limits.
  std::string limitWarnings(const Eigen::VectorXd& q) const;

  const std::vector<std::string>& jointNames() const { return names_; }
  /// Index of coordinate i in the joint-state cache.
  int stateIndex(int i) const { return state_index_[i]; }

 private:
  std::vector<std::string> names_;
  std::vector<int> state_index_;
  std::vector<double> lower_, upper_;
  std::unordered_map<std::string, int> index_;
};

}  // namespace spatial_dynamics
