// Self-test of the high-precision reference (tests/reference/reference.hpp) against closed
// forms derived by hand, in 2D and 3D.  All inputs are exactly representable doubles, so the
// closed forms hold to the full ~50 digits of Real; tolerances are ~1e-44 relative unless a
// comment says otherwise.
#include "reference.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <sstream>
#include <type_traits>

#include <Eigen/Geometry>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect::reference;

template <int N> using DV = Eigen::Matrix<double, N, 1>;
template <int N> using DM = Eigen::Matrix<double, N, N>;
template <int N> using RV = Eigen::Matrix<Real, N, 1>;

const Real kTol("1e-44");

std::string str(const Real& x) {
  std::ostringstream os;
  os << std::setprecision(52) << x;
  return os.str();
}

::testing::AssertionResult near(const Real& a, const Real& b, const Real& tol = kTol,
                                bool relative = true) {
  const Real scale = relative ? std::max(Real(1), std::max(abs(a), abs(b))) : Real(1);
  const Real d = abs(a - b);
  if (d <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\n  got      " << str(a) << "\n  expected " << str(b)
                                       << "\n  |diff|   " << str(d);
}

template <int N>
::testing::AssertionResult near_vec(const RV<N>& a, const RV<N>& b, const Real& tol = kTol) {
  for (int i = 0; i < N; ++i) {
    auto r = near(a(i), b(i), tol);
    if (!r) return r << "\n  (component " << i << ")";
  }
  return ::testing::AssertionSuccess();
}

template <int N> DV<N> V(double x, double y, double z = 0) {
  DV<N> v;
  v(0) = x;
  v(1) = y;
  if constexpr (N == 3) v(2) = z;
  return v;
}
template <int N> RV<N> RVv(const Real& x, const Real& y, const Real& z = 0) {
  RV<N> v;
  v(0) = x;
  v(1) = y;
  if constexpr (N == 3) v(2) = z;
  return v;
}
template <int N> Body<N> ball(const DV<N>& c, double r) {
  return Body<N>{c, DM<N>::Identity(), DV<N>::Constant(r)};
}
template <int N> Body<N> aligned(const DV<N>& c, const DV<N>& radii) {
  return Body<N>{c, DM<N>::Identity(), radii};
}
// The same body as aligned(c, radii), described with a signed cyclic permutation of the axes:
// column j = sign_j * e_{(j+1) mod N}, radius_j = radii((j+1) mod N).
template <int N> Body<N> aligned_permuted(const DV<N>& c, const DV<N>& radii) {
  Body<N> b{c, DM<N>::Zero(), DV<N>::Zero()};
  for (int j = 0; j < N; ++j) {
    const int k = (j + 1) % N;
    b.axes(k, j) = (j % 2 == 0) ? -1.0 : 1.0;
    b.radii(j) = radii(k);
  }
  return b;
}
template <int N> Real rnorm(const RV<N>& v) {
  Real s = 0;
  for (int i = 0; i < N; ++i) s += v(i) * v(i);
  return sqrt(s);
}
template <int N> Real quad(const Body<N>& b, const RV<N>& x) {  // (x-c)^T M (x-c), axis aligned only
  Real s = 0;
  for (int i = 0; i < N; ++i) {
    const Real d = (x(i) - Real(b.center(i))) / Real(b.radii(i));
    s += d * d;
  }
  return s;
}

template <class T> class Ref : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(Ref, Dims);

// --------------------------------------------------------------------------- spheres

TYPED_TEST(Ref, SpheresScalePointLambda) {
  constexpr int N = TypeParam::value;
  struct Case { double ra, rb; double x, y, z; };
  const Case cases[] = {{1.5, 1.0, 3, 4, 12}, {0.25, 7.0, -1, 2, 2}, {2, 2, 0.5, 0.25, 0},
                        {1e-3, 1e3, 1e3, 0, 1}, {3, 2, 3, 4, 0} /* touching in 2D */};
  for (const auto& cs : cases) {
    const Body<N> a = ball<N>(V<N>(1, -2, 0.5), cs.ra);
    const Body<N> b = ball<N>(V<N>(1 + cs.x, -2 + cs.y, 0.5 + cs.z), cs.rb);
    const RV<N> r = RVv<N>(cs.x, cs.y, cs.z);
    const Real sum = Real(cs.ra) + Real(cs.rb);
    const PwResult<N> p = pw(a, b);
    EXPECT_TRUE(near(p.mu, rnorm<N>(r) / sum));
    EXPECT_TRUE(near(pw_scale(a, b), rnorm<N>(r) / sum));
    EXPECT_TRUE(near(p.lambda, Real(cs.ra) / sum));
    const RV<N> expect = to_real<N>(a.center) + r * (Real(cs.ra) / sum);
    EXPECT_TRUE(near_vec<N>(p.point, expect));
    // Symmetry: swapping the bodies gives lambda -> 1 - lambda, same mu and point.
    const PwResult<N> q = pw(b, a);
    EXPECT_TRUE(near(q.mu, p.mu));
    EXPECT_TRUE(near(q.lambda, 1 - p.lambda));
    EXPECT_TRUE(near_vec<N>(q.point, p.point));
  }
  // Coincident centres: mu = 0.
  EXPECT_EQ(pw_scale(ball<N>(V<N>(1, 1, 1), 1), ball<N>(V<N>(1, 1, 1), 2)), 0);
}

TYPED_TEST(Ref, SpheresContactTime) {
  constexpr int N = TypeParam::value;
  const double ra = 1.5, rb = 0.75;
  const DV<N> ca = V<N>(1, 2, -1), cb = V<N>(9, 7, 3);
  const DV<N> va = V<N>(0.5, 0.25, 0), vb = V<N>(-1.5, -0.75, -1);
  const Body<N> a = ball<N>(ca, ra), b = ball<N>(cb, rb);
  const RV<N> r0 = to_real<N>(cb) - to_real<N>(ca), v = to_real<N>(vb) - to_real<N>(va);
  const Real R = Real(ra) + Real(rb);
  // |r0 + t v| = R, smaller root.
  const Real A = v.dot(v), B = r0.dot(v), C = r0.dot(r0) - R * R;
  const Real t = (-B - sqrt(B * B - A * C)) / A;
  const Contact<N> c = first_contact<N>(a, va, b, vb, INFINITY, 1e-12);
  ASSERT_EQ(c.kind, ContactKind::hit);
  EXPECT_TRUE(near(c.time, t));
  const RV<N> rt = r0 + v * t;
  const RV<N> cat = to_real<N>(ca) + to_real<N>(va) * t;
  EXPECT_TRUE(near_vec<N>(c.point, RV<N>(cat + rt * (Real(ra) / R))));
  EXPECT_TRUE(near_vec<N>(c.normal, RV<N>(rt / R)));
  // min_mu = closest approach / (ra + rb).
  const RV<N> closest = r0 - v * (B / A);
  EXPECT_TRUE(near(c.min_mu, rnorm<N>(closest) / R));
  EXPECT_TRUE(near(c.t_min, -B / A));
  // pw_at at the contact time gives mu = 1.
  EXPECT_TRUE(near(pw_at<N>(a, va, b, vb, c.time).mu, Real(1)));
  // A window that ends before the contact: none, min_mu = mu(t_max) (mu still decreasing).
  const double tm = 0.5 * to_double(t);
  const Contact<N> n = first_contact<N>(a, va, b, vb, tm, 1e-12);
  EXPECT_EQ(n.kind, ContactKind::none);
  EXPECT_TRUE(isinf(n.time));
  EXPECT_TRUE(near(n.min_mu, rnorm<N>(RV<N>(r0 + v * Real(tm))) / R));
  // Receding: none, min_mu = mu(0).
  const Contact<N> rec = first_contact<N>(a, vb, b, va, INFINITY, 1e-12);
  EXPECT_EQ(rec.kind, ContactKind::none);
  EXPECT_TRUE(near(rec.min_mu, rnorm<N>(r0) / R));
  EXPECT_EQ(rec.t_min, 0);
  // Overlapping at the start, then moving apart through the closest approach: the start state
  // is reported, min_mu / t_min still describe the whole window.
  // A: radius 1 at the origin, B: radius 2 at (2, 1/2), r(t) = (2 - t, 1/2): closest at t = 2.
  const Contact<N> ov = first_contact<N>(ball<N>(V<N>(0, 0, 0), 1), V<N>(0, 0, 0),
                                         ball<N>(V<N>(2, 0.5, 0), 2), V<N>(-1, 0, 0), INFINITY,
                                         1e-12);
  EXPECT_EQ(ov.kind, ContactKind::overlapping_at_start);
  EXPECT_EQ(ov.time, 0);
  EXPECT_TRUE(near(ov.t_min, Real(2)));
  EXPECT_TRUE(near(ov.min_mu, Real(0.5) / 3));
}

TYPED_TEST(Ref, SphereMissAndHeadOn) {
  constexpr int N = TypeParam::value;
  // Miss: closest approach 5 > 3 at t = 4.
  const Body<N> a = ball<N>(V<N>(0, 0, 0), 1), b = ball<N>(V<N>(-8, 5, 0), 2);
  const Contact<N> c = first_contact<N>(a, V<N>(0, 0, 0), b, V<N>(2, 0, 0), INFINITY, 0);
  EXPECT_EQ(c.kind, ContactKind::none);
  EXPECT_TRUE(near(c.min_mu, Real(5) / 3));
  EXPECT_TRUE(near(c.t_min, Real(4)));
  EXPECT_TRUE(near_vec<N>(c.point, RVv<N>(0, Real(5) / 3)));  // PW point at argmin (t = 4)
  EXPECT_TRUE(near_vec<N>(c.normal, RVv<N>(0, 1)));
  // Head-on through the centre: contact at t = (8 - 3) / 2 = 2.5, point (-1, 0).
  const Body<N> b2 = ball<N>(V<N>(-8, 0, 0), 2);
  const Contact<N> h = first_contact<N>(a, V<N>(0, 0, 0), b2, V<N>(2, 0, 0), INFINITY, 0);
  ASSERT_EQ(h.kind, ContactKind::hit);
  EXPECT_TRUE(near(h.time, Real(2.5)));
  EXPECT_TRUE(near_vec<N>(h.point, RVv<N>(-1, 0)));
  EXPECT_TRUE(near_vec<N>(h.normal, RVv<N>(-1, 0)));
  EXPECT_TRUE(near(h.min_mu, Real(0)));  // centres pass through each other at t = 4
  EXPECT_TRUE(near(h.t_min, Real(4)));
}

// --------------------------------------------------------------------------- metric_range

TYPED_TEST(Ref, SphereInsideSphere) {
  constexpr int N = TypeParam::value;
  const double R = 5, rho = 1.25;
  const DV<N> cR = V<N>(0.5, -1, 2), cr = V<N>(1.5, 0.5, 2.75);  // d = (1, 1.5, 0.75)
  const Body<N> big = ball<N>(cR, R), small = ball<N>(cr, rho);
  const Real d = rnorm<N>(RV<N>(to_real<N>(cr) - to_real<N>(cR)));
  const Range<N> m1 = metric_range(big, small);  // boundary of small in big's metric
  EXPECT_TRUE(near(m1.max, (d + Real(rho)) / Real(R)));
  EXPECT_TRUE(near(m1.min, abs(d - Real(rho)) / Real(R)));
  const Range<N> m2 = metric_range(small, big);  // boundary of big in small's metric
  EXPECT_TRUE(near(m2.max, (Real(R) + d) / Real(rho)));
  EXPECT_TRUE(near(m2.min, (Real(R) - d) / Real(rho)));
  const Classification<N> c1 = classify(big, small, 1e-12);
  EXPECT_EQ(c1.relation, Relation::a_contains_b);
  EXPECT_TRUE(near(c1.b_in_a, m1.max));
  EXPECT_TRUE(near(c1.min_a_over_b, m1.min));
  EXPECT_TRUE(near(c1.a_in_b, m2.max));
  EXPECT_TRUE(near(c1.min_b_over_a, m2.min));
  EXPECT_TRUE(near(c1.margin, 1 - m1.max));
  EXPECT_EQ(classify(small, big, 1e-12).relation, Relation::b_contains_a);
  // Internal tangency (d + rho = R exactly): b_in_a = 1, still a_contains_b (exact test).
  const Body<N> tangent = ball<N>(V<N>(0.5 + 3.75, -1, 2), rho);
  const Classification<N> c2 = classify(big, tangent, 1e-12);
  EXPECT_TRUE(near(c2.b_in_a, Real(1)));
  EXPECT_TRUE(near(c2.margin, Real(0)));
  // Identical bodies: equal.
  const Classification<N> c3 = classify(big, big, 1e-12);
  EXPECT_EQ(c3.relation, Relation::equal);
  EXPECT_TRUE(near(c3.a_in_b, Real(1)));
  EXPECT_TRUE(near(c3.min_a_over_b, Real(1)));
  EXPECT_EQ(c3.mu, 0);
}

TYPED_TEST(Ref, ConcentricHardCase) {
  constexpr int N = TypeParam::value;
  // A: radii (3, 1[, 1]) (repeated radii in 3D), B: ball of radius 2, same centre: g = 0.
  const DV<N> c = V<N>(0.25, -4, 8);
  const Body<N> A = aligned<N>(c, V<N>(3, 1, 1)), B = ball<N>(c, 2);
  const Range<N> ba = metric_range(B, A);  // |x - c| / 2 over boundary(A): [1/2, 3/2]
  EXPECT_TRUE(near(ba.min, Real(0.5)));
  EXPECT_TRUE(near(ba.max, Real(1.5)));
  const Range<N> ab = metric_range(A, B);  // boundary(B) in A's metric: [2/3, 2]
  EXPECT_TRUE(near(ab.min, Real(2) / 3));
  EXPECT_TRUE(near(ab.max, Real(2)));
  const Classification<N> cl = classify(A, B, 1e-12);
  EXPECT_EQ(cl.relation, Relation::overlapping);
  EXPECT_EQ(cl.mu, 0);
  EXPECT_TRUE(near(cl.margin, Real(1) / 3));
  // Nested concentric ellipses, described with permuted axes: b_in_a = max(1/3, 1.5/2) = 3/4.
  const Body<N> outer = aligned_permuted<N>(c, V<N>(3, 2, 2)),
                inner = aligned<N>(c, V<N>(1, 1.5, 1));
  const Classification<N> nest = classify(outer, inner, 1e-12);
  EXPECT_EQ(nest.relation, Relation::a_contains_b);
  EXPECT_TRUE(near(nest.b_in_a, Real(0.75)));
  // min over boundary(inner) of sqrt(x^2/9 + y^2/4 [+ z^2/4]) = sqrt(1/9) at (1, 0[, 0]).
  EXPECT_TRUE(near(nest.min_a_over_b, Real(1) / 3));
  // Same shape, different centre/orientation description: equal.
  EXPECT_EQ(classify(aligned<N>(c, V<N>(3, 2, 2)), outer, 1e-30).relation, Relation::equal);
}

TYPED_TEST(Ref, HardCaseOffCentre) {
  constexpr int N = TypeParam::value;
  // Metric: ball radius 2 at the origin; boundary: radii (3, 1[, 1]) centred at (0, 1/2).
  // |x|^2 = 9 - 8 s^2 + s + 1/4 (s = y-component of u; 3D: same with s^2 -> u2^2 + u3^2):
  // max at s = 1/16: 9.28125 (the gradient is orthogonal to the top eigenvector: hard case),
  // min at s = -1: 1/4.
  const Body<N> m = ball<N>(V<N>(0, 0, 0), 2), bd = aligned<N>(V<N>(0, 0.5, 0), V<N>(3, 1, 1));
  const Range<N> r = metric_range(m, bd);
  EXPECT_TRUE(near(r.max, sqrt(Real(9.28125)) / 2));
  EXPECT_TRUE(near(r.min, Real(0.25)));
}

// --------------------------------------------------------------------------- ellipses on an axis

TYPED_TEST(Ref, AxisAlignedEllipsesOnAxis) {
  constexpr int N = TypeParam::value;
  // Centres on the x axis: the scaled bodies touch at (mu a1, 0), mu = D / (a1 + a2).
  const Body<N> A = aligned<N>(V<N>(0, 0, 0), V<N>(3, 1, 2));
  const Body<N> B = aligned_permuted<N>(V<N>(10, 0, 0), V<N>(2, 5, 1));
  const PwResult<N> p = pw(A, B);
  EXPECT_TRUE(near(p.mu, Real(2)));
  EXPECT_TRUE(near_vec<N>(p.point, RVv<N>(6, 0)));
  const Classification<N> cl = classify(A, B, 1e-12);
  EXPECT_EQ(cl.relation, Relation::separated);
  // Touching distance a1 + a2 = 5.
  const Body<N> T = aligned_permuted<N>(V<N>(-5, 0, 0), V<N>(2, 5, 1));
  const Classification<N> ct = classify(A, T, 1e-30);
  EXPECT_EQ(ct.relation, Relation::touching);
  EXPECT_TRUE(near(ct.mu, Real(1)));
  EXPECT_TRUE(near_vec<N>(pw(A, T).point, RVv<N>(-3, 0)));
  // B approaching along -x at speed 2 (A also moving along y: relative motion along x only
  // when both move the same in y): contact at t = (10 - 5) / 2 = 2.5.
  const DV<N> va = V<N>(0, 0.5, 0.25), vb = V<N>(-2, 0.5, 0.25);
  const Contact<N> c = first_contact<N>(A, va, B, vb, INFINITY, 1e-12);
  ASSERT_EQ(c.kind, ContactKind::hit);
  EXPECT_TRUE(near(c.time, Real(2.5)));
  EXPECT_TRUE(near_vec<N>(c.point, RVv<N>(3, 1.25, 0.625)));
  EXPECT_TRUE(near_vec<N>(c.normal, RVv<N>(1, 0)));
  // Window too short (t_max = 2): none, min_mu = mu(2) = 6 / 5.
  const Contact<N> n = first_contact<N>(A, va, B, vb, 2.0, 1e-12);
  EXPECT_EQ(n.kind, ContactKind::none);
  EXPECT_TRUE(near(n.min_mu, Real(6) / 5));
  EXPECT_EQ(n.t_min, 2);
}

// --------------------------------------------------------------------------- known contact point

TEST(Ref2, EllipseCircleKnownPoint) {
  // Ellipse radii (10, 25): (6, 20) is on it (0.36 + 0.64 = 1), outward normal
  // (6/100, 20/625) ~ (15, 8)/17; circle of radius 17 at (6, 20) + (15, 8) = (21, 28).
  const Body<2> E = aligned_permuted<2>(V<2>(0, 0), V<2>(10, 25));
  const Body<2> C = ball<2>(V<2>(21, 28), 17);
  const PwResult<2> p = pw(E, C);
  EXPECT_TRUE(near(p.mu, Real(1)));
  EXPECT_TRUE(near_vec<2>(p.point, RVv<2>(6, 20)));
  EXPECT_EQ(classify(E, C, 1e-30).relation, Relation::touching);
  // The circle moving along the normal: contact at t = 2 (E moves, circle at rest; world
  // frame point = (6, 20) + 2 * (15, 8)).
  const Body<2> C0 = ball<2>(V<2>(51, 44), 17);
  const Contact<2> c = first_contact<2>(E, V<2>(15, 8), C0, V<2>(0, 0), INFINITY, 1e-12);
  ASSERT_EQ(c.kind, ContactKind::hit);
  EXPECT_TRUE(near(c.time, Real(2)));
  EXPECT_TRUE(near_vec<2>(c.point, RVv<2>(36, 36)));
  EXPECT_TRUE(near_vec<2>(c.normal, RVv<2>(Real(15) / 17, Real(8) / 17)));
  // Circle shifted by (-2, 3.75) = 17/4 along the tangent (-8, 15)/17: no closed form, but
  // the contact point must lie on both surfaces at the contact time.
  const Body<2> C1 = ball<2>(V<2>(49, 47.75), 17);
  const Contact<2> c1 = first_contact<2>(E, V<2>(15, 8), C1, V<2>(0, 0), INFINITY, 1e-12);
  ASSERT_EQ(c1.kind, ContactKind::hit);
  const RV<2> ce = RVv<2>(15 * c1.time, 8 * c1.time);
  const RV<2> x = c1.point - ce;
  EXPECT_TRUE(near((x(0) / 10) * (x(0) / 10) + (x(1) / 25) * (x(1) / 25), Real(1)));
  EXPECT_TRUE(near(rnorm<2>(RV<2>(c1.point - RVv<2>(49, 47.75))), Real(17)));
}

TEST(Ref3, EllipsoidSphereKnownPoint) {
  // Ellipsoid radii (3, 6, 12): (1, 4, 8) is on it (1/9 + 16/36 + 64/144 = 1), outward normal
  // ~ (2, 2, 1)/3; sphere of radius 3 at (1, 4, 8) + (2, 2, 1) = (3, 6, 9).
  const Body<3> E = aligned_permuted<3>(V<3>(0, 0, 0), V<3>(3, 6, 12));
  const Body<3> S = ball<3>(V<3>(3, 6, 9), 3);
  const PwResult<3> p = pw(E, S);
  EXPECT_TRUE(near(p.mu, Real(1)));
  EXPECT_TRUE(near_vec<3>(p.point, RVv<3>(1, 4, 8)));
  EXPECT_EQ(classify(E, S, 1e-30).relation, Relation::touching);
  // Sphere moving in along the normal from (3, 6, 9) + 4 (2, 2, 1) at velocity -(2, 2, 1):
  // contact at t = 4.
  const Body<3> S0 = ball<3>(V<3>(11, 14, 13), 3);
  const Contact<3> c = first_contact<3>(E, V<3>(0, 0, 0), S0, V<3>(-2, -2, -1), INFINITY, 0);
  ASSERT_EQ(c.kind, ContactKind::hit);
  EXPECT_TRUE(near(c.time, Real(4)));
  EXPECT_TRUE(near_vec<3>(c.point, RVv<3>(1, 4, 8)));
  EXPECT_TRUE(near_vec<3>(c.normal, RVv<3>(Real(2) / 3, Real(2) / 3, Real(1) / 3)));
  // Reversed roles (the sphere is A): normal points from the sphere to the ellipsoid.
  const Contact<3> r = first_contact<3>(S0, V<3>(-2, -2, -1), E, V<3>(0, 0, 0), INFINITY, 0);
  ASSERT_EQ(r.kind, ContactKind::hit);
  EXPECT_TRUE(near(r.time, Real(4)));
  EXPECT_TRUE(near_vec<3>(r.point, RVv<3>(1, 4, 8)));
  EXPECT_TRUE(near_vec<3>(r.normal, RVv<3>(-Real(2) / 3, -Real(2) / 3, -Real(1) / 3)));
}

// --------------------------------------------------------------------------- grazing

TYPED_TEST(Ref, GrazingPath) {
  constexpr int N = TypeParam::value;
  // A radii (3, 1, 2), B radii (2, 0.5, 1), B moving along +x at height h. The line y = b1 + b2
  // supports the Minkowski sum A - B only at x = 0, so min_mu = h / (b1 + b2) exactly, at
  // r_x = 0 (t = 10), where the scaled bodies touch at (0, mu b1).
  const Body<N> A = aligned<N>(V<N>(0, 0, 0), V<N>(3, 1, 2));
  for (double h : {1.5, 1.75, 1.25}) {
    const Body<N> B = aligned_permuted<N>(V<N>(-10, h, 0), V<N>(2, 0.5, 1));
    const Contact<N> c = first_contact<N>(A, V<N>(0, 0, 0), B, V<N>(1, 0, 0), INFINITY, 0);
    EXPECT_TRUE(near(c.min_mu, Real(h) / Real(1.5))) << "h = " << h;
    EXPECT_TRUE(near(c.t_min, Real(10), Real("1e-40"))) << "h = " << h;
    if (h > 1.5) {
      EXPECT_EQ(c.kind, ContactKind::none);
      EXPECT_TRUE(near_vec<N>(c.point, RVv<N>(0, Real(h) / Real(1.5))));
      EXPECT_TRUE(near_vec<N>(c.normal, RVv<N>(0, 1)));
    } else if (h < 1.5) {
      ASSERT_EQ(c.kind, ContactKind::hit);
      EXPECT_LT(c.time, 10);
      EXPECT_TRUE(near(pw_at<N>(A, V<N>(0, 0, 0), B, V<N>(1, 0, 0), c.time).mu, Real(1)));
    } else if (c.kind == ContactKind::hit) {  // exactly grazing: a double root
      EXPECT_TRUE(near(c.time, Real(10), Real("1e-20")));
      EXPECT_TRUE(near_vec<N>(c.point, RVv<N>(0, 1), Real("1e-20")));
    }
  }
  // Spheres: radii 1 and 2, offset 3 -> exact grazing at t = 10 (B at speed 1).
  const Contact<N> s = first_contact<N>(ball<N>(V<N>(0, 0, 0), 1), V<N>(0, 0, 0),
                                        ball<N>(V<N>(-10, 3, 0), 2), V<N>(1, 0, 0), INFINITY, 0);
  EXPECT_TRUE(near(s.min_mu, Real(1)));
  EXPECT_TRUE(near(s.t_min, Real(10), Real("1e-40")));
}

// --------------------------------------------------------------------------- zero velocity

TYPED_TEST(Ref, ZeroRelativeVelocity) {
  constexpr int N = TypeParam::value;
  const DV<N> v = V<N>(1, -2, 3);
  const Body<N> a = aligned<N>(V<N>(0, 0, 0), V<N>(3, 1, 2));
  const Body<N> far = aligned<N>(V<N>(10, 0, 0), V<N>(2, 5, 1));
  const Contact<N> c = first_contact<N>(a, v, far, v, INFINITY, 1e-12);
  EXPECT_EQ(c.kind, ContactKind::none);
  EXPECT_TRUE(isinf(c.time));
  EXPECT_TRUE(near(c.min_mu, Real(2)));
  const Body<N> touch = aligned<N>(V<N>(5, 0, 0), V<N>(2, 5, 1));
  const Contact<N> t = first_contact<N>(a, v, touch, v, INFINITY, 1e-12);
  EXPECT_EQ(t.kind, ContactKind::touching_at_start);
  EXPECT_EQ(t.time, 0);
  EXPECT_TRUE(near_vec<N>(t.point, RVv<N>(3, 0)));
  EXPECT_TRUE(near_vec<N>(t.normal, RVv<N>(1, 0)));
  const Body<N> over = aligned<N>(V<N>(4, 0, 0), V<N>(2, 5, 1));
  EXPECT_EQ(first_contact<N>(a, v, over, v, INFINITY, 1e-12).kind,
            ContactKind::overlapping_at_start);
  // Start states are reported whatever the velocities.
  EXPECT_EQ(first_contact<N>(a, V<N>(0, 0, 0), over, v, INFINITY, 1e-12).kind,
            ContactKind::overlapping_at_start);
}

// --------------------------------------------------------------------------- random consistency

template <int N> Body<N> random_body(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-1, 1), r(0.2, 3);
  Body<N> b;
  for (int i = 0; i < N; ++i) {
    b.center(i) = spread * u(rng);
    b.radii(i) = r(rng);
  }
  if constexpr (N == 2) {
    const double th = 3.2 * u(rng);
    b.axes << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
  } else {
    const double w = u(rng), x = u(rng), y = u(rng), z = u(rng);  // sequenced: portable
    Eigen::Quaterniond q(w, x, y, z);
    q.normalize();
    b.axes = q.toRotationMatrix();
  }
  return b;
}

// Quadric value with the Real body built exactly as the reference does.
template <int N> Real qform(const Body<N>& b, const RV<N>& x) {
  const auto rb = ellipsect::reference::detail::make_rbody<N>(b);
  const RV<N> d = x - rb.c;
  return d.dot(rb.M * d);
}

TYPED_TEST(Ref, RandomPwPointIsTouchingPoint) {
  constexpr int N = TypeParam::value;
  std::mt19937_64 rng(7 + N);
  for (int k = 0; k < 200; ++k) {
    const Body<N> a = random_body<N>(rng, 4), b = random_body<N>(rng, 4);
    const PwResult<N> p = pw(a, b);
    const Real mu2 = p.mu * p.mu;
    // x is on both bodies scaled by mu, with antiparallel gradients: the scaled bodies touch.
    EXPECT_TRUE(near(qform(a, p.point), mu2, Real("1e-42")));
    EXPECT_TRUE(near(qform(b, p.point), mu2, Real("1e-42")));
    const auto ra = ellipsect::reference::detail::make_rbody<N>(a);
    const auto rb = ellipsect::reference::detail::make_rbody<N>(b);
    const RV<N> ga = ra.M * (p.point - ra.c), gb = rb.M * (p.point - rb.c);
    const Real cosang = ga.dot(gb) / (rnorm<N>(ga) * rnorm<N>(gb));
    EXPECT_TRUE(near(cosang, Real(-1), Real("1e-42")));
  }
}

// classify_stored's body is the quadric of the axes as given: with axes 1e-9 off
// orthonormal, M = A diag(r)^-2 A^T (formed here directly), P = M^-1, and the boundary
// parametrisation c + L u lies on (x - c)^T M (x - c) = 1; with exactly orthonormal axes
// (signed permutations) it is classify's body, measure for measure.
TYPED_TEST(Ref, StoredBodyIsTheStoredQuadric) {
  constexpr int N = TypeParam::value;
  std::mt19937_64 rng(31 + N);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 50; ++k) {
    Body<N> b = random_body<N>(rng, 4);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) b.axes(i, j) += 1e-9 * u(rng);
    const auto rb = ellipsect::reference::detail::make_stored_rbody<N>(b);
    Eigen::Matrix<Real, N, N> M = Eigen::Matrix<Real, N, N>::Zero();
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j)
        for (int m = 0; m < N; ++m)
          M(i, j) += Real(b.axes(i, m)) * Real(b.axes(j, m)) / (Real(b.radii(m)) * Real(b.radii(m)));
    const Eigen::Matrix<Real, N, N> PM = rb.P * M;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        EXPECT_TRUE(near(rb.M(i, j), M(i, j)));
        EXPECT_TRUE(near(PM(i, j), Real(i == j ? 1 : 0)));
      }
    RV<N> v;
    for (int i = 0; i < N; ++i) v(i) = Real(u(rng));
    const RV<N> x = rb.c + rb.L * (v / rnorm<N>(v));
    EXPECT_TRUE(near((x - rb.c).dot(M * (x - rb.c)), Real(1)));
  }
  for (int k = 0; k < 20; ++k) {
    const Body<N> a = aligned_permuted<N>(V<N>(u(rng), u(rng), u(rng)), V<N>(1 + u(rng) / 2, 2, 1.5)),
                  b = aligned<N>(V<N>(1 + u(rng), u(rng), u(rng)), V<N>(0.5, 1 + u(rng) / 2, 0.75));
    const auto want = classify<N>(a, b, 1e-30), got = classify_stored<N>(a, b, 1e-30);
    EXPECT_EQ(got.relation, want.relation);
    EXPECT_TRUE(near(got.mu, want.mu));
    EXPECT_TRUE(near(got.a_in_b, want.a_in_b));
    EXPECT_TRUE(near(got.b_in_a, want.b_in_a));
  }
}

// metric_range against an unrelated method: Newton on the Lagrange (KKT) system
// (H - s I) u = -g, |u| = 1, in Real, started from the best boundary samples (double), the
// eigenvectors of H and random directions.  Every converged KKT point is feasible, so the
// reference must bracket all of them, and the best ones must match it.
template <int N>
bool kkt_newton(const Eigen::Matrix<Real, N, N>& H, const RV<N>& g, const Real& c0,
                const DV<N>& start, Real& q) {
  RV<N> u = to_real<N>(start);
  u /= rnorm<N>(u);
  Real s = u.dot(H * u + g);
  for (int it = 0; it < 80; ++it) {
    Eigen::Matrix<Real, N + 1, N + 1> J = Eigen::Matrix<Real, N + 1, N + 1>::Zero();
    Eigen::Matrix<Real, N + 1, 1> F;
    J.template topLeftCorner<N, N>() = H - s * Eigen::Matrix<Real, N, N>::Identity();
    J.template topRightCorner<N, 1>() = -u;
    J.template bottomLeftCorner<1, N>() = u.transpose();
    F.template head<N>() = H * u + g - s * u;
    F(N) = (u.dot(u) - 1) / 2;
    const Eigen::Matrix<Real, N + 1, 1> d = J.fullPivLu().solve(F);
    if (!(abs(d(N)) < 1e10)) return false;
    u -= d.template head<N>();
    s -= d(N);
    if (abs(d(N)) + rnorm<N>(RV<N>(d.template head<N>())) < Real("1e-46")) break;
  }
  const RV<N> res = H * u + g - s * u;
  q = u.dot(H * u) + 2 * g.dot(u) + c0;
  return abs(u.dot(u) - 1) < Real("1e-45") &&
         rnorm<N>(res) < Real("1e-40") * (1 + abs(s) + rnorm<N>(g));
}

TYPED_TEST(Ref, RandomMetricRangeVsKktNewton) {
  constexpr int N = TypeParam::value;
  std::mt19937_64 rng(11 + N);
  std::uniform_real_distribution<double> uni(-1, 1);
  for (int k = 0; k < 24; ++k) {
    const Body<N> m = random_body<N>(rng, k % 3 == 0 ? 0 : 2), bd = random_body<N>(rng, 2);
    const Range<N> r = metric_range(m, bd);
    const auto rm = ellipsect::reference::detail::make_rbody<N>(m);
    const auto rbd = ellipsect::reference::detail::make_rbody<N>(bd);
    const Eigen::Matrix<Real, N, N> H = rbd.L.transpose() * rm.M * rbd.L;
    const RV<N> dc = rbd.c - rm.c;
    const RV<N> g = rbd.L.transpose() * (rm.M * dc);
    const Real c0 = dc.dot(rm.M * dc);
    DM<N> Hd;
    DV<N> gd;
    for (int i = 0; i < N; ++i) {
      gd(i) = to_double(g(i));
      for (int j = 0; j < N; ++j) Hd(i, j) = to_double(H(i, j));
    }
    std::vector<DV<N>> starts;
    double lo = INFINITY, hi = -INFINITY;
    DV<N> ulo = DV<N>::Zero(), uhi = DV<N>::Zero();
    auto sample = [&](const DV<N>& u) {
      const double q = u.dot(Hd * u) + 2 * gd.dot(u);
      if (q < lo) lo = q, ulo = u;
      if (q > hi) hi = q, uhi = u;
    };
    const int n = N == 2 ? 2000 : 120;
    if constexpr (N == 2) {
      for (int i = 0; i < n; ++i) sample(DV<N>(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n)));
    } else {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j <= n / 2; ++j) {
          const double th = 2 * M_PI * i / n, ph = M_PI * j / (n / 2);
          sample(DV<N>(std::sin(ph) * std::cos(th), std::sin(ph) * std::sin(th), std::cos(ph)));
        }
    }
    starts.push_back(ulo);
    starts.push_back(uhi);
    for (int i = 0; i < N; ++i) {
      DV<N> e = DV<N>::Zero();
      e(i) = 1;
      starts.push_back(e);
      starts.push_back(-e);
    }
    for (int i = 0; i < 8; ++i) {
      DV<N> v;
      for (int j = 0; j < N; ++j) v(j) = uni(rng);
      starts.push_back(v);
    }
    Real best_min = 1e300, best_max = -1;
    for (const DV<N>& st : starts) {
      Real q;
      if (!kkt_newton<N>(H, g, c0, st, q)) continue;
      const Real sq = sqrt(std::max(q, Real(0)));
      EXPECT_LE(r.min, sq + Real("1e-45") * r.max);
      EXPECT_GE(r.max, sq - Real("1e-45") * r.max);
      best_min = std::min(best_min, sq);
      best_max = std::max(best_max, sq);
    }
    EXPECT_TRUE(near(r.max, best_max, Real("1e-44") * r.max, false)) << "case " << k;
    EXPECT_TRUE(near(r.min, best_min, Real("1e-44") * r.max, false)) << "case " << k;
  }
}

// The contact time makes mu = 1, mu > 1 a little earlier, and the point/normal are the
// touching point / outward normal of A.
TYPED_TEST(Ref, RandomContactConsistency) {
  constexpr int N = TypeParam::value;
  std::mt19937_64 rng(23 + N);
  int hits = 0;
  for (int k = 0; k < 20; ++k) {
    Body<N> a = random_body<N>(rng, 0), b = random_body<N>(rng, 1);
    b.center(0) += 12;
    DV<N> vb = DV<N>::Zero(), va = DV<N>::Zero();
    vb(0) = -2;
    vb(1) = 0.3 * (k % 5 - 2);
    va(1) = 0.125;
    const Contact<N> c = first_contact<N>(a, va, b, vb, INFINITY, 1e-12);
    if (c.kind != ContactKind::hit) continue;
    ++hits;
    EXPECT_TRUE(near(pw_at<N>(a, va, b, vb, c.time).mu, Real(1), Real("1e-42")));
    EXPECT_GT(pw_at<N>(a, va, b, vb, c.time * Real(0.999)).mu, 1);
    const RV<N> x = c.point;
    const auto ra = ellipsect::reference::detail::make_rbody<N>(a);
    const RV<N> cat = ra.c + to_real<N>(va) * c.time;
    EXPECT_TRUE(near(RV<N>(x - cat).dot(ra.M * (x - cat)), Real(1), Real("1e-42")));
    const RV<N> n = ra.M * (x - cat);
    EXPECT_TRUE(near_vec<N>(c.normal, RV<N>(n / rnorm<N>(n)), Real("1e-42")));
    EXPECT_LE(c.min_mu, 1);
  }
  EXPECT_GE(hits, 10);
}

// --------------------------------------------------------------------------- timings

TYPED_TEST(Ref, Timings) {
  constexpr int N = TypeParam::value;
  std::mt19937_64 rng(99 + N);
  using clock = std::chrono::steady_clock;
  const int nc = 300;
  std::vector<std::pair<Body<N>, Body<N>>> pairs;
  for (int k = 0; k < nc; ++k) pairs.emplace_back(random_body<N>(rng, 3), random_body<N>(rng, 3));
  auto t0 = clock::now();
  int sep = 0;
  for (const auto& [a, b] : pairs) sep += classify(a, b, 1e-12).relation == Relation::separated;
  const double ms_class = std::chrono::duration<double, std::milli>(clock::now() - t0).count() / nc;

  const int nk = 40;
  int hits = 0;
  t0 = clock::now();
  for (int k = 0; k < nk; ++k) {
    Body<N> a = random_body<N>(rng, 0), b = random_body<N>(rng, 3);
    b.center(0) += 15;
    DV<N> vb = DV<N>::Zero();
    vb(0) = -1;
    vb(1) = 0.2 * (k % 7 - 3);
    hits += first_contact<N>(a, DV<N>::Zero(), b, vb, INFINITY, 1e-12).kind == ContactKind::hit;
  }
  const double ms_contact = std::chrono::duration<double, std::milli>(clock::now() - t0).count() / nk;
  std::printf("[ timing   ] N=%d classify: %.3f ms/call (%d/%d separated), first_contact: %.3f "
              "ms/call (%d/%d hits)\n",
              N, ms_class, sep, nc, ms_contact, hits, nk);
  this->RecordProperty("classify_ms_per_call", std::to_string(ms_class));
  this->RecordProperty("first_contact_ms_per_call", std::to_string(ms_contact));
  EXPECT_GT(hits, 0);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
