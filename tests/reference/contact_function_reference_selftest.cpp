// Self-test of the contact-function reference (tests/reference/contact_function_reference.hpp)
// against closed forms for balls and against reference.hpp's Newton route to F, in 2D and 3D:
// the golden-section F equals pw()'s mu^2, and b placed at ca + sigma u has pw()'s mu = 1.
#include "contact_function_reference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <random>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect::reference;

template <int N>
Body<N> random_body(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> c(-3, 3), r(0.05, 4);
  Eigen::Matrix<double, N, N> q = Eigen::Matrix<double, N, N>::Random();
  Body<N> b{Eigen::Matrix<double, N, 1>::Zero(), Eigen::HouseholderQR<Eigen::Matrix<double, N, N>>(q).householderQ(),
            Eigen::Matrix<double, N, 1>::Zero()};
  for (int i = 0; i < N; ++i) {
    b.center[i] = c(rng);
    b.radii[i] = r(rng);
  }
  return b;
}

template <int N>
void balls() {
  Body<N> a{DVec<N>::Zero(), DMat<N>::Identity(), DVec<N>::Constant(1.5)};
  Body<N> b{DVec<N>::Zero(), DMat<N>::Identity(), DVec<N>::Constant(1)};
  b.center[0] = 3;
  b.center[1] = 4;
  const auto f = contact_function<N>(a, b);
  EXPECT_LE(abs(f.f - 4), Real("1e-45"));  // 25 / 2.5^2
  EXPECT_LE(abs(f.lambda - Real("0.6")), Real("1e-24"));  // golden section: ~sqrt(eps)
  DVec<N> u = DVec<N>::Zero();
  u[1] = -3;
  EXPECT_LE(abs(closest_approach<N>(a, b, u) - Real("2.5")), Real("1e-44"));
}

TEST(ContactFunctionReference, Balls) {
  balls<2>();
  balls<3>();
}

template <int N>
void agrees_with_newton_route() {
  std::mt19937_64 rng(17);
  for (int i = 0; i < 20; ++i) {
    const Body<N> a = random_body<N>(rng), b = random_body<N>(rng);
    const auto f = contact_function<N>(a, b);
    const auto p = pw<N>(a, b);
    EXPECT_LE(abs(f.f - p.mu * p.mu), Real("1e-44") * f.f);
    EXPECT_LE(abs(f.lambda - p.lambda), Real("1e-24"));
    DVec<N> u = DVec<N>::Zero();
    u[i % N] = 1;
    u[(i + 1) % N] = -0.5;
    const Real sigma = closest_approach<N>(a, b, u);
    // b at ca + sigma u exactly, in Real: F = 1.
    detail::RBody<N> ra = detail::make_rbody<N>(a), rb = detail::make_rbody<N>(b);
    RVec<N> dir = to_real<N>(u);
    dir /= sqrt(detail::dot<N>(dir, dir));
    const auto s = detail::pw_solve<N>(ra.P, rb.P, RVec<N>(dir * sigma));
    EXPECT_LE(abs(s.F - 1), Real("1e-40"));
  }
}

TEST(ContactFunctionReference, AgreesWithNewtonRoute2D) { agrees_with_newton_route<2>(); }
TEST(ContactFunctionReference, AgreesWithNewtonRoute3D) { agrees_with_newton_route<3>(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
