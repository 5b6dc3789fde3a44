// Checks shared by the algorithms: a wrong-length vector is an error that says which argument
// and what length was expected, never an out-of-bounds read; a non-finite result is an error
// that names the first coordinate concerned, never a return value.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {

namespace detail {
template <class T>
struct NonDeduced {
  using type = T;
};
}  // namespace detail

/// A read-only view of a vector argument. The scalar is deduced from the Model, never from
/// the view, so plain VectorX<S>, segments and maps can all be passed without a copy.
template <class S>
using ConstVectorRef = typename detail::NonDeduced<Eigen::Ref<const VectorX<S>>>::type;

namespace detail {

inline void check_length(const char* what, Eigen::Index actual, int expected) {
  if (actual != expected)
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(actual) +
                                " entries; the model expects " + std::to_string(expected));
}

template <class S>
void check_external_forces(const Model<S>& model, const std::vector<ForceVector<S>>& f_ext) {
  if (static_cast<int>(f_ext.size()) != model.nbodies())
    throw std::invalid_argument("external forces: " + std::to_string(f_ext.size()) +
                                " given; the model expects one per body (" +
                                std::to_string(model.nbodies()) + ")");
}

inline const char* non_finite_reason() {
  return " is not finite: an input or a model parameter is not finite, or so large that the computation overflows";
}

/// `what` (+ " for '<coordinate>'") is not finite: std::domain_error. Only on the error path.
template <class S>
[[noreturn]] void throw_non_finite(const Model<S>& model, const char* what, Eigen::Index coordinate) {
  std::string where;
  if (coordinate >= 0) {
    const std::vector<std::string> names = model.velocityNames();
    if (coordinate < static_cast<Eigen::Index>(names.size())) where = " for '" + names[coordinate] + "'";
  }
  throw std::domain_error(std::string(what) + where + non_finite_reason());
}

/// A result indexed by velocity coordinate — a vector (τ, q̈) or a matrix by column (M, J) —
/// must be finite: with finite inputs a non-finite entry is an overflow, and it is reported
/// (naming the first coordinate concerned) rather than returned.
template <class S, class Derived>
void check_finite_result(const Model<S>& model, const char* what, const Eigen::DenseBase<Derived>& x) {
  // x − x is 0 for a finite entry and NaN otherwise, and a NaN survives the sum: one vectorised
  // reduction instead of a test per entry.
  if ((x.derived().array() - x.derived().array()).sum() == S(0)) return;
  Eigen::Index coordinate = -1;
  if (x.cols() == 1) {
    for (Eigen::Index k = 0; k < x.rows() && coordinate < 0; ++k)
      if (!x.row(k).allFinite()) coordinate = k;
  } else {
    for (Eigen::Index k = 0; k < x.cols() && coordinate < 0; ++k)
      if (!x.col(k).allFinite()) coordinate = k;
  }
  throw_non_finite(model, what, coordinate);
}

/// The same for a value not tied to a coordinate (an energy, a momentum).
template <class S, class Derived>
void check_finite_value(const Model<S>& model, const char* what, const Eigen::DenseBase<Derived>& x) {
  if (!x.allFinite()) throw_non_finite(model, what, -1);
}

}  // namespace detail
}  // namespace spatial_dynamics
