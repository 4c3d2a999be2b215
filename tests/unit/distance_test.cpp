// distance and signed_distance against closed forms: balls, bodies on a common axis,
// containment, equal bodies, statuses, symmetry and scale invariance.
#include <ellipsect/classify.hpp>
#include <ellipsect/distance.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;

template <int N>
Vec<double, N> along(double x, double y = 0) {
  Vec<double, N> v = Vec<double, N>::Zero();
  v[0] = x;
  v[1] = y;
  return v;
}

template <int N>
Ellipsoid<double, N> aligned(const Vec<double, N>& c, double r0, double r1, double r2 = 1) {
  Vec<double, N> r;
  r[0] = r0;
  r[1] = r1;
  if constexpr (N == 3) r[2] = r2;
  return Ellipsoid<double, N>::from_axes(c, Mat<double, N>::Identity(), r);
}

template <class T, int N>
void expect_consistent(const Distance<T, N>& d, double tol) {
  EXPECT_NEAR(d.normal.norm(), 1.0, tol);
  EXPECT_LT((d.point_b - d.point_a - d.distance * d.normal).norm(), tol);
}

template <int N>
void balls() {
  const auto a = make_ball<double, N>(along<N>(1, 2), 2.0);
  // Separated: the gap along the line of centers.
  const auto b = make_ball<double, N>(along<N>(1 + 3, 2 + 4), 1.5);  // 5 apart
  const auto d = distance(a, b);
  EXPECT_EQ(d.status, DistanceStatus::separated);
  EXPECT_NEAR(d.distance, 1.5, 1e-15);
  EXPECT_LT((d.normal - along<N>(0.6, 0.8)).norm(), 1e-15);
  EXPECT_LT((d.point_a - along<N>(1 + 1.2, 2 + 1.6)).norm(), 1e-15);
  EXPECT_LT((d.point_b - along<N>(4 - 0.9, 6 - 1.2)).norm(), 1e-15);
  // Overlapping: depth r_a + r_b - |c|, pushed apart along the line of centers.
  const auto c = make_ball<double, N>(along<N>(1 + 1.5, 2 + 2), 1.0);  // 2.5 apart
  const auto p = signed_distance(a, c);
  EXPECT_EQ(p.status, DistanceStatus::overlapping);
  EXPECT_NEAR(p.distance, -0.5, 1e-15);
  EXPECT_LT((p.normal - along<N>(0.6, 0.8)).norm(), 1e-15);
  expect_consistent(p, 1e-15);
  // distance() does not compute the penetration.
  const auto q = distance(a, c);
  EXPECT_EQ(q.status, DistanceStatus::overlapping);
  EXPECT_EQ(q.distance, 0.0);
  EXPECT_TRUE(std::isnan(q.point_a[0]) && std::isnan(q.point_b[0]) && std::isnan(q.normal[0]));
  // Concentric: every direction separates, by r_a + r_b.
  const auto e = signed_distance(a, make_ball<double, N>(along<N>(1, 2), 0.5));
  EXPECT_EQ(e.status, DistanceStatus::overlapping);
  EXPECT_NEAR(e.distance, -2.5, 1e-15);
  expect_consistent(e, 1e-15);
}

TEST(Distance, Balls2D) { balls<2>(); }
TEST(Distance, Balls3D) { balls<3>(); }

// An ellipse (2, 1) at the origin and a ball on its major axis: gap, touching, and
// penetration from above its flat side.
template <int N>
void on_axis() {
  const auto e = aligned<N>(Vec<double, N>::Zero(), 2, 1, 0.5);
  const auto far = distance(e, make_ball<double, N>(along<N>(4), 0.5));
  EXPECT_EQ(far.status, DistanceStatus::separated);
  EXPECT_NEAR(far.distance, 1.5, 1e-15);
  EXPECT_LT((far.point_a - along<N>(2)).norm(), 1e-15);
  EXPECT_LT((far.point_b - along<N>(3.5)).norm(), 1e-15);

  const auto touch = signed_distance(e, make_ball<double, N>(along<N>(2.5), 0.5));
  EXPECT_EQ(touch.status, DistanceStatus::touching);
  EXPECT_LT(std::abs(touch.distance), 1e-15);
  EXPECT_LT((touch.point_a - along<N>(2)).norm(), 1e-15);
  EXPECT_EQ(distance(e, make_ball<double, N>(along<N>(2.5), 0.5)).distance, touch.distance);

  // Ball of radius 1 at (0, 1.5): the smallest push is 0.5 straight up (the ellipse's
  // radius of curvature there, 4, exceeds the depth, so the vertex is the minimum).
  const auto deep = signed_distance(e, make_ball<double, N>(along<N>(0, 1.5), 1.0));
  EXPECT_EQ(deep.status, DistanceStatus::overlapping);
  EXPECT_NEAR(deep.distance, -0.5, 1e-15);
  EXPECT_LT((deep.normal - along<N>(0, 1)).norm(), 1e-15);
  EXPECT_LT((deep.point_a - along<N>(0, 1)).norm(), 1e-15);
  EXPECT_LT((deep.point_b - along<N>(0, 0.5)).norm(), 1e-15);
}

TEST(Distance, BallOnAxis2D) { on_axis<2>(); }
TEST(Distance, BallOnAxis3D) { on_axis<3>(); }

// Containment and equal bodies: the ball (or the copy) must leave through the thinnest
// direction, by the sum of the support radii there.
TEST(Distance, ContainedAndEqualBodies) {
  const auto e = aligned<3>(Vec3<double>(1, -2, 0.5), 3, 2, 1);
  const auto inner = signed_distance(e, make_ball<double, 3>(Vec3<double>(1, -2, 0.5), 0.25));
  EXPECT_EQ(inner.status, DistanceStatus::overlapping);
  EXPECT_NEAR(inner.distance, -1.25, 1e-15);
  EXPECT_NEAR(std::abs(inner.normal.z()), 1.0, 1e-15);
  const auto same = signed_distance(e, e);
  EXPECT_NEAR(same.distance, -2.0, 1e-15);
  EXPECT_NEAR(std::abs(same.normal.z()), 1.0, 1e-15);
  expect_consistent(same, 1e-15);
  const auto e2 = aligned<2>(Vec2<double>(0, 0), 2, 0.5);
  EXPECT_NEAR(signed_distance(e2, e2).distance, -1.0, 1e-15);
}

// Two needles (aspect 1e4) tip to tip along x, and side by side: the gaps are exact.
TEST(Distance, NeedleTipsAndSides) {
  for (double gap : {1e-12, 1e-6, 1.0}) {
    const auto a = aligned<3>(Vec3<double>(0, 0, 0), 1, 1e-4, 1e-4);
    const auto b = aligned<3>(Vec3<double>(2 + gap, 0, 0), 1, 1e-4, 1e-4);
    const auto tip = distance(a, b);
    EXPECT_NEAR(tip.distance, gap, 4e-16 * 2) << gap;
    EXPECT_LT((tip.normal - Vec3<double>(1, 0, 0)).norm(), 1e-9) << gap;
    const auto c = aligned<3>(Vec3<double>(0, 2e-4 + gap, 0), 1, 1e-4, 1e-4);
    EXPECT_NEAR(distance(a, c).distance, gap, 4e-16 * 2) << gap;
  }
}

// Bodies far apart: the answer is accurate relative to the distance.
TEST(Distance, FarApart) {
  const auto a = make_ellipsoid<double>(Vec3<double>(0, 0, 0), Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3<double>(1, 0, 0))),
                                        Vec3<double>(2, 1, 0.5));
  for (double x : {1e3, 1e6, 1e9}) {
    const auto d = distance(a, make_ball<double, 3>(Vec3<double>(x, 0, 0), 1.0));
    EXPECT_EQ(d.status, DistanceStatus::separated);
    EXPECT_NEAR(d.distance, x - 3, x * 4e-16) << x;
    EXPECT_LT((d.point_a - Vec3<double>(2, 0, 0)).norm(), 4e-16 * 2) << x;
  }
}

// Swapping the arguments swaps the points and negates the normal, bit for bit; a scene
// scaled by a power of two scales every output exactly.
TEST(Distance, SwapSymmetryAndScaleInvariance) {
  const auto a = make_ellipsoid<double>(Vec3<double>(0.1, 0.2, -0.3), Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized(),
                                        Vec3<double>(2, 0.7, 0.3));
  for (const Vec3<double>& cb : {Vec3<double>(2.5, 1, 0.4), Vec3<double>(0.8, 0.3, 0.1)}) {
    const auto b = make_ellipsoid<double>(cb, Eigen::Quaterniond(0.2, 0.8, 0.1, -0.5).normalized(), Vec3<double>(1.1, 0.4, 0.9));
    const auto ab = signed_distance(a, b), ba = signed_distance(b, a);
    EXPECT_EQ(ab.distance, ba.distance);
    EXPECT_EQ(ab.point_a, ba.point_b);
    EXPECT_EQ(ab.point_b, ba.point_a);
    EXPECT_EQ(ab.normal, Vec3<double>(-ba.normal));
    const double s = 0x1p-30;
    const auto as = Ellipsoid3<double>::from_axes(a.center() * s, a.axes(), a.radii() * s);
    const auto bs = Ellipsoid3<double>::from_axes(b.center() * s, b.axes(), b.radii() * s);
    const auto scaled = signed_distance(as, bs);
    EXPECT_EQ(scaled.distance, ab.distance * s);
    EXPECT_EQ(scaled.point_a, Vec3<double>(ab.point_a * s));
    EXPECT_EQ(scaled.normal, ab.normal);
  }
}

// The status is classify's: separated, touching and overlapping (containment and equal
// bodies count as overlapping), also on the edges of the band (gaps of +-1e-12, decided
// in the wider type).
TEST(Distance, StatusAgreesWithClassify) {
  const auto a = aligned<2>(Vec2<double>(0, 0), 2, 1);
  for (double x : {0.0, 0.5, 2.9, 3.0 - 1e-12, 3.0 - 1e-13, 3.0, 3.0 + 1e-13, 3.0 + 1e-12, 3.1, 10.0}) {
    const auto b = make_ball<double, 2>(Vec2<double>(x, 0), 1.0);
    const Relation r = classify(a, b);
    const DistanceStatus want = r == Relation::separated  ? DistanceStatus::separated
                                : r == Relation::touching ? DistanceStatus::touching
                                                          : DistanceStatus::overlapping;
    EXPECT_EQ(signed_distance(a, b).status, want) << x;
    EXPECT_EQ(distance(a, b).status, want) << x;
  }
}

TEST(Distance, IterationCapIsAStatus) {
  const auto a = aligned<3>(Vec3<double>(0, 0, 0), 3, 0.01, 1);
  const auto b = make_ellipsoid<double>(Vec3<double>(2, 3, 1), Eigen::Quaterniond(0.3, 0.5, 0.1, 0.8).normalized(),
                                        Vec3<double>(4, 0.02, 0.5));
  Options options;
  options.max_distance_iterations = 1;
  const auto d = distance(a, b, options);
  EXPECT_EQ(d.status, DistanceStatus::did_not_converge);
  EXPECT_EQ(d.iterations, 1);
  EXPECT_NE(distance(a, b).status, DistanceStatus::did_not_converge);
}

TEST(Distance, FloatInstantiation) {
  const auto a = make_ellipse<float>({0, 0}, 0, {2, 1});
  const auto b = make_ball<float, 2>({4, 0}, 0.5f);
  EXPECT_FLOAT_EQ(distance(a, b).distance, 1.5f);
  const auto c = make_ball<float, 3>({0, 0, 1.5f}, 1.0f);
  const auto e = Ellipsoid3<float>::from_axes({0, 0, 0}, Mat3<float>::Identity(), {2, 2, 1});
  EXPECT_NEAR(signed_distance(e, c).distance, -0.5f, 1e-6f);
}

TEST(Distance, StatusNames) {
  EXPECT_EQ(to_string(DistanceStatus::separated), "separated");
  EXPECT_EQ(to_string(DistanceStatus::touching), "touching");
  EXPECT_EQ(to_string(DistanceStatus::overlapping), "overlapping");
  EXPECT_EQ(to_string(DistanceStatus::did_not_converge), "did_not_converge");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
