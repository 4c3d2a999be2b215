// Regressions: each test names a defect of the published algorithm or code (Eberly,
// "Intersection of Swept Ellipses and Swept Ellipsoids") that ellipsect must not repeat.
#include <ellipsect/contact.hpp>

#include "detail/reduce.hpp"
#include "detail/secular.hpp"

#include <Eigen/Eigenvalues>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/eigen.hpp>
#include "tests/contact_wrappers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
constexpr double inf = std::numeric_limits<double>::infinity();

// The seed returns `false` both when the bodies overlap at the start and when they never
// touch; a caller cannot tell a collision already in progress from a miss.
TEST(SeedBugs, OverlapAtStartIsNotNeverTouch) {
  const auto a = make_ball<double, 2>({0, 0}, 1);
  EXPECT_EQ(contact2(a, {0, 0}, make_ball<double, 2>({1, 0}, 1), {1, 0}, inf).status,
            ContactStatus::overlapping_at_start);
  EXPECT_EQ(contact2(a, {0, 0}, make_ball<double, 2>({5, 0}, 1), {1, 0}, inf).status,
            ContactStatus::no_contact_in_window);
}

// The seed stops Newton when |h| < 1e-8, an absolute tolerance: in a scene scaled by 1e-6
// that is already a huge relative error (and 1e6 scenes never reach it in 128 steps).
// ellipsect's tolerances are relative, so a scaled scene gives the same time.
TEST(SeedBugs, AbsoluteToleranceBreaksScaledScenes) {
  for (double s : {1e-6, 1.0, 1e6}) {
    const auto a = make_ellipse<double>({0, 0}, 0.4, {2 * s, 0.5 * s});
    const auto b = make_ellipse<double>({9 * s, 3 * s}, -0.2, {s, 1.5 * s});
    const auto c = contact2(a, {0, 0}, b, {-s, -0.3 * s}, inf);
    const auto ref = contact2(make_ellipse<double>({0, 0}, 0.4, {2, 0.5}), {0, 0},
                                              make_ellipse<double>({9, 3}, -0.2, {1, 1.5}), {-1, -0.3}, inf);
    ASSERT_EQ(c.status, ContactStatus::hit) << s;
    EXPECT_NEAR(c.time, ref.time, 1e-14 * ref.time) << s;
    EXPECT_LT((c.point / s - ref.point).norm(), 1e-13) << s;
  }
}

// The seed's equation (35) maps the contact point back with K0, the first body's center
// at t = 0, although that body moves with V0: the point is off by t * V0.
TEST(SeedBugs, ContactPointFollowsTheFirstBody) {
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({10, 0}, 1);
  const auto c = contact2(a, {2, 0}, b, {0, 0}, inf);  // a runs into b at t = 4
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_NEAR(c.time, 4.0, 1e-15);
  EXPECT_LT((c.point - Vec2<double>(9, 0)).norm(), 1e-14);
}

// Equation (29) and the code give h'(t) = 4 W.P; the true derivative of
// h(t) = |P(t)|^2 - 1 is 2 W.P (envelope theorem). With the factor 4 every Newton step is
// halved and convergence is only linear. Checked by central differences.
TEST(SeedBugs, DerivativeOfHIsTwoWDotP) {
  const Vec3<double> e(3, 1, 0.5), k(4, -2, 1.5), w(-1, 0.3, -0.2);
  auto h = [&](double t) {
    return detail::closest_from_outside<double, 3>(e, k + t * w).point.squaredNorm() - 1;
  };
  const double t = 0.7, dt = 1e-5;
  const double numeric = (h(t + dt) - h(t - dt)) / (2 * dt);
  const Vec3<double> p = detail::closest_from_outside<double, 3>(e, k + t * w).point;
  EXPECT_NEAR(numeric, 2 * w.dot(p), 1e-8 * std::abs(numeric));
  EXPECT_GT(std::abs(numeric - 4 * w.dot(p)), 0.1 * std::abs(numeric));
}

// The seed factors M2 with a symmetric eigensolver. For two needles (aspect 1e4) the
// eigenvalues of M2 spread over 1e16 and the small ones are lost entirely; the SVD of the
// one-sided factor L keeps every semi-axis to a few ulps. Reference: 50-digit SVD.
TEST(SeedBugs, SymmetricEigensolverLosesThinDirections) {
  using Real = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<50>, boost::multiprecision::et_off>;
  const Mat3<double> r0 = Eigen::AngleAxisd(0.3, Vec3<double>(1, 2, 3).normalized()).toRotationMatrix();
  const Mat3<double> r1 = Eigen::AngleAxisd(-1.1, Vec3<double>(3, -1, 2).normalized()).toRotationMatrix();
  const auto s = make_ellipsoid<double>({0, 0, 0}, r0, {1, 1e-4, 1e-4});
  const auto o = make_ellipsoid<double>({5, 1, 2}, r1, {1e-4, 1, 1e-4});
  const auto red = detail::reduce<double>(s, o);

  const Mat3<Real> l = s.radii().cast<Real>().cwiseInverse().asDiagonal() * s.axes().cast<Real>().transpose() *
                       o.axes().cast<Real>() * o.radii().cast<Real>().asDiagonal();
  const Eigen::JacobiSVD<Mat3<Real>> exact(l);
  Vec3<double> e = red.e;
  std::sort(e.data(), e.data() + 3, std::greater<>());  // the exact ones come sorted
  for (int i = 0; i < 3; ++i) {
    const double rel = static_cast<double>(abs((Real(e[i]) - exact.singularValues()[i]) / exact.singularValues()[i]));
    EXPECT_LT(rel, 1e-13) << i;
  }
  // The seed's route: eigenvalues of M2 = L^-T L^-1 by a symmetric solver, d = 1/e^2.
  const Mat3<double> ld = l.cast<double>();
  const Mat3<double> m2 = (ld * ld.transpose()).inverse();
  const Eigen::SelfAdjointEigenSolver<Mat3<double>> eig(m2);
  const double largest_axis = exact.singularValues()[0].convert_to<double>();  // largest semi-axis
  const double seed_axis = 1 / std::sqrt(std::abs(eig.eigenvalues()[0]));
  EXPECT_GT(std::abs(seed_axis - largest_axis) / largest_axis, 1e-6);
}

// Nearly equal eigenvalues: two almost-spheres (radii differing by 1e-12) have M2 with a
// cluster of eigenvalues, where eigenvectors are ill-determined but the ellipsoid is not:
// the reduced body U diag(e)^2 U^T must reproduce L L^T to a few ulps.
TEST(SeedBugs, NearlyEqualEigenvaluesKeepTheShape) {
  using Real = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<50>, boost::multiprecision::et_off>;
  const Mat3<double> r0 = Eigen::AngleAxisd(0.9, Vec3<double>(1, -2, 1).normalized()).toRotationMatrix();
  const Mat3<double> r1 = Eigen::AngleAxisd(2.1, Vec3<double>(0, 1, 3).normalized()).toRotationMatrix();
  const auto s = make_ellipsoid<double>({0, 0, 0}, r0, {1, 1 + 1e-12, 1 - 1e-12});
  const auto o = make_ellipsoid<double>({3, 0, 1}, r1, {2, 2 + 2e-12, 2});
  const auto red = detail::reduce<double>(s, o);
  const Mat3<Real> l = s.radii().cast<Real>().cwiseInverse().asDiagonal() * s.axes().cast<Real>().transpose() *
                       o.axes().cast<Real>() * o.radii().cast<Real>().asDiagonal();
  const Mat3<Real> exact = l * l.transpose();
  const Mat3<double> u = (red.to_z * s.axes() * s.radii().asDiagonal()).transpose();  // to_z = U^T diag(1/a) R0^T
  const Mat3<Real> got = u.cast<Real>() * red.e.cast<Real>().cwiseAbs2().asDiagonal() * u.cast<Real>().transpose();
  EXPECT_LT(static_cast<double>((got - exact).cwiseAbs().maxCoeff()), 1e-14 * 4);
  // The singular values themselves, within the 32 ulps the rounding model assumes.
  const Eigen::JacobiSVD<Mat3<Real>> svd(l);
  Vec3<double> e = red.e;
  std::sort(e.data(), e.data() + 3, std::greater<>());
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(static_cast<double>(abs(Real(e[i]) - svd.singularValues()[i]) / svd.singularValues()[i]), 32 * 2.3e-16);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
