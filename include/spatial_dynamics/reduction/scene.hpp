// What a scene needs of a robot: the joints to keep, positions for the joints to lock, and
// the frames that must stay addressable (the reduction layer: doc/library.md).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace spatial_dynamics {

struct Scene {
  /// Joints that stay degrees of freedom. Every other 1-DoF joint is locked; free and planar
  /// joints always stay.
  std::vector<std::string> kept_joints;
  /// Positions of locked joints; a locked joint not listed here is locked at 0.
  std::map<std::string, double> locked_positions;
};

/// The common shorthand: keep the joints on the paths from `root_link` to each tip link; the
/// rest (including everything past the tips, which then rides on them as payload) is locked.
struct RootTipScene {
  std::string root_link;
  std::vector<std::string> tip_links;
  std::map<std::string, double> locked_positions;
};

}  // namespace spatial_dynamics
