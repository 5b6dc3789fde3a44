// Model.from_urdf, the model's sizes and names, and the reduced models (reduce, lock).
#pragma once

#include <pybind11/pybind11.h>

#include <memory>

#include "bound_model.hpp"

namespace spatial_dynamics {
namespace python {

void def_model(pybind11::class_<BoundModel, std::shared_ptr<BoundModel>>& cls);

}  // namespace python
}  // namespace spatial_dynamics
