// The latest position and velocity of every model joint, merged by name from joint_states
// messages that may each carry only some joints (several publishers, any order). Thread-safe.
// ROS-free: it takes plain vectors, so it is tested without a master.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace spatial_dynamics {

class JointStateCache {
 public:
  struct Snapshot {
    Eigen::VectorXd position;
    Eigen::VectorXd velocity;            // zero for a joint whose publisher sends no velocity
    std::vector<char> position_known;    // per joint: a position has been received
    std::vector<char> velocity_known;    // per joint: a velocity has been received
    std::vector<double> received;        // per joint: when its last value arrived (steady clock, s)
    double now = 0;                      // when the snapshot was taken (steady clock, s)
    double max_age = 0;                  // the cache's age limit for values taken from it (s)
    bool complete = false;               // every joint's position is known
  };

  /// What a message naming a joint the model does not have gets.
  enum class UnknownJoints {
    kDrop,    // the whole message is dropped (the previous state stays)
    kIgnore,  // the unknown names are skipped and the model's joints of the message merged
  };

  /// `joint_names` in the model's joint order; values older than `max_age_seconds` are stale.
  explicit JointStateCache(std::vector<std::string> joint_names,
                           double max_age_seconds = std::numeric_limits<double>::infinity(),
                           UnknownJoints unknown_joints = UnknownJoints::kDrop);

  /// The steady clock the cache stamps values with, in seconds.
  static double steadyNow();

  /// Merges one message. Returns an empty string when it was merged, otherwise why it was
  /// dropped (mismatched lengths, a non-finite value, a duplicate name, with kDrop a name the
  /// model does not have); the previous state stays. With kIgnore, names the model does not have
  /// are skipped and listed in `unknown_names`.
  std::string update(const std::vector<std::string>& names, const std::vector<double>& positions,
                     const std::vector<double>& velocities, std::vector<std::string>* unknown_names = nullptr);

  /// Copies the current state (buffers in `out` are reused).
  void snapshot(Snapshot& out) const;

  bool complete() const;
  const std::vector<std::string>& jointNames() const { return names_; }

 private:
  const std::vector<std::string> names_;
  const double max_age_;
  const UnknownJoints unknown_joints_;
  std::unordered_map<std::string, int> index_;
  mutable std::mutex mutex_;
  Snapshot state_;
  int known_positions_ = 0;
};

}  // namespace spatial_dynamics
