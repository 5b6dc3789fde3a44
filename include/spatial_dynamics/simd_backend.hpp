// The double instances of the algorithms (rnea, aba, aba_refined, crba, forward_dynamics,
// forward_kinematics, frame_jacobian, rnea_batch) are compiled into the package's library
// `spatial_dynamics` twice from one source, portable and with AVX2 + FMA, and one of the two is
// chosen at start-up from the CPU: a program built without -march=native still runs the packed
// paths where the CPU has them. The environment variable SPATIAL_DYNAMICS_SIMD=portable forces the
// portable build (SPATIAL_DYNAMICS_SIMD=avx2_fma asks for the other, an error on a CPU without it).
// Other scalars, and every call from a translation unit that defines SPATIAL_DYNAMICS_HEADER_ONLY
// (such a program need not link the library), instantiate the header templates instead.
#pragma once

#if !defined(SPATIAL_DYNAMICS_HEADER_ONLY)
#define SD_COMPILED_DOUBLE 1
#endif

namespace spatial_dynamics {

/// "avx2_fma" or "portable": the build of the double instances that this process runs. Throws
/// std::invalid_argument naming SPATIAL_DYNAMICS_SIMD when that variable asks for an unknown or
/// unsupported build (then so does every double algorithm call).
const char* simd_backend();

}  // namespace spatial_dynamics
