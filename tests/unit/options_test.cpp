// Options are input: every field rejects what it cannot mean with an InputError naming it,
// and across the accepted tolerances every query gives the same answer on exactly tangent
// pairs and on pairs an ulp from tangent.
#include "../support.hpp"

#include <ellipsect/ellipsect.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Options stays an aggregate of plain values: designated initializers, constant
// expressions and memcpy keep working.
constexpr Options designated{.tolerance = 1e-10, .max_distance_iterations = 16, .max_motion_steps = 100};
static_assert(designated.tolerance == 1e-10 && designated.max_distance_iterations == 16 &&
              designated.max_contact_iterations == 64 && designated.max_motion_steps == 100);
static_assert(2 * Options{}.tolerance == 2e-12 && Options{}.max_contact_iterations == 64 &&
              Options{}.max_distance_iterations == 64 && Options{}.max_contact_function_iterations == 64 &&
              Options{}.max_slide_rounds == 64 && Options{}.max_motion_steps == 10000 && Options{}.max_slabs == 10000);
static_assert(std::is_aggregate_v<Options> && std::is_trivially_copyable_v<Options>);

TEST(Options, InvalidToleranceNamesTheField) {
  const double smallest = Tolerance::min, largest = Tolerance::max;
  for (const double t : {nan, -nan, inf, -inf, -1e-12, std::numeric_limits<double>::denorm_min(),
                         std::nextafter(smallest, 0.0), std::nextafter(largest, 1.0), 1e-6, 1.0, 1e300}) {
    expect_field([&] { (void)Options{.tolerance = t}; }, "tolerance");
    expect_field([&] { (void)Options{t}; }, "tolerance");
    Options o;
    expect_field([&] { o.tolerance = t; }, "tolerance");
    EXPECT_EQ(o.tolerance, 1e-12) << "a rejected assignment leaves the old value";
  }
  try {
    (void)Options{.tolerance = nan};
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "ellipsect: tolerance: must be 0 or in [1e-14, 1e-09] (got nan)");
  }
}

// Each cap of Options: a member pointer, in Options' order.
constexpr auto caps = std::make_tuple(&Options::max_contact_iterations, &Options::max_distance_iterations,
                                      &Options::max_contact_function_iterations, &Options::max_slide_rounds,
                                      &Options::max_motion_steps, &Options::max_slabs);

template <class F>
void for_each_cap(const F& f) {
  std::apply([&](auto... member) { (f(member), ...); }, caps);
}

TEST(Options, InvalidCapsNameTheField) {
  for_each_cap([]<class Cap>(Cap Options::*member) {
    const std::string field = Cap::field;
    const int before = Options{}.*member;
    for (const std::int64_t n : {std::int64_t(0), std::int64_t(-1), std::int64_t(std::numeric_limits<int>::min()),
                                 std::int64_t(Cap::max) + 1, std::int64_t(std::numeric_limits<int>::max()),
                                 std::int64_t(1) << 32, std::numeric_limits<std::int64_t>::min()}) {
      Options o;
      expect_field([&] { o.*member = n; }, field);
      EXPECT_EQ(o.*member, before) << field << ": a rejected assignment leaves the old value";
    }
    // Unsigned values beyond int are rejected as given, not wrapped into the range.
    Options o;
    expect_field([&] { o.*member = std::numeric_limits<std::uint64_t>::max(); }, field);
    expect_field([&] { o.*member = (std::uint64_t(1) << 32) + 5; }, field);
  });
  expect_field([] { (void)Options{.max_contact_iterations = 0}; }, "max_contact_iterations");
  expect_field([] { (void)Options{.max_slabs = 1000001}; }, "max_slabs");
  try {
    (void)Options{.max_motion_steps = std::numeric_limits<std::uint64_t>::max()};
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "ellipsect: max_motion_steps: must be in [1, 1000000] (got 18446744073709551615)");
  }
}

TEST(Options, TheRangeEndsAreAcceptedAndEachCapIsItsOwn) {
  EXPECT_EQ(Options{.tolerance = Tolerance::min}.tolerance, 1e-14);
  EXPECT_EQ(Options{.tolerance = Tolerance::max}.tolerance, 1e-9);
  for_each_cap([]<class Cap>(Cap Options::*member) {
    Options o;
    o.*member = std::size_t(1);
    EXPECT_EQ(o.*member, 1) << Cap::field;
    o.*member = Cap::max;
    EXPECT_EQ(o.*member, Cap::max) << Cap::field;
    // The other caps keep their defaults.
    for_each_cap([&]<class Other>(Other Options::*other) {
      if constexpr (!std::is_same_v<Other, Cap>) {
        EXPECT_EQ(o.*other, Options{}.*other) << Cap::field << " moved " << Other::field;
      }
    });
  });
}

// The answer every query should give, and what each reports for it.
struct Expected {
  Relation relation;
  ContactStatus contact() const {
    return relation == Relation::touching    ? ContactStatus::touching_at_start
           : relation == Relation::separated ? ContactStatus::no_contact_in_window
                                             : ContactStatus::overlapping_at_start;
  }
  DistanceStatus distance() const {
    return relation == Relation::touching    ? DistanceStatus::touching
           : relation == Relation::separated ? DistanceStatus::separated
                                             : DistanceStatus::overlapping;
  }
};

// The pair's answer with b moved by `ulps` ulps along its center's coordinate `axis`: an
// exact tangency (0) is touching; an ulp away it is touching in double (a relative gap of
// about 1e-16, inside every accepted band) and separated or overlapping in float (about
// 1e-7, outside them).
template <class T>
Expected expected_at(int ulps) {
  if (ulps == 0 || std::is_same_v<T, double>) return {Relation::touching};
  return {ulps > 0 ? Relation::separated : Relation::overlapping};
}

template <class T>
T moved(T x, int ulps) {
  return ulps == 0 ? x : std::nextafter(x, ulps > 0 ? T(inf) : T(-inf));
}

template <class T, int N>
Ellipsoid<T, N> axis_aligned(const std::array<T, N>& center, const std::array<T, N>& radii) {
  return Ellipsoid<T, N>::from_axes(Vec<T, N>(center.data()), Mat<T, N>::Identity(), Vec<T, N>(radii.data()));
}

template <class T, int N>
void expect_pair(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& o, Expected want,
                 const std::string& what) {
  SCOPED_TRACE(what + " tolerance " + std::to_string(double(o.tolerance)));
  const Vec<T, N> still = Vec<T, N>::Zero();
  EXPECT_EQ(classify(a, b, o), want.relation);
  EXPECT_EQ(classify(b, a, o), want.relation);
  EXPECT_EQ(overlap(a, b, o), want.relation != Relation::separated);
  EXPECT_EQ(first_contact(a, still, b, still, T(1), o).status, want.contact());
  EXPECT_EQ(signed_distance(a, b, o).status, want.distance());
  EXPECT_EQ(distance(a, b, o).status, want.distance());
  Pairs<T, N> pairs;
  pairs.push_back(a, b);
  std::array<Relation, 1> relation{};
  std::array<bool, 1> overlapping{};
  classify(pairs, std::span<Relation>(relation), BatchOptions{o, 1});
  overlap(pairs, std::span<bool>(overlapping), BatchOptions{o, 1});
  EXPECT_EQ(relation[0], want.relation);
  EXPECT_EQ(overlapping[0], want.relation != Relation::separated);
  if constexpr (N == 2) {
    const OverlapArea<T> area = overlap_area(a, b, o);
    EXPECT_EQ(area.relation, want.relation);
    EXPECT_EQ(area.area > 0, want.relation == Relation::overlapping);
  }
}

template <class T, int N, class Shape>
void expect_shape(const Ellipsoid<T, N>& a, const Shape& b, const Options& o, Expected want, const std::string& what) {
  SCOPED_TRACE(what + " tolerance " + std::to_string(double(o.tolerance)));
  const Vec<T, N> still = Vec<T, N>::Zero();
  EXPECT_EQ(classify(a, b, o), want.relation);
  EXPECT_EQ(overlap(a, b, o), want.relation != Relation::separated);
  EXPECT_EQ(first_contact(a, still, b, still, T(1), o).status, want.contact());
  EXPECT_EQ(signed_distance(a, b, o).status, want.distance());
}

const std::vector<Options> accepted = {Options{.tolerance = Tolerance::min}, Options{},
                                       Options{.tolerance = Tolerance::max}};

// Exactly tangent pairs (every coordinate and radius exact), and b an ulp away.
template <class T>
void tangent_pairs() {
  for (const Options& o : accepted) {
    for (const int ulps : {0, 1, -1}) {
      const Expected want = expected_at<T>(ulps);
      const std::string shift = std::string(sizeof(T) == 4 ? "float" : "double") + ", b " + std::to_string(ulps) + " ulp";
      expect_pair<T, 2>(axis_aligned<T, 2>({0, 0}, {1, 1}), axis_aligned<T, 2>({moved(T(2), ulps), 0}, {1, 1}), o,
                        want, "unit circles at 0 and 2, " + shift);
      expect_pair<T, 2>(axis_aligned<T, 2>({0, 0}, {3, 3}), axis_aligned<T, 2>({moved(T(5), ulps), 0}, {2, 2}), o,
                        want, "circles of radii 3 and 2, 5 apart, " + shift);
      expect_pair<T, 2>(axis_aligned<T, 2>({0, 0}, {2, 1}), axis_aligned<T, 2>({moved(T(3), ulps), 0}, {1, 1}), o,
                        want, "ellipse (2, 1) and a unit circle at (3, 0), " + shift);
      expect_pair<T, 3>(axis_aligned<T, 3>({0, 0, 0}, {1, 1, 1}), axis_aligned<T, 3>({moved(T(2), ulps), 0, 0}, {1, 1, 1}),
                        o, want, "unit spheres at 0 and 2, " + shift);
      expect_pair<T, 3>(axis_aligned<T, 3>({0, 0, 0}, {3, 3, 3}), axis_aligned<T, 3>({0, 0, moved(T(5), ulps)}, {2, 2, 2}),
                        o, want, "spheres of radii 3 and 2, 5 apart, " + shift);
      expect_pair<T, 3>(axis_aligned<T, 3>({0, 0, 0}, {2, 1, 1}), axis_aligned<T, 3>({moved(T(3), ulps), 0, 0}, {1, 1, 1}),
                        o, want, "ellipsoid (2, 1, 1) and a unit sphere at (3, 0, 0), " + shift);
      expect_pair<T, 3>(axis_aligned<T, 3>({0, 0, 0}, {2, 1, 0.5}),
                        axis_aligned<T, 3>({0, 0, moved(T(1.5), ulps)}, {1, 1, 1}), o, want,
                        "ellipsoid (2, 1, 0.5) and a unit sphere at (0, 0, 1.5), " + shift);
    }
  }
}

TEST(Options, TangentPairsAgreeAcrossQueriesDouble) { tangent_pairs<double>(); }
TEST(Options, TangentPairsAgreeAcrossQueriesFloat) { tangent_pairs<float>(); }

// The ellipse (2, 1) or ellipsoid (2, 1, 1) at the origin against shapes whose boundary
// holds the plane x = 2 near (2, 0, ...) and lie beyond it, moved by `ulps` along x.
template <class T, int N>
void tangent_shapes() {
  Vec<T, N> radii = Vec<T, N>::Ones(), e0 = Vec<T, N>::Zero(), e1 = Vec<T, N>::Zero();
  radii[0] = 2;
  e0[0] = 1;
  e1[1] = 1;
  const Ellipsoid<T, N> a = Ellipsoid<T, N>::from_axes(Vec<T, N>::Zero(), Mat<T, N>::Identity(), radii);
  for (const Options& o : accepted) {
    for (const int ulps : {0, 1, -1}) {
      const Expected want = expected_at<T>(ulps);
      const std::string shift = std::string(sizeof(T) == 4 ? "float" : "double") + " " + std::to_string(N) + "D, " +
                                std::to_string(ulps) + " ulp";
      const T two = moved(T(2), ulps), three = moved(T(3), ulps);
      expect_shape(a, make_half_space<T, N>(two * e0, -e0), o, want, "half-space x >= 2, " + shift);
      Vec<T, N> v1 = two * e0 + T(2) * e1, v2 = two * e0 - e1, v3 = two * e0 - e1;
      if constexpr (N == 3) {
        v2[2] = -1;
        v3[2] = 1;
      } else {
        v3 = three * e0;
      }
      expect_shape(a, make_triangle<T, N>(v1, v2, v3), o, want, "triangle with a side on x = 2, " + shift);
      expect_shape(a, make_box<T, N>(three * e0, Mat<T, N>::Identity(), Vec<T, N>::Ones()), o, want,
                   "box with a face on x = 2, " + shift);
      expect_shape(a, make_capsule<T, N>(three * e0 - e1, three * e0 + e1, T(1)), o, want,
                   "capsule with its side on x = 2, " + shift);
    }
  }
}

TEST(Options, TangentShapesAgreeAcrossQueries) {
  tangent_shapes<double, 2>();
  tangent_shapes<double, 3>();
  tangent_shapes<float, 2>();
  tangent_shapes<float, 3>();
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
