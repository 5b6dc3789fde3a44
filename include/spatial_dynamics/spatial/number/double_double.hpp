// A double-double number: the unevaluated sum hi + lo of two doubles, |lo| ≤ ulp(hi)/2, about
// 106 significant bits (Dekker, "A floating-point technique for extending the available
// precision", 1971; the error-free transformations TwoSum (Knuth) and TwoProduct). Its
// arithmetic stays in the vector registers: where long double's x87 arithmetic moves every
// operand through 80-bit memory words, these few double operations are several times faster.
// Used as the wide type of the refinement residual (aba_refined.hpp). Sums and products are
// rounded to double-double (relative error a few 2^-104); sin and cos to about 1e-21.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "spatial_dynamics/spatial/eigen_types.hpp"

namespace spatial_dynamics {

/// Whether the target has a fused multiply-add: an exact product then takes two instructions
/// instead of Dekker's seventeen.
#if defined(__FMA__) || defined(__aarch64__)
constexpr bool kFusedMultiplyAdd = true;
#else
constexpr bool kFusedMultiplyAdd = false;
#endif

struct DoubleDouble {
  double hi = 0.0;
  double lo = 0.0;

  DoubleDouble() = default;
  DoubleDouble(double x) : hi(x) {}  // NOLINT: exact, implicit like double's own widening
  DoubleDouble(int x) : hi(x) {}     // NOLINT
  DoubleDouble(double high, double low) : hi(high), lo(low) {}
  /// Rounds a long double to the nearest double-double (exact: 64 bits fit in 106).
  explicit DoubleDouble(long double x) : hi(static_cast<double>(x)), lo(static_cast<double>(x - static_cast<long double>(hi))) {}

  explicit operator double() const { return hi + lo; }
  explicit operator float() const { return static_cast<float>(hi + lo); }
  explicit operator long double() const { return static_cast<long double>(hi) + static_cast<long double>(lo); }

  DoubleDouble& operator+=(const DoubleDouble& y);
  DoubleDouble& operator-=(const DoubleDouble& y);
  DoubleDouble& operator*=(const DoubleDouble& y);
  DoubleDouble& operator/=(const DoubleDouble& y);
};

namespace detail {

/// s + e = a + b exactly, for any a and b (Knuth's TwoSum).
SD_INLINE DoubleDouble two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

/// s + e = a + b exactly, for |a| ≥ |b| or a = 0 (Dekker's FastTwoSum).
SD_INLINE DoubleDouble fast_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

/// p + e = a b exactly (barring underflow): with a fused multiply-add where the target has one,
/// else by Dekker's splitting of each factor into two 26-bit halves.
SD_INLINE DoubleDouble two_product(double a, double b) {
  const double p = a * b;
  if constexpr (kFusedMultiplyAdd) return {p, std::fma(a, b, -p)};
  constexpr double split = 134217729.0;  // 2^27 + 1
  const double ta = split * a, tb = split * b;
  const double a_high = ta - (ta - a), b_high = tb - (tb - b);
  const double a_low = a - a_high, b_low = b - b_high;
  return {p, ((a_high * b_high - p) + a_high * b_low + a_low * b_high) + a_low * b_low};
}

/// sin x and cos x for x = k π/2 + y from sin y and cos y: the quarter turns rotate (cos, sin).
template <class T>
inline void sin_cos_of_quadrant(long long k, const T& sin_y, const T& cos_y, T& s, T& c) {
  switch (k & 3) {
    case 0: s = sin_y; c = cos_y; return;
    case 1: s = cos_y; c = -sin_y; return;
    case 2: s = -sin_y; c = -cos_y; return;
    default: s = -cos_y; c = sin_y; return;
  }
}

}  // namespace detail

// The arithmetic is forced inline (SD_INLINE): a call spills every live vector register around
// it, and aba_refined's wide RNEA residual is made of these (inlined, the call takes 0.89–0.95 of its time).
SD_INLINE DoubleDouble operator-(const DoubleDouble& x) { return {-x.hi, -x.lo}; }

/// x + y: TwoSum of the high parts, the low parts added to its error. Not renormalised: the
/// high part then needs one addition, so chains of operations run at double's latency.
SD_INLINE DoubleDouble operator+(const DoubleDouble& x, const DoubleDouble& y) {
  const DoubleDouble s = detail::two_sum(x.hi, y.hi);
  return {s.hi, s.lo + (x.lo + y.lo)};
}
SD_INLINE DoubleDouble operator-(const DoubleDouble& x, const DoubleDouble& y) { return x + (-y); }

/// x y: TwoProduct of the high parts plus the cross terms (lo·lo is below the result's precision).
SD_INLINE DoubleDouble operator*(const DoubleDouble& x, const DoubleDouble& y) {
  const DoubleDouble p = detail::two_product(x.hi, y.hi);
  return {p.hi, p.lo + (x.hi * y.lo + x.lo * y.hi)};
}

// With a double operand (a model parameter), its missing low part saves the cross terms.
SD_INLINE DoubleDouble operator*(double a, const DoubleDouble& y) {
  const DoubleDouble p = detail::two_product(a, y.hi);
  return {p.hi, p.lo + a * y.lo};
}
SD_INLINE DoubleDouble operator*(const DoubleDouble& x, double b) { return b * x; }
SD_INLINE DoubleDouble operator+(const DoubleDouble& x, double b) {
  const DoubleDouble s = detail::two_sum(x.hi, b);
  return {s.hi, s.lo + x.lo};
}
SD_INLINE DoubleDouble operator+(double a, const DoubleDouble& y) { return y + a; }
SD_INLINE DoubleDouble operator-(const DoubleDouble& x, double b) { return x + (-b); }
SD_INLINE DoubleDouble operator-(double a, const DoubleDouble& y) { return (-y) + a; }

/// x / y: the double quotient corrected once by the double-double remainder x − q y (whose
/// high part alone is not its value: the high parts cancel).
inline DoubleDouble operator/(const DoubleDouble& x, const DoubleDouble& y) {
  const double q = x.hi / y.hi;
  const DoubleDouble remainder = x - q * y;
  return detail::fast_two_sum(q, (remainder.hi + remainder.lo) / y.hi);
}

SD_INLINE DoubleDouble& DoubleDouble::operator+=(const DoubleDouble& y) { return *this = *this + y; }
SD_INLINE DoubleDouble& DoubleDouble::operator-=(const DoubleDouble& y) { return *this = *this - y; }
SD_INLINE DoubleDouble& DoubleDouble::operator*=(const DoubleDouble& y) { return *this = *this * y; }
SD_INLINE DoubleDouble& DoubleDouble::operator/=(const DoubleDouble& y) { return *this = *this / y; }

// Normalised pairs compare as their high parts, ties broken by the low parts.
inline bool operator==(const DoubleDouble& x, const DoubleDouble& y) { return x.hi == y.hi && x.lo == y.lo; }
inline bool operator!=(const DoubleDouble& x, const DoubleDouble& y) { return !(x == y); }
inline bool operator<(const DoubleDouble& x, const DoubleDouble& y) { return x.hi < y.hi || (x.hi == y.hi && x.lo < y.lo); }
inline bool operator>(const DoubleDouble& x, const DoubleDouble& y) { return y < x; }
inline bool operator<=(const DoubleDouble& x, const DoubleDouble& y) { return x.hi < y.hi || (x.hi == y.hi && x.lo <= y.lo); }
inline bool operator>=(const DoubleDouble& x, const DoubleDouble& y) { return y <= x; }

inline DoubleDouble abs(const DoubleDouble& x) { return x.hi < 0.0 || (x.hi == 0.0 && x.lo < 0.0) ? -x : x; }
inline DoubleDouble abs2(const DoubleDouble& x) { return x * x; }
inline bool isfinite(const DoubleDouble& x) { return std::isfinite(x.hi) && std::isfinite(x.lo); }
inline bool isnan(const DoubleDouble& x) { return std::isnan(x.hi) || std::isnan(x.lo); }
inline bool isinf(const DoubleDouble& x) { return std::isinf(x.hi); }

/// √x: the double root corrected by one Newton step in double-double, s + (x − s²)/(2s).
inline DoubleDouble sqrt(const DoubleDouble& x) {
  const double s = std::sqrt(x.hi);
  if (!(s > 0.0) || !std::isfinite(s)) return DoubleDouble(s);
  const DoubleDouble square = detail::two_product(s, s);
  return detail::fast_two_sum(s, ((x.hi - square.hi) - square.lo + x.lo) / (2.0 * s));
}

/// sin x and cos x to about 1e-21 absolute for |x| ≤ 1e5: Cody–Waite reduction x = k π/2 + y
/// (π/2 in pieces of ≤ 33 bits, so each k·piece is exact, and x − k·piece₁ is exact by
/// Sterbenz's lemma), then the Taylor series on |y| ≤ π/4: the terms up to y⁷ (sin) and y⁸ (cos)
/// in double-double, the rest (below 3.2e-7 and 3.6e-6) in double, up to the last term above
/// 1e-22 (y¹⁹/19!, y²⁰/20!). Beyond 1e5 (and for non-finite x), long double's library functions.
inline void sin_cos(const DoubleDouble& x, DoubleDouble& s, DoubleDouble& c) {
  if (!(std::abs(x.hi) <= 1e5)) {
    const long double wide = static_cast<long double>(x);
    s = DoubleDouble(std::sin(wide));
    c = DoubleDouble(std::cos(wide));
    return;
  }
  constexpr double pio2_1 = 1.57079632673412561417e+00;   // 33 bits of π/2 (fdlibm)
  constexpr double pio2_2 = 6.07710050630396597660e-11;   // the next 33
  constexpr double pio2_3 = 2.02226624871116645580e-21;   // the next 33
  constexpr double pio2_3t = 8.47842766036889956997e-32;  // π/2 − pio2_1 − pio2_2 − pio2_3
  constexpr double round_shift = 6755399441055744.0;      // 1.5·2⁵²: adding and subtracting it rounds to an integer
  const double k = (x.hi * 0.63661977236758134308 + round_shift) - round_shift;  // round(x 2/π)
  const DoubleDouble y = detail::two_sum(x.hi - k * pio2_1, -(k * pio2_2)) - k * pio2_3 + (x.lo - k * pio2_3t);
  const DoubleDouble z = y * y;
  const double w = z.hi;
  // (−1)^j / (2j+1)! for j = 4 … 9 and (−1)^j / (2j)! for j = 5 … 10, in double.
  const double sin_tail = 2.7557319223985893e-06 + w * (-2.505210838544172e-08 + w * (1.6059043836821613e-10 +
                          w * (-7.647163731819816e-13 + w * (2.8114572543455206e-15 + w * -8.22063524662433e-18))));
  const double cos_tail = -2.755731922398589e-07 + w * (2.08767569878681e-09 + w * (-1.1470745597729725e-11 +
                          w * (4.779477332387385e-14 + w * (-1.5619206968586225e-16 + w * 4.110317623312165e-19))));
  // 1/3!, 1/5!, 1/7!, 1/4!, 1/6!, 1/8! in double-double.
  const DoubleDouble inv3(0x1.5555555555555p-3, 0x1.5555555555555p-57), inv5(0x1.1111111111111p-7, 0x1.1111111111111p-63),
      inv7(0x1.a01a01a01a01ap-13, 0x1.a01a01a01a01ap-73), inv4(0x1.5555555555555p-5, 0x1.5555555555555p-59),
      inv6(0x1.6c16c16c16c17p-10, -0x1.f49f49f49f49fp-65), inv8(0x1.a01a01a01a01ap-16, 0x1.a01a01a01a01ap-76);
  const DoubleDouble sin_y = y + (y * z) * (-inv3 + z * (inv5 + z * (-inv7 + z * sin_tail)));
  const DoubleDouble cos_y = 1.0 + z * (-0.5 + z * (inv4 + z * (-inv6 + z * (inv8 + z * cos_tail))));
  const DoubleDouble sn = detail::fast_two_sum(sin_y.hi, sin_y.lo), cs = detail::fast_two_sum(cos_y.hi, cos_y.lo);
  detail::sin_cos_of_quadrant(static_cast<long long>(k), sn, cs, s, c);
}

inline DoubleDouble sin(const DoubleDouble& x) {
  DoubleDouble s, c;
  sin_cos(x, s, c);
  return s;
}
inline DoubleDouble cos(const DoubleDouble& x) {
  DoubleDouble s, c;
  sin_cos(x, s, c);
  return c;
}

/// About twice S's precision at a few operations each: double-double for double, double for
/// float; any other scalar (float128, long double, double-double) is its own. The ABA forms
/// τ − τ_g(q) in it (algorithms/gravity_split.hpp).
template <class S>
struct WiderScalarOf {
  using type = S;
};
template <>
struct WiderScalarOf<double> {
  using type = DoubleDouble;
};
template <>
struct WiderScalarOf<float> {
  using type = double;
};
template <class S>
using WiderScalar = typename WiderScalarOf<S>::type;

}  // namespace spatial_dynamics

namespace Eigen {

template <>
struct NumTraits<spatial_dynamics::DoubleDouble> : GenericNumTraits<double> {
  using Real = spatial_dynamics::DoubleDouble;
  using NonInteger = spatial_dynamics::DoubleDouble;
  using Nested = spatial_dynamics::DoubleDouble;
  using Literal = spatial_dynamics::DoubleDouble;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 0, ReadCost = 2, AddCost = 10, MulCost = 8 };
  static Real epsilon() { return Real(0x1p-104); }  // 2^-104: the relative rounding of a sum or product
  static Real dummy_precision() { return Real(1e-28); }
  static Real highest() { return Real(std::numeric_limits<double>::max()); }
  static Real lowest() { return Real(std::numeric_limits<double>::lowest()); }
  static Real infinity() { return Real(std::numeric_limits<double>::infinity()); }
  static Real quiet_NaN() { return Real(std::numeric_limits<double>::quiet_NaN()); }
  static int digits10() { return 31; }
  static int digits() { return 106; }
};

}  // namespace Eigen
