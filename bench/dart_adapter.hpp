// DART 6.12 (Debian's libdart, libdart-utils-urdf): DartLoader builds a Skeleton from the URDF,
// with a FreeJoint root for floating-base models. RNEA: computeInverseDynamics; forward
// dynamics: computeForwardDynamics (articulated-body method); M: getMassMatrix; g:
// getGravityForces; FK: getWorldTransform of every body. Joint damping, spring stiffness and
// Coulomb friction read from the URDF are set to zero, as in the other libraries.
#pragma once

#include <memory>
#include <string>

#include "benchmark_types.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace bench {

std::unique_ptr<Adapter> make_dart_adapter(const spatial_dynamics::Model<double>& model, const std::string& urdf_text,
                                           std::string& why);

}  // namespace bench
