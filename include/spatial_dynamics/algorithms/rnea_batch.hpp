// Inverse dynamics of many states of one model: τ_k = ID(q_k, q̇_k, q̈_k) for the columns k of a
// trajectory, each through the one-state RNEA of rnea.hpp (RBDA Table 5.1) in the workspace's Data.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include "spatial_dynamics/algorithms/input_checks.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"
#include "spatial_dynamics/compiled/compiled_functions.hpp"
#include "spatial_dynamics/model/batch_data.hpp"
#include "spatial_dynamics/model/model.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {

/// Read-only and writable views of a matrix argument (states as columns); the scalar is deduced
/// from the Model. Any matrix or block of columns with contiguous columns binds without a copy.
template <class S>
using ConstMatrixRef = typename detail::NonDeduced<Eigen::Ref<const MatrixX<S>>>::type;
template <class S>
using MatrixRef = typename detail::NonDeduced<Eigen::Ref<MatrixX<S>>>::type;

namespace detail {

/// "state k: " in front of an error's message.
inline std::string at_state(Eigen::Index k, const std::string& message) {
  return "state " + std::to_string(k) + ": " + message;
}

}  // namespace detail

/// τ(:, k) = ID(q(:, k), q̇(:, k), q̈(:, k)) for every column k: q is nq × N, q̇ and q̈ nv × N, τ
/// nv × N (sized by the caller; N may be 0): rnea's numbers for each state. Errors as rnea's, their
/// message starting with "state k: ". No allocation.
template <class S, int L>
void rnea_batch(const Model<S>& model, BatchData<S, L>& data, const ConstMatrixRef<S>& q, const ConstMatrixRef<S>& qd,
                const ConstMatrixRef<S>& qdd, MatrixRef<S> tau) {
  detail::check_length("q (rows)", q.rows(), model.nq);
  detail::check_length("velocity (rows)", qd.rows(), model.nv);
  detail::check_length("acceleration (rows)", qdd.rows(), model.nv);
  detail::check_length("tau (rows)", tau.rows(), model.nv);
  const Eigen::Index n = q.cols();
  for (const auto& [what, cols] : {std::pair<const char*, Eigen::Index>{"velocity", qd.cols()},
                                   {"acceleration", qdd.cols()}, {"tau", tau.cols()}})
    if (cols != n)
      throw std::invalid_argument(std::string(what) + " has " + std::to_string(cols) + " columns (states); q has " +
                                  std::to_string(n));
  if (static_cast<int>(data.single.X_up.size()) != model.nbodies() || data.single.tau.size() != model.nv)
    throw std::invalid_argument("the batch workspace was made for another model");

  for (Eigen::Index c = 0; c < n; ++c) {
    try {
      tau.col(c) = rnea<S>(model, data.single, q.col(c), qd.col(c), qdd.col(c));
    } catch (const std::domain_error& e) {
      throw std::domain_error(detail::at_state(c, e.what()));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(detail::at_state(c, e.what()));
    }
  }
}

}  // namespace spatial_dynamics
