// External wrenches from Python: {frame or link name: (τx, τy, τz, fx, fy, fz)}, each a wrench in
// that frame's coordinates about its origin, turned into forces on the bodies (body coordinates)
// as the node does for its requests: f_B += ^FX_Bᵀ f_F (PluckerTransform::applyInverse, eq. 12).
#pragma once

#include <pybind11/pybind11.h>

#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"

namespace spatial_dynamics {
namespace python {

/// Fills f_ext (one entry per body, zeroed first) from `wrenches` (a dict; None: no wrench).
/// Returns whether any was given; throws std::invalid_argument naming the frame on an unknown
/// frame, a wrong length or a non-finite entry.
bool decode_external_wrenches(const Model<double>& model, const pybind11::handle& wrenches,
                              std::vector<ForceVector<double>>& f_ext);

}  // namespace python
}  // namespace spatial_dynamics
