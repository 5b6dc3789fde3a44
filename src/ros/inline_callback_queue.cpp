#include "spatial_dynamics/ros/inline_callback_queue.hpp"

namespace spatial_dynamics {

void InlineCallbackQueue::addCallback(const ros::CallbackInterfacePtr& callback, uint64_t owner_id) {
  if (callback->ready() && callback->call() != ros::CallbackInterface::TryAgain) return;
  fallback_.addCallback(callback, owner_id);
}

void InlineCallbackQueue::removeByID(uint64_t owner_id) { fallback_.removeByID(owner_id); }

}  // namespace spatial_dynamics
