// Orocos KDL (Debian's liborocos-kdl, kdl_parser): fixed base only (KDL has no free joint).
// Models whose movable joints form one root-to-tip path (fixed side links allowed, their inertia
// folded into the path) use ChainIdSolver_RNE, ChainDynParam, ChainFdSolver_RNE (mass matrix + LDLᵀ)
// and ChainFkSolverPos_recursive; trees use TreeIdSolver_RNE (RNEA, gravity torques) and
// TreeFkSolverPos_recursive, and have no mass matrix or forward dynamics solver in KDL.
#pragma once

#include <memory>
#include <string>

#include "benchmark_types.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace bench {

/// Returns nullptr and sets `why` when KDL cannot take the model.
std::unique_ptr<Adapter> make_kdl_adapter(const spatial_dynamics::Model<double>& model, const std::string& urdf_text,
                                          std::string& why);

}  // namespace bench
