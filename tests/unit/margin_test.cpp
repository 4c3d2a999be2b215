// margin.hpp: signed_distance_within is sound (nullopt only where signed_distance exceeds the
// margin) and complete (signed_distance's answer, bit for bit, wherever it is at most the margin),
// for bodies, half-spaces, boxes, capsules and triangles (degenerate ones too) made from every
// scenario category's pairs, 2D and 3D, at the origin and 1e6 sizes from it, at three bands, at
// margins just below, at and just above each pair's distance, and at margins whose grown radii
// overflow; at a margin <= 0 every separated pair is skipped. (Invalid Options cannot reach it:
// they are refused where they are made, options_test.cpp.)
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/margin.hpp>
#include <ellipsect/triangle.hpp>

#include "scenarios/scenarios.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <tuple>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;

template <class T, int N>
bool same_bits(const Distance<T, N>& x, const Distance<T, N>& y) {
  auto bits = [](const Distance<T, N>& d) {
    return std::make_tuple(d.status, d.iterations, std::bit_cast<std::uint64_t>(double(d.distance)));
  };
  return bits(x) == bits(y) && std::memcmp(x.point_a.data(), y.point_a.data(), sizeof(T) * N) == 0 &&
         std::memcmp(x.normal.data(), y.normal.data(), sizeof(T) * N) == 0;
}

template <int N, class Shape>
void check(const Ellipsoid<double, N>& a, const Shape& b, int& skipped, const char* what, const Options& options = {}) {
  const auto full = signed_distance(a, b, options);
  const double d = full.distance;
  const double scale = a.radii().maxCoeff() + std::abs(d);
  for (const double margin : {0.0, -std::abs(d), d * (1 - 1e-9), d, d * (1 + 1e-9), 2 * std::abs(d) + scale, 1e307}) {
    const auto got = signed_distance_within(a, b, margin, options);
    if (got) {
      EXPECT_TRUE(same_bits(*got, full)) << what << " margin " << margin;
    } else {
      ++skipped;
      EXPECT_GT(d, margin - 1e-12 * scale) << what << " margin " << margin;
    }
    if (d < margin - 1e-12 * scale) {
      EXPECT_TRUE(got.has_value()) << what << " margin " << margin << " d " << d;
    }
    // At a margin <= 0 the filter is the exact overlap test: every separated pair is skipped.
    if (margin <= 0 && full.status == DistanceStatus::separated) {
      EXPECT_FALSE(got.has_value()) << what;
    }
  }
}

// Every category's pairs, as made and moved 1e6 sizes from the origin, with the default
// options, the exact band and the widest one; degenerate triangles (collinear, a point) and a
// zero-length capsule (a ball) beside them.
template <int N>
void check_all(int& skipped) {
  for (const auto category : scenarios::all_categories)
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
      const auto c0 = scenarios::make_case<N>(category, seed);
      const Vec<double, N> far = Vec<double, N>::Constant(1e6 * (c0.a.radii().maxCoeff() + c0.b.radii().maxCoeff()));
      for (const bool moved : {false, true}) {
        const Ellipsoid<double, N> a = moved ? c0.a.translated(far) : c0.a;
        const Ellipsoid<double, N> b = moved ? c0.b.translated(far) : c0.b;
        const Options options{.tolerance = seed % 3 == 0 ? 0.0 : seed % 3 == 1 ? 1e-12 : 1e-9};
        const Vec<double, N> u = b.axes().col(N - 1), v = b.axes().col(0);
        const Vec<double, N> o = b.center();
        check<N>(a, b, skipped, "body", options);
        check<N>(a, make_half_space<double, N>(o, u), skipped, "half-space", options);
        check<N>(a, make_box<double, N>(o, b.axes(), b.radii()), skipped, "box", options);
        check<N>(a, make_capsule<double, N>(o - b.radii()[N - 1] * u, o + b.radii()[N - 1] * u, b.radii()[0]), skipped,
                 "capsule", options);
        check<N>(a, make_capsule<double, N>(o, o, b.radii()[0]), skipped, "zero-length capsule", options);
        check<N>(a, make_triangle<double, N>(o, o + b.radii()[0] * v, o + b.radii()[1] * u), skipped, "triangle",
                 options);
        check<N>(a, make_triangle<double, N>(o, o + b.radii()[0] * v, o + 2 * b.radii()[0] * v), skipped,
                 "collinear triangle", options);
        check<N>(a, make_triangle<double, N>(o, o, o), skipped, "point triangle", options);
      }
    }
}

TEST(SignedDistanceWithin, SoundAndCompleteOnEveryCategoryAndShape) {
  int skipped2 = 0, skipped3 = 0;
  check_all<2>(skipped2);
  check_all<3>(skipped3);
  // The filter does its work beyond margin 0 too: of the 22,400 queries per dimension, those
  // at margins below the distance are mostly skipped.
  EXPECT_GT(skipped2, 2000);
  EXPECT_GT(skipped3, 2000);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
