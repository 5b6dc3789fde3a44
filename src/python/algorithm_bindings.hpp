// Model.rnea, aba, aba_refined, crba, gravity_torques, nonlinear_effects, frame_jacobian.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>

#include "bound_model.hpp"

namespace spatial_dynamics {
namespace python {

void def_algorithms(pybind11::class_<BoundModel, std::shared_ptr<BoundModel>>& cls);

}  // namespace python
}  // namespace spatial_dynamics
