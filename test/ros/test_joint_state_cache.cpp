// JointStateCache without a master: partial messages merge by name, malformed messages are
// dropped whole with the reason, and a name the model does not have is dropped or skipped as the
// policy says.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "spatial_dynamics/ros/joint_state_cache.hpp"

namespace sd = spatial_dynamics;

namespace {

const std::vector<std::string> kJoints = {"a", "b", "c"};

sd::JointStateCache::Snapshot state_of(const sd::JointStateCache& cache) {
  sd::JointStateCache::Snapshot s;
  cache.snapshot(s);
  return s;
}

}  // namespace

TEST(JointStateCache, PartialMessagesMergeByNameInAnyOrder) {
  sd::JointStateCache cache(kJoints);
  EXPECT_EQ(cache.update({"c", "a"}, {3.0, 1.0}, {}), "");
  EXPECT_FALSE(cache.complete());
  EXPECT_EQ(cache.update({"b"}, {2.0}, {-2.0}), "");
  ASSERT_TRUE(cache.complete());
  const auto s = state_of(cache);
  EXPECT_EQ(s.position[0], 1.0);
  EXPECT_EQ(s.position[1], 2.0);
  EXPECT_EQ(s.position[2], 3.0);
  EXPECT_EQ(s.velocity[1], -2.0);
  EXPECT_FALSE(s.velocity_known[0]);
  EXPECT_TRUE(s.velocity_known[1]);
}

TEST(JointStateCache, MalformedMessagesAreDroppedWholeNamingTheProblem) {
  sd::JointStateCache cache(kJoints);
  ASSERT_EQ(cache.update(kJoints, {1.0, 2.0, 3.0}, {0.1, 0.2, 0.3}), "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(cache.update(kJoints, {9.0, 9.0}, {}), "position has 2 entries but name has 3");
  EXPECT_EQ(cache.update(kJoints, {9.0, 9.0, 9.0}, {1.0}), "velocity has 1 entries but name has 3");
  EXPECT_EQ(cache.update({"a", "b", "a"}, {9.0, 9.0, 9.0}, {}), "joint 'a' appears twice");
  EXPECT_EQ(cache.update(kJoints, {9.0, nan, 9.0}, {}), "position of joint 'b' is not finite");
  EXPECT_EQ(cache.update(kJoints, {9.0, 9.0, 9.0}, {0.0, 0.0, -std::numeric_limits<double>::infinity()}),
            "velocity of joint 'c' is not finite");
  const auto s = state_of(cache);
  EXPECT_EQ(s.position[0], 1.0);
  EXPECT_EQ(s.position[1], 2.0);
  EXPECT_EQ(s.position[2], 3.0);
  EXPECT_EQ(s.velocity[2], 0.3);
}

TEST(JointStateCache, AnUnknownNameDropsTheMessageByDefault) {
  sd::JointStateCache cache(kJoints);
  ASSERT_EQ(cache.update(kJoints, {1.0, 2.0, 3.0}, {}), "");
  std::vector<std::string> unknown;
  EXPECT_EQ(cache.update({"a", "gripper"}, {7.0, 0.5}, {}, &unknown),
            "joint 'gripper' is not a joint of the robot model");
  EXPECT_TRUE(unknown.empty());
  EXPECT_EQ(state_of(cache).position[0], 1.0);
}

TEST(JointStateCache, WithIgnoreAnUnknownNameIsSkippedAndListed) {
  sd::JointStateCache cache(kJoints, 1.0, sd::JointStateCache::UnknownJoints::kIgnore);
  std::vector<std::string> unknown;
  EXPECT_EQ(cache.update({"a", "gripper", "b", "c"}, {7.0, 0.5, 8.0, 9.0}, {}, &unknown), "");
  ASSERT_EQ(unknown, std::vector<std::string>{"gripper"});
  const auto s = state_of(cache);
  EXPECT_EQ(s.position[0], 7.0);
  EXPECT_EQ(s.position[1], 8.0);
  EXPECT_EQ(s.position[2], 9.0);
  EXPECT_TRUE(cache.complete());
}

TEST(JointStateCache, ValuesAreStampedForTheAgeLimit) {
  sd::JointStateCache cache(kJoints, 0.25);
  const double before = sd::JointStateCache::steadyNow();
  ASSERT_EQ(cache.update(kJoints, {1.0, 2.0, 3.0}, {}), "");
  const auto s = state_of(cache);
  EXPECT_EQ(s.max_age, 0.25);
  for (double t : s.received) {
    EXPECT_GE(t, before);
    EXPECT_LE(t, s.now);
  }
}
