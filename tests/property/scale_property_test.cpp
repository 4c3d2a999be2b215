// Property: every query is exactly equivariant under scaling the scene by 2^k, k = +-500 and
// +-1000 (docs/method.md, section 7). Multiplying by a power of two is exact, so the scaled
// pair must give the same relation, overlap, statuses, contact time and normals, and
// lengths (points, distances) times exactly 2^k, areas times 2^2k; the batch functions
// must equal the scalar ones bit for bit on the scaled pairs. A case is used when its
// scaling is exact (no coordinate leaves the normal range); the test counts those.
#include <ellipsect/batch.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>
#include <ellipsect/point.hpp>

#include "tests/property/common.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ellipsect::testing {
namespace {
namespace ELLIPSECT_UNITY_ID {

constexpr int exponents[] = {500, -500, 1000, -1000};

// x * 2^k, or nothing when that is not exact (overflow, or a nonzero result below the
// normal range).
bool exact(double x, int k, double& y) {
  y = std::ldexp(x, k);
  return std::isfinite(y) && std::ldexp(y, -k) == x && (y == 0 || std::abs(y) >= std::numeric_limits<double>::min());
}

template <int N>
bool exact(const VecArg<double, N>& v, int k, Vec<double, N>& out) {
  for (int i = 0; i < N; ++i)
    if (!exact(v[i], k, out[i])) return false;
  return true;
}

template <int N>
bool exact(const Ellipsoid<double, N>& e, int k, std::optional<Ellipsoid<double, N>>& out) {
  Vec<double, N> c, r;
  if (!exact(e.center(), k, c) || !exact(e.radii(), k, r)) return false;
  out = Ellipsoid<double, N>::from_axes(c, e.axes(), r);
  return out->axes() == e.axes();
}

// want * 2^k where that is exact; a NaN stays NaN.
template <class T>
void expect_scaled(T got, T want, int k, const std::string& what) {
  if (std::isnan(want)) {
    EXPECT_TRUE(std::isnan(got)) << what;
    return;
  }
  double w;
  if (exact(want, k, w)) {
    EXPECT_EQ(got, w) << what;
  }
}

template <int N>
void expect_scaled(const Vec<double, N>& got, const Vec<double, N>& want, int k, const std::string& what) {
  for (int i = 0; i < N; ++i) expect_scaled(got[i], want[i], k, what);
}

template <int N>
void expect_same(const Vec<double, N>& got, const Vec<double, N>& want, const std::string& what) {
  for (int i = 0; i < N; ++i) {
    if (std::isnan(want[i]))
      EXPECT_TRUE(std::isnan(got[i])) << what;
    else
      EXPECT_EQ(got[i], want[i]) << what;
  }
}

template <int N>
void expect_contact(const Contact<double, N>& got, const Contact<double, N>& want, int k, const std::string& what) {
  ASSERT_EQ(got.status, want.status) << what;
  expect_scaled(got.time, want.time, 0, what + " time");
  expect_scaled<N>(got.point, want.point, k, what + " point");
  expect_same<N>(got.normal, want.normal, what + " normal");
}

template <int N>
void expect_distance(const Distance<double, N>& got, const Distance<double, N>& want, int k, const std::string& what) {
  ASSERT_EQ(got.status, want.status) << what;
  expect_scaled(got.distance, want.distance, k, what + " distance");
  expect_scaled<N>(got.point_a, want.point_a, k, what + " point_a");
  expect_scaled<N>(got.point_b, want.point_b, k, what + " point_b");
  expect_same<N>(got.normal, want.normal, what + " normal");
}

template <int N>
void check_scales(int per_category) {
  int used = 0, skipped = 0;
  for (const auto category : scenarios::all_categories) {
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_contact_case<N>(category, 900000 + i, 0.05);
      const std::string id = describe(c);
      const Relation relation = classify(c.a, c.b);
      const bool overlaps = overlap(c.a, c.b);
      const auto contact = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
      const auto dist = distance(c.a, c.b);
      const auto signed_dist = signed_distance(c.a, c.b);
      const auto point = closest_point(c.a, c.b.center());
      const auto pw = perram_wertheim(c.a, c.b);
      const Vec<double, N> dir = Vec<double, N>::LinSpaced(1.0, 0.3) + 1e-3 * c.vb;  // not scaled: a direction
      const auto approach = closest_approach(c.a, c.b, dir);
      for (const int k : exponents) {
        std::optional<Ellipsoid<double, N>> a, b;
        Vec<double, N> va, vb;
        if (!exact(c.a, k, a) || !exact(c.b, k, b) || !exact<N>(c.va, k, va) || !exact<N>(c.vb, k, vb)) {
          ++skipped;
          continue;
        }
        ++used;
        const std::string what = id + "\n  k=" + std::to_string(k);
        ASSERT_EQ(classify(*a, *b), relation) << what;
        ASSERT_EQ(overlap(*a, *b), overlaps) << what;
        expect_contact<N>(first_contact(*a, va, *b, vb, c.t_max), contact, k, what + " first_contact");
        expect_distance<N>(distance(*a, *b), dist, k, what + " distance");
        expect_distance<N>(signed_distance(*a, *b), signed_dist, k, what + " signed_distance");
        const auto p = closest_point(*a, b->center());
        expect_scaled<N>(p.point, point.point, k, what + " closest_point");
        expect_scaled(p.signed_distance, point.signed_distance, k, what + " closest_point");
        const auto pw_k = perram_wertheim(*a, *b);
        ASSERT_EQ(pw_k.status, pw.status) << what;
        expect_scaled(pw_k.f, pw.f, 0, what + " perram_wertheim");
        expect_scaled(pw_k.lambda, pw.lambda, 0, what + " perram_wertheim");
        const auto approach_k = closest_approach(*a, *b, dir);
        ASSERT_EQ(approach_k.status, approach.status) << what;
        expect_scaled(approach_k.distance, approach.distance, k, what + " closest_approach");
        expect_scaled<N>(approach_k.point, approach.point, k, what + " closest_approach");
        expect_same<N>(approach_k.normal, approach.normal, what + " closest_approach");
        if constexpr (N == 2) {
          const auto x = intersect_boundaries(c.a, c.b), xs = intersect_boundaries(*a, *b);
          ASSERT_EQ(xs.status, x.status) << what;
          ASSERT_EQ(xs.count, x.count) << what;
          for (int j = 0; j < x.count; ++j) {
            expect_scaled<2>(xs.points[j], x.points[j], k, what + " intersect_boundaries");
            EXPECT_EQ(xs.kinds[j], x.kinds[j]) << what;
          }
          const auto area = overlap_area(c.a, c.b), as = overlap_area(*a, *b);
          ASSERT_EQ(as.relation, area.relation) << what;
          expect_scaled(as.area, area.area, 2 * k, what + " overlap_area");
        }
      }
    }
  }
  std::printf("N=%d: %d scaled pairs checked, %d not exactly scalable\n", N, used, skipped);
  EXPECT_GT(used, 10 * per_category * 2);
}

TEST(ScaleProperty, AnswersScaleExactly2D) { check_scales<2>(cases(200)); }
TEST(ScaleProperty, AnswersScaleExactly3D) { check_scales<3>(cases(200)); }

// The batch functions equal the scalar ones bit for bit on scaled pairs (the filter leaves
// them to the scalar path) and on the unscaled ones mixed in the same chunks.
template <int N>
void check_batch(int per_category) {
  Pairs<double, N> pairs;
  for (const auto category : scenarios::all_categories)
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_contact_case<N>(category, 910000 + i, 0.05);
      pairs.push_back(c.a, c.va, c.b, c.vb, c.t_max);
      for (const int k : exponents) {
        std::optional<Ellipsoid<double, N>> a, b;
        Vec<double, N> va, vb;
        if (exact(c.a, k, a) && exact(c.b, k, b) && exact<N>(c.va, k, va) && exact<N>(c.vb, k, vb))
          pairs.push_back(*a, va, *b, vb, c.t_max);
      }
    }
  const std::size_t n = pairs.size();
  std::vector<Relation> relations(n);
  std::vector<Contact<double, N>> contacts(n);
  classify(pairs, std::span<Relation>(relations));
  std::unique_ptr<bool[]> flags(new bool[n]);
  overlap(pairs, std::span<bool>(flags.get(), n));
  first_contact(pairs, std::span<Contact<double, N>>(contacts));
  for (std::size_t i = 0; i < n; ++i) {
    const std::string what = "pair " + std::to_string(i);
    ASSERT_EQ(relations[i], classify(pairs.a(i), pairs.b(i))) << what;
    ASSERT_EQ(flags[i], overlap(pairs.a(i), pairs.b(i))) << what;
    const auto want = first_contact(pairs.a(i), pairs.velocity_a(i), pairs.b(i), pairs.velocity_b(i), pairs.t_max(i));
    expect_contact<N>(contacts[i], want, 0, what);
  }
}

TEST(ScaleProperty, BatchEqualsScalarOnScaledPairs2D) { check_batch<2>(cases(100)); }
TEST(ScaleProperty, BatchEqualsScalarOnScaledPairs3D) { check_batch<3>(cases(100)); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
}  // namespace ellipsect::testing
