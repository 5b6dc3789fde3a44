// LatencyRecorder: nearest-rank percentiles over the most recent events only.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "spatial_dynamics/ros/latency_recorder.hpp"

namespace sd = spatial_dynamics;

TEST(LatencyRecorder, NearestRankPercentilesOfAShuffledSequence) {
  std::vector<double> values(200);
  for (int k = 0; k < 200; ++k) values[k] = k + 1;  // 1 .. 200
  std::mt19937 rng(7);
  std::shuffle(values.begin(), values.end(), rng);
  sd::LatencyRecorder recorder(1000);
  EXPECT_EQ(recorder.summary().count, 0);
  for (double v : values) recorder.record(v);
  const auto s = recorder.summary();
  EXPECT_EQ(s.count, 200);
  EXPECT_EQ(s.p50, 100.0);  // ⌈0.5·200⌉ = 100th smallest
  EXPECT_EQ(s.p99, 198.0);  // ⌈0.99·200⌉ = 198th smallest
  EXPECT_EQ(s.max, 200.0);
}

TEST(LatencyRecorder, OnlyTheMostRecentEventsCount) {
  sd::LatencyRecorder recorder(10);
  for (int k = 0; k < 10; ++k) recorder.record(1000.0);  // pushed out below
  for (int k = 1; k <= 10; ++k) recorder.record(k);
  const auto s = recorder.summary();
  EXPECT_EQ(s.count, 10);
  EXPECT_EQ(s.max, 10.0);
  EXPECT_EQ(s.p50, 5.0);
  EXPECT_EQ(s.p99, 10.0);
  EXPECT_THROW(sd::LatencyRecorder(0), std::invalid_argument);
}
