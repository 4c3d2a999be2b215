// first_contact on configurations with closed-form answers, and every status.
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>

#include "tests/contact_wrappers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

TEST(FirstContact, HeadOnCircles) {
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({10, 0}, 1);
  const auto c = contact2(a, {1, 0}, b, {-1, 0}, 100);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 4.0, 1e-15);
  EXPECT_NEAR(c.point.x(), 5.0, 1e-14);
  EXPECT_NEAR(c.point.y(), 0.0, 1e-14);
  EXPECT_NEAR(c.normal.x(), 1.0, 1e-15);
  // Swapped: same time and point, normal reversed (it points from the first to the second body).
  const auto s = contact2(b, {-1, 0}, a, {1, 0}, 100);
  ASSERT_EQ(s.status, ContactStatus::hit);
  EXPECT_EQ(s.time, c.time);
  EXPECT_EQ(s.point, c.point);
  EXPECT_EQ(s.normal, Vec2<double>(-c.normal));
}

// Spheres of radii 1 and 2, relative velocity (-1, 0, 0) with offset 1.5 in y: the centers
// are 3 apart when (x0 - t)^2 + 1.5^2 = 9, i.e. t = x0 - sqrt(6.75).
TEST(FirstContact, OffsetSpheres) {
  const double x0 = 20;
  const auto a = make_ball<double, 3>({0, 0, 0}, 1);
  const auto b = make_ball<double, 3>({x0, 1.5, 0}, 2);
  const auto c = contact3(a, {0.5, 0, 0}, b, {-0.5, 0, 0}, inf);
  ASSERT_EQ(c.status, ContactStatus::hit);
  const double t = x0 - std::sqrt(6.75);
  EXPECT_NEAR(c.time, t, 1e-14 * t);
  const Vec3<double> ca(0.5 * t, 0, 0), cb(x0 - 0.5 * t, 1.5, 0);
  const Vec3<double> n = (cb - ca).normalized();
  EXPECT_LT((c.normal - n).norm(), 1e-14);
  EXPECT_LT((c.point - (ca + n)).norm(), 1e-14);
}

// Axis-aligned ellipses moving along x: (2, 1) at rest, (1, 3) from x = 10 at speed 1
// touch when the centers are 3 apart, at t = 7, at the point (2, 0).
TEST(FirstContact, AxisAlignedEllipses) {
  const auto a = make_ellipse<double>({0, 0}, 0, {2, 1});
  const auto b = make_ellipse<double>({10, 0}, 0, {1, 3});
  const auto c = contact2(a, {0, 0}, b, {-1, 0}, 100);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 7.0, 1e-14);
  EXPECT_LT((c.point - Vec2<double>(2, 0)).norm(), 1e-14);
  EXPECT_LT((c.normal - Vec2<double>(1, 0)).norm(), 1e-14);
  // The moving frame: both bodies drift by (3, 4); the same contact time, the point moved by 7 * (3, 4).
  const auto d = contact2(a, {3, 4}, b, {2, 4}, 100);
  ASSERT_EQ(d.status, ContactStatus::hit);
  EXPECT_NEAR(d.time, 7.0, 1e-14);
  EXPECT_LT((d.point - Vec2<double>(2 + 21, 28)).norm(), 1e-13);
}

TEST(FirstContact, Statuses) {
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto far = make_ball<double, 2>({10, 0}, 1);
  // Moving apart: the seed's W.P >= 0 quick-out.
  EXPECT_EQ(contact2(a, {0, 0}, far, {1, 0}, inf).status, ContactStatus::no_contact_in_window);
  // Zero relative velocity.
  EXPECT_EQ(contact2(a, {1, 1}, far, {1, 1}, inf).status, ContactStatus::no_contact_in_window);
  // Contact at t = 8 is outside the window [0, 7].
  EXPECT_EQ(contact2(a, {0, 0}, far, {-1, 0}, 7.0).status, ContactStatus::no_contact_in_window);
  EXPECT_EQ(contact2(a, {0, 0}, far, {-1, 0}, 8.5).status, ContactStatus::hit);
  // Passing by at distance 2.5 between centers: never within 2.
  EXPECT_EQ(contact2(a, {0, 0}, make_ball<double, 2>({10, 2.5}, 1), {-1, 0}, inf).status,
            ContactStatus::no_contact_in_window);
  // Overlapping and touching at the start.
  const auto c = contact2(a, {0, 0}, make_ball<double, 2>({1, 0}, 1), {-1, 0}, inf);
  EXPECT_EQ(c.status, ContactStatus::overlapping_at_start);
  EXPECT_EQ(c.time, 0.0);
  EXPECT_TRUE(std::isnan(c.point.x()));
  const auto t = contact2(a, {0, 0}, make_ball<double, 2>({2, 0}, 1), {1, 0}, inf);
  EXPECT_EQ(t.status, ContactStatus::touching_at_start);
  EXPECT_LT((t.point - Vec2<double>(1, 0)).norm(), 1e-15);
  EXPECT_LT((t.normal - Vec2<double>(1, 0)).norm(), 1e-15);
  // Containment at the start counts as overlapping.
  EXPECT_EQ(contact2(a, {0, 0}, make_ball<double, 2>({0, 0}, 0.1), {1, 0}, inf).status,
            ContactStatus::overlapping_at_start);
}

// Overlapping by a relative gap of -5e-10 (unit balls 2 - 5e-10 apart): past the default
// band, inside the widest accepted band, 1e-9.
TEST(FirstContact, ShallowOverlapFollowsTheTolerance) {
  const auto a = make_ball<double, 3>({0, 0, 0}, 1);
  const auto b = make_ball<double, 3>({2 - 5e-10, 0, 0}, 1);
  const Vec3<double> still(0, 0, 0), closing(-1, 0, 0);
  EXPECT_EQ(first_contact(a, still, b, closing, inf).status, ContactStatus::overlapping_at_start);
  Options wide;
  wide.tolerance = Tolerance::max;
  const auto c = first_contact(a, still, b, closing, inf, wide);
  EXPECT_EQ(c.status, ContactStatus::touching_at_start);
  EXPECT_LT((c.normal - Vec3<double>(1, 0, 0)).norm(), 1e-12);
}

TEST(FirstContact, InvalidInput) {
  const auto a = make_ball<double, 3>({0, 0, 0}, 1);
  const auto b = make_ball<double, 3>({5, 0, 0}, 1);
  EXPECT_EQ(contact3(a, {nan, 0, 0}, b, {0, 0, 0}, 1).status, ContactStatus::invalid_input);
  EXPECT_EQ(contact3(a, {0, 0, 0}, b, {0, inf, 0}, 1).status, ContactStatus::invalid_input);
  EXPECT_EQ(contact3(a, {0, 0, 0}, b, {-1, 0, 0}, -1).status, ContactStatus::invalid_input);
  EXPECT_EQ(contact3(a, {0, 0, 0}, b, {-1, 0, 0}, nan).status, ContactStatus::invalid_input);
}

// Unit circles, the mover's center passing at exactly 2 from the other's: a double root
// of the distance, tangency at t = 10 at the point (0, 1).
TEST(FirstContact, GrazingPath) {
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto c = contact2(a, {0, 0}, make_ball<double, 2>({-10, 2}, 1), {1, 0}, inf);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 10.0, 1e-5);  // sqrt(tolerance)-conditioned
  EXPECT_NEAR(c.normal.y(), 1.0, 1e-5);
  // Missing by 1e-9 (relative 5e-10 of the size) is a miss, outside the 1e-12 band.
  EXPECT_EQ(contact2(a, {0, 0}, make_ball<double, 2>({-10, 2 + 1e-9}, 1), {1, 0}, inf).status,
            ContactStatus::no_contact_in_window);
  // Passing 1e-9 too close is a hit, earlier than the tangency.
  const auto h = contact2(a, {0, 0}, make_ball<double, 2>({-10, 2 - 1e-9}, 1), {1, 0}, inf);
  ASSERT_EQ(h.status, ContactStatus::hit);
  EXPECT_NEAR(h.time, 10 - std::sqrt(4 - (2 - 1e-9) * (2 - 1e-9)), 1e-9);
}

TEST(FirstContact, IterationCapIsReported) {
  const auto a = make_ellipse<double>({0, 0}, 0.3, {3, 1});
  const auto b = make_ellipse<double>({10, 1}, -0.2, {1, 2});
  Options o;
  o.max_contact_iterations = 1;
  const auto c = contact2(a, {0, 0}, b, {-1, 0}, inf, o);
  EXPECT_EQ(c.status, ContactStatus::did_not_converge);
  EXPECT_EQ(c.iterations, 1);
  o.max_contact_iterations = 64;
  EXPECT_EQ(contact2(a, {0, 0}, b, {-1, 0}, inf, o).status, ContactStatus::hit);
}

TEST(FirstContact, FloatInstantiation) {
  const auto a = make_ball<float, 3>({0, 0, 0}, 1);
  const auto b = make_ball<float, 3>({10, 0, 0}, 1);
  const auto c = first_contact<float, 3>(a, {0, 0, 0}, b, {-2, 0, 0}, 100.0f);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_FLOAT_EQ(c.time, 4.0f);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
