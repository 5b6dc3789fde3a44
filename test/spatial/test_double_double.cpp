// The double-double arithmetic against float128 (113-bit significand, so every double-double
// value and every exact sum or product of two doubles is held exactly or nearly so): the
// error-free transformations are exact, and sums, products, quotients and roots are within a
// few units of 2^-104 of the exact results, relative to the operands' magnitudes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/spatial/number/double_double.hpp"

namespace sd = spatial_dynamics;
using sd::DoubleDouble;
using sd::Quad;

namespace {

constexpr double kUnit = 0x1p-104;  // double-double's unit roundoff

Quad exact(const DoubleDouble& x) { return Quad(x.hi) + Quad(x.lo); }

/// A normalised double-double of random sign, with magnitude 10^U(−e, e).
DoubleDouble random_double_double(std::mt19937& rng, double e = 8) {
  std::uniform_real_distribution<double> exponent(-e, e), mantissa(1, 10), sign(-1, 1);
  const double hi = std::copysign(mantissa(rng) * std::pow(10.0, exponent(rng)), sign(rng));
  const double lo = std::uniform_real_distribution<double>(-0.5, 0.5)(rng) * std::ldexp(std::abs(hi), -52);
  const double s = hi + lo;  // renormalise
  return {s, lo - (s - hi)};
}

/// |computed − reference| / scale, in units of 2^-104.
double units(const DoubleDouble& computed, const Quad& reference, const Quad& scale) {
  return static_cast<double>(abs(exact(computed) - reference) / scale) / kUnit;
}

}  // namespace

TEST(DoubleDouble, ErrorFreeTransformationsAreExact) {
  std::mt19937 rng(21);
  for (int k = 0; k < 10000; ++k) {
    const double a = random_double_double(rng).hi, b = random_double_double(rng).hi;
    EXPECT_EQ(exact(sd::detail::two_sum(a, b)), Quad(a) + Quad(b)) << a << " + " << b;
    EXPECT_EQ(exact(sd::detail::two_product(a, b)), Quad(a) * Quad(b)) << a << " * " << b;
    const double big = std::abs(a) >= std::abs(b) ? a : b, small = std::abs(a) >= std::abs(b) ? b : a;
    EXPECT_EQ(exact(sd::detail::fast_two_sum(big, small)), Quad(big) + Quad(small)) << big << " + " << small;
  }
}

TEST(DoubleDouble, ArithmeticWithinAFewUnitsOfItsRounding) {
  std::mt19937 rng(22);
  double worst_sum = 0, worst_product = 0, worst_mixed = 0, worst_quotient = 0, worst_root = 0;
  for (int k = 0; k < 20000; ++k) {
    const DoubleDouble x = random_double_double(rng), y = random_double_double(rng);
    const double p = random_double_double(rng).hi;
    const Quad xq = exact(x), yq = exact(y), pq(p);
    // Sums: relative to |x| + |y| (the norm-wise accuracy the residual needs, cancellation or not).
    worst_sum = std::max({worst_sum, units(x + y, xq + yq, abs(xq) + abs(yq)),
                          units(x - y, xq - yq, abs(xq) + abs(yq)), units(x + p, xq + pq, abs(xq) + abs(pq))});
    worst_product = std::max(worst_product, units(x * y, xq * yq, abs(xq * yq)));
    worst_mixed = std::max({worst_mixed, units(p * x, pq * xq, abs(pq * xq)), units(x * p, xq * pq, abs(pq * xq))});
    worst_quotient = std::max(worst_quotient, units(x / y, xq / yq, abs(xq / yq)));
    const DoubleDouble magnitude = sd::abs(x);
    worst_root = std::max(worst_root, units(sd::sqrt(magnitude), sqrt(abs(xq)), sqrt(abs(xq))));
  }
  std::printf("[double-double] worst errors in units of 2^-104: sum %.2f, product %.2f, "
              "product by a double %.2f, quotient %.2f, square root %.2f\n",
              worst_sum, worst_product, worst_mixed, worst_quotient, worst_root);
  EXPECT_LE(worst_sum, 4.0);
  EXPECT_LE(worst_product, 8.0);
  EXPECT_LE(worst_mixed, 4.0);
  EXPECT_LE(worst_quotient, 16.0);
  EXPECT_LE(worst_root, 8.0);
}

TEST(DoubleDouble, ChainsOfUnnormalisedOperationsKeepTheirAccuracy) {
  // A dot product of 1000 terms and a polynomial of degree 50, operations chained without
  // renormalising: the error stays at a few units of 2^-104 of the magnitudes involved.
  std::mt19937 rng(23);
  DoubleDouble dot = 0.0;
  Quad dot_exact = 0, magnitude = 0;
  for (int k = 0; k < 1000; ++k) {
    const DoubleDouble x = random_double_double(rng, 3), y = random_double_double(rng, 3);
    dot += x * y;
    dot_exact += exact(x) * exact(y);
    magnitude += abs(exact(x) * exact(y));
  }
  const double dot_units = units(dot, dot_exact, magnitude);
  const DoubleDouble t = random_double_double(rng, 0.2);
  DoubleDouble horner = 0.0;
  Quad horner_exact = 0, horner_magnitude = 0;
  for (int k = 0; k < 50; ++k) {
    const double c = random_double_double(rng, 1).hi;
    horner = horner * t + c;
    horner_exact = horner_exact * exact(t) + Quad(c);
    horner_magnitude = horner_magnitude * abs(exact(t)) + abs(Quad(c));
  }
  const double horner_units = units(horner, horner_exact, horner_magnitude);
  std::printf("[double-double] 1000-term dot product %.2f units, degree-50 Horner %.2f units\n", dot_units,
              horner_units);
  // A few units per operation at worst; far below that for the dot product's random signs.
  EXPECT_LE(dot_units, 16.0);
  EXPECT_LE(horner_units, 50 * 2.0);
}

TEST(DoubleDouble, ConversionsAreExactOrRoundedOnce) {
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int k = 0; k < 1000; ++k) {
    const long double x = static_cast<long double>(u(rng)) / 3.0L;  // 64 significant bits
    const DoubleDouble d(x);
    EXPECT_EQ(exact(d), Quad(x));  // 64 bits fit in 106
    EXPECT_EQ(static_cast<long double>(d), x);
    EXPECT_EQ(static_cast<double>(d), static_cast<double>(x));
  }
  EXPECT_TRUE(sd::isfinite(DoubleDouble(1.0)));
  EXPECT_FALSE(sd::isfinite(DoubleDouble(1.0) / DoubleDouble(0.0)));
  EXPECT_TRUE(sd::isnan(DoubleDouble(std::nan(""))));
  EXPECT_LT(DoubleDouble(1.0, -1e-20), DoubleDouble(1.0));
  EXPECT_LE(DoubleDouble(1.0), DoubleDouble(1.0));
  EXPECT_GT(DoubleDouble(1.0, 1e-20), DoubleDouble(1.0));
}

TEST(DoubleDouble, SinAndCosMatchFloat128) {
  // Reduction boundaries (multiples of π/4 and their neighbours), both signs, random arguments up
  // to the 1e5 range of the reduction and beyond it (long double's library there), and arguments
  // with a low part (a coupled joint's k q + offset).
  std::vector<DoubleDouble> xs;
  for (int k = -400; k <= 400; ++k) {
    const double x = k * M_PI / 4;
    for (double v : {x, std::nextafter(x, 1e300), std::nextafter(x, -1e300)}) xs.push_back(v);
  }
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> wide(-1e5, 1e5), narrow(-10, 10);
  for (int k = 0; k < 4000; ++k) {
    xs.push_back(wide(rng));
    xs.push_back(narrow(rng));
    xs.push_back(random_double_double(rng, 1));
  }
  for (double x : {1e-300, -3e-8, 99999.99, 1e5, 1.0000001e5, -7e6}) xs.push_back(x);
  double worst_reduced = 0, worst_beyond = 0;
  for (const DoubleDouble& x : xs) {
    DoubleDouble s, c;
    sd::sin_cos(x, s, c);
    const Quad xq = exact(x);
    const double error = std::max(static_cast<double>(abs(exact(s) - sin(xq))), static_cast<double>(abs(exact(c) - cos(xq))));
    double& worst = std::abs(x.hi) <= 1e5 ? worst_reduced : worst_beyond;
    worst = std::max(worst, error);
    EXPECT_EQ(exact(sd::sin(x)), exact(s));
    EXPECT_EQ(exact(sd::cos(x)), exact(c));
  }
  std::printf("[double-double sin, cos] max absolute error %.3g for |x| <= 1e5, %.3g beyond, over %zu arguments\n",
              worst_reduced, worst_beyond, xs.size());
  EXPECT_LE(worst_reduced, 2e-21);
  EXPECT_LE(worst_beyond, 2 * std::numeric_limits<long double>::epsilon());
}
