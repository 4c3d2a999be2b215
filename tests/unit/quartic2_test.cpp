// The closed-form closest point (the published formula and the careful quartic) on points
// whose answer is known by construction: a point moved out along the normal at a boundary
// point P has P as its closest point (the ellipse is convex), at the distance moved.
#include <ellipsect/quartic2.hpp>

#include "detail/niemitalo_quartic.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;

struct Known {
  Vec2<double> x, point;
  double distance;
};

// P at parameter theta, x = P + t * unit normal.
Known along_normal(const Ellipse2<double>& e, double theta, double t) {
  const Vec2<double> on(e.radii()[0] * std::cos(theta), e.radii()[1] * std::sin(theta));
  const Vec2<double> normal = on.cwiseQuotient(e.radii().cwiseAbs2()).normalized();
  return {e.center() + e.axes() * (on + t * normal), e.center() + e.axes() * on, t};
}

TEST(QuarticClosestPoint, PointsAlongNormals) {
  for (double aspect : {1.0, 1.001, 2.0, 10.0, 1e2, 1e4}) {
    const auto e = make_ellipse<double>({0.5, -1.5}, 0.3, {1.5, 1.5 / aspect});
    for (double theta = -3.1; theta < 3.2; theta += 0.37) {
      for (double t : {1e-9, 1e-3, 0.5, 3.0, 1e3}) {
        const Known k = along_normal(e, theta, t);
        const auto q = closest_point_quartic(e, k.x);
        ASSERT_EQ(q.status, QuarticStatus::outside) << aspect << " " << theta << " " << t;
        const double scale = 1.5 + t;
        EXPECT_LT((q.point - k.point).norm(), 1e-13 * scale) << aspect << " " << theta << " " << t;
        EXPECT_NEAR(q.distance, k.distance, 1e-13 * scale) << aspect << " " << theta << " " << t;
      }
    }
  }
}

// The published formula on moderate shapes and distances, where it is meant to work.
TEST(ClosedFormClosestPoint, PointsAlongNormals) {
  for (double aspect : {1.2, 2.0, 10.0}) {
    const auto e = make_ellipse<double>({0.5, -1.5}, 0.3, {1.5, 1.5 / aspect});
    for (double theta = -3.1; theta < 3.2; theta += 0.37) {
      for (double t : {1e-3, 0.5, 3.0}) {
        const Known k = along_normal(e, theta, t);
        const auto q = closest_point_closed_form(e, k.x);
        ASSERT_EQ(q.status, QuarticStatus::outside) << aspect << " " << theta << " " << t;
        EXPECT_LT((q.point - k.point).norm(), 1e-6) << aspect << " " << theta << " " << t;
        EXPECT_NEAR(q.distance, k.distance, 1e-6) << aspect << " " << theta << " " << t;
      }
    }
  }
}

// The document's first example as a closest-point question: the circle's center (25, 7) is
// at least 16 from the ellipse (which lies in x <= 9) and at most |(25, 7) - (9, 5)| =
// sqrt(260) from it; the radius is 15, so no collision.
TEST(QuarticClosestPoint, DocumentExampleEllipseCircle) {
  const auto e = make_ellipse<double>({-1, 5}, 0, {10, 20});
  for (const auto& q : {closest_point_closed_form(e, Vec2<double>(25, 7)), closest_point_quartic(e, Vec2<double>(25, 7))}) {
    ASSERT_EQ(q.status, QuarticStatus::outside);
    EXPECT_GE(q.distance, 16.0);
    EXPECT_LE(q.distance, std::sqrt(260.0));
    EXPECT_GT(q.distance, 15.0);
  }
}

// A circle (b = 1): the formula divides by b^2 - 1 and reports failure; the quartic gives
// the radial projection.
TEST(ClosedFormClosestPoint, CircleFails) {
  const auto c = make_ball<double, 2>({1, 1}, 2);
  EXPECT_EQ(closest_point_closed_form(c, Vec2<double>(4, 5)).status, QuarticStatus::failed);
  const auto q = closest_point_quartic(c, Vec2<double>(4, 5));  // 5 from the center
  ASSERT_EQ(q.status, QuarticStatus::outside);
  EXPECT_LT((q.point - Vec2<double>(1 + 1.2, 1 + 1.6)).norm(), 1e-15);
  EXPECT_NEAR(q.distance, 3.0, 1e-15);
  EXPECT_TRUE(std::isnan(closest_point_closed_form(c, Vec2<double>(4, 5)).distance));
}

TEST(QuarticClosestPoint, InsideAndInvalid) {
  const auto e = make_ellipse<double>({0, 0}, 0.2, {3, 1});
  for (const auto& q : {closest_point_closed_form(e, Vec2<double>(1, 0.1)), closest_point_quartic(e, Vec2<double>(1, 0.1))}) {
    EXPECT_EQ(q.status, QuarticStatus::inside);
    EXPECT_TRUE(std::isnan(q.point.x()));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(closest_point_quartic(e, Vec2<double>(nan, 0)).status, QuarticStatus::invalid_input);
  EXPECT_EQ(closest_point_closed_form(e, Vec2<double>(0, nan)).status, QuarticStatus::invalid_input);
  EXPECT_EQ(to_string(QuarticStatus::failed), "failed");
}

// Relative tolerances: scenes scaled by 1e-6 and 1e6 give the same point, scaled.
TEST(QuarticClosestPoint, ScaledScenes) {
  for (double s : {1e-6, 1e6}) {
    const auto e = make_ellipse<double>({0.5 * s, -1.5 * s}, 0.3, {1.5 * s, 0.01 * s});
    const Known k = along_normal(e, 0.7, 0.2 * s);
    const auto q = closest_point_quartic(e, k.x);
    ASSERT_EQ(q.status, QuarticStatus::outside);
    EXPECT_LT((q.point - k.point).norm(), 1e-13 * s);
    EXPECT_NEAR(q.distance, 0.2 * s, 1e-13 * s);
  }
}

TEST(QuarticClosestPoint, FloatInstantiation) {
  const auto e = make_ellipse<float>({0, 0}, 0, {2, 1});
  const auto q = closest_point_quartic(e, Vec2<float>(5, 0));
  ASSERT_EQ(q.status, QuarticStatus::outside);
  EXPECT_FLOAT_EQ(q.distance, 3.0f);
  EXPECT_FLOAT_EQ(q.point.x(), 2.0f);
  const auto c = closest_point_closed_form(e, Vec2<float>(3, 2));
  ASSERT_EQ(c.status, QuarticStatus::outside);
  EXPECT_NEAR(c.distance, closest_point_quartic(e, Vec2<float>(3, 2)).distance, 1e-4f);
}

// The careful closed form alone, before polishing: tau for the point x = P + t n has the
// closed form t = |x - P| / |(P_x / a^2, P_y / b^2)|, tau = t / a^2. Near the flat side of
// a needle the quartic itself is ill-conditioned (its root near -b^2 / a^2 is within
// that distance of the wanted one, and the foot's minor coordinate divides by it again),
// so the unpolished point is only good to about 1e-16 (a / b)^3 of a there (2e-5 at
// aspect 1e4); the polish in closest_point_quartic removes that.
TEST(QuarticClosestPoint, UnpolishedRootAccuracy) {
  for (double aspect : {1.0, 1.5, 10.0, 1e2, 1e4}) {
    const double a = 1, b = 1 / aspect;
    double worst = 0;
    for (double theta = 0.01; theta < 1.57; theta += 0.13) {
      for (double t : {1e-9, 1e-3, 0.5, 3.0, 1e3}) {
        const Vec2<double> on(a * std::cos(theta), b * std::sin(theta));
        const Vec2<double> grad(on.x() / (a * a), on.y() / (b * b));
        const Vec2<double> x = on + t * grad.normalized();
        const double tau = detail::secular_quartic_root<double>(b * b / (a * a), x.x() / a, b * x.y() / (a * a));
        const Vec2<double> p(x.x() / (1 + tau), b * b * x.y() / (b * b + tau * a * a));
        worst = std::max(worst, (p - on).norm());
      }
    }
    EXPECT_LT(worst, std::max(1e-12, 1e-16 * aspect * aspect * aspect)) << aspect;
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
