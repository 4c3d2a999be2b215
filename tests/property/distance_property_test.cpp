// distance and signed_distance against the 50-digit reference (tests/reference/
// distance_reference.hpp: a dense global search of the support gap over directions, in
// the world frame, polished in 50 digits; independent of the library's reduced-frame
// start, sampled Gauss-map starts and trust-region Newton).
//
// Claims under test (distance.hpp), with scale = largest radius of a + of b + |distance|:
//   the status is classify's (separated, touching, or overlapping for every other relation);
//   |distance - reference| <= 1e-12 * scale, separated and overlapping (penetration);
//   the witness points lie within 1e-12 * scale of their boundaries and are the support
//   points of the normal (optimality: the normal is parallel to both surface gradients,
//   to the angle a 1e-12 * scale move of the point can turn it), point_b - point_a =
//   distance * normal, and where the optimum is unique they are within 1e-10 * scale of
//   the reference's;
//   swapping the arguments swaps the points and negates the normal bit for bit.
#include <ellipsect/distance.hpp>

#include "common.hpp"
#include "detail/depth_bound.hpp"
#include "tests/reference/distance_reference.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using Real = ref::Real;
template <int N> using RVec = Eigen::Matrix<Real, N, 1>;

// Distance of p from the boundary of e (to first order, |sqrt(q) - 1| / |grad sqrt(q)|) in
// 50 digits and in e's frame, and the outward unit normal of the level set through p.
template <int N>
double off_boundary(const Ellipsoid<double, N>& e, const Vec<double, N>& p, RVec<N>& normal) {
  const Eigen::Matrix<Real, N, N> axes = e.axes().template cast<Real>();
  const RVec<N> d = axes.transpose() * (p.template cast<Real>() - e.center().template cast<Real>());
  const RVec<N> r = e.radii().template cast<Real>();
  const Real q = sqrt(d.cwiseQuotient(r).squaredNorm());
  const RVec<N> grad = axes * (d.cwiseQuotient(r.cwiseAbs2()) / q);
  normal = grad / grad.norm();
  return ref::to_double(abs(q - 1) / grad.norm());
}

DistanceStatus status_of(Relation r) {
  return r == Relation::separated  ? DistanceStatus::separated
         : r == Relation::touching ? DistanceStatus::touching
                                   : DistanceStatus::overlapping;
}

// `hint`: the queries started from it (distance.hpp's overloads), null for none; `known`: the
// reference when computed already.
template <int N>
void check_case(const scenarios::Case<N>& c, Tally& tally, const Vec<double, N>* hint = nullptr,
                const ref::SignedDistance<N>* known = nullptr) {
  const Options cold;
  const auto got = hint ? signed_distance(c.a, c.b, cold, *hint) : signed_distance(c.a, c.b);
  const auto r = known ? *known : ref::signed_distance<N>(to_ref(c.a), to_ref(c.b));
  const double want = ref::to_double(r.distance);
  const double scale = c.a.radii().maxCoeff() + c.b.radii().maxCoeff() + std::abs(want);
  const double tol = 1e-12 * scale;
  ASSERT_EQ(got.status, status_of(classify(c.a, c.b))) << describe(c);
  tally.add(scenarios::name(c.category), to_string(got.status));
  ASSERT_NEAR(got.distance, want, tol) << describe(c);

  // Witness points: on the boundaries, and the support points of the normal.
  RVec<N> na, nb;
  ASSERT_LE(off_boundary(c.a, got.point_a, na), tol) << describe(c);
  ASSERT_LE(off_boundary(c.b, got.point_b, nb), tol) << describe(c);
  ASSERT_NEAR(got.normal.norm(), 1.0, 1e-15) << describe(c);
  ASSERT_LE((got.point_b - got.point_a - got.distance * got.normal).norm(), tol) << describe(c);
  const RVec<N> n = got.normal.template cast<Real>();
  auto support = [&](const Ellipsoid<double, N>& e, const RVec<N>& dir) {
    const Eigen::Matrix<Real, N, N> axes = e.axes().template cast<Real>();
    const RVec<N> w = e.radii().template cast<Real>().cwiseProduct(axes.transpose() * dir);
    return RVec<N>(e.center().template cast<Real>() + axes * (e.radii().template cast<Real>().cwiseProduct(w) / w.norm()));
  };
  ASSERT_LE(ref::to_double((support(c.a, n) - got.point_a.template cast<Real>()).norm()), tol) << describe(c);
  ASSERT_LE(ref::to_double((support(c.b, RVec<N>(-n)) - got.point_b.template cast<Real>()).norm()), tol) << describe(c);
  // The normal is parallel to the surface gradients, to the angle by which a move of the
  // point by tol turns the normal (tol over the smallest radius of curvature).
  auto turn = [&](const Ellipsoid<double, N>& e) {
    return tol * e.radii().maxCoeff() / (e.radii().minCoeff() * e.radii().minCoeff()) + 1e-14;
  };
  ASSERT_LE(ref::to_double((na - n).norm()), turn(c.a)) << describe(c);
  ASSERT_LE(ref::to_double((nb + n).norm()), turn(c.b)) << describe(c);
  if (r.runner_up < r.distance - 1e-9 * scale) {
    ASSERT_LE((got.point_a - ref::to_double<N>(r.point_a)).norm(), 1e-10 * scale) << describe(c);
    ASSERT_LE((got.point_b - ref::to_double<N>(r.point_b)).norm(), 1e-10 * scale) << describe(c);
  }

  // Swap symmetry (identical bodies are the same call), and distance() on the same pair.
  // (With a hint, the swapped call takes it reversed: for identical bodies, the same call.)
  const bool identical = c.a.center() == c.b.center() && c.a.axes() == c.b.axes() && c.a.radii() == c.b.radii();
  const auto sw = hint ? signed_distance(c.b, c.a, cold, Vec<double, N>(identical ? *hint : -*hint))
                       : signed_distance(c.b, c.a);
  ASSERT_EQ(sw.distance, got.distance) << describe(c);
  ASSERT_EQ(sw.point_a, identical ? got.point_a : got.point_b) << describe(c);
  ASSERT_EQ(sw.point_b, identical ? got.point_b : got.point_a) << describe(c);
  ASSERT_EQ(sw.normal, (identical ? got.normal : Vec<double, N>(-got.normal))) << describe(c);
  const auto d = hint ? distance(c.a, c.b, cold, *hint) : distance(c.a, c.b);
  ASSERT_EQ(d.status, got.status) << describe(c);
  if (got.status == DistanceStatus::overlapping) {
    ASSERT_EQ(d.distance, 0.0) << describe(c);
  } else {
    ASSERT_EQ(d.distance, got.distance) << describe(c);
    ASSERT_EQ(d.point_a, got.point_a) << describe(c);
  }
}

template <int N>
void check_against_reference(int per_category) {
  Tally tally;
  for (const auto category : scenarios::all_categories)
    for (int i = 0; i < per_category; ++i) {
      check_case<N>(scenarios::make_case<N>(category, static_cast<std::uint64_t>(i)), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  tally.print("signed_distance vs reference, N=" + std::to_string(N));
  // The mix covers separation and penetration in every family of cases.
  for (const char* cat : {"random", "high_aspect", "near_tangent", "spheres", "scaled_small", "scaled_large"}) {
    EXPECT_GT(tally.count(cat, "separated"), per_category / 10) << cat;
    EXPECT_GT(tally.count(cat, "overlapping"), per_category / 10) << cat;
  }
  EXPECT_EQ(tally.count("containment", "overlapping"), per_category);
  EXPECT_EQ(tally.count("far_apart", "separated"), per_category);
}

TEST(DistanceProperty, MatchesReference2D) { check_against_reference<2>(cases(300)); }
TEST(DistanceProperty, MatchesReference3D) { check_against_reference<3>(cases(300)); }

// Started from a hint, every claim holds as without it, whatever the hint: the answer's own
// normal, that normal turned by 0.05 rad (a simulation's last step), its opposite, a random
// direction, zero and NaN. From the answer's own normal a separated pair converges at its
// start (no step: `iterations` counts the steps' evaluations); from 0.05 rad off it takes no
// more steps than the cold start's descent (Newton's quadratic phase: about three and a half
// either way), without the cold start.
template <int N>
void check_hints(int per_category) {
  Tally tally;
  std::mt19937_64 rng(11);
  int separated = 0, evaluations = 0, turned_evaluations = 0, cold_evaluations = 0;
  for (const auto category : scenarios::all_categories)
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_case<N>(category, static_cast<std::uint64_t>(i));
      const auto r = ref::signed_distance<N>(to_ref(c.a), to_ref(c.b));
      const auto answer = signed_distance(c.a, c.b);
      if (!answer.normal.allFinite()) continue;
      const Vec<double, N> turned = (answer.normal + 0.05 * scenarios::detail::unit_vector<N>(rng)).normalized();
      const std::vector<Vec<double, N>> hints{answer.normal, turned, -answer.normal, scenarios::detail::unit_vector<N>(rng),
                                              Vec<double, N>::Zero(), Vec<double, N>::Constant(std::nan(""))};
      for (const auto& h : hints) {
        check_case<N>(c, tally, &h, &r);
        if (::testing::Test::HasFatalFailure()) return;
      }
      if (answer.status == DistanceStatus::separated) {
        ++separated;
        evaluations += distance(c.a, c.b, Options{}, answer.normal).iterations;
        turned_evaluations += distance(c.a, c.b, Options{}, turned).iterations;
        cold_evaluations += distance(c.a, c.b).iterations;
      }
    }
  tally.print("signed_distance from hints vs reference, N=" + std::to_string(N));
  std::printf("  steps per separated pair (%d pairs): %.2f from the answer's normal, %.2f from 0.05 rad off, %.2f cold\n",
              separated, double(evaluations) / separated, double(turned_evaluations) / separated,
              double(cold_evaluations) / separated);
  EXPECT_LE(evaluations, separated / 20);
  EXPECT_LE(turned_evaluations, cold_evaluations + separated / 20);
}

TEST(DistanceProperty, HintsKeepEveryClaim2D) { check_hints<2>(cases(40)); }
TEST(DistanceProperty, HintsKeepEveryClaim3D) { check_hints<3>(cases(40)); }

// The certificate that lets penetration stop after one descent (src/detail/depth_bound.hpp)
// is a lower bound: at the optimum and at sampled directions, the depth of r in the inner
// ellipsoid fitted there is never above the reference depth (beyond its own rounding, a few
// dozen ulps of the size); at the reference optimum it reaches the depth for most pairs of
// every category; for two balls it is the depth.
template <int N>
void check_depth_bound(int per_category) {
  std::mt19937_64 rng(5);
  for (const auto category : scenarios::all_categories) {
    int overlapping = 0, certified = 0;
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_case<N>(category, static_cast<std::uint64_t>(i));
      const Relation rel = classify(c.a, c.b);
      if (rel == Relation::separated || rel == Relation::touching) continue;
      const auto r = ref::signed_distance<N>(to_ref(c.a), to_ref(c.b));
      const double depth = -ref::to_double(r.distance);
      const double scale = c.a.radii().maxCoeff() + c.b.radii().maxCoeff() + depth;
      const auto g = ellipsect::detail::gap_bodies<double>(c.a, c.b);
      std::vector<Vec<double, N>> directions{Vec<double, N>(ref::to_double(r.normal).normalized())};
      for (int k = 0; k < 8; ++k) directions.push_back(scenarios::detail::unit_vector<N>(rng));
      for (std::size_t k = 0; k < directions.size(); ++k) {
        const auto at = ellipsect::detail::gap_at<double, N>(g, directions[k]);
        const double bound = ellipsect::detail::depth_lower_bound<double, N>(g, at);
        ASSERT_LE(bound, depth + 1e-13 * scale) << describe(c) << " direction " << k;
        if (k == 0) certified += bound >= depth - 1e-13 * scale;
      }
      ++overlapping;
    }
    std::printf("  %s: the bound reaches the depth at the optimum for %d of %d overlapping pairs\n",
                std::string(scenarios::name(category)).c_str(), certified, overlapping);
    if (overlapping >= 20) {
      EXPECT_GE(certified, overlapping / 2) << scenarios::name(category);
    }
  }
  // Two balls, any frames: the inner ellipsoid is their Minkowski sum itself.
  for (int i = 0; i < 20; ++i) {
    const auto a = Ellipsoid<double, N>::from_axes(Vec<double, N>::Zero(), scenarios::detail::rotation<N>(rng),
                                                    Vec<double, N>::Constant(1.0 + i));
    const auto b = Ellipsoid<double, N>::from_axes(scenarios::detail::unit_vector<N>(rng),
                                                    scenarios::detail::rotation<N>(rng), Vec<double, N>::Constant(0.5));
    const auto g = ellipsect::detail::gap_bodies<double>(a, b);
    const Vec<double, N> u = b.center().normalized();
    const double depth = (1.0 + i) + 0.5 - 1.0;  // radii less the centers' distance
    const auto deepest = ellipsect::detail::gap_at<double, N>(g, u), opposite = ellipsect::detail::gap_at<double, N>(g, Vec<double, N>(-u));
    EXPECT_NEAR(deepest.phi, depth, 1e-14 * depth);
    // The fitted turn takes one ball's frame to the other's from any direction: E is M.
    EXPECT_NEAR((ellipsect::detail::depth_lower_bound<double, N>(g, deepest)), depth, 1e-14 * depth) << i;
    EXPECT_NEAR((ellipsect::detail::depth_lower_bound<double, N>(g, opposite)), depth, 1e-14 * depth) << i;
  }
}

TEST(DistanceProperty, DepthBoundIsALowerBound2D) { check_depth_bound<2>(cases(100)); }
TEST(DistanceProperty, DepthBoundIsALowerBound3D) { check_depth_bound<3>(cases(100)); }

// Thin bodies beyond the scenarios' 1e4: aspect ratios 1e6 to 1e8, random orientations and
// sizes, both bodies needles or discs (radii r, r / aspect, ...) or with log-uniform radii
// across the ratio, centers up to the sum of the largest radii apart. Claims: every query
// converges, the status is classify's and the signed distance is the reference's to
// 1e-12 * scale (the witness-point claims are made to aspect ratio 1e4 only).
template <int N>
scenarios::Case<N> thin_case(std::uint64_t seed) {
  using namespace scenarios::detail;
  Rng rng(seed * 0x9E3779B97F4A7C15ull + 7001);
  const double aspect = log_uniform(rng, 1e6, 1e8);
  auto shape = [&] {
    const double size = log_uniform(rng, 0.3, 3.0);
    const double kind = uniform(rng, 0, 1);
    if (kind < 1.0 / 3) return radii<N>(rng, size, aspect);
    Vec<double, N> r = Vec<double, N>::Constant(kind < 2.0 / 3 ? size / aspect : size);  // needle, disc
    r[kind < 2.0 / 3 ? 0 : N - 1] = kind < 2.0 / 3 ? size : size / aspect;
    return r;
  };
  const Vec<double, N> ra = shape(), rb = shape();
  const Vec<double, N> ca = unit_vector<N>(rng) * uniform(rng, 0, 5);
  const auto a = body<N>(ca, rotation<N>(rng), ra);
  const auto b = body<N>(Vec<double, N>(ca + unit_vector<N>(rng) * (ra.maxCoeff() + rb.maxCoeff()) * uniform(rng, 0, 1)),
                         rotation<N>(rng), rb);
  return {scenarios::Category::high_aspect, seed, a, b, Vec<double, N>::Zero(), Vec<double, N>::Zero(), 0.0};
}

// One body inside the other, touching it from inside at a random boundary point and then
// moved inwards by 0 (internal tangency), or by 1e-12 to 0.3 of its size; aspect ratios to
// 100 and 10. The penetration depth here is the non-convex case (several local minima on
// the inner body's far side). All claims of check_case apply.
template <int N>
scenarios::Case<N> inner_tangent_case(std::uint64_t seed) {
  using namespace scenarios::detail;
  Rng rng(seed * 0x9E3779B97F4A7C15ull + 7002);
  const Vec<double, N> ra = radii<N>(rng, log_uniform(rng, 0.3, 3.0), 100.0);
  const Vec<double, N> rb = radii<N>(rng, ra.minCoeff() * uniform(rng, 0.05, 0.95), 10.0);
  auto a = body<N>(unit_vector<N>(rng), rotation<N>(rng), ra);
  const Mat<double, N> axes_b = rotation<N>(rng);
  const double inward = uniform(rng, 0, 1) < 0.3 ? 0.0 : log_uniform(rng, 1e-12, 0.3);
  const Vec<double, N> p = a.center() + a.axes() * ra.asDiagonal() * unit_vector<N>(rng);
  const Vec<double, N> n = (a.quadric() * (p - a.center())).normalized();
  const Mat<double, N> minv = axes_b * rb.cwiseAbs2().asDiagonal() * axes_b.transpose();
  const Vec<double, N> support = minv * n / std::sqrt(n.dot(minv * n));  // b's point with normal n
  auto b = body<N>(Vec<double, N>(p - support - inward * rb.maxCoeff() * n), axes_b, rb);
  if (uniform(rng, 0, 1) < 0.5) std::swap(a, b);
  return {scenarios::Category::containment, seed, a, b, Vec<double, N>::Zero(), Vec<double, N>::Zero(), 0.0};
}

template <int N>
void check_thin(int n) {
  Tally tally;
  for (int i = 0; i < n; ++i) {
    SCOPED_TRACE("thin_case seed " + std::to_string(i));
    const auto c = thin_case<N>(static_cast<std::uint64_t>(i));
    const auto got = signed_distance(c.a, c.b);
    tally.add("aspect 1e6..1e8", to_string(got.status));
    const auto r = ref::signed_distance<N>(to_ref(c.a), to_ref(c.b));
    const double want = ref::to_double(r.distance);
    ASSERT_EQ(got.status, status_of(classify(c.a, c.b))) << describe(c);
    ASSERT_NEAR(got.distance, want, 1e-12 * (c.a.radii().maxCoeff() + c.b.radii().maxCoeff() + std::abs(want)))
        << describe(c);
  }
  tally.print("signed_distance at aspect 1e6..1e8, N=" + std::to_string(N));
  EXPECT_GT(tally.count("aspect 1e6..1e8", "separated"), n / 10);
  EXPECT_GT(tally.count("aspect 1e6..1e8", "overlapping"), n / 10);
}

template <int N>
void check_inner_tangent(int n) {
  Tally tally;
  for (int i = 0; i < n; ++i) {
    SCOPED_TRACE("inner_tangent_case seed " + std::to_string(i));
    check_case<N>(inner_tangent_case<N>(static_cast<std::uint64_t>(i)), tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
  tally.print("signed_distance under containment and internal tangency, N=" + std::to_string(N));
  EXPECT_EQ(tally.count("containment", "overlapping"), n);
}

TEST(DistanceProperty, Aspect1e6To1e8_2D) { check_thin<2>(cases(300)); }
TEST(DistanceProperty, Aspect1e6To1e8_3D) { check_thin<3>(cases(300)); }
TEST(DistanceProperty, InternalTangency2D) { check_inner_tangent<2>(cases(300)); }
TEST(DistanceProperty, InternalTangency3D) { check_inner_tangent<3>(cases(300)); }

// Pairs placed within the tangency band of touching (gap 0 or +-1e-14 of the size, any
// orientation, aspect ratios to 1e3): the status is classify's and the signed distance is
// the reference's, with no jump between touching and either side.
template <int N>
void check_touching(int n) {
  Tally tally;
  for (int i = 0; i < n; ++i) {
    scenarios::detail::Rng rng(5000 + i);
    using namespace scenarios::detail;
    const auto a = Ellipsoid<double, N>::from_axes(unit_vector<N>(rng), rotation<N>(rng), radii<N>(rng, 1.0, 1e3));
    const Mat<double, N> axes_b = rotation<N>(rng);
    const Vec<double, N> radii_b = radii<N>(rng, log_uniform(rng, 0.1, 10), 1e3);
    const double gap = std::array<double, 3>{0.0, 1e-14, -1e-14}[i % 3];
    const auto b = Ellipsoid<double, N>::from_axes(tangent_center<N>(a, unit_vector<N>(rng), axes_b, radii_b, gap), axes_b, radii_b);
    scenarios::Case<N> c{scenarios::Category::near_tangent, static_cast<std::uint64_t>(i), a, b,
                         Vec<double, N>::Zero(), Vec<double, N>::Zero(), 0.0};
    check_case<N>(c, tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
  tally.print("signed_distance at touching, N=" + std::to_string(N));
  EXPECT_GT(tally.count("near_tangent", "touching"), n / 2);
}

TEST(DistanceProperty, Touching2D) { check_touching<2>(cases(300)); }
TEST(DistanceProperty, Touching3D) { check_touching<3>(cases(300)); }

// Scaling a scene by a power of two scales the answer exactly (the tolerances are
// relative); a rigid motion changes it by rounding only.
template <int N>
void check_invariance(int n) {
  for (int i = 0; i < n; ++i) {
    for (const auto category : {scenarios::Category::random, scenarios::Category::high_aspect, scenarios::Category::containment}) {
      const auto c = scenarios::make_case<N>(category, 100000 + i);
      const auto got = signed_distance(c.a, c.b);
      for (double s : {0x1p-40, 0x1p40}) {
        const auto as = Ellipsoid<double, N>::from_axes(c.a.center() * s, c.a.axes(), c.a.radii() * s);
        const auto bs = Ellipsoid<double, N>::from_axes(c.b.center() * s, c.b.axes(), c.b.radii() * s);
        const auto scaled = signed_distance(as, bs);
        ASSERT_EQ(scaled.distance, got.distance * s) << describe(c);
        ASSERT_EQ(scaled.normal, got.normal) << describe(c);
      }
      scenarios::detail::Rng rng(i);
      const Mat<double, N> q = scenarios::detail::rotation<N>(rng);
      const Vec<double, N> t = scenarios::detail::unit_vector<N>(rng) * 7.0;
      const auto am = Ellipsoid<double, N>::from_axes(q * c.a.center() + t, q * c.a.axes(), c.a.radii());
      const auto bm = Ellipsoid<double, N>::from_axes(q * c.b.center() + t, q * c.b.axes(), c.b.radii());
      const double scale = c.a.radii().maxCoeff() + c.b.radii().maxCoeff() + std::abs(got.distance);
      ASSERT_NEAR(signed_distance(am, bm).distance, got.distance, 1e-12 * scale) << describe(c);
    }
  }
}

TEST(DistanceProperty, ScaleAndRigidMotionInvariance2D) { check_invariance<2>(cases(200)); }
TEST(DistanceProperty, ScaleAndRigidMotionInvariance3D) { check_invariance<3>(cases(200)); }

// float bodies are computed in double: the answer is the reference's on the float bodies
// to a few float roundings of the scale.
TEST(DistanceProperty, FloatMatchesReference) {
  for (int i = 0; i < cases(300); ++i) {
    const auto category = scenarios::all_categories[i % scenarios::all_categories.size()];
    const auto c = scenarios::make_case<3>(category, 300000 + i);
    const auto af = Ellipsoid3<float>::from_axes(c.a.center().cast<float>(), c.a.axes().cast<float>(), c.a.radii().cast<float>());
    const auto bf = Ellipsoid3<float>::from_axes(c.b.center().cast<float>(), c.b.axes().cast<float>(), c.b.radii().cast<float>());
    auto as_ref = [](const Ellipsoid3<float>& e) {
      return ref::Body<3>{e.center().cast<double>(), e.axes().cast<double>(), e.radii().cast<double>()};
    };
    const auto r = ref::signed_distance<3>(as_ref(af), as_ref(bf));
    const auto got = signed_distance(af, bf);
    const double want = ref::to_double(r.distance);
    const double scale = c.a.radii().maxCoeff() + c.b.radii().maxCoeff() + std::abs(want);
    ASSERT_NE(got.status, DistanceStatus::did_not_converge) << describe(c);
    ASSERT_NEAR(got.distance, want, 1e-6 * scale) << describe(c);
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
