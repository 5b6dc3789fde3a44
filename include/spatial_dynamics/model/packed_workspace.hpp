// The packed CRBA's own buffers (algorithms/crba_packed.hpp): per body, the state it keeps as
// packed 3-vectors' storage. One layout in every build (Packed3Storage); a
// Data<double> holds one, sized to the model, and other scalars an empty one.
#pragma once

#include <vector>

#include "spatial_dynamics/spatial/packed3.hpp"

namespace spatial_dynamics {

struct PackedWorkspace {
  // CRBA: the rows of ^iX_λ's rotation, its translation, the composite inertia, and for the
  // carry in base coordinates the rows of ^iX_0's rotation and its translation.
  struct CrbaBody {
    Packed3Storage t0, t1, t2, r, I0, I1, I2, h, base_t0, base_t1, base_t2, base_r;
    double mass;
  };
  std::vector<CrbaBody> crba;

  explicit PackedWorkspace(int nbodies) : crba(nbodies) {}
};

}  // namespace spatial_dynamics
