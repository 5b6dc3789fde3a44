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

/// As inertia_problem for a body given by its ten parameters about its frame origin (eq. 25): a
/// body with mass must have a physical inertia about its centre of mass; a massless one no first
/// moment and no rotational inertia (there is no such body otherwise).
template <class Body>
std::string rigid_inertia_problem(const Body& body) {
  const double mass = static_cast<double>(body.mass);
  Eigen::Vector3d h;
  Eigen::Matrix3d inertia_about_origin;
  for (int r = 0; r < 3; ++r) {
    h[r] = static_cast<double>(body.first_moment[r]);
    for (int c = 0; c < 3; ++c) inertia_about_origin(r, c) = static_cast<double>(body.rotational_inertia(r, c));
  }
  if (!h.allFinite() || !inertia_about_origin.allFinite() || !std::isfinite(mass))
    return "a parameter is not finite";
  if (mass == 0.0)
    return h.isZero(0.0) && inertia_about_origin.isZero(0.0) ? "" : "zero mass with a first moment or a rotational inertia";
  if (mass < 0.0) return inertia_problem(mass, h, inertia_about_origin);
  const Eigen::Vector3d c = h / mass;  // Ī_c = Ī_O + m (c cᵀ − c·c 1)   (eq. 25 solved for Ī_c)
  const Eigen::Matrix3d about_com = inertia_about_origin + mass * (c * c.transpose() - c.squaredNorm() * Eigen::Matrix3d::Identity());
  return inertia_problem(mass, c, about_com);
}

}  // namespace spatial_dynamics
