// Frames outside the robot model, from tf2: used for poses only (tf2's own wrench transform in
// ROS 1 drops the r × f moment).
#pragma once

#include <string>

#include <tf2_ros/buffer.h>

#include "spatial_dynamics/ros/service_handlers.hpp"

namespace spatial_dynamics {

class TfFrames : public FrameLookup {
 public:
  explicit TfFrames(const tf2_ros::Buffer& buffer) : buffer_(buffer) {}
  bool hasFrame(const std::string& frame) const override;
  PluckerTransform<double> transform(const std::string& target, const std::string& source,
                                     const ros::Time& stamp) const override;

 private:
  const tf2_ros::Buffer& buffer_;
};

}  // namespace spatial_dynamics
