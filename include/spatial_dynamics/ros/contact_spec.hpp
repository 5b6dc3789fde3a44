// The node's contacts as configured (~contacts) or set at run time (~set_contacts): names, not yet
// resolved against a model (each scene builds its ContactSet from them, model/contact_set.hpp).
#pragma once

#include <string>
#include <vector>

namespace spatial_dynamics {

struct ContactSpec {
  std::vector<std::string> frames;
  std::vector<std::string> kinds;   // point | surface
  std::vector<double> frictions;    // empty, or μ per frame (0: no cone checked)
};

}  // namespace spatial_dynamics
