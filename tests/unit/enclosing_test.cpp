// The minimum-volume enclosing ellipsoid (geometry.hpp): closed-form optima (box corners,
// simplex vertices), the certificate recomputed in 50 digits from the support and weights,
// containment of every point evaluated in 50 digits from the stored numbers, invariance
// under translation and scale, thin and large clouds, the cap, and bad input.
#include <ellipsect/geometry.hpp>

#include "scenarios/scenarios.hpp"

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

// The lower bound of the weights, log sqrt(det(N S_u)), in 50 digits (geometry.hpp).
template <class T, int N>
F log_lower_bound(const EnclosingEllipsoid<T, N>& e, const Points<T, N>& points) {
  F total = 0;
  for (double u : e.weights) total += F(u);
  Eigen::Matrix<F, N, 1> c = Eigen::Matrix<F, N, 1>::Zero();
  for (std::size_t i = 0; i < e.support.size(); ++i)
    for (int j = 0; j < N; ++j) c[j] += F(e.weights[i]) / total * F(double(points[e.support[i]][j]));
  Eigen::Matrix<F, N, N> s = Eigen::Matrix<F, N, N>::Zero();
  for (std::size_t i = 0; i < e.support.size(); ++i) {
    Eigen::Matrix<F, N, 1> d;
    for (int j = 0; j < N; ++j) d[j] = F(double(points[e.support[i]][j])) - c[j];
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
  const F ratio = exp(log_volume(e.body) - log_lower_bound(e, points));
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

TEST(EnclosingEllipsoid, BadInputNamesThePoints) {
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
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
