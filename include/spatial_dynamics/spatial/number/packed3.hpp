// A 3-vector of doubles held in one 4-lane vector register (x, y, z, pad): how Vec3<double> and
// Mat3<double> (spatial/vec3.hpp, spatial/mat3.hpp) compute where the CPU has AVX2 and FMA. A cross product is three lane permutations, a
// product and a fused subtraction; a 3×3 matrix times a vector is three broadcasts, a product and
// two fused additions: about a third of the instructions of the same operations on Eigen's
// 3-vectors, which mix scalar and 2-lane code. Only lanes 0–2 carry the vector: the pad lane holds
// whatever the load brought with it and no operation below moves it into lanes 0–2.
//
// Selected here, in one place: with GCC where AVX2 and FMA are enabled (the compiled library's
// AVX2 build, simd_backend.hpp; or -mavx2 -mfma, -march=native) SD_PACKED3 is defined, and each
// primitive's double case takes its packed form; otherwise every scalar computes coordinate by coordinate.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__AVX2__) && defined(__FMA__)
#define SD_PACKED3 1  // GCC's __builtin_shuffle below; Clang spells it differently
#endif

#ifdef SD_PACKED3
#include <immintrin.h>
#endif

#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {

#ifdef SD_PACKED3
namespace packed3 {

typedef double Packed3 __attribute__((vector_size(32)));
typedef long long LaneIndex __attribute__((vector_size(32)));

SD_INLINE Packed3 splat(double x) { return Packed3{x, x, x, x}; }

/// Lane k of x in every lane.
template <int k>
SD_INLINE Packed3 broadcast(Packed3 x) {
  return __builtin_shuffle(x, LaneIndex{k, k, k, k});
}

/// (y, z, x, pad).
SD_INLINE Packed3 yzx(Packed3 a) { return __builtin_shuffle(a, LaneIndex{1, 2, 0, 3}); }

/// a × b = yzx(a ∘ yzx(b) − yzx(a) ∘ b).
SD_INLINE Packed3 cross(Packed3 a, Packed3 b) { return yzx(a * yzx(b) - yzx(a) * b); }

/// x₀ + x₁ + x₂, in that order.
SD_INLINE double sum3(Packed3 x) {
  const __m128d low = _mm256_castpd256_pd128(x);
  const __m128d pair = _mm_add_sd(low, _mm_unpackhi_pd(low, low));
  return _mm_cvtsd_f64(_mm_add_sd(pair, _mm256_extractf128_pd(x, 1)));
}

/// E x for E given by its columns c0, c1, c2: x₀ c0 + x₁ c1 + x₂ c2.
SD_INLINE Packed3 mat_vec(Packed3 c0, Packed3 c1, Packed3 c2, Packed3 x) {
  return c0 * broadcast<0>(x) + c1 * broadcast<1>(x) + c2 * broadcast<2>(x);
}

/// The rows of the matrix with columns c0, c1, c2 (the columns of its transpose).
SD_INLINE void transpose(Packed3 c0, Packed3 c1, Packed3 c2, Packed3& t0, Packed3& t1, Packed3& t2) {
  const Packed3 even = __builtin_shuffle(c0, c1, LaneIndex{0, 4, 2, 6});  // (c0.x, c1.x, c0.z, c1.z)
  const Packed3 odd = __builtin_shuffle(c0, c1, LaneIndex{1, 5, 3, 7});   // (c0.y, c1.y, ·, ·)
  t0 = __builtin_shuffle(even, c2, LaneIndex{0, 1, 4, 4});
  t1 = __builtin_shuffle(odd, c2, LaneIndex{0, 1, 5, 5});
  t2 = __builtin_shuffle(even, c2, LaneIndex{2, 3, 6, 6});
}

}  // namespace packed3
#endif

}  // namespace spatial_dynamics
