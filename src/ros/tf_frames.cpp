#include "spatial_dynamics/ros/tf_frames.hpp"

#include <stdexcept>

#include <tf2/exceptions.h>

namespace spatial_dynamics {

bool TfFrames::hasFrame(const std::string& frame) const { return buffer_._frameExists(frame); }

PluckerTransform<double> TfFrames::transform(const std::string& target, const std::string& source,
                                             const ros::Time& stamp) const {
  geometry_msgs::TransformStamped t;
  try {
    t = buffer_.lookupTransform(target, source, stamp, ros::Duration(0.1));
  } catch (const tf2::TransformException& e) {
    throw std::runtime_error("tf2 cannot transform from '" + source + "' to '" + target + "': " + e.what());
  }
  // t is the pose of `source` in `target`; FromPose gives ^{source}X_{target}.
  const Eigen::Quaterniond rotation(t.transform.rotation.w, t.transform.rotation.x, t.transform.rotation.y,
                                    t.transform.rotation.z);
  const Eigen::Vector3d translation(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z);
  return PluckerTransform<double>::FromPose(rotation.normalized().toRotationMatrix(), translation).inverse();
}

}  // namespace spatial_dynamics
