// The node's ~external_torques/* parameters as read (node_config.cpp), before they are checked
// against a model (external_torque_estimator.hpp).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace spatial_dynamics {

/// ~external_torques/* as read (node_config.cpp), before they are checked against a model.
struct ExternalTorqueSettings {
  bool enabled = false;                        // ~external_torques/enabled
  std::string parameter = "~external_torques";  // its resolved name, for messages
  double gain = 50.0;                          // ~external_torques/gain: one number (1/s) for every joint,
  std::map<std::string, double> joint_gains;   //   or a map joint → number (joints not named: 50)
  bool frames_given = false;                   // ~external_torques/frames (default: the leaf links)
  std::vector<std::string> frames;
  bool detect_collisions = false;              // ~external_torques/collision_threshold given:
  double threshold = 0.0;                      //   one number for every joint, or
  std::map<std::string, double> joint_thresholds;  // a map joint → number (other joints: no threshold)
  double max_gap = 0.1;                        // ~external_torques/max_gap [s]
  std::string error;                           // the first malformed parameter ("" when none)
};

}  // namespace spatial_dynamics
