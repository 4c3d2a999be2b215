// Classification and overlap on configurations whose answer follows from elementary
// geometry.
#include <ellipsect/classify.hpp>

#include <gtest/gtest.h>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;

Relation mirrored(Relation r) {
  if (r == Relation::a_contains_b) return Relation::b_contains_a;
  if (r == Relation::b_contains_a) return Relation::a_contains_b;
  return r;
}

template <class T, int N>
void expect_relation(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, Relation expected) {
  EXPECT_EQ(classify(a, b), expected) << to_string(classify(a, b));
  EXPECT_EQ(classify(b, a), mirrored(expected));
  EXPECT_EQ(overlap(a, b), expected != Relation::separated);
  EXPECT_EQ(overlap(b, a), expected != Relation::separated);
}

TEST(Classify, Circles) {
  const auto a = make_ball<double, 2>({0, 0}, 1);
  expect_relation(a, make_ball<double, 2>({3, 0}, 1), Relation::separated);
  expect_relation(a, make_ball<double, 2>({2, 0}, 1), Relation::touching);
  expect_relation(a, make_ball<double, 2>({1.5, 0}, 1), Relation::overlapping);
  expect_relation(a, make_ball<double, 2>({0.25, 0}, 0.5), Relation::a_contains_b);
  expect_relation(a, make_ball<double, 2>({0.5, 0}, 0.5), Relation::a_contains_b);  // internally tangent
  expect_relation(a, make_ball<double, 2>({0, 0}, 1), Relation::equal);
  expect_relation(make_ball<double, 2>({0.5, 0}, 0.25), make_ball<double, 2>({0, 0}, 3), Relation::b_contains_a);
}

// Axis-aligned ellipses (2, 1) at the origin and (1, 3) at (x, 0) touch exactly at x = 3.
TEST(Classify, EllipsesTouchingAlongAnAxis) {
  const auto a = make_ellipse<double>({0, 0}, 0, {2, 1});
  auto b = [](double x) { return make_ellipse<double>({x, 0}, 0, {1, 3}); };
  expect_relation(a, b(3), Relation::touching);
  expect_relation(a, b(3 + 1e-9), Relation::separated);
  expect_relation(a, b(3 - 1e-9), Relation::overlapping);
  // Scaled by 1e6 and 1e-6: the same answers (relative tolerances).
  for (double s : {1e-6, 1e6}) {
    const auto as = make_ellipse<double>({0, 0}, 0, {2 * s, s});
    auto bs = [s](double x) { return make_ellipse<double>({x * s, 0}, 0, {s, 3 * s}); };
    expect_relation(as, bs(3), Relation::touching);
    expect_relation(as, bs(3 + 1e-9), Relation::separated);
    expect_relation(as, bs(3 - 1e-9), Relation::overlapping);
  }
}

// An ellipse rotated by pi is the same set.
TEST(Classify, EqualUnderSymmetry) {
  expect_relation(make_ellipse<double>({1, 1}, 0.3, {2, 1}), make_ellipse<double>({1, 1}, 0.3 + M_PI, {2, 1}),
                  Relation::equal);
  const auto e = make_ellipsoid<double>({0, 0, 0}, Mat3<double>::Identity(), {3, 2, 1});
  Mat3<double> flip = -Mat3<double>::Identity();
  flip(2, 2) = 1;
  expect_relation(e, make_ellipsoid<double>({0, 0, 0}, flip, {3, 2, 1}), Relation::equal);
}

// Concentric ellipsoids: containment decided by the radii alone (repeated radii included).
TEST(Classify, ConcentricEllipsoids) {
  const auto big = make_ellipsoid<double>({1, 2, 3}, Mat3<double>::Identity(), {3, 2, 2});
  expect_relation(big, make_ellipsoid<double>({1, 2, 3}, Mat3<double>::Identity(), {2.9, 1.9, 1.0}),
                  Relation::a_contains_b);
  expect_relation(big, make_ellipsoid<double>({1, 2, 3}, Mat3<double>::Identity(), {3, 2, 2}), Relation::equal);
  expect_relation(big, make_ellipsoid<double>({1, 2, 3}, Mat3<double>::Identity(), {3.5, 1, 1}),
                  Relation::overlapping);
  expect_relation(make_ball<double, 3>({1, 2, 3}, 1.5), big, Relation::b_contains_a);
  expect_relation(make_ball<double, 3>({1, 2, 3}, 2.0), big, Relation::b_contains_a);  // tangent inside
  expect_relation(make_ball<double, 3>({1, 2, 3}, 2.5), big, Relation::overlapping);
}

// A needle through a disc: aspect ratios 1e4, crossing at right angles.
TEST(Classify, NeedleThroughDisc) {
  const auto disc = make_ellipsoid<double>({0, 0, 0}, Mat3<double>::Identity(), {1, 1, 1e-4});
  const auto needle = make_ellipsoid<double>({0.5, 0, 0}, Mat3<double>::Identity(), {1e-4, 1e-4, 1});
  expect_relation(disc, needle, Relation::overlapping);
  // Lift the needle so its tip is 1e-12 (relative 1e-12) above the disc's top.
  const auto above = make_ellipsoid<double>({0.0, 0, 1 + 1e-4 + 1e-9}, Mat3<double>::Identity(), {1e-4, 1e-4, 1});
  expect_relation(disc, above, Relation::separated);
  const auto tip = make_ellipsoid<double>({0.0, 0, 1 + 1e-4}, Mat3<double>::Identity(), {1e-4, 1e-4, 1});
  expect_relation(disc, tip, Relation::touching);
}

TEST(Classify, FloatInstantiation) {
  const auto a = make_ball<float, 3>({0, 0, 0}, 1);
  expect_relation(a, make_ball<float, 3>({2, 0, 0}, 1), Relation::touching);
  expect_relation(a, make_ball<float, 3>({2.5f, 0, 0}, 1), Relation::separated);
}

TEST(Classify, ToString) {
  EXPECT_EQ(to_string(Relation::b_contains_a), "b_contains_a");
  EXPECT_EQ(to_string(Relation::touching), "touching");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
