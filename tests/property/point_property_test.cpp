// closest_point on random bodies (aspect ratios to 1e4) and query points near, far,
// inside and outside. Checked by (1) the optimality conditions evaluated in 50 digits:
// the point is on the boundary and the offset is along the normal, outward for outside
// points; and (2) an independent brute-force bound: no boundary sample is closer.
#include <ellipsect/point.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/reference/reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using Real = ellipsect::reference::Real;

template <int N>
void run(int n) {
  scenarios::detail::Rng rng(7);
  for (int i = 0; i < n; ++i) {
    const double size = scenarios::detail::log_uniform(rng, 1e-3, 1e3);
    const double aspect = i % 3 == 0 ? 1e4 : 10.0;
    const auto body = Ellipsoid<double, N>::from_axes(scenarios::detail::unit_vector<N>(rng) * size,
                                                      scenarios::detail::rotation<N>(rng),
                                                      scenarios::detail::radii<N>(rng, size, aspect));
    // Query: a boundary point pushed along a random direction by a log-uniform amount.
    const Vec<double, N> u = scenarios::detail::unit_vector<N>(rng);
    const Vec<double, N> on = body.center() + body.axes() * body.radii().asDiagonal() * u;
    const double push = (i % 2 ? 1 : -1) * scenarios::detail::log_uniform(rng, 1e-12, 1e4) * body.radii().minCoeff();
    Vec<double, N> x = on + push * scenarios::detail::unit_vector<N>(rng);
    if (i % 7 == 0) x = body.center();  // the center: hard case for repeated radii
    const auto cp = closest_point(body, x);

    // (1) Optimality in 50 digits.
    // In the body frame, in 50 digits (a world-frame quadric rounded to double would lose
    // the small eigenvalues of a 1e4 needle).
    const Eigen::Matrix<Real, N, N> axes = body.axes().template cast<Real>();
    const Eigen::Matrix<Real, N, 1> inv_r2 = body.radii().template cast<Real>().cwiseAbs2().cwiseInverse();
    const Eigen::Matrix<Real, N, 1> d =
        axes.transpose() * (cp.point.template cast<Real>() - body.center().template cast<Real>());
    const Real q = d.dot(inv_r2.asDiagonal() * d);
    // The point is a double: its rounding (ulp of |point| <= |center| + r_max) moves q by
    // about 2 ulp / r_min.
    const double r_ratio = (body.center().norm() + body.radii().maxCoeff()) / body.radii().minCoeff();
    ASSERT_LT(abs(q - 1).template convert_to<double>(), 16 * 2.3e-16 * r_ratio) << i;
    const Eigen::Matrix<Real, N, 1> grad = axes * (inv_r2.asDiagonal() * d);
    const Eigen::Matrix<Real, N, 1> off = x.template cast<Real>() - cp.point.template cast<Real>();
    const double dist = off.norm().template convert_to<double>();
    const double scale = body.radii().maxCoeff() + (x - body.center()).norm();
    if (dist > 1e-9 * scale) {
      const Real cosine = grad.dot(off) / (grad.norm() * off.norm());
      ASSERT_GT((abs(cosine) - 1 + 1e-8).template convert_to<double>(), 0) << i << " cos=" << cosine;
      ASSERT_EQ(cosine > 0, cp.signed_distance > 0) << i;
    }
    ASSERT_NEAR(std::abs(cp.signed_distance), dist, 1e-14 * scale) << i;

    // (2) No sampled boundary point is closer (the sample includes the query's own
    // boundary point `on`, and a few thousand others).
    double best = (on - x).norm();
    scenarios::detail::Rng srng(i);
    for (int s = 0; s < 2000; ++s) {
      const Vec<double, N> p = body.center() + body.axes() * body.radii().asDiagonal() * scenarios::detail::unit_vector<N>(srng);
      best = std::min(best, (p - x).norm());
    }
    ASSERT_LE(std::abs(cp.signed_distance), best + 1e-14 * scale) << i;
  }
}

TEST(PointProperty, ClosestPointIsOptimal2D) { run<2>(ellipsect::testing::cases(3000)); }
TEST(PointProperty, ClosestPointIsOptimal3D) { run<3>(ellipsect::testing::cases(3000)); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
