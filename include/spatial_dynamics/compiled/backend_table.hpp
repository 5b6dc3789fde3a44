// One build of the compiled double instances (simd_backend.hpp): a table of entry points, one
// per line of compiled_functions.def, each the header template instantiated with that build's
// flags. The library holds two (portable, avx2_fma), each in a shared object of its own with
// hidden symbols, so that the inline functions of the two builds are never merged.
#pragma once

#include "spatial_dynamics/compiled/compiled_functions.hpp"

namespace spatial_dynamics {
namespace detail {

struct BackendTable {
  const char* name;
#define SD_COMPILED(member, ret, name, params, args) ret (*member) params;
#include "spatial_dynamics/compiled/compiled_functions.def"
};

/// The build `request` names: "portable", "avx2_fma", or "" for the one the CPU runs best.
/// Throws std::invalid_argument naming SPATIAL_DYNAMICS_SIMD for another name, or for
/// "avx2_fma" on a CPU without AVX2 and FMA.
const BackendTable& simd_backend_table(const char* request);

}  // namespace detail
}  // namespace spatial_dynamics
