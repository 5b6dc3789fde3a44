// sin and cos of every lane at once (spatial/number/lanes.hpp), for the joint rotations of the batched
// algorithms: a call of the C library's sincos per lane would cost as much as the rest of a
// revolute joint's arithmetic. Double lanes use the classic scheme: reduce x by the nearest
// multiple k of π/2 (Cody–Waite, π/2 split into three 33-bit parts so that k·part is exact for
// |k| < 2^20), evaluate the minimax polynomials of sin and cos on |r| ≤ π/4 (the coefficients of
// fdlibm's k_sin.c and k_cos.c), and pick sign and function by k mod 4. Within 1 ulp of the
// correctly rounded value plus the reduction's ≈ 1e-21·|k| absolute error. Lanes with |x| > 1e5 or
// non-finite take std::sin and std::cos; other scalar types take sin_cos_wide below, one lane at a
// time.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>

#include "spatial_dynamics/spatial/number/double_double.hpp"
#include "spatial_dynamics/spatial/number/lanes.hpp"

namespace spatial_dynamics {
namespace detail {

/// sin x and cos x of one scalar. For long double: Cody–Waite reduction x = k π/2 + y (π/2 split into
/// three pieces of ≤ 33 bits, so k·piece is exact for |k| < 2^31) and Taylor series of ten terms
/// on |y| ≤ π/4, whose truncations (|y|²¹/21! < 2e-22 for sin, |y|²⁰/20! < 4e-21 for cos) are
/// below long double's ε. k is rounded in double (exact to within 1e-11 of x 2/π for |x| ≤ 1e5,
/// so |y| stays within π/4 + 2e-11), which avoids the x87 rounding-mode switch; glibc's sinl and
/// cosl take several times longer. Double-double takes its own (double_double.hpp); other types
/// std::sin and std::cos.
template <class W>
inline void sin_cos_wide(const W& x, W& s, W& c) {
  using std::cos;
  using std::sin;
  s = sin(x);
  c = cos(x);
}
/// (−1)^j / (2j + offset)! for j = 0 … count−1: Taylor coefficients of sin (offset 1) and cos (0).
template <int count>
constexpr std::array<long double, count> alternating_inverse_factorials(int offset) {
  std::array<long double, count> c{};
  long double factorial = 1.0L;
  int n = 1;
  for (int j = 0; j < count; ++j) {
    for (; n <= 2 * j + offset; ++n) factorial *= n;  // exact: the odd part of 22! has 52 bits
    c[j] = (j % 2 ? -1.0L : 1.0L) / factorial;
  }
  return c;
}

inline void sin_cos_wide(const long double& x, long double& s, long double& c) {
  if (!(x <= 1e5L && x >= -1e5L)) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  constexpr long double pio2_1 = 1.57079632673412561417e+00L;   // 0x3FF921FB 54400000 (fdlibm)
  constexpr long double pio2_2 = 6.07710050630396597660e-11L;   // 0x3DD0B461 1A600000
  constexpr long double pio2_3 = 2.02226624871116645580e-21L;   // 0x3BA3198A 2E000000
  constexpr long double pio2_3t = 8.47842766036889956997e-32L;  // π/2 − pio2_1 − pio2_2 − pio2_3
  constexpr long double two_over_pi = 0.636619772367581343075535053490057448L;
  static constexpr std::array<long double, 10> sin_coefficients = alternating_inverse_factorials<10>(1);
  static constexpr std::array<long double, 10> cos_coefficients = alternating_inverse_factorials<10>(0);
  constexpr double round_shift = 6755399441055744.0;  // 1.5·2⁵²: adding and subtracting it rounds to an integer
  const double k_double = (static_cast<double>(x) * static_cast<double>(two_over_pi) + round_shift) - round_shift;
  const long long quadrant = static_cast<long long>(k_double);  // round(x 2/π)
  const long double k = k_double;
  const long double y = (((x - k * pio2_1) - k * pio2_2) - k * pio2_3) - k * pio2_3t;
  const long double z = y * y;
  long double ps = sin_coefficients[9], pc = cos_coefficients[9];
  for (int j = 8; j >= 0; --j) {
    ps = sin_coefficients[j] + z * ps;  // sin y = y Σ (−z)^j/(2j+1)!
    pc = cos_coefficients[j] + z * pc;  // cos y = Σ (−z)^j/(2j)!
  }
  const long double sy = y * ps;
  sin_cos_of_quadrant(quadrant, sy, pc, s, c);  // x = k π/2 + y
}

inline void sin_cos_wide(const DoubleDouble& x, DoubleDouble& s, DoubleDouble& c) { sin_cos(x, s, c); }

}  // namespace detail


template <class S, int L>
SD_LANE_INLINE void sincos_lanes(const Lanes<S, L>& x, Lanes<S, L>& sine, Lanes<S, L>& cosine) {
  using std::abs;
  bool reducible = std::is_same<S, double>::value;
  for (int l = 0; l < L; ++l) reducible = reducible && abs(x[l]) <= S(1e5);  // false for NaN
  if (!reducible) {
    for (int l = 0; l < L; ++l) {
      S s, c;
      detail::sin_cos_wide(x[l], s, c);
      sine.set(l, s);
      cosine.set(l, c);
    }
    return;
  }
  using Lane = Lanes<S, L>;
  // k = round(x · 2/π): adding and subtracting 1.5·2^52 rounds to the nearest integer.
  const S round_to_integer = S(6755399441055744.0);
  const Lane k = (x * S(6.36619772367581382433e-01) + round_to_integer) - round_to_integer;
  // r = x − k π/2, with π/2 = p1 + p2 + p3 (each k·p exact).
  const Lane r = ((x - k * S(1.57079632673412561417e+00)) - k * S(6.07710050630396597660e-11)) -
                 k * S(2.02226624871116645580e-21);
  const Lane z = r * r;
  // sin r = r + r³ (S1 + z (S2 + z (S3 + z (S4 + z (S5 + z S6)))))
  const Lane ps = S(8.33333333332248946124e-03) +
                  z * (S(-1.98412698298579493134e-04) +
                       z * (S(2.75573137070700676789e-06) +
                            z * (S(-2.50507602534068634195e-08) + z * S(1.58969099521155010221e-10))));
  const Lane sin_r = r + (z * r) * (S(-1.66666666666666324348e-01) + z * ps);
  // cos r = w + ((1 − w) − z/2 + z² (C1 + z (C2 + … + z C6))), w = 1 − z/2 (fdlibm's compensated form)
  const Lane pc = z * (S(4.16666666666666019037e-02) +
                       z * (S(-1.38888888888741095749e-03) +
                            z * (S(2.48015872894767294178e-05) +
                                 z * (S(-2.75573143513906633035e-07) +
                                      z * (S(2.08757232129817482790e-09) + z * S(-1.13596475577881948265e-11))))));
  const Lane half_z = S(0.5) * z;
  const Lane w = S(1) - half_z;
  const Lane cos_r = w + (((S(1) - w) - half_z) + z * pc);
  // x = r + k π/2: (sin, cos) x = (sin r, cos r), (cos r, −sin r), (−sin r, −cos r), (−cos r, sin r) for
  // k mod 4 = 0 … 3, picked without branches (the quadrant is random from lane to lane): with
  // o = k mod 2 and h = ⌊k/2⌋ mod 2, each 0 or 1, the products below only select and negate.
  const Lane odd_k = k - S(2) * ((k * S(0.5) + round_to_integer) - round_to_integer);  // ±1 or 0
  const Lane o = odd_k * odd_k;
  const Lane half_k = (k - o) * S(0.5);
  const Lane odd_half_k = half_k - S(2) * ((half_k * S(0.5) + round_to_integer) - round_to_integer);
  const Lane sign = S(1) - S(2) * (odd_half_k * odd_half_k);
  const Lane keep = S(1) - o;
  sine = sign * (keep * sin_r + o * cos_r);
  cosine = sign * (keep * cos_r - o * sin_r);
}

}  // namespace spatial_dynamics
