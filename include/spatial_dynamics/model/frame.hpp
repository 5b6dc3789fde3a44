// A named frame rigidly attached to a body: every URDF link is one, including links merged
// into a body through fixed joints.
#pragma once

#include <string>

#include "spatial_dynamics/spatial/plucker_transform.hpp"

namespace spatial_dynamics {

template <class S>
struct Frame {
  std::string name;
  int body = 0;                          // the body the frame is fixed to
  PluckerTransform<S> X_frame_body;      // ^FX_B: from body coordinates to frame coordinates

  template <class T>
  Frame<T> cast() const {
    return {name, body, X_frame_body.template cast<T>()};
  }
};

}  // namespace spatial_dynamics
