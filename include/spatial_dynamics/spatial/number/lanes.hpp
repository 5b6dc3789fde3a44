// L numbers side by side, each operation one vector operation across the lanes: what the joint
// angles' sines and cosines are computed in, several angles at once (lane_trigonometry.hpp,
// model/joints/body_joint.hpp), and the lane counts of this build.
#pragma once

#include <type_traits>

#include "spatial_dynamics/spatial/eigen_types.hpp"

// The lane operations are tiny and sit in the inner loops: inlined, the lanes stay in registers
// instead of travelling through memory as returned structs.
#if defined(__GNUC__)
#define SD_LANE_INLINE inline __attribute__((always_inline))
#else
#define SD_LANE_INLINE inline
#endif

namespace spatial_dynamics {

/// Bytes of the widest vector register the compiler was allowed to use.
#if defined(__AVX512F__)
constexpr int kSimdBytes = 64;
#elif defined(__AVX__)
constexpr int kSimdBytes = 32;
#else
constexpr int kSimdBytes = 16;  // SSE2 (every x86-64), NEON
#endif

/// Scalars that fill one vector register of this build (2 doubles with SSE2, 4 with AVX, 8 with
/// AVX-512): the lane count of the vectorised steps inside one-state algorithms (joint sines and
/// cosines, the CRBA's carry over revolute runs).
template <class S>
constexpr int kRegisterLanes = sizeof(S) < kSimdBytes ? static_cast<int>(kSimdBytes / sizeof(S)) : 1;

/// States evaluated together by default (BatchData): one 256-bit register's worth at least on
/// x86-64, whatever this translation unit's flags, since the compiled library runs its AVX2 build
/// where the CPU has it (simd_backend.hpp); more with AVX-512. More lanes than a register holds
/// measured slower: the lanes no longer fit in the registers (the batched RNEA on the Panda: 8
/// double lanes with AVX2, 268 ns per state against 109 ns with 4; 16 with AVX-512, 137 ns
/// against 91 ns with 8).
#if defined(__x86_64__)
constexpr int kBatchBytes = kSimdBytes > 32 ? kSimdBytes : 32;
#else
constexpr int kBatchBytes = kSimdBytes;
#endif
template <class S>
constexpr int kDefaultBatchLanes = sizeof(S) < kBatchBytes ? static_cast<int>(kBatchBytes / sizeof(S)) : 1;

namespace detail {

/// Whether the compiler's vector extension (GCC, Clang) holds L scalars of type S: float or
/// double, L a power of two. Other scalars (long double, multiprecision) take plain arrays.
template <class S, int L>
constexpr bool kLaneVectorExtension =
#if defined(__GNUC__)
    (std::is_same<S, double>::value || std::is_same<S, float>::value) && L > 0 && (L & (L - 1)) == 0;
#else
    false;
#endif

template <class S, int L, bool = kLaneVectorExtension<S, L>>
struct LaneStorage {
  S v[L];
};
#if defined(__GNUC__)
// The alignment is spelled out: a vector type's own alignment follows the instruction set (16
// bytes for 4 doubles without AVX, 32 with it), and the layout of the batch workspace must be the
// same in the portable and AVX2 builds of the compiled library (simd_backend.hpp).
template <class S, int L>
struct alignas(sizeof(S) * L < 64 ? sizeof(S) * L : 64) LaneStorage<S, L, true> {
  typedef S Vector __attribute__((vector_size(sizeof(S) * L)));  // one SIMD value (or a few, split)
  Vector v;
};
#endif

}  // namespace detail

/// One scalar per lane. With the vector extension each operation below is one vector operation
/// by construction (the compiler splits it over registers narrower than L lanes); otherwise a
/// loop over the lanes. Everything is force-inlined, so the lanes stay in registers.
template <class S, int L>
struct Lanes : detail::LaneStorage<S, L> {
  static constexpr bool kVector = detail::kLaneVectorExtension<S, L>;

  SD_LANE_INLINE static Lanes Zero() { return Constant(S(0)); }
  SD_LANE_INLINE static Lanes Constant(const S& x) {
    Lanes out;
    if constexpr (kVector) {
      // One broadcast: x − 0 = x for every x, −0 included. (A store per lane became one masked
      // broadcast per lane with AVX-512.)
      out.v = x - decltype(out.v){};
    } else {
      for (int l = 0; l < L; ++l) out.v[l] = x;
    }
    return out;
  }
  SD_LANE_INLINE S operator[](int l) const { return this->v[l]; }
  SD_LANE_INLINE void set(int l, const S& x) { this->v[l] = x; }

  SD_LANE_INLINE Lanes operator-() const {
    Lanes out;
    if constexpr (kVector) {
      out.v = -this->v;
    } else {
      for (int l = 0; l < L; ++l) out.v[l] = -this->v[l];
    }
    return out;
  }
  SD_LANE_INLINE Lanes& operator+=(const Lanes& o) { return *this = *this + o; }
  SD_LANE_INLINE Lanes& operator-=(const Lanes& o) { return *this = *this - o; }
};

#define SD_LANE_BINARY_OPERATOR(op)                                                      \
  template <class S, int L>                                                              \
  SD_LANE_INLINE Lanes<S, L> operator op(const Lanes<S, L>& a, const Lanes<S, L>& b) {   \
    Lanes<S, L> out;                                                                     \
    if constexpr (Lanes<S, L>::kVector) {                                                \
      out.v = a.v op b.v;                                                                \
    } else {                                                                             \
      for (int l = 0; l < L; ++l) out.v[l] = a.v[l] op b.v[l];                           \
    }                                                                                    \
    return out;                                                                          \
  }                                                                                      \
  template <class S, int L>                                                              \
  SD_LANE_INLINE Lanes<S, L> operator op(const Lanes<S, L>& a, const S& b) {             \
    return a op Lanes<S, L>::Constant(b);                                                \
  }                                                                                      \
  template <class S, int L>                                                              \
  SD_LANE_INLINE Lanes<S, L> operator op(const S& a, const Lanes<S, L>& b) {             \
    return Lanes<S, L>::Constant(a) op b;                                                \
  }
SD_LANE_BINARY_OPERATOR(+)
SD_LANE_BINARY_OPERATOR(-)
SD_LANE_BINARY_OPERATOR(*)
#undef SD_LANE_BINARY_OPERATOR

}  // namespace spatial_dynamics
