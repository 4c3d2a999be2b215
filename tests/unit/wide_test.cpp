// The wide type of the certified fallbacks (src/detail/wide.hpp) has the format the rounding
// models assume on every platform, and is the emulated one exactly where the build asks for
// it or the platform's long double is double; pairs beyond double's range are answered
// through it.
#include <ellipsect/ellipsect.hpp>

#include "detail/wide.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <type_traits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using W = detail::WideFloat;

static_assert(std::numeric_limits<W>::digits >= 64, "the rounding models give the wide type 11 bits over double");
// (Boost counts the exponent of a significand in [1, 2), the standard one in [0.5, 1).)
static_assert(std::numeric_limits<W>::max_exponent >= 16383, "the wide type holds the squares and cubes of any double");
static_assert(std::is_same_v<W, long double> == !ELLIPSECT_EMULATED_WIDE);
#if LDBL_MANT_DIG < 64 || LDBL_MAX_EXP < 16384
static_assert(ELLIPSECT_EMULATED_WIDE, "a long double no wider than double takes the emulated type");
#endif

TEST(Wide, ArithmeticHasTheFormat) {
  // 1 + eps is representable, 1 + eps / 2 rounds to 1 (to even); the square of the
  // smallest double and the cube of the largest are normal and finite.
  constexpr int digits = std::numeric_limits<W>::digits;
  EXPECT_NE(W(1) + ldexp(W(1), 1 - digits), W(1));
  EXPECT_EQ(W(1) + ldexp(W(1), -digits), W(1));
  const W tiny = W(std::numeric_limits<double>::denorm_min()), huge = W(std::numeric_limits<double>::max());
  EXPECT_EQ(ilogb(tiny * tiny), -2148);
  EXPECT_EQ(ilogb(huge * huge * huge), 3071);
  EXPECT_LE(abs(sqrt(W(2)) * sqrt(W(2)) - W(2)), ldexp(W(1), -61));
}

// Radii 2^200 apart: not representable in double (detail/scale.hpp, ratio_bits = 160), so the
// whole query runs in the wide type. The small ball's center 1e-9 of the big one's radius
// outside its boundary (beyond the tangency band), on it, and 1e-9 inside.
TEST(Wide, PairsBeyondDoublesRange) {
  const double small = std::ldexp(1.0, -200), gap = 1e-9;
  const Ellipsoid3<double> big = make_ball<double, 3>(Vec3<double>::Zero(), 1.0);
  const Ellipsoid3<double> out = make_ball<double, 3>(Vec3<double>(1 + gap, 0, 0), small);
  const Ellipsoid3<double> on = make_ball<double, 3>(Vec3<double>(1, 0, 0), small);
  const Ellipsoid3<double> in = make_ball<double, 3>(Vec3<double>(1 - gap, 0, 0), small);
  EXPECT_EQ(classify(big, out), Relation::separated);
  EXPECT_EQ(classify(big, on), Relation::touching);
  EXPECT_EQ(classify(big, in), Relation::a_contains_b);
  EXPECT_EQ(classify(out, big), Relation::separated);
  EXPECT_EQ(classify(in, big), Relation::b_contains_a);
  // The centers' offsets from the boundary as stored (exact differences). The queries state
  // 1e-12 of the larger radius; the wide type's rounding, 2^-63 of it, gives far better.
  const double outside = (1 + gap) - 1, inside = 1 - (1 - gap), accuracy = 1e-15;
  const auto d = signed_distance(big, out);
  EXPECT_EQ(d.status, DistanceStatus::separated);
  EXPECT_NEAR(d.distance, outside - small, accuracy);
  const auto p = signed_distance(big, in);
  EXPECT_EQ(p.status, DistanceStatus::overlapping);
  EXPECT_NEAR(p.distance, -(inside + small), accuracy);
  const auto c = first_contact(big, Vec3<double>::Zero(), out, Vec3<double>(-1, 0, 0), 1.0);
  EXPECT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, outside - small, accuracy);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
