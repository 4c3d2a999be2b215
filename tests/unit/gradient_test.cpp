// quaternion_gradient (gradient.hpp): the chain from the world rotation vector to a
// quaternion's components, against central differences in long double of a function of the
// rotation whose rotation-vector gradient is known in closed form, and through the library's
// quaternion factory and signed_distance_gradient.
#include <ellipsect/distance.hpp>
#include <ellipsect/gradient.hpp>

#include <gtest/gtest.h>

#include <random>

namespace ellipsect {
namespace {
namespace ELLIPSECT_UNITY_ID {

using L = long double;

// The rotation of q / |q| (Eigen normalizes inside toRotationMatrix only for unit input).
Mat<L, 3> rotation_of(const Vec<L, 4>& q) {
  return Eigen::Quaternion<L>(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

// f(R) = sum_i u_i . R e_i: turning R by dphi in the world changes R e_i by dphi x R e_i, so
// df/dphi = sum_i (R e_i) x u_i.
TEST(QuaternionGradient, MatchesDifferencesOfAFunctionOfTheRotation) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    Vec<L, 4> q;
    for (int k = 0; k < 4; ++k) q[k] = normal(rng);
    if (trial % 2) q *= L(3.5);  // any nonzero norm
    Mat<L, 3> u;
    for (int k = 0; k < 9; ++k) u(k) = normal(rng);
    auto f = [&](const Vec<L, 4>& x) {
      const Mat<L, 3> r = rotation_of(x);
      L s = 0;
      for (int i = 0; i < 3; ++i) s += u.col(i).dot(r.col(i));
      return s;
    };
    const Mat<L, 3> r = rotation_of(q);
    Vec<L, 3> g = Vec<L, 3>::Zero();
    for (int i = 0; i < 3; ++i) g += r.col(i).cross(u.col(i));
    const Vec<L, 4> chained = quaternion_gradient<L>(q, g);
    const L h = L(1e-6) * q.norm();
    for (int k = 0; k < 4; ++k) {
      Vec<L, 4> plus = q, minus = q;
      plus[k] += h;
      minus[k] -= h;
      const L difference = (f(plus) - f(minus)) / (2 * h);
      EXPECT_NEAR(double(chained[k]), double(difference), 1e-9 * double(g.norm() / q.norm()))
          << "trial " << trial << " component " << k;
    }
    // A change along q itself turns nothing.
    EXPECT_NEAR(double(chained.dot(q)), 0.0, 1e-15 * double(g.norm() * q.norm()));
  }
}

// Through the library: the signed distance of an ellipsoid made from a quaternion, by the
// chained orientation gradient and by differences of signed_distance over the quaternion (in
// double: the value is accurate to about 1e-15 of the scale, so the differences to about 1e-7).
TEST(QuaternionGradient, ChainsSignedDistanceThroughTheQuaternionFactory) {
  std::mt19937_64 rng(23);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 50; ++trial) {
    Vec<double, 4> q;
    for (int k = 0; k < 4; ++k) q[k] = normal(rng);
    q.normalize();
    const Vec3<double> radii(1.5, 0.7, 0.3), center(4.0 + normal(rng) * 0.1, 0.4, -0.3);
    auto body = [&](const Vec<double, 4>& x) {
      const Vec<double, 4> unit = x / x.norm();
      return make_ellipsoid<double>(center, Quat<double>(unit[0], unit[1], unit[2], unit[3]), radii);
    };
    const Ellipsoid3<double> other = make_ellipsoid<double>(Vec3<double>::Zero(), Mat3<double>::Identity(),
                                                            Vec3<double>(1.0, 0.8, 0.5));
    const DistanceGradient<double, 3> g = signed_distance_gradient(body(q), other);
    ASSERT_EQ(g.value.status, DistanceStatus::separated);
    const Vec<double, 4> chained = quaternion_gradient<double>(q, g.a.orientation);
    const double h = 1e-5;
    for (int k = 0; k < 4; ++k) {
      Vec<double, 4> plus = q, minus = q;
      plus[k] += h;
      minus[k] -= h;
      const double difference =
          (signed_distance(body(plus), other).distance - signed_distance(body(minus), other).distance) / (2 * h);
      EXPECT_NEAR(chained[k], difference, 1e-7) << "trial " << trial << " component " << k;
    }
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
}  // namespace ellipsect
