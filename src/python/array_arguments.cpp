#include "array_arguments.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace spatial_dynamics {
namespace python {

InputArray checked_vector(const char* name, const py::handle& value, const std::vector<std::string>& coordinates) {
  if (value.is_none()) throw std::invalid_argument(std::string(name) + " is None; expected an array of floats");
  InputArray a;
  try {
    a = InputArray::ensure(value);
  } catch (const py::error_already_set&) {
    a = InputArray();
  }
  if (!a) {
    PyErr_Clear();
    throw std::invalid_argument(std::string(name) + " is not an array of floats");
  }
  if (a.ndim() != 1)
    throw std::invalid_argument(std::string(name) + " has " + std::to_string(a.ndim()) +
                                " dimensions; expected a 1-D array");
  const auto expected = static_cast<py::ssize_t>(coordinates.size());
  if (a.shape(0) != expected)
    throw std::invalid_argument(std::string(name) + " has " + std::to_string(a.shape(0)) +
                                " entries; the model expects " + std::to_string(expected));
  const double* x = a.data();
  for (py::ssize_t k = 0; k < expected; ++k)
    if (!std::isfinite(x[k]))
      throw std::invalid_argument(std::string(name) + "[" + std::to_string(k) + "] ('" + coordinates[k] +
                                  "') is not finite");
  return a;
}

py::array_t<double> new_vector(Eigen::Index n) { return py::array_t<double>(static_cast<py::ssize_t>(n)); }

py::array_t<double> new_matrix(Eigen::Index rows, Eigen::Index cols) {
  return py::array_t<double>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
}

void copy_into(double* out, const Eigen::VectorXd& v) {
  if (v.size() > 0) std::memcpy(out, v.data(), sizeof(double) * static_cast<std::size_t>(v.size()));
}

}  // namespace python
}  // namespace spatial_dynamics
