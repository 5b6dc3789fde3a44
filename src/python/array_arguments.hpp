// numpy arguments and results: a 1-D float64 argument is checked (dimension, length, finite
// entries, each error naming the argument and the coordinate) and read in place; results are new
// arrays, copies of the workspace's.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include <Eigen/Core>

namespace spatial_dynamics {
namespace python {

namespace py = pybind11;

/// A float64 array (lists and other dtypes converted; no copy for a contiguous float64 array).
using InputArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The array `value` as argument `name`: 1-D, one entry per name in `coordinates`, all finite.
/// Throws std::invalid_argument naming `name` (and the coordinate) otherwise.
InputArray checked_vector(const char* name, const py::handle& value, const std::vector<std::string>& coordinates);

/// A read-only view of a checked array (valid while the array lives).
inline Eigen::Map<const Eigen::VectorXd> view(const InputArray& a) {
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

/// New result arrays (allocated with the GIL held, filled without it).
py::array_t<double> new_vector(Eigen::Index n);
py::array_t<double> new_matrix(Eigen::Index rows, Eigen::Index cols);

/// Copies into the storage of a result array (taken with the GIL held), row-major as numpy's default layout.
void copy_into(double* out, const Eigen::VectorXd& v);
template <class Derived>
void copy_matrix_into(double* out, const Eigen::MatrixBase<Derived>& m) {
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out, m.rows(), m.cols()) = m;
}

}  // namespace python
}  // namespace spatial_dynamics
