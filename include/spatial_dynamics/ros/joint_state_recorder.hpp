// Records joint_states for ~identify_payload's record_seconds (doc/payload_identification.md): one
// recording at a time, fed every merged message by the joint-state pipeline. A message is kept when
// it carries positions, velocities and efforts for its joints, stamped after the previous kept one
// with the same joints; the recording is the set of joints with the most names (then the most
// messages), and the messages of other sets are counted. Thread-safe; while nothing records a
// message costs one atomic load.
#pragma once

#include <atomic>
#include <cstddef>
#include <mutex>
#include <map>
#include <string>
#include <vector>

#include <sensor_msgs/JointState.h>
#include <trajectory_msgs/JointTrajectory.h>

namespace spatial_dynamics {

class JointStateRecorder {
 public:
  struct Recording {
    trajectory_msgs::JointTrajectory samples;  // time_from_start from the first kept stamp
    std::size_t without_effort = 0;            // messages lacking velocity or effort for their joints
    std::size_t other_joints = 0;              // kept messages of other joint sets than the recording's
    std::size_t not_later = 0;                 // messages stamped at or before the previous kept one
  };

  /// Starts a recording; false when one runs already.
  bool start();
  /// Adds `msg` to the recording in progress (none: nothing happens).
  void add(const sensor_msgs::JointState& msg);
  /// Ends the recording in progress and returns it.
  Recording finish();
  bool recording() const { return recording_; }

 private:
  std::atomic<bool> recording_{false};
  std::mutex mutex_;  // guards the members below
  struct Stream {  // the kept messages of one set of joints
    trajectory_msgs::JointTrajectory samples;
    ros::Time first, last;
  };
  std::map<std::vector<std::string>, Stream> streams_;
  std::size_t without_effort_ = 0, not_later_ = 0;
};

}  // namespace spatial_dynamics
