// sin and cos of every lane at once (spatial/lanes.hpp), for the joint rotations of the batched
// algorithms: a call of the C library's sincos per lane would cost as much as the rest of a
// revolute joint's arithmetic. Double lanes use the classic scheme: reduce x by the nearest
// multiple k of π/2 (Cody–Waite, π/2 split into three 33-bit parts so that k·part is exact for
// |k| < 2^20), evaluate the minimax polynomials of sin and cos on |r| ≤ π/4 (the coefficients of
// fdlibm's k_sin.c and k_cos.c), and pick sign and function by k mod 4. Within 1 ulp of the
// correctly rounded value plus the reduction's ≈ 1e-21·|k| absolute error. Lanes with |x| > 1e5 or
// non-finite, and other scalar types, take std::sin and std::cos.
#pragma once

#include <cmath>
#include <type_traits>

#include "spatial_dynamics/spatial/lanes.hpp"

namespace spatial_dynamics {

template <class S, int L>
SD_LANE_INLINE void sincos_lanes(const Lanes<S, L>& x, Lanes<S, L>& sine, Lanes<S, L>& cosine) {
  using std::abs;
  using std::cos;
  using std::sin;
  bool reducible = std::is_same<S, double>::value;
  for (int l = 0; l < L; ++l) reducible = reducible && abs(x[l]) <= S(1e5);  // false for NaN
  if (!reducible) {
    for (int l = 0; l < L; ++l) {
      sine.set(l, sin(x[l]));
      cosine.set(l, cos(x[l]));
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
