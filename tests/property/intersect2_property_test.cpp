// intersect_boundaries and overlap_area against the 50-digit reference (tests/reference/
// distance_reference.hpp: real roots of the tan-half-angle quartic for the points,
// adaptive Gauss-Kronrod quadrature of the common vertical chord for the area; independent
// of the library's secular critical points, bracketed roots and arc segments).
//
// Claims under test (intersect2.hpp), with scale = largest radius of a + of b:
//   every reported point lies within 1e-12 * scale of both boundaries; a transverse one
//   within 1e-12 * scale / sin(crossing angle) of a reference crossing;
//   the number of transverse crossings is the reference's whenever the pair is farther
//   than the tangency band from every tangency (classify's margin and no two reference
//   roots closer than 1e-6 * scale), and tangent points only occur inside that band;
//   status equal exactly when classify says equal;
//   |area - reference| <= 1e-12 * the smaller ellipse's area;
//   swapping the arguments gives the same points and the same area, bit for bit.
#include <ellipsect/intersect2.hpp>

#include "common.hpp"
#include "tests/reference/distance_reference.hpp"

#include <cmath>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using Real = ref::Real;
using RVec2 = Eigen::Matrix<Real, 2, 1>;

constexpr double band = 2 * Options{}.tolerance;

// Distance of p from the boundary of e to first order, in 50 digits in e's frame, and
// the boundary's unit normal there.
double off_boundary(const Ellipse2<double>& e, const RVec2& p, RVec2& normal) {
  const Eigen::Matrix<Real, 2, 2> axes = e.axes().cast<Real>();
  const RVec2 d = axes.transpose() * (p - e.center().cast<Real>());
  const RVec2 r = e.radii().cast<Real>();
  const Real q = sqrt(d.cwiseQuotient(r).squaredNorm());
  const RVec2 grad = axes * (d.cwiseQuotient(r.cwiseAbs2()) / q);
  normal = grad / grad.norm();
  return ref::to_double(abs(q - 1) / grad.norm());
}

void check_pair(const Ellipse2<double>& a, const Ellipse2<double>& b, const std::string& what, const std::string& category,
                Tally& tally) {
  const auto got = intersect_boundaries(a, b);
  const auto area = overlap_area(a, b);
  const auto points = ref::boundary_intersection(to_ref(a), to_ref(b));
  const double want_area = ref::to_double(ref::overlap_area(to_ref(a), to_ref(b)));
  const auto rc = ref::classify<2>(to_ref(a), to_ref(b), band);
  const Relation relation = classify(a, b);
  const double scale = a.radii().maxCoeff() + b.radii().maxCoeff();
  const double tol = 1e-12 * scale;

  ASSERT_EQ(got.status == BoundaryStatus::equal, relation == Relation::equal) << what;
  ASSERT_EQ(area.relation, relation) << what;
  int transverse = 0;
  for (int i = 0; i < got.count; ++i) {
    const RVec2 p = got.points[i].cast<Real>();
    RVec2 na, nb;
    ASSERT_LE(off_boundary(a, p, na), tol) << what << "\n  point " << i;
    ASSERT_LE(off_boundary(b, p, nb), tol) << what << "\n  point " << i;
    if (got.kinds[i] != CrossingKind::transverse) continue;
    ++transverse;
    double best = std::numeric_limits<double>::infinity();
    double sine = 1;
    for (const RVec2& x : points) {
      const double dist = ref::to_double((x - p).norm());
      if (dist < best) {
        best = dist;
        off_boundary(a, x, na);
        off_boundary(b, x, nb);
        sine = std::abs(ref::to_double(na[0] * nb[1] - na[1] * nb[0]));
      }
    }
    ASSERT_LE(best, tol / std::max(sine, 1e-6)) << what << "\n  point " << i << " sin " << sine;
  }
  double closest_roots = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j)
      closest_roots = std::min(closest_roots, ref::to_double((points[i] - points[j]).norm()));
  const bool decidable = rc.margin > band && closest_roots > 1e-6 * scale;
  if (decidable && got.status == BoundaryStatus::points) {
    ASSERT_EQ(transverse, static_cast<int>(points.size())) << what;
    ASSERT_EQ(got.count, transverse) << what;  // no tangent point away from the band
  }
  tally.add(category, got.status == BoundaryStatus::equal ? "equal"
                      : !decidable                         ? "in_band"
                                                           : std::to_string(transverse) + "_crossings");

  const double smaller = M_PI * std::min(a.radii().prod(), b.radii().prod());
  ASSERT_NEAR(area.area, want_area, 1e-12 * smaller) << what;

  const auto sw = intersect_boundaries(b, a);
  ASSERT_EQ(sw.count, got.count) << what;
  for (int i = 0; i < got.count; ++i) {
    bool found = false;
    for (int j = 0; j < sw.count; ++j) found = found || (sw.points[j] == got.points[i] && sw.kinds[j] == got.kinds[i]);
    ASSERT_TRUE(found) << what << "\n  point " << i;
  }
  ASSERT_EQ(overlap_area(b, a).area, area.area) << what;
}

TEST(Intersect2Property, MatchesReference) {
  Tally tally;
  const int n = cases(150);
  for (const auto category : scenarios::all_categories)
    for (int i = 0; i < n; ++i) {
      const auto c = scenarios::make_case<2>(category, static_cast<std::uint64_t>(i));
      check_pair(c.a, c.b, describe(c), std::string(scenarios::name(category)), tally);
      if (HasFatalFailure()) return;
    }
  tally.print("intersect_boundaries vs reference");
  if (!full_case_counts()) return;
  EXPECT_GT(tally.count("random", "2_crossings"), n / 5);
  int four = 0;
  for (const auto category : scenarios::all_categories) four += tally.count(std::string(scenarios::name(category)), "4_crossings");
  EXPECT_GT(four, 0);
  EXPECT_GT(tally.count("spheres", "equal"), 0);
  EXPECT_GT(tally.count("near_tangent", "2_crossings"), n / 5);
  EXPECT_GT(tally.count("containment", "0_crossings"), n / 2);
}

// Configurations that exercise every branch of the critical points: nearly concentric
// pairs (four crossings: the middle branch of the secular equation), a center on an axis
// of the other ellipse (the mirrored hard-case points), concentric pairs (the four
// vertices) and needles crossing discs (aspect ratios to 1e4).
TEST(Intersect2Property, CriticalPointBranches) {
  Tally tally;
  scenarios::detail::Rng rng(42);
  using namespace scenarios::detail;
  const char* modes[] = {"near_concentric", "on_axis", "concentric", "needle"};
  for (int i = 0; i < cases(400); ++i) {
    const int mode = i % 4;
    const Vec2<double> ra = radii<2>(rng, 1.0, mode == 3 ? 1e4 : 10), rb = radii<2>(rng, 1.0, 10);
    Vec2<double> cb = unit_vector<2>(rng) * uniform(rng, 0, mode == 0 ? 0.05 : 0.8);
    if (mode == 1) cb[0] = 0;
    if (mode == 2) cb.setZero();
    const bool aligned = mode == 1 || mode == 2;
    const auto a = Ellipse2<double>::from_axes(Vec2<double>::Zero(), aligned ? Mat2<double>::Identity() : rotation<2>(rng), ra);
    const auto b = Ellipse2<double>::from_axes(cb, aligned ? Mat2<double>::Identity() : rotation<2>(rng), rb);
    std::ostringstream what;
    what.precision(17);
    what << modes[mode] << " i=" << i << "\n  a: r=" << ra.transpose() << " axes=" << a.axes().col(0).transpose()
         << "\n  b: c=" << cb.transpose() << " r=" << rb.transpose() << " axes=" << b.axes().col(0).transpose();
    check_pair(a, b, what.str(), modes[mode], tally);
    if (HasFatalFailure()) return;
  }
  tally.print("intersect_boundaries, critical point branches");
  if (!full_case_counts()) return;
  EXPECT_GT(tally.count("near_concentric", "4_crossings"), cases(400) / 20);
  EXPECT_GT(tally.count("concentric", "4_crossings"), cases(400) / 20);
  EXPECT_GT(tally.count("on_axis", "4_crossings") + tally.count("on_axis", "2_crossings"), cases(400) / 20);
}

// float ellipses: the points lie on the float ellipses' boundaries to float rounding and
// the area matches the reference on the float ellipses.
TEST(Intersect2Property, FloatMatchesReference) {
  for (int i = 0; i < cases(200); ++i) {
    const auto c = scenarios::make_case<2>(scenarios::Category::random, 400000 + i);
    auto to_float = [](const Ellipse2<double>& e) {
      return Ellipse2<float>::from_axes(e.center().cast<float>(), e.axes().cast<float>(), e.radii().cast<float>());
    };
    auto as_ref = [](const Ellipse2<float>& e) {
      return ref::Body<2>{e.center().cast<double>(), e.axes().cast<double>(), e.radii().cast<double>()};
    };
    const auto af = to_float(c.a), bf = to_float(c.b);
    const double smaller = M_PI * std::min(c.a.radii().prod(), c.b.radii().prod());
    ASSERT_NEAR(overlap_area(af, bf).area, ref::to_double(ref::overlap_area(as_ref(af), as_ref(bf))), 1e-6 * smaller)
        << describe(c);
    const auto x = intersect_boundaries(af, bf);
    for (int k = 0; k < x.count; ++k) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& p : ref::boundary_intersection(as_ref(af), as_ref(bf)))
        best = std::min(best, (ref::to_double<2>(p) - x.points[k].cast<double>()).norm());
      ASSERT_LE(best, 1e-5 * (c.a.radii().maxCoeff() + c.b.radii().maxCoeff())) << describe(c);
    }
  }
}

// Nearly concentric pairs: b's center is d * (random direction) off a's, for d = 0,
// subnormals, 1e-300 .. 1e-8 (relative to the bodies' size 1), random shapes (aspect ratios
// to 1e3, sizes within 5x: crossings, containment, four-crossing lenses). The relation, the
// points, the kinds and the area must match the reference at every offset: O's reduced center
// is then far below e's rounding, or subnormal, and the middle critical points of h sit next
// to a pole of the secular equation.
TEST(Intersect2Property, NearlyConcentricOffsets) {
  Tally tally;
  scenarios::detail::Rng rng(2718);
  using namespace scenarios::detail;
  const double offsets[] = {0,     4.9406564584124654e-324, 2.4031353013718232e-320, 1e-310, 1e-300, 1e-200, 1e-100,
                            1e-50, 1e-30,  1e-20,  1e-17,  1e-16,   4e-16,  1e-15,   1e-14,  1e-12,  1e-10, 1e-8};
  for (int i = 0; i < cases(60); ++i) {
    const Vec2<double> ra = radii<2>(rng, 1.0, 1e3), rb = radii<2>(rng, log_uniform(rng, 0.2, 5), 1e3);
    const Mat2<double> qa = rotation<2>(rng), qb = rotation<2>(rng);
    const Vec2<double> dir = unit_vector<2>(rng);
    for (const double d : offsets) {
      const auto a = Ellipse2<double>::from_axes(Vec2<double>::Zero(), qa, ra);
      const auto b = Ellipse2<double>::from_axes(dir * d, qb, rb);
      std::ostringstream what;
      what.precision(17);
      what << "i=" << i << " offset=" << d << "\n  a: r=" << ra.transpose() << " axes=" << qa.col(0).transpose()
           << "\n  b: c=" << b.center().transpose() << " r=" << rb.transpose() << " axes=" << qb.col(0).transpose();
      const auto rc = ref::classify<2>(to_ref(a), to_ref(b), band);
      if (rc.margin > band) {
        ASSERT_EQ(classify(a, b), from_ref(rc.relation)) << what.str();
      }
      check_pair(a, b, what.str(), "offset", tally);
      if (HasFatalFailure()) return;
    }
  }
  tally.print("intersect_boundaries, nearly concentric offsets");
  EXPECT_GT(tally.count("offset", "4_crossings"), cases(60));
  EXPECT_GT(tally.count("offset", "0_crossings"), cases(60));
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
