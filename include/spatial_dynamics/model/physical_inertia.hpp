// Whether mass, centre of mass and rotational inertia (about the centre of mass) describe a
// physical rigid body: finite, non-negative mass, a positive semi-definite tensor whose
// principal moments satisfy the triangle inequality λ_i + λ_j ≥ λ_k.
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <string>

namespace spatial_dynamics {

/// "" when physical, else the reason (without the culprit's name, which the caller adds).
inline std::string inertia_problem(double mass, const Eigen::Vector3d& center_of_mass, const Eigen::Matrix3d& inertia) {
  std::ostringstream why;
  why.precision(17);
  if (!std::isfinite(mass)) return (why << "mass " << mass << " is not finite", why.str());
  if (mass < 0.0) return (why << "mass " << mass << " is negative", why.str());
  if (!center_of_mass.allFinite()) return "centre of mass is not finite";
  if (!inertia.allFinite()) return "inertia tensor has a non-finite entry";
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia, Eigen::EigenvaluesOnly).eigenvalues();
  const double tolerance = 1e-9 * moments.cwiseAbs().maxCoeff();  // relative: URDF values carry rounding
  if (moments.minCoeff() < -tolerance)
    return (why << "inertia tensor is not positive semi-definite (principal moments " << moments[0] << ", "
                << moments[1] << ", " << moments[2] << ")",
            why.str());
  if (moments[0] + moments[1] < moments[2] - tolerance)
    return (why << "inertia tensor violates the triangle inequality (principal moments " << moments[0] << " + "
                << moments[1] << " < " << moments[2] << ")",
            why.str());
  return {};
}

}  // namespace spatial_dynamics
