// The minimum-norm least-squares solution of A x = b, pinv(A) b, for the reference in any scalar
// (Boost's float128 included, for which Eigen's SVDs, orthogonal decompositions and LDLT solves
// do not compile with GCC 12): a full-rank factorization A = B Z, B the columns of A that span
// its range (chosen by full-pivoting LU at a relative threshold), Z = (BᵀB)⁻¹BᵀA of full row rank,
// and pinv(A) = Zᵀ(ZZᵀ)⁻¹(BᵀB)⁻¹Bᵀ (Ben-Israel and Greville, Generalized Inverses, 2003, §1.7).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "spatial_dynamics/reference/spatial_matrices.hpp"

namespace spatial_dynamics {
namespace reference {

/// pinv(A) b; singular values below `threshold` relative to A's largest pivot count as zero.
template <class S>
VecX<S> pseudo_inverse_solve(const MatX<S>& A, const VecX<S>& b, const S& threshold) {
  Eigen::FullPivLU<MatX<S>> lu(A);
  lu.setThreshold(threshold);
  const MatX<S> B = lu.image(A);
  const Eigen::LLT<MatX<S>> BtB(B.transpose() * B);
  const MatX<S> Z = BtB.solve(B.transpose() * A);
  const VecX<S> y = BtB.solve(B.transpose() * b);
  return Z.transpose() * MatX<S>(Z * Z.transpose()).llt().solve(y);
}

}  // namespace reference
}  // namespace spatial_dynamics
