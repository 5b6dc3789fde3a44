// A 3-vector of double-doubles held in two 4-lane registers (hi, lo), for the ABA's gravity split
// (spatial/number/wide_vector3.hpp, for algorithms/gravity_split.hpp) and aba_refined's residual RNEA
// (algorithms/wide_residual_form.hpp): the error-free transformations of double_double.hpp
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

/// E y, or Eᵀ y with `transposed`, for E a rotation about a coordinate axis (packed3.hpp's
/// AxisRotation): cv ∘ y ± sv ∘ swap(y), each product with its error.
template <int axis>
SD_INLINE PackedDoubleDouble times(const AxisRotation<axis>& E, const PackedDoubleDouble& y, bool transposed) {
  const PackedDoubleDouble swapped{E.swap(y.hi), E.swap(y.lo)};
  return scale(E.cv, y) + scale(transposed ? -E.sv : E.sv, swapped);
}

// Both operands double-double (the residual RNEA on the double model, algorithms/wide_residual_form.hpp).

SD_INLINE PackedDoubleDouble operator-(const PackedDoubleDouble& x, const PackedDoubleDouble& y) { return x + (-y); }
SD_INLINE PackedDoubleDouble& operator+=(PackedDoubleDouble& x, const PackedDoubleDouble& y) { return x = x + y; }
SD_INLINE PackedDoubleDouble& operator-=(PackedDoubleDouble& x, const PackedDoubleDouble& y) { return x = x - y; }

/// a ∘ b for double-double a and b: TwoProduct of the high parts plus the cross terms.
SD_INLINE PackedDoubleDouble operator*(const PackedDoubleDouble& a, const PackedDoubleDouble& b) {
  const Packed3 p = a.hi * b.hi;
  return {p, fma(a.hi, b.hi, -p) + (a.hi * b.lo + a.lo * b.hi)};
}

/// a × b for double-double a and b: yzx(a ∘ yzx(b) − yzx(a) ∘ b).
SD_INLINE PackedDoubleDouble cross(const PackedDoubleDouble& a, const PackedDoubleDouble& b) {
  const PackedDoubleDouble yzx_a{yzx(a.hi), yzx(a.lo)}, yzx_b{yzx(b.hi), yzx(b.lo)};
  const PackedDoubleDouble difference = a * yzx_b - yzx_a * b;
  return {yzx(difference.hi), yzx(difference.lo)};
}

SD_INLINE PackedDoubleDouble splat(const DoubleDouble& x) { return {splat(x.hi), splat(x.lo)}; }

/// E x for E given by its double-double columns: the product with the high parts as above, and
/// the low parts' product with x's high parts in double (below the result's low parts' rounding).
SD_INLINE PackedDoubleDouble mat_vec(const PackedDoubleDouble& c0, const PackedDoubleDouble& c1,
                                     const PackedDoubleDouble& c2, const PackedDoubleDouble& x) {
  const PackedDoubleDouble of_high = mat_vec(c0.hi, c1.hi, c2.hi, x);
  return {of_high.hi, of_high.lo + mat_vec(c0.lo, c1.lo, c2.lo, x.hi)};
}

/// AxisRotation's rotation about coordinate axis k by an angle of double-double sine s and
/// cosine c: E y = cv ∘ y + sv ∘ swap(y), each product double-double; Eᵀ is the one of −s.
template <int axis>
struct WideAxisRotation {
  PackedDoubleDouble cv, sv;
  WideAxisRotation(const DoubleDouble& s, const DoubleDouble& c) {
    const AxisRotation<axis> high(s.hi, c.hi), low(s.lo, c.lo, 0.0);
    cv = {high.cv, low.cv};
    sv = {high.sv, low.sv};
  }
  SD_INLINE PackedDoubleDouble times(const PackedDoubleDouble& y) const {
    return cv * y + sv * PackedDoubleDouble{AxisRotation<axis>::swap(y.hi), AxisRotation<axis>::swap(y.lo)};
  }
};

/// Σ of lanes 0–2.
SD_INLINE DoubleDouble lane_sum(const PackedDoubleDouble& x) {
  return (DoubleDouble(x.hi[0], x.lo[0]) + DoubleDouble(x.hi[1], x.lo[1])) + DoubleDouble(x.hi[2], x.lo[2]);
}

/// a · x for double a.
SD_INLINE DoubleDouble dot(Packed3 a, const PackedDoubleDouble& x) { return lane_sum(scale(a, x)); }

}  // namespace packed3
}  // namespace spatial_dynamics

#endif  // SD_PACKED3
