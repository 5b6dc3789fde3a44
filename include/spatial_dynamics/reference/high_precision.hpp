// The high-precision reference: the library instantiated with Boost.Multiprecision's float128
// (IEEE quadruple, 113-bit significand, ε ≈ 1.9e-34: 10^18 times finer than double). A model
// and its inputs convert to it exactly, so the errors measured against it are those of the
// double (or float) computation alone. Needs libquadmath (-lquadmath).
#pragma once

#include <boost/multiprecision/eigen.hpp>
#include <boost/multiprecision/float128.hpp>

#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {

using Quad = boost::multiprecision::float128;

/// Exact conversion of a float, double or long double vector (or matrix) to Quad.
template <class Derived>
Eigen::Matrix<Quad, Derived::RowsAtCompileTime, Derived::ColsAtCompileTime> to_quad(const Eigen::MatrixBase<Derived>& x) {
  return x.template cast<Quad>();
}

/// Norm-wise relative error ‖x − ref‖ / ‖ref‖ computed in Quad (absolute when ref is zero);
/// Frobenius norms for matrices.
template <class Derived, class RefDerived>
double relative_error_to(const Eigen::MatrixBase<Derived>& x, const Eigen::MatrixBase<RefDerived>& reference) {
  const Quad denominator = reference.norm();
  const Quad difference = (x.template cast<Quad>() - reference).norm();
  return static_cast<double>(denominator > 0 ? Quad(difference / denominator) : difference);
}

}  // namespace spatial_dynamics
