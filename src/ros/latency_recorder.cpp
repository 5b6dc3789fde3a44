#include "spatial_dynamics/ros/latency_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace spatial_dynamics {

LatencyRecorder::LatencyRecorder(std::size_t capacity) : ring_(capacity) {
  if (capacity == 0) throw std::invalid_argument("LatencyRecorder: capacity must be > 0");
}

void LatencyRecorder::record(double latency) {
  std::lock_guard<std::mutex> lock(mutex_);
  ring_[next_] = latency;
  next_ = (next_ + 1) % ring_.size();
  size_ = std::min(size_ + 1, ring_.size());
}

LatencyRecorder::Summary LatencyRecorder::summary() const {
  std::vector<double> sorted;
  {
    // Copy under the lock and sort outside it, so that record() never waits for a sort.
    std::lock_guard<std::mutex> lock(mutex_);
    sorted.assign(ring_.begin(), ring_.begin() + static_cast<std::ptrdiff_t>(size_));
  }
  Summary s;
  s.count = static_cast<long>(sorted.size());
  if (sorted.empty()) return s;
  std::sort(sorted.begin(), sorted.end());
  const auto rank = [&](double p) {  // nearest rank, 1-based ⌈p·n⌉
    const auto r = static_cast<std::size_t>(std::ceil(p * static_cast<double>(sorted.size())));
    return sorted[std::max<std::size_t>(r, 1) - 1];
  };
  s.p50 = rank(0.50);
  s.p99 = rank(0.99);
  s.max = sorted.back();
  return s;
}

}  // namespace spatial_dynamics
