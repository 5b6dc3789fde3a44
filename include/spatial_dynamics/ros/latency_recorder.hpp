// Latencies of the most recent events (a ring of fixed capacity, allocated once), with their
// percentiles: the node records how long each joint_states message took from its arrival to its
// ~computed_torques messages. Thread-safe; ROS-free.
#pragma once

#include <cstddef>
#include <mutex>
#include <vector>

namespace spatial_dynamics {

class LatencyRecorder {
 public:
  struct Summary {
    long count = 0;  // events in the window (at most the capacity)
    double p50 = 0, p99 = 0, max = 0;
  };

  explicit LatencyRecorder(std::size_t capacity);

  /// Records one latency (any unit; the summary is in the same unit).
  void record(double latency);

  /// Percentiles of the window by the nearest-rank method (p-th: the ⌈p·n⌉-th smallest). Copies the
  /// window (allocates); meant for a diagnostics thread, not the recording one.
  Summary summary() const;

 private:
  mutable std::mutex mutex_;
  std::vector<double> ring_;
  std::size_t next_ = 0;
  std::size_t size_ = 0;
};

}  // namespace spatial_dynamics
