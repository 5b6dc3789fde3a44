// The module spatial_dynamics.dynamics: the library's algorithms on a URDF model, numpy in and out.
// Errors of the library and of the argument checks (which name the argument, joint or frame)
// raise ValueError with their messages.
#include <pybind11/pybind11.h>

#include <stdexcept>

#include "algorithm_bindings.hpp"
#include "bound_model.hpp"
#include "model_bindings.hpp"
#include "spatial_dynamics/simd_backend.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

namespace py = pybind11;
using spatial_dynamics::python::BoundModel;

PYBIND11_MODULE(dynamics, m) {
  m.doc() = "Rigid-body dynamics of URDF robots (the spatial_dynamics library's compiled double instances).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::out_of_range& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::domain_error& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const spatial_dynamics::ModelError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  py::class_<BoundModel, std::shared_ptr<BoundModel>> model(
      m, "Model",
      "A robot model (immutable). Its methods may be called from several threads at once: each call computes in\n"
      "a workspace of its own, with the GIL released.");
  spatial_dynamics::python::def_model(model);
  spatial_dynamics::python::def_algorithms(model);
  m.def("simd_backend", &spatial_dynamics::simd_backend,
        "'avx2_fma' or 'portable': the build of the library's double instances this process runs.");
}
