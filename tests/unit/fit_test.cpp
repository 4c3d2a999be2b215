// The least-squares ellipse and ellipsoid (geometry.hpp, fit_ellipsoid): the answer against a
// 50-digit Gauss-Newton by another route (distances by bisection on the secular equation,
// derivatives by central differences, the rotation by Rodrigues' formula), the generating body
// recovered from points on it (random poses, aspect ratios to 1e3, scales 1e-6 and 1e6, 1e6 from
// the origin), descent from the algebraic fit and stationarity on noisy clouds, near circles of
// 10^4 points, short noisy arcs, hyperbolas and hyperboloids, the covariance against repeated
// noisy draws, exact scaling, the cap, and bad input.
#include <ellipsect/geometry.hpp>
#include <ellipsect/point.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/eigen.hpp>
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using F = boost::multiprecision::cpp_bin_float_50;

template <class T, int N>
using Points = std::vector<Vec<T, N>>;
template <int N>
using FV = Eigen::Matrix<F, N, 1>;
template <int N>
using FM = Eigen::Matrix<F, N, N>;
template <int N>
inline constexpr int P = fit_parameter_count<N>;
template <int N>
using FP = Eigen::Matrix<F, P<N>, 1>;

// ---- the 50-digit reference ----------------------------------------------------------------

// The signed distance of x to the ellipsoid (c, R, r), in 50 digits: in the body's frame
// u = R^T (x - c) the closest point is y_k = r_k^2 u_k / (r_k^2 + t) for the root t > -r_min^2
// of sum (r_k u_k / (r_k^2 + t))^2 = 1 (decreasing in t there), found by bisection: t > 0
// outside, t < 0 inside.
template <int N>
F distance50(const FV<N>& c, const FM<N>& R, const FV<N>& r, const FV<N>& x) {
  const FV<N> u = R.transpose() * (x - c);
  const auto s = [&](const F& t) {
    F sum = 0;
    for (int k = 0; k < N; ++k) {
      const F q = r[k] * u[k] / (r[k] * r[k] + t);
      sum += q * q;
    }
    return sum;
  };
  F rmin = r.minCoeff(), rmax = r.maxCoeff();
  F lo, hi;
  if (s(F(0)) > 1) {
    lo = 0;
    hi = rmax * u.norm() + rmax * rmax;
  } else {
    lo = -rmin * rmin;
    hi = 0;
  }
  for (int i = 0; i < 175; ++i) {
    const F mid = (lo + hi) / 2;
    (s(mid) > 1 ? lo : hi) = mid;
  }
  const F t = (lo + hi) / 2;
  FV<N> y;
  for (int k = 0; k < N; ++k) y[k] = r[k] * r[k] * u[k] / (r[k] * r[k] + t);
  const F d = (u - y).norm();
  return t < 0 ? F(-d) : d;
}

// A body's parameters in 50 digits: center, a turn (2D an angle, 3D a rotation vector) applied
// to the base axes R0, radii.
template <int N>
struct Params {
  FM<N> R0;
  FP<N> theta;  // (center, turn, radii)
  FM<N> axes(const FP<N>& th) const {
    if constexpr (N == 2) {
      const F a = th[N];
      FM<N> R;
      R << cos(a), -sin(a), sin(a), cos(a);
      return R * R0;
    } else {
      const FV<3> w = th.template segment<3>(N);
      const F angle = w.norm();
      FM<3> K;
      K << 0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0;
      FM<3> E = FM<3>::Identity();
      if (angle > 0) E += sin(angle) / angle * K + (1 - cos(angle)) / (angle * angle) * K * K;
      return E * R0;
    }
  }
};

template <class T, int N>
Params<N> params_of(const Ellipsoid<T, N>& b) {
  Params<N> p;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) p.R0(i, j) = F(double(b.axes()(i, j)));
  p.theta.setZero();
  for (int i = 0; i < N; ++i) {
    p.theta[i] = F(double(b.center()[i]));
    p.theta[P<N> - N + i] = F(double(b.radii()[i]));
  }
  return p;
}

template <int N>
Eigen::Matrix<F, Eigen::Dynamic, 1> distances50(const Params<N>& p, const FP<N>& th, const std::vector<FV<N>>& x) {
  Eigen::Matrix<F, Eigen::Dynamic, 1> d(Eigen::Index(x.size()));
  const FM<N> R = p.axes(th);
  const FV<N> c = th.template head<N>(), r = th.template tail<N>();
  for (std::size_t i = 0; i < x.size(); ++i) d[Eigen::Index(i)] = distance50<N>(c, R, r, x[i]);
  return d;
}

// The Jacobian of the distances by central differences (steps 1e-18 of the size: truncation
// 1e-36, rounding 1e-32).
template <int N>
Eigen::Matrix<F, Eigen::Dynamic, P<N>> jacobian50(const Params<N>& p, const FP<N>& th, const std::vector<FV<N>>& x,
                                                   const F& size) {
  Eigen::Matrix<F, Eigen::Dynamic, P<N>> J(Eigen::Index(x.size()), P<N>);
  for (int j = 0; j < P<N>; ++j) {
    const F h = (j >= N && j < P<N> - N) ? F(1e-18) : F(1e-18) * size;
    FP<N> a = th, b = th;
    a[j] += h;
    b[j] -= h;
    J.col(j) = (distances50<N>(p, a, x) - distances50<N>(p, b, x)) / (2 * h);
  }
  return J;
}

template <class T, int N>
struct Reference {
  FP<N> theta;            // the 50-digit stationary point near the answer (in the answer's Params)
  F rms_at_answer;        // the RMS distance of the stored body, 50 digits
  double cosine = 0;      // max_j |J_j . d| / (|J_j| |d|) at the stored body
};

// Gauss-Newton in 50 digits from the stored body until the step is below 1e-30 of the size.
template <class T, int N>
Reference<T, N> reference_fit(const Ellipsoid<T, N>& body, const Points<T, N>& points) {
  const Params<N> p = params_of(body);
  std::vector<FV<N>> x;
  for (const auto& q : points) {
    FV<N> y;
    for (int k = 0; k < N; ++k) y[k] = F(double(q[k]));
    x.push_back(y);
  }
  const F size = p.theta.template tail<N>().maxCoeff();
  Reference<T, N> out;
  FP<N> th = p.theta;
  for (int it = 0; it < 8; ++it) {
    const auto d = distances50<N>(p, th, x);
    const auto J = jacobian50<N>(p, th, x, size);
    if (it == 0) {
      out.rms_at_answer = sqrt(d.squaredNorm() / F(points.size()));
      const FP<N> g = J.transpose() * d;
      for (int j = 0; j < P<N>; ++j) out.cosine = std::max(out.cosine, double(abs(g[j]) / (J.col(j).norm() * d.norm())));
    }
    const Eigen::Matrix<F, P<N>, P<N>> A = J.transpose() * J;
    const FP<N> step = -A.fullPivLu().solve(FP<N>(J.transpose() * d));
    th += step;
    if (step.template lpNorm<Eigen::Infinity>() < F(1e-30) * size) break;
  }
  out.theta = th;
  return out;
}

// ---- clouds -------------------------------------------------------------------------------

template <int N>
Vec<double, N> on_sphere(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec<double, N> u;
  for (int k = 0; k < N; ++k) u[k] = g(rng);
  return u.normalized();
}

// m points on the body (center c, axes R, radii r) at directions u, each moved along a random
// direction by noise (a length).
template <int N>
Points<double, N> cloud_on(const Vec<double, N>& c, const Mat<double, N>& R, const Vec<double, N>& r, int m,
                           double noise, std::mt19937_64& rng, double arc = 2 * std::numbers::pi) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> t(0, arc);
  Points<double, N> out;
  for (int i = 0; i < m; ++i) {
    Vec<double, N> u;
    if constexpr (N == 2) {
      const double a = t(rng);
      u = Vec<double, 2>(std::cos(a), std::sin(a));
    } else {
      u = on_sphere<N>(rng);
    }
    Vec<double, N> e;
    for (int k = 0; k < N; ++k) e[k] = g(rng);
    out.push_back(Vec<double, N>(c + R * r.cwiseProduct(u) + noise * e));
  }
  return out;
}

// The largest distance between the boundaries of a and b, sampled at a's points.
template <int N>
double boundary_gap(const Ellipsoid<double, N>& a, const Ellipsoid<double, N>& b, std::mt19937_64& rng) {
  double worst = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec<double, N> u = on_sphere<N>(rng);
    const Vec<double, N> q = Vec<double, N>(a.center()) + Mat<double, N>(a.axes()) * Vec<double, N>(a.radii()).cwiseProduct(u);
    worst = std::max(worst, std::abs(closest_point(b, q).signed_distance));
  }
  return worst;
}

// max_j |dS/dtheta_j| / (2 |d| |dd/dtheta_j|) at the stored body by central differences of
// closest_point in double (steps 1e-6): a route independent of the solver's Jacobian.
template <int N>
double difference_cosine(const Ellipsoid<double, N>& b, const Points<double, N>& points) {
  const Vec<double, N> c = b.center();
  const Mat<double, N> R = b.axes();
  const Vec<double, N> r = b.radii();
  const double size = r.maxCoeff();
  const auto body = [&](int j, double h) {
    Vec<double, N> cc = c, rr = r;
    Mat<double, N> RR = R;
    if (j < N) {
      cc[j] += h * size;
    } else if (j >= P<N> - N) {
      rr[j - (P<N> - N)] += h * size;
    } else {
      if constexpr (N == 2) RR = Eigen::Rotation2D<double>(h).toRotationMatrix() * R;
      else RR = Eigen::AngleAxisd(h, Eigen::Vector3d::Unit(j - N)).toRotationMatrix() * R;
    }
    return Ellipsoid<double, N>::from_axes(cc, RR, rr);
  };
  Eigen::VectorXd d(Eigen::Index(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) d[Eigen::Index(i)] = closest_point(b, points[i]).signed_distance;
  double worst = 0;
  for (int j = 0; j < P<N>; ++j) {
    const double h = 1e-6;
    const auto plus = body(j, h), minus = body(j, -h);
    Eigen::VectorXd col(d.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      col[Eigen::Index(i)] =
          (closest_point(plus, points[i]).signed_distance - closest_point(minus, points[i]).signed_distance) / (2 * h);
    worst = std::max(worst, std::abs(col.dot(d)) / (col.norm() * d.norm()));
  }
  return worst;
}

// ---- tests ---------------------------------------------------------------------------------

// Noisy small clouds at fit_tolerance 1e-10: the answer is the 50-digit stationary point
// (parameters within 1e-9 of the largest radius, angles within 1e-9), its residuals as stated
// to 1e-12, the gradient's cosine below 1e-8 in 50 digits.
template <int N>
void expect_matches_reference(const Points<double, N>& points, const char* what) {
  SCOPED_TRACE(what);
  const auto fit = fit_ellipsoid<double, N>(points, {.fit_tolerance = 1e-10});
  EXPECT_EQ(fit.status, FitStatus::converged) << to_string(fit.status);
  const auto ref = reference_fit<double, N>(fit.body, points);
  const auto p = params_of(fit.body);
  const F size = p.theta.template tail<N>().maxCoeff();
  for (int j = 0; j < P<N>; ++j) {
    const bool turn = j >= N && j < P<N> - N;
    EXPECT_LE(abs(ref.theta[j] - p.theta[j]), F(1e-9) * (turn ? F(1) : size)) << "parameter " << j;
  }
  EXPECT_LE(abs(F(fit.rms_residual) - ref.rms_at_answer), F(1e-12) * ref.rms_at_answer + F(1e-15) * size);
  EXPECT_LE(ref.cosine, 1e-8);
  EXPECT_LE(fit.rms_residual, fit.algebraic_rms_residual);
}

TEST(FitEllipsoid, MatchesA50DigitGaussNewton2D) {
  std::mt19937_64 rng(48);
  struct Case {
    double aspect, scale, offset, noise;
  };
  for (const Case k : {Case{1.5, 1, 0, 0.02}, Case{6, 1e-6, 1e6, 0.01}, Case{20, 1e6, -3e6, 0.005}, Case{1.05, 1, 7, 0.05}}) {
    const Mat<double, 2> R = scenarios::detail::orthogonal<2>(rng);
    const Vec<double, 2> r = k.scale * Vec<double, 2>(k.aspect, 1);
    const Vec<double, 2> c = k.scale * Vec<double, 2>(k.offset, 0.5 * k.offset + 1);
    const auto points = cloud_on<2>(c, R, r, 24, k.noise * k.scale * k.aspect, rng);
    expect_matches_reference<2>(points, ("aspect " + std::to_string(k.aspect)).c_str());
  }
}

TEST(FitEllipsoid, MatchesA50DigitGaussNewton3D) {
  std::mt19937_64 rng(49);
  for (int trial = 0; trial < 2; ++trial) {
    const Mat<double, 3> R = scenarios::detail::orthogonal<3>(rng);
    const Vec<double, 3> r(3, 1.5 + trial, 1);
    const Vec<double, 3> c(trial * 1e3, 2, -1);
    const auto points = cloud_on<3>(c, R, r, 40, 0.03, rng);
    expect_matches_reference<3>(points, trial ? "3D far" : "3D");
  }
}

// Points on a known body: the fit is that body, its boundary within 1e-9 of the largest radius
// (the points' own rounding, 1e-16 of their coordinates, included), its center and radii too.
template <int N>
void expect_recovers(const Ellipsoid<double, N>& truth, int m, std::mt19937_64& rng, double tolerance) {
  const Points<double, N> points =
      cloud_on<N>(truth.center(), truth.axes(), truth.radii(), m, 0, rng);
  const auto fit = fit_ellipsoid<double, N>(points);
  EXPECT_EQ(fit.status, FitStatus::converged) << to_string(fit.status);
  const double size = truth.radii().maxCoeff();
  EXPECT_LE(boundary_gap<N>(truth, fit.body, rng), tolerance * size);
  EXPECT_LE(boundary_gap<N>(fit.body, truth, rng), tolerance * size);
  EXPECT_LE((fit.body.center() - truth.center()).norm(), tolerance * size);
  Vec<double, N> a = fit.body.radii(), b = truth.radii();
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_LE((a - b).template lpNorm<Eigen::Infinity>(), tolerance * size);
  EXPECT_LE(fit.max_residual, tolerance * size);
  EXPECT_LE(fit.rms_residual, fit.algebraic_rms_residual + 1e-14 * (size + truth.center().norm()));
  EXPECT_EQ(fit.rank, P<N>);
}

TEST(FitEllipsoid, RecoversNoiseFreeEllipses) {
  std::mt19937_64 rng(50);
  for (double aspect : {1.5, 10.0, 1e3})
    for (double scale : {1e-6, 1.0, 1e6})
      for (double offset : {0.0, 1e6}) {
        SCOPED_TRACE(aspect);
        SCOPED_TRACE(scale);
        SCOPED_TRACE(offset);
        const Vec<double, 2> c = scale * Vec<double, 2>(offset, -0.5 * offset + 0.25);
        const auto truth = Ellipse2<double>::from_axes(c, scenarios::detail::orthogonal<2>(rng),
                                                       scale * Vec<double, 2>(1, aspect));
        expect_recovers<2>(truth, 60, rng, 1e-9);
      }
}

TEST(FitEllipsoid, RecoversNoiseFreeEllipsoids) {
  std::mt19937_64 rng(51);
  for (double aspect : {1.5, 30.0, 1e3})
    for (double scale : {1e-6, 1e6})
      for (double offset : {0.0, 1e6}) {
        SCOPED_TRACE(aspect);
        SCOPED_TRACE(scale);
        SCOPED_TRACE(offset);
        const Vec<double, 3> c = scale * Vec<double, 3>(offset, 1, -offset);
        const auto truth = Ellipsoid3<double>::from_axes(c, scenarios::detail::orthogonal<3>(rng),
                                                         scale * Vec<double, 3>(1, std::sqrt(aspect), aspect));
        expect_recovers<3>(truth, 200, rng, 1e-9);
      }
}

// Noisy clouds: no farther from the points than the algebraic fit, and stationary (the
// differences of closest_point agree).
TEST(FitEllipsoid, NoisyCloudsDescendAndAreStationary) {
  std::mt19937_64 rng(52);
  for (int trial = 0; trial < 12; ++trial) {
    SCOPED_TRACE(trial);
    const double aspect = std::pow(10.0, trial % 4 / 2.0);
    const double noise = trial % 3 == 0 ? 0.1 : 0.01;
    if (trial % 2 == 0) {
      const auto points = cloud_on<2>(Vec<double, 2>(trial, -trial), scenarios::detail::orthogonal<2>(rng),
                                      Vec<double, 2>(aspect, 1), 300, noise, rng);
      const auto fit = fit_ellipsoid<double, 2>(points);
      EXPECT_EQ(fit.status, FitStatus::converged);
      EXPECT_LE(fit.rms_residual, fit.algebraic_rms_residual);
      EXPECT_LE(difference_cosine<2>(fit.body, points), 1e-6);
    } else {
      const auto points = cloud_on<3>(Vec<double, 3>(trial, 0, 1), scenarios::detail::orthogonal<3>(rng),
                                      Vec<double, 3>(aspect, 1, 2), 300, noise, rng);
      const auto fit = fit_ellipsoid<double, 3>(points);
      EXPECT_EQ(fit.status, FitStatus::converged);
      EXPECT_LE(fit.rms_residual, fit.algebraic_rms_residual);
      EXPECT_LE(difference_cosine<3>(fit.body, points), 1e-6);
    }
  }
}

// Near circles with 10^4 points (the clouds on which a fixed determinant threshold fails): the
// circle, to the noise's average.
TEST(FitEllipsoid, NearCirclesWithManyPoints) {
  std::mt19937_64 rng(53);
  for (double noise : {0.0, 1e-6, 1e-3}) {
    SCOPED_TRACE(noise);
    const double radius = 250;
    const Vec<double, 2> c(1e6, -2e3);
    const auto points = cloud_on<2>(c, Mat<double, 2>::Identity(), Vec<double, 2>(radius, radius * (1 + 1e-7)), 10000,
                                    noise * radius, rng);
    const auto fit = fit_ellipsoid<double, 2>(points);
    EXPECT_EQ(fit.status, FitStatus::converged) << to_string(fit.status);
    const double allowed = (noise == 0 ? 1e-9 : 20 * noise / 100) * radius;  // noise / sqrt(m), with room
    EXPECT_LE((fit.body.center() - c).norm(), allowed);
    EXPECT_LE(std::abs(fit.body.radii()[0] - radius), allowed + 1e-7 * radius);
    EXPECT_LE(std::abs(fit.body.radii()[1] - radius), allowed + 1e-7 * radius);
    EXPECT_LE(fit.rms_residual, fit.algebraic_rms_residual + 1e-12 * radius);
  }
}

// 30 degree arcs. With noise of 1e-4 of the radius the fit converges, its residual the noise's,
// stationary, its center within 4 of its reported standard deviations of the truth (a 30 degree
// arc pins an ellipse's center only to tens of percent of its radius). With 1e-3 the
// least-squares ellipse may run off towards a parabola: then the status says not_an_ellipse.
TEST(FitEllipsoid, ShortNoisyArcs) {
  std::mt19937_64 rng(54);
  for (const double relative : {1e-4, 1e-3})
    for (int trial = 0; trial < 6; ++trial) {
      SCOPED_TRACE(relative);
      SCOPED_TRACE(trial);
      const Vec<double, 2> c(3, 4);
      const Vec<double, 2> r(10, trial % 2 ? 5 : 10);
      const double noise = relative * 10;
      const auto points = cloud_on<2>(c, scenarios::detail::orthogonal<2>(rng), r, 200, noise / std::sqrt(2.0), rng,
                                      std::numbers::pi / 6);
      const auto fit = fit_ellipsoid<double, 2>(points);
      EXPECT_LE(fit.rms_residual, fit.algebraic_rms_residual);
      if (relative == 1e-3 && fit.status == FitStatus::not_an_ellipse) {
        EXPECT_GT(fit.body.radii().maxCoeff(), 1e4);
        continue;
      }
      EXPECT_EQ(fit.status, FitStatus::converged) << to_string(fit.status);
      EXPECT_LE(fit.rms_residual, 1.2 * noise);
      EXPECT_LE(difference_cosine<2>(fit.body, points), 1e-6);
      const double spread = std::sqrt(fit.covariance(0, 0) + fit.covariance(1, 1));
      EXPECT_LE((fit.body.center() - c).norm(), 4 * spread);
    }
}

// Points on a hyperbola (both branches, one branch, with and without noise) and a hyperboloid:
// not an ellipse, said by the status.
TEST(FitEllipsoid, HyperbolasAreNotEllipses) {
  std::mt19937_64 rng(55);
  std::uniform_real_distribution<double> t(-1.5, 1.5);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 4; ++trial) {
    SCOPED_TRACE(trial);
    const Mat<double, 2> R = scenarios::detail::orthogonal<2>(rng);
    const double noise = trial % 2 ? 1e-3 : 0;
    Points<double, 2> points;
    for (int i = 0; i < 200; ++i) {
      const double s = t(rng), branch = trial < 2 && i % 2 ? -1 : 1;
      points.push_back(Vec<double, 2>(5, 5) + R * Vec<double, 2>(branch * 2 * std::cosh(s), std::sinh(s)) +
                       noise * Vec<double, 2>(g(rng), g(rng)));
    }
    const auto fit = fit_ellipsoid<double, 2>(points);
    EXPECT_EQ(fit.status, FitStatus::not_an_ellipse) << to_string(fit.status) << " rms " << fit.rms_residual;
  }
  Points<double, 3> sheet;  // x^2 + y^2 - z^2 = 1
  for (int i = 0; i < 300; ++i) {
    const double a = 2 * std::numbers::pi * (i * 0.618034 - std::floor(i * 0.618034)), s = t(rng);
    sheet.push_back(Vec<double, 3>(std::cosh(s) * std::cos(a), std::cosh(s) * std::sin(a), std::sinh(s)));
  }
  const auto hyperboloid = fit_ellipsoid<double, 3>(sheet);
  EXPECT_EQ(hyperboloid.status, FitStatus::not_an_ellipse);
}

// The reported covariance against the scatter of repeated fits to fresh noise: the standard
// deviations of the center and radii within 25% (the sample of 300 fits has about 4% error).
TEST(FitEllipsoid, CovarianceMatchesRepeatedDraws) {
  std::mt19937_64 rng(56);
  const Mat<double, 2> R = scenarios::detail::orthogonal<2>(rng);
  const Vec<double, 2> c(1e3, 2e3), r(40, 15);
  std::vector<Eigen::Matrix<double, 5, 1>> draws;
  Eigen::Matrix<double, 5, 5> reported = Eigen::Matrix<double, 5, 5>::Zero();
  for (int k = 0; k < 300; ++k) {
    std::mt19937_64 local(1000 + k);
    const auto fit = fit_ellipsoid<double, 2>(cloud_on<2>(c, R, r, 100, 0.5, local));
    ASSERT_EQ(fit.status, FitStatus::converged);
    Eigen::Matrix<double, 5, 1> v;
    const Mat<double, 2> axes = fit.body.axes();
    // Radii in the truth's order (the axis closest to the truth's first), and the angle of it.
    const int first = std::abs(axes.col(0).dot(R.col(0))) > std::abs(axes.col(1).dot(R.col(0))) ? 0 : 1;
    v << fit.body.center()[0], fit.body.center()[1], 0, fit.body.radii()[first], fit.body.radii()[1 - first];
    draws.push_back(v);
    Eigen::Matrix<double, 5, 5> cov = fit.covariance;
    if (first == 1) std::swap(cov(3, 3), cov(4, 4));
    reported += cov / 300;
  }
  Eigen::Matrix<double, 5, 1> mean = Eigen::Matrix<double, 5, 1>::Zero();
  for (const auto& v : draws) mean += v / 300;
  for (int j : {0, 1, 3, 4}) {
    double var = 0;
    for (const auto& v : draws) var += (v[j] - mean[j]) * (v[j] - mean[j]) / 299;
    EXPECT_NEAR(std::sqrt(var) / std::sqrt(reported(j, j)), 1, 0.25) << "parameter " << j;
  }
}

// Scaling the points by 2^k scales the answer by 2^k exactly.
TEST(FitEllipsoid, ExactUnderPowerOfTwoScaling) {
  std::mt19937_64 rng(57);
  const auto base = cloud_on<2>(Vec<double, 2>(1, 2), scenarios::detail::orthogonal<2>(rng), Vec<double, 2>(3, 1), 100, 0.05, rng);
  const auto a = fit_ellipsoid<double, 2>(base);
  for (int k : {-40, 30}) {
    Points<double, 2> scaled;
    for (const auto& p : base) scaled.push_back(std::ldexp(1.0, k) * p);
    const auto b = fit_ellipsoid<double, 2>(scaled);
    EXPECT_EQ(b.iterations, a.iterations);
    const Vec<double, 2> c = std::ldexp(1.0, k) * a.body.center(), r = std::ldexp(1.0, k) * a.body.radii();
    const Vec<double, 2> bc = b.body.center(), br = b.body.radii();
    const Mat<double, 2> ba = b.body.axes(), aa = a.body.axes();
    EXPECT_TRUE(bc == c);
    EXPECT_TRUE(br == r);
    EXPECT_TRUE(ba == aa);
    EXPECT_EQ(b.rms_residual, std::ldexp(a.rms_residual, k));
  }
}

TEST(FitEllipsoid, CapReachedStillNoFartherThanTheStart) {
  std::mt19937_64 rng(58);
  const auto points = cloud_on<2>(Vec<double, 2>(0, 0), scenarios::detail::orthogonal<2>(rng), Vec<double, 2>(5, 1), 200, 0.2, rng);
  const auto fit = fit_ellipsoid<double, 2>(points, {.max_fit_iterations = 1});
  EXPECT_EQ(fit.status, FitStatus::did_not_converge);
  EXPECT_EQ(fit.iterations, 1);
  EXPECT_LE(fit.rms_residual, fit.algebraic_rms_residual);
  const auto loose = fit_ellipsoid<double, 2>(points, {.fit_tolerance = 1e-4});
  EXPECT_EQ(loose.status, FitStatus::converged);
  const auto tight = fit_ellipsoid<double, 2>(points);
  EXPECT_LE(loose.iterations, tight.iterations);
}

// float points: the fit in double, the body stored in float.
TEST(FitEllipsoid, FloatPoints) {
  std::mt19937_64 rng(59);
  const auto d = cloud_on<3>(Vec<double, 3>(1, 2, 3), scenarios::detail::orthogonal<3>(rng), Vec<double, 3>(2, 1, 0.5), 300, 0, rng);
  Points<float, 3> points;
  for (const auto& p : d) points.push_back(p.cast<float>());
  const auto fit = fit_ellipsoid<float, 3>(points);
  EXPECT_EQ(fit.status, FitStatus::converged);
  EXPECT_LE((fit.body.center().cast<double>() - Vec<double, 3>(1, 2, 3)).norm(), 1e-5);
  EXPECT_LE(fit.max_residual, 1e-5);
  const auto f2 = fit_ellipsoid<float, 2>(Points<float, 2>{{1, 0}, {0, 2}, {-1, 0}, {0, -2}, {0.6f, 1.6f}, {-0.6f, -1.6f}});
  EXPECT_EQ(f2.status, FitStatus::converged);
  EXPECT_NEAR(f2.body.radii().maxCoeff(), 2, 1e-5);
}

TEST(FitEllipsoid, BadInputNamesThePoints) {
  const auto message = [](auto&& f) { return ellipsect::testing::error_message(f); };
  EXPECT_NE(message([] { fit_ellipsoid<double, 2>(Points<double, 2>{}); }).find("at least 5"), std::string::npos);
  EXPECT_NE(message([] { fit_ellipsoid<double, 3>(Points<double, 3>(8, Vec<double, 3>(1, 2, 3))); }).find("at least 9"),
            std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double bad : {nan, inf}) {
    try {
      fit_ellipsoid<double, 2>(Points<double, 2>{{0, 0}, {1, 0}, {0, 1}, {1, bad}, {1, 1}, {2, 3}});
      ADD_FAILURE() << "accepted " << bad;
    } catch (const RowInputError& e) {
      EXPECT_EQ(e.row(), 3u);
      EXPECT_EQ(e.field(), "points");
    }
  }
  EXPECT_NE(message([] { fit_ellipsoid<double, 2>(Points<double, 2>{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {4, 4}, {5, 5}}); })
                .find("line"),
            std::string::npos);
  EXPECT_NE(message([] {
              Points<double, 3> flat;
              for (int i = 0; i < 20; ++i) flat.push_back({std::cos(i), std::sin(2 * i), 1e-12 * i});
              fit_ellipsoid<double, 3>(flat);
            }).find("plane"),
            std::string::npos);
  EXPECT_NE(message([] { fit_ellipsoid<double, 2>(Points<double, 2>(7, Vec<double, 2>(3, 4))); }).find("equal"),
            std::string::npos);
  EXPECT_NE(message([] { FitOptions o; o.fit_tolerance = 0; }).find("fit_tolerance"), std::string::npos);
  EXPECT_NE(message([nan] { FitOptions o; o.fit_tolerance = nan; }).find("fit_tolerance"), std::string::npos);
  EXPECT_NE(message([] { FitOptions o; o.max_fit_iterations = 0; }).find("max_fit_iterations"), std::string::npos);
  EXPECT_EQ(to_string(FitStatus::not_an_ellipse), "not_an_ellipse");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
