// Dyadic rationals (detail/rational.hpp): sums, differences, products, signs, comparisons and
// the rounded quotient against the same expressions in Boost's (or GMP's) normalized
// rationals, on doubles across the whole exponent range: subnormals, huge magnitudes, signed
// zeros, exact cancellation.
#include "detail/rational.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using ellipsect::detail::rational::Dyadic;
using ellipsect::detail::rational::Q;

Q rational(const Dyadic& d) {
  const Q two = 2;
  Q p = 1;
  for (int k = 0; k < std::abs(d.e); ++k) p *= two;
  return d.e >= 0 ? Q(d.m) * p : Q(d.m) / p;
}

std::vector<double> samples() {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-1074, 1000);
  std::vector<double> out = {0.0, -0.0, 1.0, -1.0, 0.5, 3.0, -2.5, std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::min(), std::numeric_limits<double>::max(), 1e6 + 0.1,
                             1e-300};
  for (int i = 0; i < 200; ++i) out.push_back(std::ldexp(mantissa(rng), exponent(rng)));
  for (int i = 0; i < 200; ++i) out.push_back(std::ldexp(mantissa(rng), exponent(rng) / 20));  // nearby scales
  return out;
}

TEST(Dyadic, DoublesAreExact) {
  for (double x : samples()) {
    const Dyadic d(x);
    EXPECT_EQ(rational(d), Q(x)) << x;
    if (d.m != 0) {
      EXPECT_TRUE(d.m % 2 != 0) << x;  // trailing zeros stripped
    }
  }
}

TEST(Dyadic, ArithmeticMatchesRationals) {
  const std::vector<double> x = samples();
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, x.size() - 1);
  for (int i = 0; i < 2000; ++i) {
    const double a = x[pick(rng)], b = x[pick(rng)], c = x[pick(rng)], d = x[pick(rng)];
    const Dyadic v = Dyadic(a) * Dyadic(b) - Dyadic(c) * Dyadic(d) + Dyadic(c);
    const Q w = Q(a) * Q(b) - Q(c) * Q(d) + Q(c);
    ASSERT_EQ(rational(v), w) << a << " " << b << " " << c << " " << d;
    EXPECT_EQ(sign(v), w > 0 ? 1 : w < 0 ? -1 : 0);
    EXPECT_EQ(Dyadic(a) < Dyadic(b), Q(a) < Q(b)) << a << " " << b;
  }
  // Exact cancellation: (a + b) - a - b is zero however far apart a and b are.
  for (int i = 0; i < 200; ++i) {
    const double a = x[pick(rng)], b = x[pick(rng)];
    EXPECT_EQ(sign(Dyadic(a) + Dyadic(b) - Dyadic(a) - Dyadic(b)), 0) << a << " " << b;
  }
}

TEST(Dyadic, QuotientIsTheRationalRounded) {
  const std::vector<double> x = samples();
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::size_t> pick(0, x.size() - 1);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const double a = x[pick(rng)], b = x[pick(rng)], c = x[pick(rng)];
    if (b == 0) continue;
    const Dyadic num = Dyadic(a) * Dyadic(c) + Dyadic(c), den = Dyadic(b) * Dyadic(b);
    const Q q = (Q(a) * Q(c) + Q(c)) / (Q(b) * Q(b));
    EXPECT_EQ(ellipsect::detail::rational::quotient(num, den), static_cast<double>(q)) << a << " " << b << " " << c;
    ++checked;
  }
  EXPECT_GT(checked, 1900);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
