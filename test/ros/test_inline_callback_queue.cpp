// InlineCallbackQueue: a callback runs in the adding thread; one that cannot run now waits in the
// fallback queue, in order, and is removed with its owner.
#include <gtest/gtest.h>

#include <boost/make_shared.hpp>
#include <thread>
#include <vector>

#include "spatial_dynamics/ros/inline_callback_queue.hpp"

namespace {

/// Records the thread it ran in; answers TryAgain the first `refusals` times.
class RecordingCallback : public ros::CallbackInterface {
 public:
  RecordingCallback(int id, std::vector<int>& order, int refusals = 0) : id_(id), order_(order), refusals_(refusals) {}
  CallResult call() override {
    if (refusals_ > 0) {
      --refusals_;
      return TryAgain;
    }
    thread_ = std::this_thread::get_id();
    order_.push_back(id_);
    return Success;
  }
  std::thread::id thread() const { return thread_; }

 private:
  int id_;
  std::vector<int>& order_;
  int refusals_;
  std::thread::id thread_;
};

TEST(InlineCallbackQueue, RunsTheCallbackInTheAddingThread) {
  spatial_dynamics::InlineCallbackQueue queue;
  std::vector<int> order;
  auto first = boost::make_shared<RecordingCallback>(1, order);
  auto second = boost::make_shared<RecordingCallback>(2, order);
  std::thread adder([&] {
    queue.addCallback(first, 7);
    queue.addCallback(second, 7);
  });
  const std::thread::id adder_id = adder.get_id();
  adder.join();
  EXPECT_EQ(order, (std::vector<int>{1, 2}));
  EXPECT_EQ(first->thread(), adder_id);
  EXPECT_EQ(second->thread(), adder_id);
  EXPECT_TRUE(queue.fallback().empty());
}

TEST(InlineCallbackQueue, ACallbackThatMustWaitGoesToTheFallbackQueue) {
  spatial_dynamics::InlineCallbackQueue queue;
  std::vector<int> order;
  auto busy = boost::make_shared<RecordingCallback>(1, order, 1);
  queue.addCallback(busy, 7);
  EXPECT_TRUE(order.empty());
  ASSERT_FALSE(queue.fallback().empty());
  queue.fallback().callAvailable();
  EXPECT_EQ(order, (std::vector<int>{1}));
  EXPECT_TRUE(queue.fallback().empty());
}

TEST(InlineCallbackQueue, RemovingTheOwnerDropsItsWaitingCallbacks) {
  spatial_dynamics::InlineCallbackQueue queue;
  std::vector<int> order;
  queue.addCallback(boost::make_shared<RecordingCallback>(1, order, 1), 7);
  queue.addCallback(boost::make_shared<RecordingCallback>(2, order, 1), 8);
  queue.removeByID(7);
  queue.fallback().callAvailable();
  EXPECT_EQ(order, (std::vector<int>{2}));
}

}  // namespace
