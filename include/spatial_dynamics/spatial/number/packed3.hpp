// A 3-vector of doubles held in one 4-lane vector register (x, y, z, pad): how the spatial
// primitives for double are implemented where the CPU has AVX2 and FMA (the cross products, the
// Plücker transform's rotations, the rigid inertia's product, the joint rotation), and what the
// packed RNEA and CRBA passes hold their bodies in. A cross product is three lane permutations, a
// product and a fused subtraction; a 3×3 matrix times a vector is three broadcasts, a product and
// two fused additions: about a third of the instructions of the same operations on Eigen's
// 3-vectors, which mix scalar and 2-lane code. Only lanes 0–2 carry the vector: the pad lane holds
// whatever the load brought with it and no operation below moves it into lanes 0–2.
//
// Selected here, in one place: with GCC where AVX2 and FMA are enabled (the compiled library's
// AVX2 build, simd_backend.hpp; or -mavx2 -mfma, -march=native) SD_PACKED3 is defined, and each
// primitive's double case takes its packed form; otherwise every scalar takes the Eigen code.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__AVX2__) && defined(__FMA__)
#define SD_PACKED3 1  // GCC's __builtin_shuffle below; Clang spells it differently
#endif

#include <cstring>
#include <type_traits>

#ifdef SD_PACKED3
#include <immintrin.h>
#endif

#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {

/// Memory for one packed 3-vector, declared in every build so that structs holding it have one
/// layout whether or not SD_PACKED3 is defined.
struct alignas(32) Packed3Storage {
  double lane[4];
};

/// Memory for a 3-vector in the passes' per-body buffers: Packed3Storage for double (one layout
/// in every build), Vector3<S> otherwise.
template <class S>
struct Vector3StorageOf {
  using type = Vector3<S>;
};
template <>
struct Vector3StorageOf<double> {
  using type = Packed3Storage;
};
template <class S>
using Vector3Storage = typename Vector3StorageOf<S>::type;

#ifdef SD_PACKED3
namespace packed3 {

typedef double Packed3 __attribute__((vector_size(32)));
typedef long long LaneIndex __attribute__((vector_size(32)));

/// The four doubles from p on (lane 3 is the pad); p need not be aligned.
SD_INLINE Packed3 load(const double* p) {
  Packed3 x;
  std::memcpy(&x, p, sizeof x);
  return x;
}

/// The 3-vector that ends a struct, read from the coefficient before it: (p[1], p[2], p[3]),
/// so that nothing past the struct is read.
SD_INLINE Packed3 load_after(const double* p) { return __builtin_shuffle(load(p), LaneIndex{1, 2, 3, 0}); }

SD_INLINE Packed3 load(const Packed3Storage& s) { return load(s.lane); }

SD_INLINE void store(Packed3 x, Packed3Storage& s) { std::memcpy(s.lane, &x, sizeof x); }

/// The four lanes into p[0..3]; p need not be aligned.
SD_INLINE void store4(Packed3 x, double* p) { std::memcpy(p, &x, sizeof x); }

/// A 3-vector from exactly three doubles (two loads: nothing past p[2] is read; pad 0).
SD_INLINE Packed3 load3(const double* p) {
  return (Packed3)_mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p)), _mm_load_sd(p + 2), 1);
}
SD_INLINE Packed3 load3(const Vector3<double>& v) { return load3(v.data()); }
/// Lanes 0–2 into exactly three doubles.
SD_INLINE void store3(Packed3 x, double* p) {
  _mm_storeu_pd(p, _mm256_castpd256_pd128((__m256d)x));
  _mm_store_sd(p + 2, _mm256_extractf128_pd((__m256d)x, 1));
}
SD_INLINE Vector3<double> to_vector3(Packed3 x) {
  Vector3<double> v;
  store3(x, v.data());
  return v;
}

/// (x, y, z, 0).
SD_INLINE Packed3 make(double x, double y, double z) { return Packed3{x, y, z, 0.0}; }

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

/// Columns of a Matrix3<double> (column-major, 9 coefficients): the third one is read through
/// load_after so that nothing past the matrix is read.
SD_INLINE void load_columns(const Matrix3<double>& M, Packed3& c0, Packed3& c1, Packed3& c2) {
  c0 = load(M.data());
  c1 = load(M.data() + 3);
  c2 = load_after(M.data() + 5);
}

/// A 3×3 matrix by its columns in registers: of M, or of Mᵀ (M's rows).
struct Columns {
  Packed3 c0, c1, c2;
};
SD_INLINE Columns columns(const Matrix3<double>& M) {
  Columns C;
  load_columns(M, C.c0, C.c1, C.c2);
  return C;
}
SD_INLINE Columns transposed_columns(const Matrix3<double>& M) {
  const Columns C = columns(M);
  Columns T;
  transpose(C.c0, C.c1, C.c2, T.c0, T.c1, T.c2);
  return T;
}

/// A rotation E about coordinate axis k (RBDA Table 2.2's rx, ry, rz at angle θ, s = sin θ,
/// c = cos θ) on packed lanes: E y = cv ∘ y + sv ∘ swap(y) and Eᵀ y = cv ∘ y − sv ∘ swap(y), where
/// swap exchanges the two lanes the rotation mixes, m = k + 1 and n = k + 2 (mod 3); E's column m is
/// (c e_m − s e_n), its column n (s e_m + c e_n).
template <int axis>
struct AxisRotation {
  static constexpr int m = (axis + 1) % 3, n = (axis + 2) % 3;
  Packed3 cv, sv;
  /// `unit` is cv's lane k (and pad): 1, or 0 for the low parts of a double-double rotation
  /// (packed3_double_double.hpp's WideAxisRotation).
  AxisRotation(double s, double c, double unit = 1.0) {
    // c and s in every lane, then lane k and the pad set to unit and sv's signs applied: a
    // broadcast and a blend or product each, where building the lanes one by one takes several
    // inserts.
    constexpr LaneIndex unit_lanes = {axis == 0 ? 4 : 0, axis == 1 ? 5 : 1, axis == 2 ? 6 : 2, 7};
    cv = __builtin_shuffle(splat(c), splat(unit), unit_lanes);
    if constexpr (axis == 0) sv = splat(s) * Packed3{0, 1, -1, 0};
    else if constexpr (axis == 1) sv = splat(s) * Packed3{-1, 0, 1, 0};
    else sv = splat(s) * Packed3{1, -1, 0, 0};
  }
  static SD_INLINE Packed3 swap(Packed3 y) {
    if constexpr (axis == 0) return __builtin_shuffle(y, LaneIndex{0, 2, 1, 3});
    else if constexpr (axis == 1) return __builtin_shuffle(y, LaneIndex{2, 1, 0, 3});
    else return __builtin_shuffle(y, LaneIndex{1, 0, 2, 3});
  }
  SD_INLINE Packed3 times(Packed3 y) const { return cv * y + sv * swap(y); }
  SD_INLINE Packed3 transposed_times(Packed3 y) const { return cv * y - sv * swap(y); }
};

/// fn(std::integral_constant<int, axis>()) for axis 0, 1 or 2, known at run time: the branch
/// that selects a rotation's compiled form once, outside its products.
template <class Fn>
SD_INLINE void with_axis(int axis, Fn&& fn) {
  switch (axis) {
    case 0: fn(std::integral_constant<int, 0>()); return;
    case 1: fn(std::integral_constant<int, 1>()); return;
    default: fn(std::integral_constant<int, 2>()); return;
  }
}

}  // namespace packed3
#endif

}  // namespace spatial_dynamics
