#include "spatial_dynamics/ros/joint_state_recorder.hpp"

#include <utility>

namespace spatial_dynamics {

bool JointStateRecorder::start() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (recording_) return false;
  streams_.clear();
  without_effort_ = not_later_ = 0;
  recording_ = true;
  return true;
}

void JointStateRecorder::add(const sensor_msgs::JointState& msg) {
  if (!recording_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!recording_) return;
  const std::size_t n = msg.name.size();
  if (n == 0 || msg.position.size() != n || msg.velocity.size() != n || msg.effort.size() != n) {
    ++without_effort_;
    return;
  }
  Stream& stream = streams_[msg.name];
  if (stream.samples.points.empty()) {
    stream.samples.joint_names = msg.name;
    stream.first = msg.header.stamp;
  } else if (!(msg.header.stamp > stream.last)) {
    ++not_later_;
    return;
  }
  stream.last = msg.header.stamp;
  trajectory_msgs::JointTrajectoryPoint point;
  point.positions = msg.position;
  point.velocities = msg.velocity;
  point.effort = msg.effort;
  point.time_from_start = msg.header.stamp - stream.first;
  stream.samples.points.push_back(std::move(point));
}

JointStateRecorder::Recording JointStateRecorder::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  recording_ = false;
  Recording out;
  out.without_effort = without_effort_;
  out.not_later = not_later_;
  const Stream* best = nullptr;
  std::size_t kept = 0;
  for (const auto& [names, stream] : streams_) {
    kept += stream.samples.points.size();
    if (!best || names.size() > best->samples.joint_names.size() ||
        (names.size() == best->samples.joint_names.size() && stream.samples.points.size() > best->samples.points.size()))
      best = &stream;
  }
  if (best) out.samples = best->samples;
  out.other_joints = kept - out.samples.points.size();
  streams_.clear();
  return out;
}

}  // namespace spatial_dynamics
