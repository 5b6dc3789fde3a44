// The log-Cholesky parameterisation of rigid-body inertia (Rucker and Wensing, "Smooth
// Parameterization of Rigid-Body Inertia", RA-L 2022): every θ ∈ R¹⁰ gives a physically consistent
// body and every body with a positive-definite pseudo-inertia has one θ. The pseudo-inertia of the
// ten parameters π = (m, h, Ī_O) (RigidInertia::toParameters) is
//   J = [Σ  h; hᵀ  m],  Σ = ½ tr(Ī_O) 1 − Ī_O,  and  Ī_O = tr(Σ) 1 − Σ  (eq. 5 of the paper);
// J ≻ 0 exactly when the body is physical, mass positive and the principal moments about the
// centre of mass meeting the triangle inequality strictly (Wensing, Kim and Slotine, RA-L 2018).
// θ = (α, d₁, d₂, d₃, s₁₂, s₂₃, s₁₃, t₁, t₂, t₃) gives J = U Uᵀ with the upper-triangular
//   U = e^α [e^d₁ s₁₂ s₁₃ t₁; 0 e^d₂ s₂₃ t₂; 0 0 e^d₃ t₃; 0 0 0 1]   (eq. 11).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

namespace spatial_dynamics {

using InertialParameters = Eigen::Matrix<double, 10, 1>;
using LogCholesky = Eigen::Matrix<double, 10, 1>;

/// J of π.
inline Eigen::Matrix4d pseudo_inertia(const InertialParameters& pi) {
  Eigen::Matrix3d I;
  I << pi[4], pi[5], pi[7], pi[5], pi[6], pi[8], pi[7], pi[8], pi[9];
  Eigen::Matrix4d J;
  J.topLeftCorner<3, 3>() = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
  J.topRightCorner<3, 1>() = pi.segment<3>(1);
  J.bottomLeftCorner<1, 3>() = pi.segment<3>(1).transpose();
  J(3, 3) = pi[0];
  return J;
}

/// π of a pseudo-inertia J (the linear map back).
inline InertialParameters parameters_of_pseudo_inertia(const Eigen::Matrix4d& J) {
  const Eigen::Matrix3d Sigma = J.topLeftCorner<3, 3>();
  const Eigen::Matrix3d I = Sigma.trace() * Eigen::Matrix3d::Identity() - Sigma;
  InertialParameters pi;
  pi << J(3, 3), J(0, 3), J(1, 3), J(2, 3), I(0, 0), I(0, 1), I(1, 1), I(0, 2), I(1, 2), I(2, 2);
  return pi;
}

/// U(θ) of eq. 11.
inline Eigen::Matrix4d log_cholesky_factor(const LogCholesky& theta) {
  Eigen::Matrix4d U = Eigen::Matrix4d::Zero();
  for (int k = 0; k < 3; ++k) U(k, k) = std::exp(theta[1 + k]);
  U(0, 1) = theta[4], U(1, 2) = theta[5], U(0, 2) = theta[6];
  U(0, 3) = theta[7], U(1, 3) = theta[8], U(2, 3) = theta[9];
  U(3, 3) = 1.0;
  return std::exp(theta[0]) * U;
}

/// π(θ) and, when `jacobian` is given, ∂π/∂θ (dJ = dU Uᵀ + U dUᵀ, mapped linearly to π).
inline InertialParameters parameters_of_log_cholesky(const LogCholesky& theta, Eigen::Matrix<double, 10, 10>* jacobian = nullptr) {
  const Eigen::Matrix4d U = log_cholesky_factor(theta);
  if (jacobian) {
    const double scale = std::exp(theta[0]);
    const int rows[9] = {0, 1, 2, 0, 1, 0, 0, 1, 2}, cols[9] = {0, 1, 2, 1, 2, 2, 3, 3, 3};  // θ₁ … θ₉'s entry of U
    for (int k = 0; k < 10; ++k) {
      Eigen::Matrix4d dU = Eigen::Matrix4d::Zero();
      if (k == 0)
        dU = U;  // ∂U/∂α = U
      else
        dU(rows[k - 1], cols[k - 1]) = k <= 3 ? U(k - 1, k - 1) : scale;  // ∂(e^α e^dᵢ)/∂dᵢ, ∂(e^α s)/∂s
      jacobian->col(k) = parameters_of_pseudo_inertia(dU * U.transpose() + U * dU.transpose());
    }
  }
  return parameters_of_pseudo_inertia(U * U.transpose());
}

/// θ of π, after lifting J's eigenvalues to at least `floor` · its largest (a body that is not
/// strictly physical becomes the nearest one that is, in that sense): J = U Uᵀ with U upper
/// triangular is the Cholesky factor of J with rows and columns reversed.
inline LogCholesky log_cholesky_of_parameters(const InertialParameters& pi, double floor = 1e-9) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(pseudo_inertia(pi));
  const double largest = std::max(eigen.eigenvalues().cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::Vector4d lifted = eigen.eigenvalues().cwiseMax(floor * largest);
  const Eigen::Matrix4d J = eigen.eigenvectors() * lifted.asDiagonal() * eigen.eigenvectors().transpose();
  const Eigen::Matrix4d reverse = Eigen::Matrix4d::Identity().rowwise().reverse();
  const Eigen::Matrix4d L = Eigen::LLT<Eigen::Matrix4d>(reverse * J * reverse).matrixL();
  const Eigen::Matrix4d U = reverse * L * reverse;  // upper triangular, U Uᵀ = J
  const double scale = U(3, 3);
  LogCholesky theta;
  theta[0] = std::log(scale);
  for (int k = 0; k < 3; ++k) theta[1 + k] = std::log(U(k, k) / scale);
  theta[4] = U(0, 1) / scale, theta[5] = U(1, 2) / scale, theta[6] = U(0, 2) / scale;
  theta[7] = U(0, 3) / scale, theta[8] = U(1, 3) / scale, theta[9] = U(2, 3) / scale;
  return theta;
}

}  // namespace spatial_dynamics
