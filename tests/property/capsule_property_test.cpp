// Bodies against capsules (capsule.hpp) against the 50-digit reference: the signed distance
// is the segment's less the radius (the capsule's support function is the segment's plus
// R |n|), the segment's from tests/reference/support_gap_reference.hpp (the support gap
// maximized over the sphere by search); the signed distance of an end point to the body's
// boundary from the same search with that point alone.
//
// Claims under test, with scale = largest radius + R + largest |p_k - c|:
//   signed_distance within 1e-12 scale of the reference; the reference's gap at the returned
//   normal within 1e-12 scale of its maximum; point_a on the body;
//   classify: separated / touching / overlapping as the reference's relative gap L / rho
//   outside the band widened by 1e-12 scale / rho; a_contains_b exactly when the reference's
//   end points lie R inside the boundary (outside that margin); b_contains_a exactly when the
//   body's farthest point from the segment lies within R (outside that margin);
//   first_contact: a hit where the reference's gap at the returned time is within 1e-12 scale
//   of 0 and positive at 0.999 of it (the first root); no contact only where the reference's
//   gap stays positive at 8 times across the window.
// Cases: random; aspect ratios to 1e4; near tangency (relative gaps 1e-10 to 1e-4, either
// side, by moving the capsule along the reference's normal); balls (p0 = p1) and segments
// 1e-15 to 1e-9 long; long capsules
// (1e3); the capsule inside the body; the body inside the capsule; needles (aspect 100 to
// 1000) with their center inside the capsule, inside it or through its surface (b_contains_a
// against the body's farthest point from the segment, searched on the body's boundary);
// scale 1e-6 and 1e6.
#include <ellipsect/capsule.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/support_gap_reference.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
namespace ref = ellipsect::reference;
using Real = ref::Real;

enum class Kind { random, aspect, near, ball, long_capsule, capsule_inside, body_inside, small, huge, needle, speck };
constexpr Kind kinds[] = {Kind::random,      Kind::aspect, Kind::near,   Kind::ball,  Kind::long_capsule, Kind::capsule_inside,
                          Kind::body_inside, Kind::small,  Kind::huge,   Kind::needle, Kind::speck};

template <int N>
struct Case {
  Ellipsoid<double, N> a;
  Capsule<double, N> b;
  Vec<double, N> va, vb;
  double t_max;
};

// The reference's signed distance of the body and the capsule shifted by `shift`.
template <int N>
ref::SupportGapMaximum<N> reference_gap(const Case<N>& c, const Vec<double, N>& shift) {
  const auto body = ref::to_ref(c.a);
  ref::SupportGapMaximum<N> m = ref::max_support_gap<N>(body, {c.b.point(0) + shift, c.b.point(1) + shift});
  m.gap -= Real(c.b.radius());
  return m;
}

// The body's greatest distance from the capsule's segment less R (the body lies in the
// capsule exactly when it is <= 0), by another route than the library's support functions:
// the distance from the segment, a convex function of the point, is greatest on the body's
// boundary c + A diag(r) u, |u| = 1, searched over u as support_gap_reference.hpp searches
// directions (the local maxima among evenly spread directions, refined by golden sections).
template <class S, int N>
struct FromSegment {
  Eigen::Matrix<S, N, 1> c, p0, e;
  Eigen::Matrix<S, N, N> shape;  // A diag(r)

  S operator()(Eigen::Matrix<S, N, 1> u) const {
    using std::sqrt;
    u /= S(sqrt(u.dot(u)));
    const Eigen::Matrix<S, N, 1> w = c + shape * u - p0;
    const S ee = e.dot(e);
    S t = ee > S(0) ? w.dot(e) / ee : S(0);
    t = t < S(0) ? S(0) : t > S(1) ? S(1) : t;
    const Eigen::Matrix<S, N, 1> d = w - t * e;
    return sqrt(d.dot(d));
  }
};

template <class S, int N>
FromSegment<S, N> from_segment(const Ellipsoid<double, N>& a, const Capsule<double, N>& b) {
  FromSegment<S, N> f;
  for (int i = 0; i < N; ++i) {
    f.c[i] = S(a.center()[i]);
    f.p0[i] = S(b.point(0)[i]);
    f.e[i] = S(b.point(1)[i]) - S(b.point(0)[i]);
    for (int j = 0; j < N; ++j) f.shape(i, j) = S(a.axes()(i, j)) * S(a.radii()[j]);
  }
  return f;
}

template <int N>
Real farthest_outside(const Ellipsoid<double, N>& a, const Capsule<double, N>& b) {
  std::vector<ref::detail::Candidate<N>> found;
  const auto gl = from_segment<long double, N>(a, b);
  const auto gr = from_segment<Real, N>(a, b);
  ref::detail::sphere_maxima<N>(from_segment<double, N>(a, b), gl, gr, found);
  // Polished in Real: the maxima within 1e-9 of the lengths of the best in long double.
  long double best_l = 0;
  for (const auto& c : found) best_l = std::max(best_l, gl(c.direction));
  const long double size = a.radii().maxCoeff() + (b.point(0) - a.center()).norm() + (b.point(1) - a.center()).norm();
  Real best = -std::numeric_limits<Real>::infinity();
  for (const auto& c : found)
    if (gl(c.direction) >= best_l - 1e-9L * size) best = std::max(best, gr(c.polish()));
  return best - Real(b.radius());
}

template <int N>
Case<N> make_case(Kind kind, int seed) {
  using namespace scenarios::detail;
  using V = Vec<double, N>;
  Rng rng(static_cast<std::uint64_t>(seed) * 6361 + static_cast<std::uint64_t>(kind) * 911 + 3);
  const double size = kind == Kind::small ? 1e-6 : kind == Kind::huge ? 1e6 : 1;
  V r = radii<N>(rng, 1.0, kind == Kind::aspect ? 1e4 : 10);
  if (kind == Kind::needle) {
    // Aspect 100 to 1000, length 0.5 to 3.
    const double length = uniform(rng, 0.5, 3);
    r = V::Constant(length * log_uniform(rng, 1e-3, 1e-2));
    r[0] = length;
  }
  const V c = V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -2, 2); });
  const auto a = Ellipsoid<double, N>::from_axes(size * c, rotation<N>(rng), size * r);
  V p0 = c + unit_vector<N>(rng) * uniform(rng, 0, 4), p1 = p0 + unit_vector<N>(rng) * log_uniform(rng, 0.1, 4);
  double R = log_uniform(rng, 0.05, 2);
  if (kind == Kind::ball) p1 = p0;
  if (kind == Kind::speck) p1 = p0 + unit_vector<N>(rng) * log_uniform(rng, 1e-15, 1e-9);  // nearly a ball
  if (kind == Kind::long_capsule) p1 = p0 + unit_vector<N>(rng) * 1e3;
  if (kind == Kind::capsule_inside) {
    // A short capsule about the center, within a tenth of the smallest radius.
    p0 = c + unit_vector<N>(rng) * 0.02 * r.minCoeff();
    p1 = c + unit_vector<N>(rng) * 0.02 * r.minCoeff();
    R = 0.05 * r.minCoeff();
  }
  if (kind == Kind::body_inside) {
    // The body's center on the segment, R beyond its largest radius or short of its smallest.
    const V along = unit_vector<N>(rng);
    p0 = c - along * (2 * r.maxCoeff() + 1);
    p1 = c + along * (2 * r.maxCoeff() + 1);
    R = seed % 2 == 0 ? 1.5 * r.maxCoeff() : 0.8 * r.minCoeff();
  }
  if (kind == Kind::needle) {
    // The needle's center inside the capsule: on even seeds the needle inside it (R beyond
    // both tips' distances from the segment by its width), on odd seeds through its surface
    // (R between the center's distance and the farther tip's; classify said b_contains_a for
    // 10% of these in 2D, 45% in 3D).
    p0 = c + unit_vector<N>(rng) * uniform(rng, 0, 0.5) * r[0];
    p1 = p0 + unit_vector<N>(rng) * log_uniform(rng, 0.1, 2) * r[0];
    const V e = p1 - p0;
    const auto to_segment = [&](const V& x) {
      return (x - p0 - std::clamp((x - p0).dot(e) / e.squaredNorm(), 0.0, 1.0) * e).norm();
    };
    const V tip = a.axes().col(0) * r[0];
    const double center = to_segment(c), tips = std::max(to_segment(c + tip), to_segment(c - tip));
    R = seed % 2 == 0 ? tips + 2 * r[1] + uniform(rng, 0.01, 0.3) * r[0]
                      : center + uniform(rng, 0.1, 0.9) * (tips - center);
  }
  Case<N> out{a, make_capsule<double, N>(size * p0, size * p1, size * R), V::Zero(), V::Zero(), 0};
  if (kind == Kind::near) {
    // Moved along the reference's normal so that its gap is about g rho.
    const auto m = reference_gap<N>(out, V::Zero());
    const V n = ref::to_double<N>(m.normal);
    const double rho = std::sqrt(n.dot(a.axes() * a.radii().cwiseAbs2().asDiagonal() * a.axes().transpose() * n));
    const double g = (seed % 2 == 0 ? 1 : -1) * log_uniform(rng, 1e-10, 1e-4);
    const V shift = (g * rho - ref::to_double(m.gap)) * n;
    out.b = out.b.translated(shift);
  }
  const double speed = log_uniform(rng, 0.1, 10) * size;
  out.va = unit_vector<N>(rng) * speed * uniform(rng, 0, 0.5);
  // The capsule heads for the body's center, or passes it by.
  const V towards = (a.center() - (out.b.point(0) + out.b.point(1)) / 2).normalized();
  out.vb = out.va + speed * (towards + uniform(rng, -0.7, 0.7) * unit_vector<N>(rng)).normalized();
  out.t_max = uniform(rng, 0, 1) < 0.3 ? std::numeric_limits<double>::infinity() : log_uniform(rng, 0.5, 20);
  return out;
}

template <int N>
std::string describe(Kind kind, int seed, const Case<N>& c) {
  std::ostringstream s;
  s.precision(17);
  s << "N=" << N << " kind=" << static_cast<int>(kind) << " seed=" << seed << "\n  a: c=" << c.a.center().transpose()
    << " r=" << c.a.radii().transpose() << "\n  b: " << c.b.point(0).transpose() << " | " << c.b.point(1).transpose()
    << " R=" << c.b.radius() << "\n  va=" << c.va.transpose() << " vb=" << c.vb.transpose() << " t_max=" << c.t_max;
  return s.str();
}

template <int N>
void check(Kind kind, int seed, std::map<std::string, int>& tally) {
  const Case<N> c = make_case<N>(kind, seed);
  const std::string what = describe<N>(kind, seed, c);
  const auto body = ref::to_ref(c.a);
  double scale = c.a.radii().maxCoeff() + c.b.radius();
  for (int k = 0; k < 2; ++k) scale = std::max(scale, c.a.radii().maxCoeff() + c.b.radius() + (c.b.point(k) - c.a.center()).norm());
  const double tol = 1e-12 * scale;
  const Vec<double, N> zero = Vec<double, N>::Zero();
  const ref::SupportGapMaximum<N> want = reference_gap<N>(c, zero);

  const Distance<double, N> got = signed_distance(c.a, c.b);
  ASSERT_NEAR(got.distance, ref::to_double(want.gap), tol) << what;
  const Real at_normal =
      ref::support_gap_at<N>(body, {c.b.point(0), c.b.point(1)}, got.normal) - Real(c.b.radius());
  ASSERT_LE(ref::to_double(Real(want.gap - at_normal)), tol) << what;
  const Vec<double, N> u = c.a.axes().transpose() * (got.point_a - c.a.center());
  ASSERT_NEAR(u.cwiseQuotient(c.a.radii()).norm(), 1, 1e-12) << what;

  // The relation.
  const Relation relation = classify(c.a, c.b);
  ASSERT_EQ(overlap(c.a, c.b), relation != Relation::separated) << what;
  const Vec<double, N> n = ref::to_double<N>(want.normal);
  const double rho = std::sqrt(n.dot(c.a.axes() * c.a.radii().cwiseAbs2().asDiagonal() * c.a.axes().transpose() * n));
  const double g = ref::to_double(want.gap) / rho, band = 1e-12, margin = tol / rho;
  if (std::abs(g - band) > margin && std::abs(g + band) > margin) {
    if (g > band) {
      ASSERT_EQ(relation, Relation::separated) << what;
    } else if (g >= -band) {
      ASSERT_EQ(relation, Relation::touching) << what;
    } else {
      ASSERT_NE(relation, Relation::separated) << what;
      ASSERT_NE(relation, Relation::touching) << what;
      // a_contains_b: both end points R inside the boundary.
      Real deepest = -std::numeric_limits<Real>::infinity();
      for (int k = 0; k < 2; ++k) deepest = std::max(deepest, ref::max_support_gap<N>(body, {c.b.point(k)}).gap);
      const double inside = ref::to_double(Real(deepest + Real(c.b.radius())));
      if (std::abs(inside) > tol) {
        ASSERT_EQ(relation == Relation::a_contains_b, inside < 0) << what << " " << inside;
      }
    }
  }
  if (kind == Kind::capsule_inside) {
    ASSERT_EQ(relation, Relation::a_contains_b) << what;
  }
  if (kind == Kind::body_inside) {
    // The center on the segment, the ends beyond the body: inside when R exceeds the largest
    // radius, crossing the capsule's surface when R is below the smallest.
    ASSERT_EQ(relation, seed % 2 == 0 ? Relation::b_contains_a : Relation::overlapping) << what;
  }
  if (kind == Kind::needle || kind == Kind::body_inside || relation == Relation::b_contains_a) {
    // b_contains_a exactly when the body's farthest point from the segment is within R.
    const double outside = ref::to_double(farthest_outside<N>(c.a, c.b));
    if (std::abs(outside) > tol) {
      ASSERT_EQ(relation == Relation::b_contains_a, outside < 0) << what << " " << outside;
    }
    tally[std::string("needle ") + (outside < 0 ? "inside" : "across")] += kind == Kind::needle;
  }
  tally[std::string(to_string(relation))]++;

  // First contact.
  const Contact<double, N> hit = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
  tally[std::string("contact ") + std::string(to_string(hit.status))]++;
  const Vec<double, N> w = c.vb - c.va;
  if (relation != Relation::separated) {
    ASSERT_EQ(hit.status, relation == Relation::touching ? ContactStatus::touching_at_start
                                                         : ContactStatus::overlapping_at_start)
        << what;
    return;
  }
  if (hit.status == ContactStatus::hit) {
    ASSERT_LE(hit.time, c.t_max) << what;
    const Real at = reference_gap<N>(c, Vec<double, N>(hit.time * w)).gap;
    ASSERT_LE(abs(at), Real(tol)) << what << "\n  gap at the hit " << at.str(5);
    const Real before = reference_gap<N>(c, Vec<double, N>(0.999 * hit.time * w)).gap;
    ASSERT_GT(before, Real(0)) << what;
    ASSERT_NEAR(hit.normal.norm(), 1, 1e-12) << what;
  } else {
    ASSERT_EQ(hit.status, ContactStatus::no_contact_in_window) << what;
    // The gap stays open across the window (its end, or a horizon past the closest approach).
    const double horizon = std::isfinite(c.t_max) ? c.t_max : 4 * (scale + 1) / std::max(w.norm(), 1e-300);
    for (int k = 1; k <= 8; ++k) {
      const double t = horizon * k / 8;
      ASSERT_GT(reference_gap<N>(c, Vec<double, N>(t * w)).gap, Real(0)) << what << " t=" << t;
    }
  }
}

template <int N>
void run() {
  std::map<std::string, int> tally;
  const int seeds = full_case_counts() ? 6 : 2;
  for (const Kind kind : kinds)
    for (int seed = 0; seed < seeds; ++seed) {
      check<N>(kind, seed, tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  std::printf("capsules %dD:", N);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  if (!full_case_counts()) return;
  for (const char* outcome : {"separated", "overlapping", "a_contains_b", "b_contains_a", "contact hit",
                              "contact no_contact_in_window", "needle inside", "needle across"})
    EXPECT_GT(tally[outcome], 0) << outcome;
}

TEST(CapsuleProperty, MatchesReference2D) { run<2>(); }
TEST(CapsuleProperty, MatchesReference3D) { run<3>(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
