// A 3-vector of double-doubles held in two 4-lane registers (hi, lo): how Vec3<DoubleDouble>'s sums
// and the gravity split's products of it with doubles (wide_vec3.hpp) compute where the CPU has
// AVX2 and FMA: the error-free transformations of double_double.hpp
// (TwoSum, TwoProduct by a fused multiply-add) applied to three lanes at once. As there, sums are
// not renormalised; lane 3 is a pad that no operation moves into lanes 0–2.
#pragma once

#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/number/packed3.hpp"

#ifdef SD_PACKED3
#include <immintrin.h>

namespace spatial_dynamics {
namespace packed3 {

struct PackedDoubleDouble {
  Packed3 hi, lo;
};

/// a ∘ b + c with one rounding.
SD_INLINE Packed3 fma(Packed3 a, Packed3 b, Packed3 c) { return _mm256_fmadd_pd(a, b, c); }

/// x + p + e for a double product p with its error e: TwoSum of the high parts, every low part
/// added to its error.
SD_INLINE PackedDoubleDouble add_product(const PackedDoubleDouble& x, Packed3 p, Packed3 e) {
  const Packed3 s = x.hi + p;
  const Packed3 bb = s - x.hi;
  const Packed3 err = (x.hi - (s - bb)) + (p - bb);
  return {s, err + (x.lo + e)};
}

/// x + y.
SD_INLINE PackedDoubleDouble operator+(const PackedDoubleDouble& x, const PackedDoubleDouble& y) {
  return add_product(x, y.hi, y.lo);
}

/// a ∘ x for double a and double-double x.
SD_INLINE PackedDoubleDouble scale(Packed3 a, const PackedDoubleDouble& x) {
  const Packed3 p = a * x.hi;
  return {p, fma(a, x.lo, fma(a, x.hi, -p))};
}

SD_INLINE PackedDoubleDouble operator-(const PackedDoubleDouble& x) { return {-x.hi, -x.lo}; }

/// E x for E given by its columns (doubles) and a double-double x. The high parts' chain is a
/// product and two sums; every error and x's low parts join in a separate tree, so that a chain
/// of rotations (gravity carried out along a limb) waits on x.hi only a few operations.
SD_INLINE PackedDoubleDouble mat_vec(Packed3 c0, Packed3 c1, Packed3 c2, const PackedDoubleDouble& x) {
  const Packed3 b0 = broadcast<0>(x.hi), b1 = broadcast<1>(x.hi), b2 = broadcast<2>(x.hi);
  const Packed3 p0 = c0 * b0, p1 = c1 * b1, p2 = c2 * b2;
  const Packed3 e0 = fma(c0, b0, -p0), e1 = fma(c1, b1, -p1), e2 = fma(c2, b2, -p2);
  const Packed3 s1 = p0 + p1, v1 = s1 - p0, t1 = (p0 - (s1 - v1)) + (p1 - v1);  // TwoSum(p0, p1)
  const Packed3 s = s1 + p2, v2 = s - s1, t2 = (s1 - (s - v2)) + (p2 - v2);      // TwoSum(s1, p2)
  const Packed3 low_of_x = fma(c0, broadcast<0>(x.lo), fma(c1, broadcast<1>(x.lo), c2 * broadcast<2>(x.lo)));
  return {s, ((e0 + e1) + (e2 + (t1 + t2))) + low_of_x};
}

/// a × b = yzx(a ∘ yzx(b) − yzx(a) ∘ b) for double-double a and double b.
SD_INLINE PackedDoubleDouble cross(const PackedDoubleDouble& a, Packed3 b) {
  const PackedDoubleDouble difference = scale(yzx(b), a) + (-scale(b, {yzx(a.hi), yzx(a.lo)}));
  return {yzx(difference.hi), yzx(difference.lo)};
}

/// a × b for double a and double-double b: −(b × a).
SD_INLINE PackedDoubleDouble cross(Packed3 a, const PackedDoubleDouble& b) { return -cross(b, a); }

SD_INLINE PackedDoubleDouble operator-(const PackedDoubleDouble& x, const PackedDoubleDouble& y) { return x + (-y); }
}  // namespace packed3
}  // namespace spatial_dynamics

#endif  // SD_PACKED3
