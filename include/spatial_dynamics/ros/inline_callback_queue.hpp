// A callback queue that runs each callback at once, in the thread that adds it: for a subscription,
// roscpp's receiving thread. It saves the hand-over to a spinner thread (a condition-variable
// wake-up, tens of µs) on the joint_states → ~computed_torques path.
//
// The callback runs while roscpp holds that subscription's lock, so it must not subscribe to or
// unsubscribe from the same topic, and it delays the receiving thread's other reads while it runs:
// use it only for short callbacks. A callback that cannot run now (TryAgain: another thread is in
// it) goes to the fallback queue, which a spinner of the owner's serves; nothing is dropped.
#pragma once

#include <cstdint>

#include <ros/callback_queue.h>
#include <ros/callback_queue_interface.h>

namespace spatial_dynamics {

class InlineCallbackQueue : public ros::CallbackQueueInterface {
 public:
  void addCallback(const ros::CallbackInterfacePtr& callback, uint64_t owner_id) override;
  void removeByID(uint64_t owner_id) override;

  /// Where callbacks that could not run inline wait; serve it with a ros::AsyncSpinner.
  ros::CallbackQueue& fallback() { return fallback_; }

 private:
  ros::CallbackQueue fallback_;
};

}  // namespace spatial_dynamics
