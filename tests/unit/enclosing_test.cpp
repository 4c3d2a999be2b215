// The minimum-volume enclosing ellipsoid (geometry.hpp): closed-form optima (box corners,
// simplex vertices), the certificate recomputed in 50 digits from the support and weights,
// containment of every point evaluated in 50 digits from the stored numbers, invariance
// under translation and scale, thin and large clouds, the cap, and bad input.
#include <ellipsect/geometry.hpp>


#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"
#include "tests/reference/reference.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using F = boost::multiprecision::cpp_bin_float_50;

template <class T, int N>
using Points = std::vector<Vec<T, N>>;

// (p - c)^T A (p - c), A = axes diag(radii)^-2 axes^T from the stored numbers (the axes of
// double bodies as stored; the tests' float bodies check with the margin of their axes).
template <class T, int N>
F form(const Ellipsoid<T, N>& b, const Vec<T, N>& p) {
  F q = 0;
  for (int k = 0; k < N; ++k) {
    F y = 0;
    for (int j = 0; j < N; ++j) y += F(double(b.axes()(j, k))) * (F(double(p[j])) - F(double(b.center()[j])));
    y /= F(double(b.radii()[k]));
    q += y * y;
  }
  return q;
}

// log of the volume of the stored body over that of the unit ball: sum log r - log|det R|.
template <class T, int N>
F log_volume(const Ellipsoid<T, N>& b) {
  F s = 0;
  for (int k = 0; k < N; ++k) s += log(F(double(b.radii()[k])));
  Eigen::Matrix<F, N, N> r;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) r(i, j) = F(double(b.axes()(i, j)));
  return s - log(abs(r.determinant()));
}

// The lower bound of the weights, log sqrt(det(N S_u)), in 50 digits (geometry.hpp), from
// the support points as returned.
template <class T, int N>
F log_lower_bound(const EnclosingEllipsoid<T, N>& e) {
  F total = 0;
  for (double u : e.weights) total += F(u);
  Eigen::Matrix<F, N, 1> c = Eigen::Matrix<F, N, 1>::Zero();
  for (std::size_t i = 0; i < e.support.size(); ++i)
    for (int j = 0; j < N; ++j) c[j] += F(e.weights[i]) / total * F(double(e.support_points[i][j]));
  Eigen::Matrix<F, N, N> s = Eigen::Matrix<F, N, N>::Zero();
  for (std::size_t i = 0; i < e.support.size(); ++i) {
    Eigen::Matrix<F, N, 1> d;
    for (int j = 0; j < N; ++j) d[j] = F(double(e.support_points[i][j])) - c[j];
    s += F(e.weights[i]) / total * F(N) * d * d.transpose();
  }
  return log(s.determinant()) / 2;
}

// Every point inside, the reported gap bounding the body's volume over the 50-digit lower
// bound, and that over a known optimum (log_optimum, when given): the optimum is never
// beaten and never missed by more than the gap.
template <class T, int N>
void expect_certified(const EnclosingEllipsoid<T, N>& e, const Points<T, N>& points, double inside_margin,
                      const F* log_optimum = nullptr, double optimum_slack = 1e-13, double volume_slack = 0) {
  F worst = 0;
  for (const auto& p : points) worst = std::max(worst, form(e.body, p));
  EXPECT_LE(worst, 1 + inside_margin) << double(worst - 1);
  ASSERT_EQ(e.support_points.size(), e.support.size());
  for (std::size_t i = 0; i < e.support.size(); ++i) EXPECT_EQ(e.support_points[i], points[e.support[i]]);
  const F ratio = exp(log_volume(e.body) - log_lower_bound(e));
  EXPECT_LE(ratio, 1 + F(e.volume_gap) + F(volume_slack)) << double(ratio - 1) << " gap " << e.volume_gap;
  EXPECT_GE(ratio, 1 - F(volume_slack)) << double(ratio - 1);
  if (log_optimum) {
    // The optimum of the points as rounded: within optimum_slack of the closed form.
    const F to_optimum = exp(log_volume(e.body) - *log_optimum);
    EXPECT_LE(to_optimum, 1 + F(e.volume_gap) + F(optimum_slack)) << double(to_optimum - 1) << " gap " << e.volume_gap;
    EXPECT_GE(to_optimum, 1 - F(optimum_slack)) << double(to_optimum - 1);
  }
}

// The 2^N corners of the box of half-extents h, turned by r, about c: the optimum is the
// box's circumscribed ellipsoid, radii sqrt(N) h (by symmetry, the weights uniform).
template <int N>
Points<double, N> box_corners(const Vec<double, N>& h, const Mat<double, N>& r, const Vec<double, N>& c) {
  Points<double, N> out;
  for (int mask = 0; mask < (1 << N); ++mask) {
    Vec<double, N> p;
    for (int i = 0; i < N; ++i) p[i] = (mask >> i & 1) ? h[i] : -h[i];
    out.push_back(c + r * p);
  }
  return out;
}

template <int N>
F log_box_optimum(const Vec<double, N>& h) {
  F s = 0;
  for (int i = 0; i < N; ++i) s += log(F(h[i]) * sqrt(F(N)));
  return s;
}

TEST(EnclosingEllipsoid, BoxCornersGiveTheCircumscribedEllipsoid) {
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3<double> h(1, 0.5 + trial, std::pow(10.0, trial % 5 - 2));
    const Vec3<double> c(trial, -3, 7e-3);
    const auto points = box_corners<3>(h, scenarios::detail::orthogonal<3>(rng), c);
    const auto e = enclosing_ellipsoid<double, 3>(points);
    SCOPED_TRACE(trial);
    EXPECT_EQ(e.status, EnclosingStatus::optimal);
    EXPECT_LE(e.volume_gap, 1e-9);
    const F opt = log_box_optimum<3>(h);
    expect_certified(e, points, 0, &opt);
    EXPECT_LT((e.body.center() - c).norm(), 1e-9 * h.maxCoeff());
  }
  const Vec2<double> h2(3, 1e-3);
  const auto points2 = box_corners<2>(h2, scenarios::detail::orthogonal<2>(rng), Vec2<double>(1, 2));
  const auto e2 = enclosing_ellipsoid<double, 2>(points2);
  EXPECT_EQ(e2.status, EnclosingStatus::optimal);
  const F opt2 = log_box_optimum<2>(h2);
  expect_certified(e2, points2, 0, &opt2);
}

// A regular simplex's vertices: the optimum is its circumscribed ball.
TEST(EnclosingEllipsoid, SimplexGivesItsCircumscribedBall) {
  const Points<double, 3> tet{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const auto e = enclosing_ellipsoid<double, 3>(tet);
  const F opt = 3 * log(sqrt(F(3)));
  expect_certified(e, tet, 0, &opt);
  const Points<double, 2> tri{{0, 1}, {std::sqrt(3.0) / 2, -0.5}, {-std::sqrt(3.0) / 2, -0.5}};
  const auto e2 = enclosing_ellipsoid<double, 2>(tri);
  const F opt2 = 0;  // the unit circle
  expect_certified(e2, tri, 0, &opt2);
  EXPECT_NEAR(e2.body.radii()[0], 1, 1e-9);
  EXPECT_NEAR(e2.body.radii()[1], 1, 1e-9);
}

// Points on and inside a given ellipsoid E0: E0 encloses them, so the optimum is no larger.
TEST(EnclosingEllipsoid, NoLargerThanAnEllipsoidHoldingThePoints) {
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 10; ++trial) {
    const Vec3<double> radii(1, 1 + trial, std::pow(10.0, trial % 4));
    const Mat3<double> r = scenarios::detail::orthogonal<3>(rng);
    const Vec3<double> c(-1e6 * trial, 2, 3);
    Points<double, 3> points;
    for (int i = 0; i < 400; ++i) {
      Vec3<double> d(g(rng), g(rng), g(rng));
      d *= (i % 2 ? 0.999 : unit(rng)) / d.norm();
      points.push_back(c + r * radii.cwiseProduct(d));
    }
    const auto e = enclosing_ellipsoid<double, 3>(points);
    SCOPED_TRACE(trial);
    EXPECT_EQ(e.status, EnclosingStatus::optimal);
    expect_certified(e, points, 0);
    F given = 0;
    for (int k = 0; k < 3; ++k) given += log(F(radii[k]));
    EXPECT_LE(log_volume(e.body), given + F(1e-12));
  }
}

// Scaling the cloud by s scales the volume by s^N; translating it changes nothing.
TEST(EnclosingEllipsoid, ScaleAndTranslationInvariant) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  Points<double, 2> base;
  for (int i = 0; i < 300; ++i) base.push_back({g(rng), 0.3 * g(rng) + 0.2 * g(rng)});
  const auto reference = enclosing_ellipsoid<double, 2>(base);
  const F log_ref = log_volume(reference.body);
  for (double s : {1e-6, 1.0, 1e6})
    for (double offset : {0.0, 1e6, -1e9}) {
      Points<double, 2> points;
      for (const auto& p : base) points.push_back(Vec2<double>(p * s) + Vec2<double>(offset * s, -offset * s));
      const auto e = enclosing_ellipsoid<double, 2>(points);
      SCOPED_TRACE(s);
      SCOPED_TRACE(offset);
      // 1e9 away, the stored center's ulp is 1e-7 of the cloud: the body as stored cannot
      // carry a gap of 1e-9, and says so.
      if (offset == -1e9) {
        EXPECT_EQ(e.status, EnclosingStatus::rounding_limited);
        EXPECT_LE(e.volume_gap, 1e-6);
      } else {
        EXPECT_EQ(e.status, EnclosingStatus::optimal);
        EXPECT_LE(e.volume_gap, 1e-9);
      }
      expect_certified(e, points, 0);
      // Both within their gaps of the one optimum; the offset's rounding of the points
      // (relative 2^-53 of 1e9 over a cloud of size 1) moves it by about 1e-7.
      const F moved = abs(log_volume(e.body) - 2 * log(F(s)) - log_ref);
      EXPECT_LE(moved, F(offset == -1e9 ? 1e-6 : 3e-9));
    }
}

// A needle: 10^4 aspect, turned; and 2*10^4 points in a cube.
TEST(EnclosingEllipsoid, ThinAndLargeClouds) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  const Mat3<double> r = scenarios::detail::orthogonal<3>(rng);
  Points<double, 3> needle;
  for (int i = 0; i < 2000; ++i) needle.push_back(r * Vec3<double>(u(rng), 1e-4 * u(rng), 1e-2 * u(rng)));
  const auto e = enclosing_ellipsoid<double, 3>(needle);
  EXPECT_EQ(e.status, EnclosingStatus::optimal);
  EXPECT_LE(e.volume_gap, 1e-9);
  expect_certified(e, needle, 0);
  Points<double, 3> cube;
  for (int i = 0; i < 20000; ++i) cube.push_back({u(rng), u(rng), u(rng)});
  const auto c = enclosing_ellipsoid<double, 3>(cube);
  EXPECT_EQ(c.status, EnclosingStatus::optimal);
  EXPECT_LE(c.volume_gap, 1e-9);
  expect_certified(c, cube, 0);
  EXPECT_LT(c.support.size(), 200u);
}

// Duplicated points and points repeated on the boundary change nothing.
TEST(EnclosingEllipsoid, DuplicatesAreHarmless) {
  Points<double, 2> points{{1, 0}, {-1, 0}, {0, 2}, {0, -2}};
  for (int i = 0; i < 5; ++i) points.push_back(points[std::size_t(i % 4)]);
  points.push_back({0, 0});
  const auto e = enclosing_ellipsoid<double, 2>(points);
  const F opt = log(F(1)) + log(F(2));  // the ellipse through the four (by symmetry)
  expect_certified(e, points, 0, &opt);
}

// At the cap the body still holds every point and its gap is still a bound.
TEST(EnclosingEllipsoid, CapReachedStillCertified) {
  std::mt19937_64 rng(5);
  const Vec3<double> h(1, 2, 3);
  const auto points = box_corners<3>(h, scenarios::detail::orthogonal<3>(rng), Vec3<double>(0, 0, 0));
  const auto e = enclosing_ellipsoid<double, 3>(points, {.max_enclosing_iterations = 1});
  EXPECT_EQ(e.status, EnclosingStatus::did_not_converge);
  EXPECT_EQ(e.iterations, 1);
  const F opt = log_box_optimum<3>(h);
  expect_certified(e, points, 0, &opt);
  const auto loose = enclosing_ellipsoid<double, 3>(points, {.volume_gap = 0.5});
  EXPECT_EQ(loose.status, EnclosingStatus::optimal);
  EXPECT_LE(loose.volume_gap, 0.5);
  expect_certified(loose, points, 0, &opt);
}

// float: the body as stored in float holds the points, its gap (about 1e-6 of rounding,
// above the default request: rounding_limited) a bound. Its axes are checked with the margin of their orthonormality in float.
TEST(EnclosingEllipsoid, FloatBodiesHoldTheirPoints) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<float> u(-1, 1);
  Points<float, 3> points;
  for (int i = 0; i < 500; ++i) points.push_back({u(rng), 2 * u(rng), 0.5f * u(rng)});
  const auto e = enclosing_ellipsoid<float, 3>(points);
  EXPECT_EQ(e.status, EnclosingStatus::rounding_limited);
  EXPECT_LE(e.volume_gap, 1e-5);
  const auto loose = enclosing_ellipsoid<float, 3>(points, {.volume_gap = 1e-4});
  EXPECT_EQ(loose.status, EnclosingStatus::optimal);
  expect_certified(loose, points, 1e-6, nullptr, 0, 1e-6);
  expect_certified(e, points, 1e-6, nullptr, 0, 1e-6);
}

// ---- Of bodies, capsules, boxes and meshes ----

// The body's form as an (N+1)x(N+1) matrix of homogeneous coordinates, from the stored
// numbers: (x - c)^T M (x - c) - 1 = (x, 1)^T Q (x, 1).
template <class T, int N>
Eigen::Matrix<F, N + 1, N + 1> quadric(const Ellipsoid<T, N>& b) {
  Eigen::Matrix<F, N, N> r;
  Eigen::Matrix<F, N, 1> c;
  for (int i = 0; i < N; ++i) {
    c[i] = F(double(b.center()[i]));
    for (int j = 0; j < N; ++j) r(i, j) = F(double(b.axes()(i, j)));
  }
  Eigen::Matrix<F, N, 1> inv;
  for (int k = 0; k < N; ++k) inv[k] = 1 / (F(double(b.radii()[k])) * F(double(b.radii()[k])));
  const Eigen::Matrix<F, N, N> m = r * inv.asDiagonal() * r.transpose();
  Eigen::Matrix<F, N + 1, N + 1> q;
  q.template topLeftCorner<N, N>() = m;
  q.template topRightCorner<N, 1>() = -m * c;
  q.template bottomLeftCorner<1, N>() = -(m * c).transpose();
  q(N, N) = c.dot(m * c) - 1;
  return q;
}

// b inside e, by the S-lemma in 50 digits (another route than the library's classification):
// b in e exactly when Q_e - tau Q_b is negative semidefinite for some tau in [0, 1] (at b's
// center Q_b = -1 and Q_e >= -1). Returns min over tau of the largest eigenvalue of
// Q_e - tau Q_b, both normalized, by golden-section search (the eigenvalue is convex in tau).
template <class T, int N>
F containment_margin(const Ellipsoid<T, N>& e, const Ellipsoid<T, N>& b) {
  using Q = Eigen::Matrix<F, N + 1, N + 1>;
  Q qe = quadric(e), qb = quadric(b);
  const F ne = sqrt(qe.squaredNorm()), nb = sqrt(qb.squaredNorm());
  const F hi_tau = nb / ne;  // tau in [0, 1] before the normalization
  qe /= ne;
  qb /= nb;
  const auto largest = [&](const F& tau) {  // by the reference's cyclic Jacobi
    reference::RMat<N + 1> a, v;
    reference::RVec<N + 1> h;
    for (int i = 0; i <= N; ++i)
      for (int j = 0; j <= N; ++j) a(i, j) = reference::Real(F(qe(i, j) - tau * qb(i, j)));
    reference::detail::jacobi_eigen<N + 1>(a, h, v);
    return F(h.maxCoeff());
  };
  const F golden = (sqrt(F(5)) - 1) / 2;
  F lo = 0, hi = hi_tau;
  F x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo), f1 = largest(x1), f2 = largest(x2);
  for (int k = 0; k < 120; ++k) {  // to 1e-25 of tau
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - golden * (hi - lo), f1 = largest(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + golden * (hi - lo), f2 = largest(x2);
    }
  }
  return std::min(f1, f2);
}

// Every body inside, every support point inside the body it names, and the gap a bound over
// the 50-digit lower bound of the support points' weights.
template <class T, int N>
void expect_bodies_certified(const EnclosingEllipsoid<T, N>& e, const std::vector<Ellipsoid<T, N>>& bodies,
                             std::size_t per_body = 1, double volume_slack = 0) {
  for (const auto& b : bodies) EXPECT_LE(containment_margin(e.body, b), F(1e-30));
  ASSERT_EQ(e.support_points.size(), e.support.size());
  for (std::size_t i = 0; i < e.support.size(); ++i) {
    ASSERT_LT(e.support[i] * per_body, bodies.size());
    F best = 10;
    for (std::size_t k = 0; k < per_body; ++k) best = std::min(best, form(bodies[e.support[i] * per_body + k], e.support_points[i]));
    EXPECT_LE(best, 1);
  }
  const F ratio = exp(log_volume(e.body) - log_lower_bound(e));
  EXPECT_LE(ratio, 1 + F(e.volume_gap) + F(volume_slack)) << double(ratio - 1) << " gap " << e.volume_gap;
  EXPECT_GE(ratio, 1 - F(volume_slack));
}

template <int N>
std::vector<Ellipsoid<double, N>> random_bodies(std::mt19937_64& rng, int count, double aspect, double scale, double offset) {
  std::uniform_real_distribution<double> u(-1, 1), l(0, 1);
  std::vector<Ellipsoid<double, N>> out;
  for (int i = 0; i < count; ++i) {
    Vec<double, N> c, r;
    for (int k = 0; k < N; ++k) c[k] = offset + 3 * scale * u(rng), r[k] = scale * std::pow(aspect, -l(rng));
    out.push_back(Ellipsoid<double, N>::from_axes(c, scenarios::detail::orthogonal<N>(rng), r));
  }
  return out;
}

// One body: itself. Many: contained, within the certified gap of the support's bound, on
// random sets to aspect 1e4, at scales 1e-6 and 1e6, 1e6 from the origin.
template <int N>
void check_bodies() {
  std::mt19937_64 rng(7 + N);
  for (int trial = 0; trial < 4; ++trial) {
    const auto one = random_bodies<N>(rng, 1, std::pow(10.0, trial), 1, trial * 10.0);
    const auto e = enclosing_ellipsoid<double, N>(one);
    EXPECT_EQ(e.status, EnclosingStatus::optimal);
    expect_bodies_certified(e, one);
    F ratio = exp(log_volume(e.body) - log_volume(one[0]));
    EXPECT_LE(ratio, 1 + F(1e-9));
  }
  for (const int count : {2, 5, 12})
    for (const double aspect : {3.0, 1e4})
      for (const double scale : {1e-6, 1.0, 1e6})
        for (const double offset : {0.0, 1e6}) {
          const auto bodies = random_bodies<N>(rng, count, aspect, scale, offset * scale);
          const auto e = enclosing_ellipsoid<double, N>(bodies);
          SCOPED_TRACE(::testing::Message() << count << " bodies, aspect " << aspect << ", scale " << scale << ", offset " << offset);
          // Bodies 1e-4 thin 1e6 of their size from the origin: the points on them, rounded
          // to double, lie 1e-6 of the thin radius off (rounding_limited, geometry.hpp).
          if (aspect > 1e3 && offset > 0) {
            EXPECT_NE(e.status, EnclosingStatus::did_not_converge);
            EXPECT_LE(e.volume_gap, 1e-7);
          } else {
            EXPECT_EQ(e.status, EnclosingStatus::optimal) << e.volume_gap;
          }
          expect_bodies_certified(e, bodies);
        }
}

TEST(EnclosingEllipsoid, OfBodies2D) { check_bodies<2>(); }
TEST(EnclosingEllipsoid, OfBodies3D) { check_bodies<3>(); }

// Float bodies (axis-aligned: their axes exact): contained, the gap a bound (the volume of
// the float body read with its stored axes, 1e-6 off that of their orthonormal polar factor
// that the queries take).
TEST(EnclosingEllipsoid, OfFloatBodies) {
  std::vector<Ellipsoid<float, 3>> bodies;
  for (int i = 0; i < 6; ++i)
    bodies.push_back(make_ellipsoid<float>(Vec3<float>(float(i), float(i * i % 5), -float(i)), Mat3<float>::Identity(),
                                           Vec3<float>(1, 0.5f + float(i), 0.25f)));
  const auto e = enclosing_ellipsoid<float, 3>(bodies, {.volume_gap = 1e-4});
  EXPECT_EQ(e.status, EnclosingStatus::optimal);
  expect_bodies_certified(e, bodies, 1, 1e-6);
}

// A capsule is the hull of its end balls; a zero-length one is its ball.
TEST(EnclosingEllipsoid, OfCapsules) {
  const std::vector<Capsule<double, 3>> capsules{make_capsule<double, 3>({-1, 0, 0}, {1, 0, 0}, 1),
                                                 make_capsule<double, 3>({0, 2, 5}, {0, 2, 5}, 0.5)};
  const auto e = enclosing_ellipsoid<double, 3>(capsules);
  std::vector<Ellipsoid<double, 3>> balls;
  for (const auto& c : capsules)
    for (int k = 0; k < 2; ++k) balls.push_back(make_ball<double, 3>(c.point(k), c.radius()));
  EXPECT_EQ(e.status, EnclosingStatus::optimal);
  expect_bodies_certified(e, balls, 2);
  const auto ball = enclosing_ellipsoid<double, 2>(std::vector<Capsule<double, 2>>{make_capsule<double, 2>({3, 4}, {3, 4}, 2)});
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(ball.body.radii()[k], 2, 2e-9);
  EXPECT_LT((ball.body.center() - Vec2<double>(3, 4)).norm(), 1e-9);
}

// Boxes by their corners (the circumscribed ellipsoid of one: radii sqrt(N) h); a mesh by its
// vertices (a cube's eight).
TEST(EnclosingEllipsoid, OfBoxesAndMeshes) {
  std::mt19937_64 rng(9);
  const Vec3<double> h(1, 2, 0.5);
  const auto box = Box<double, 3>::from_axes(Vec3<double>(5, -1, 2), scenarios::detail::orthogonal<3>(rng), h);
  const auto e = enclosing_ellipsoid<double, 3>(std::vector<Box<double, 3>>{box});
  Points<double, 3> corners;
  for (int k = 0; k < 8; ++k) corners.push_back(box.corner(k));
  const F opt = log_box_optimum<3>(h);
  EXPECT_EQ(e.status, EnclosingStatus::optimal);
  for (std::size_t j : e.support) EXPECT_EQ(j, 0u);
  F worst = 0;
  for (const auto& p : corners) worst = std::max(worst, form(e.body, p));
  EXPECT_LE(worst, 1);
  EXPECT_LE(abs(log_volume(e.body) - opt), F(2e-9));
  const auto two = enclosing_ellipsoid<double, 2>(std::vector<Box<double, 2>>{
      Box<double, 2>::from_axes({0, 0}, Mat2<double>::Identity(), {1, 1}), Box<double, 2>::from_axes({4, 0}, Mat2<double>::Identity(), {1, 1})});
  EXPECT_EQ(two.status, EnclosingStatus::optimal);
  for (std::size_t j : two.support) EXPECT_LT(j, 2u);
  // The two squares' corners span [-1, 5] x [-1, 1]: the ellipse through that rectangle's corners.
  EXPECT_NEAR(two.body.radii().maxCoeff(), 3 * std::sqrt(2.0), 1e-8);
  EXPECT_NEAR(two.body.radii().minCoeff(), std::sqrt(2.0), 1e-8);
  std::vector<double> vertices;
  for (const auto& p : corners) vertices.insert(vertices.end(), p.data(), p.data() + 3);
  const std::vector<std::int64_t> triangles{0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6};
  const auto mesh = make_triangle_mesh<double, 3>(vertices, triangles);
  const auto m = enclosing_ellipsoid<double, 3>(mesh);
  EXPECT_EQ(m.status, EnclosingStatus::optimal);
  EXPECT_LE(abs(log_volume(m.body) - opt), F(2e-9));
  for (std::size_t j : m.support) EXPECT_LT(j, 8u);
}

TEST(EnclosingEllipsoid, EmptyShapesAreNamed) {
  const auto field = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field([] { enclosing_ellipsoid<double, 3>(std::vector<Ellipsoid<double, 3>>{}); }), "bodies");
  EXPECT_EQ(field([] { enclosing_ellipsoid<double, 3>(std::vector<Capsule<double, 3>>{}); }), "capsules");
  EXPECT_EQ(field([] { enclosing_ellipsoid<double, 2>(std::vector<Box<double, 2>>{}); }), "boxes");
  EXPECT_EQ(field([] { enclosing_ellipsoid<double, 3>(TriangleMesh<double, 3>{}); }), "mesh");
  // Two needles along one line: their tips a line, their union no ellipsoid below 1e8 holds.
  EXPECT_EQ(field([] {
              enclosing_ellipsoid<double, 2>(std::vector<Capsule<double, 2>>{make_capsule<double, 2>({0, 0}, {1e4, 0}, 1e-9)});
            }),
            "capsules");
}

TEST(EnclosingEllipsoid, BadInputNamesThePoints) {
  const auto message = [](auto&& f) { return ellipsect::testing::error_message(f); };
  EXPECT_NE(message([] { enclosing_ellipsoid<double, 3>(Points<double, 3>{}); }).find("points"), std::string::npos);
  EXPECT_NE(message([] { enclosing_ellipsoid<double, 3>(Points<double, 3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}); })
                .find("at least 4"),
            std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  try {
    enclosing_ellipsoid<double, 2>(Points<double, 2>{{0, 0}, {1, 0}, {0, nan}, {1, 1}});
    ADD_FAILURE() << "NaN accepted";
  } catch (const RowInputError& e) {
    EXPECT_EQ(e.row(), 2u);
    EXPECT_NE(std::string(e.what()).find("points"), std::string::npos);
  }
  EXPECT_NE(message([] { enclosing_ellipsoid<double, 2>(Points<double, 2>{{0, 0}, {1, 1}, {2, 2}, {3, 3}}); }).find("line"),
            std::string::npos);
  EXPECT_NE(message([] { enclosing_ellipsoid<double, 3>(Points<double, 3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}); })
                .find("plane"),
            std::string::npos);
  EXPECT_NE(message([] { enclosing_ellipsoid<double, 2>(Points<double, 2>{{1, 1}, {1, 1}, {1, 1}}); }).find("point"),
            std::string::npos);
  EXPECT_NE(message([] { enclosing_ellipsoid<double, 2>(Points<double, 2>{{0, 0}, {1, 0}, {0, 1e-12}, {1, 1e-12}}); })
                .find("1e-9"),
            std::string::npos);
  EXPECT_NE(message([] { EnclosingOptions o; o.volume_gap = 0; }).find("volume_gap"), std::string::npos);
  EXPECT_NE(message([] { EnclosingOptions o; o.max_enclosing_iterations = 0; }).find("max_enclosing_iterations"),
            std::string::npos);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
