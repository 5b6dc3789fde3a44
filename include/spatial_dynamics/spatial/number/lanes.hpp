// The spatial algebra over L lanes: L independent states side by side, each quantity stored as
// a structure of arrays (one fixed-size Eigen array of L scalars per coordinate), so that every
// operation below is one vector operation across the lanes. Only what the batched RNEA's form
// needs (algorithms/joint_kernels_lanes.hpp): 3-vectors, their cross products, rotations and the
// transform (E, r). Each formula is written in the same order as its one-state counterpart, so a
// lane gives that counterpart's numbers (bit for bit unless the compiler fuses multiply-adds
// differently in the two).
#pragma once

#include <cstring>
#include <type_traits>

#include <Eigen/Core>

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

/// The widest register's worth of lanes of any build (AVX-512): what a buffer that a vectorised
/// step reads in blocks is padded by, so that every build may read it.
template <class S>
constexpr int kWidestLanes = sizeof(S) < 64 ? static_cast<int>(64 / sizeof(S)) : 1;

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
  /// p[0 .. L), unaligned.
  SD_LANE_INLINE static Lanes Load(const S* p) {
    Lanes out;
    if constexpr (kVector) {
      std::memcpy(&out.v, p, sizeof out.v);
    } else {
      for (int l = 0; l < L; ++l) out.v[l] = p[l];
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

/// out[k] = (column[0][k], …, column[L − 1][k]) for k < n: L columns of coordinates turned into
/// one Lanes per coordinate. With GCC, AVX and double lanes in groups of 4, blocks of 4×4 are
/// transposed in registers (4 loads, 8 shuffles, 4 stores for 16 coordinates); otherwise lane by lane.
template <class S, int L>
SD_LANE_INLINE void gather_columns(const S* const* column, int n, Lanes<S, L>* out) {
  int k = 0;
#if defined(__GNUC__) && !defined(__clang__) && defined(__AVX__)
  if constexpr (std::is_same<S, double>::value && L % 4 == 0 && Lanes<S, L>::kVector) {
    typedef double Quad __attribute__((vector_size(32)));
    typedef long long Index __attribute__((vector_size(32)));
    const auto load = [](const S* p) {  // p[0 .. 3], unaligned
      Quad x;
      std::memcpy(&x, p, sizeof x);
      return x;
    };
    for (; k + 4 <= n; k += 4)
      for (int g = 0; g < L; g += 4) {  // lanes g .. g + 3
        const Quad row0 = load(column[g] + k), row1 = load(column[g + 1] + k), row2 = load(column[g + 2] + k),
                   row3 = load(column[g + 3] + k);
        const Quad low01 = __builtin_shuffle(row0, row1, Index{0, 4, 2, 6});
        const Quad high01 = __builtin_shuffle(row0, row1, Index{1, 5, 3, 7});
        const Quad low23 = __builtin_shuffle(row2, row3, Index{0, 4, 2, 6});
        const Quad high23 = __builtin_shuffle(row2, row3, Index{1, 5, 3, 7});
        const Quad lanes[4] = {__builtin_shuffle(low01, low23, Index{0, 1, 4, 5}),
                               __builtin_shuffle(high01, high23, Index{0, 1, 4, 5}),
                               __builtin_shuffle(low01, low23, Index{2, 3, 6, 7}),
                               __builtin_shuffle(high01, high23, Index{2, 3, 6, 7})};
        for (int i = 0; i < 4; ++i) std::memcpy(reinterpret_cast<S*>(&out[k + i].v) + g, &lanes[i], sizeof(Quad));
      }
  }
#endif
  for (; k < n; ++k)
    for (int l = 0; l < L; ++l) out[k].set(l, column[l][k]);
}

/// A 3-vector per lane: x, y and z each hold L lanes.
template <class S, int L>
struct LaneVector3 {
  using Lane = Lanes<S, L>;
  Lane x, y, z;

  SD_LANE_INLINE static LaneVector3 Zero() { return {Lane::Zero(), Lane::Zero(), Lane::Zero()}; }
  /// The same vector in every lane.
  SD_LANE_INLINE static LaneVector3 Constant(const Vector3<S>& v) {
    return {Lane::Constant(v.x()), Lane::Constant(v.y()), Lane::Constant(v.z())};
  }

  SD_LANE_INLINE Lane& operator[](int k) { return k == 0 ? x : (k == 1 ? y : z); }
  SD_LANE_INLINE const Lane& operator[](int k) const { return k == 0 ? x : (k == 1 ? y : z); }

  SD_LANE_INLINE LaneVector3 operator+(const LaneVector3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  SD_LANE_INLINE LaneVector3 operator-(const LaneVector3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  SD_LANE_INLINE LaneVector3& operator+=(const LaneVector3& o) { return *this = *this + o; }
  SD_LANE_INLINE LaneVector3& operator-=(const LaneVector3& o) { return *this = *this - o; }

  /// a × b, lane by lane.
  SD_LANE_INLINE LaneVector3 cross(const LaneVector3& b) const {
    return {y * b.z - z * b.y, z * b.x - x * b.z, x * b.y - y * b.x};
  }
};

/// a × b for a vector a that is the same in every lane.
template <class S, int L>
SD_LANE_INLINE LaneVector3<S, L> cross(const Vector3<S>& a, const LaneVector3<S, L>& b) {
  return {a.y() * b.z - a.z() * b.y, a.z() * b.x - a.x() * b.z, a.x() * b.y - a.y() * b.x};
}

/// k v, k one scalar per lane.
template <class S, int L>
SD_LANE_INLINE LaneVector3<S, L> operator*(const Lanes<S, L>& k, const LaneVector3<S, L>& v) {
  return {k * v.x, k * v.y, k * v.z};
}

/// M v for a matrix that is the same in every lane.
template <class S, int L>
SD_LANE_INLINE LaneVector3<S, L> operator*(const Matrix3<S>& M, const LaneVector3<S, L>& v) {
  return {M(0, 0) * v.x + M(0, 1) * v.y + M(0, 2) * v.z, M(1, 0) * v.x + M(1, 1) * v.y + M(1, 2) * v.z,
          M(2, 0) * v.x + M(2, 1) * v.y + M(2, 2) * v.z};
}

/// A 3×3 matrix per lane, m[row][column].
template <class S, int L>
struct LaneMatrix3 {
  Lanes<S, L> m[3][3];

  SD_LANE_INLINE static LaneMatrix3 Constant(const Matrix3<S>& M) {
    LaneMatrix3 out;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) out.m[i][k] = Lanes<S, L>::Constant(M(i, k));
    return out;
  }
  /// E v
  SD_LANE_INLINE LaneVector3<S, L> operator*(const LaneVector3<S, L>& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  /// Eᵀ v
  SD_LANE_INLINE LaneVector3<S, L> transposeTimes(const LaneVector3<S, L>& v) const {
    return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
            m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
  }
};

/// ^BX_A per lane, stored as (E, r) like PluckerTransform.
template <class S, int L>
struct LaneTransform {
  LaneMatrix3<S, L> E;
  LaneVector3<S, L> r;
};

}  // namespace spatial_dynamics
