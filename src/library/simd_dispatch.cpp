// The library's double entry points (compiled/compiled_functions.def): each forwards to the build
// chosen once, at the first call, from the CPU and SPATIAL_DYNAMICS_SIMD (simd_backend.hpp). One
// indirect call per algorithm call.
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "spatial_dynamics/compiled/backend_table.hpp"
#include "spatial_dynamics/simd_backend.hpp"

namespace spatial_dynamics {
namespace detail {

// The two builds (src/library/backend.cpp), each in a shared object of its own.
const BackendTable& sd_backend_portable();
const BackendTable& sd_backend_avx2_fma();

namespace {

bool cpu_has_avx2_fma() {
#if defined(__x86_64__) || defined(__i386__)
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  return false;
#endif
}

/// The build SPATIAL_DYNAMICS_SIMD asks for, or the CPU's best: chosen at the first call. A bad
/// request throws, and so does every later call (the choice is not cached until one is made).
const BackendTable& chosen_backend() {
  static const BackendTable& table = simd_backend_table(std::getenv("SPATIAL_DYNAMICS_SIMD"));
  return table;
}

}  // namespace

const BackendTable& simd_backend_table(const char* request) {
  if (request == nullptr || *request == '\0') return cpu_has_avx2_fma() ? sd_backend_avx2_fma() : sd_backend_portable();
  if (std::strcmp(request, "portable") == 0) return sd_backend_portable();
  if (std::strcmp(request, "avx2_fma") == 0) {
    if (!cpu_has_avx2_fma())
      throw std::invalid_argument("SPATIAL_DYNAMICS_SIMD=avx2_fma: this CPU has no AVX2 and FMA (use portable, or unset it)");
    return sd_backend_avx2_fma();
  }
  throw std::invalid_argument("SPATIAL_DYNAMICS_SIMD='" + std::string(request) +
                              "': expected 'portable' or 'avx2_fma' (or unset: chosen from the CPU)");
}

}  // namespace detail

using detail::chosen_backend;

const char* simd_backend() { return chosen_backend().name; }

#define SD_COMPILED(member, ret, name, params, args) \
  ret name params { return chosen_backend().member args; }
#include "spatial_dynamics/compiled/compiled_functions.def"

}  // namespace spatial_dynamics
