// Size checks shared by the algorithms: a wrong-length vector is an error that says which
// argument and what length was expected, never an out-of-bounds read.
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

}  // namespace detail
}  // namespace spatial_dynamics
