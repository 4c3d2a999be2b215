// Niemitalo's methods (polygonal2.hpp, quartic2.hpp) against the 50-digit reference on the
// scenario categories: seeded random pairs, aspect ratios to 1e4, near tangency,
// containment, scenes scaled by 1e-6 and 1e6, far apart; rotated and axis-parallel.
//
// Claims under test:
// * Polygonal and circle-cover tests: the reference's signed distance g of the pair (as
//   rounded to T) lies in the returned band [gap_lo, gap_hi], for every answer; hence a
//   decided answer is wrong only within the rounding allowance of tangency. Undecided
//   answers are also checked on the Perram-Wertheim factor mu (affine invariant, so the
//   same in the stretched frame where the test runs): there the circle has radius R and
//   the ellipse the singular values s_max >= s_min, and the signed gap g_s between them
//   satisfies g_s / (R + s_max) <= mu - 1 <= g_s / (R + s_min). Undecided means
//   |g_s| <= niemitalo_error_bound(s_max, n), so
//       |mu - 1| <= (niemitalo_error_bound(s_max, n) + rounding) / (R + s_min).
//   The rounding term allows 16 ulps per level on the frame's coordinates.
// * segment_circle: verdicts and sides exact for small-integer inputs (against exact integer
//   arithmetic), within the stated error bound otherwise (against a 50-digit
//   point-segment distance), and unchanged by exact scalings 2^+-500, 2^+-1000 (float:
//   2^+-60, 2^+-100).
// * closest_point_quartic: every outside point to 1e-13 relative; the table of
//   closest_point_closed_form's failures is printed (docs/niemitalo.md).
#include <ellipsect/point.hpp>
#include <ellipsect/polygonal2.hpp>
#include <ellipsect/quartic2.hpp>

#include "common.hpp"
#include "tests/reference/distance_reference.hpp"

#include <Eigen/SVD>

#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using scenarios::Category;

// ----------------------------------------------------------------------------- cases

struct Pair {
  Category category;
  std::uint64_t seed;
  Ellipse2<double> a, b;  // b is a circle (make_ball) in the ellipse-circle sets
};

std::string describe(const Pair& p) {
  std::ostringstream s;
  s.precision(17);
  s << "category=" << scenarios::name(p.category) << " seed=" << p.seed << "\n  a: c=" << p.a.center().transpose()
    << " axis0=" << p.a.axes().col(0).transpose() << " r=" << p.a.radii().transpose() << "\n  b: c=" << p.b.center().transpose()
    << " axis0=" << p.b.axes().col(0).transpose() << " r=" << p.b.radii().transpose();
  return s.str();
}

// A signed gap as the generator draws it for tangent pairs (relative to b's size).
double tangent_gap(scenarios::detail::Rng& rng, double largest) {
  using namespace scenarios::detail;
  return (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-9, largest);
}

bool tangent_kind(Category c, scenarios::detail::Rng& rng) {
  return c == Category::near_tangent || (c == Category::high_aspect && scenarios::detail::uniform(rng, 0, 1) < 0.5);
}

// The ellipse a of the scenario case and a circle in place of b: containment and tangency
// are kept (b's inscribed circle stays inside a container, b's circumscribed circle still
// contains what b contained; tangent kinds are re-placed at a drawn gap); otherwise the
// circle has b's center and the geometric mean of its radii.
Pair circle_pair(Category category, std::uint64_t seed) {
  using namespace scenarios::detail;
  const auto c = scenarios::make_case<2>(category, seed);
  Rng rng(seed ^ 0x4e494d49ull);
  const Relation rel = classify(c.a, c.b);  // steers the construction only
  double r = std::sqrt(c.b.radii().prod());
  if (rel == Relation::a_contains_b) r = c.b.radii().minCoeff();
  if (rel == Relation::b_contains_a) r = c.b.radii().maxCoeff();
  Vec2<double> center = c.b.center();
  if (tangent_kind(category, rng)) {
    const double gap = tangent_gap(rng, category == Category::near_tangent ? 1e-6 : 1e-1);
    center = tangent_center<2>(c.a, unit_vector<2>(rng), Mat2<double>::Identity(), Vec2<double>(r, r), gap);
  }
  return {category, seed, c.a, make_ball<double, 2>(center, r)};
}

// The scenario pair as is (rotated: the stretch route).
Pair general_pair(Category category, std::uint64_t seed) {
  const auto c = scenarios::make_case<2>(category, seed);
  return {category, seed, c.a, c.b};
}

// b given a's axes (the parallel route), tangent kinds re-placed.
Pair parallel_pair(Category category, std::uint64_t seed) {
  using namespace scenarios::detail;
  const auto c = scenarios::make_case<2>(category, seed);
  Rng rng(seed ^ 0x50415241ull);
  Vec2<double> center = c.b.center();
  if (tangent_kind(category, rng)) {
    const double gap = tangent_gap(rng, category == Category::near_tangent ? 1e-6 : 1e-1);
    center = tangent_center<2>(c.a, unit_vector<2>(rng), c.a.axes(), c.b.radii(), gap);
  }
  return {category, seed, c.a, Ellipse2<double>::from_axes(center, c.a.axes(), c.b.radii())};
}

template <class T>
Ellipse2<T> as(const Ellipse2<double>& e) {
  return Ellipse2<T>::from_axes(e.center().cast<T>(), e.axes().cast<T>(), e.radii().cast<T>());
}

template <class T>
ref::Body<2> body(const Ellipse2<T>& e) {
  return {e.center().template cast<double>(), e.axes().template cast<double>(), e.radii().template cast<double>()};
}

// ----------------------------------------------------------------------------- bands

// The stretched frame of the test (b a circle of radius R = r_b0 r_b1, map diag(r_b1, r_b0) Q_b^T).
struct Stretched {
  double R, s_max, s_min;
  double size;  // |center offset| + s_max + R + world positions, for the rounding term
};

Stretched stretched(const ref::Body<2>& a, const ref::Body<2>& b) {
  const Eigen::Vector2d stretch(b.radii[1], b.radii[0]);
  const Eigen::Matrix2d m = stretch.asDiagonal() * b.axes.transpose();
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(m * a.axes * a.radii.asDiagonal());
  Stretched s;
  s.R = b.radii[0] * b.radii[1];
  s.s_max = svd.singularValues()[0];
  s.s_min = svd.singularValues()[1];
  s.size = (m * (b.center - a.center)).norm() + s.s_max + s.R + b.radii.maxCoeff() * (a.center.norm() + b.center.norm());
  return s;
}

double rounding(const Stretched& s, int n, double eps) { return 16 * (n + 2) * eps * s.size; }

// ----------------------------------------------------------------------------- polygonal

enum class Method { circle, ellipses, cover };

struct Stats {
  std::vector<int> undecided;  // per n
  int pairs = 0, decided = 0, wrong = 0;
  double worst_wrong = 0;      // largest |mu - 1| of a wrong answer
  double rounding_used = 0;    // largest share of the band's rounding allowance that g needed
  int n_max;
  explicit Stats(int n) : undecided(n + 1, 0), n_max(n) {}
};

template <class T>
PolygonalOverlap<T> run(Method m, const Ellipse2<T>& a, const Ellipse2<T>& b, int n) {
  switch (m) {
    case Method::circle: return polygonal_overlap(a, make_circle<T>(b.center(), b.radii()[0]), n);
    case Method::ellipses: return polygonal_overlap(a, b, n);
    case Method::cover: return circle_cover_overlap(a, make_circle<T>(b.center(), b.radii()[0]), n);
  }
  return {};
}

// The band's rounding allowance as documented in polygonal2.hpp ("The band").
template <class T>
double rho(const Ellipse2<T>& a, const Ellipse2<T>& b, int level) {
  const Vec2<double> d = (b.center() - a.center()).template cast<double>();
  return 16 * (level + 2) * double(std::numeric_limits<T>::epsilon()) *
         (std::abs(d.x()) + std::abs(d.y()) + a.radii().maxCoeff() + b.radii().maxCoeff());
}

// Checks one pair at every n against mu and the signed distance g (of the pair as rounded
// to T; g is computed only where mu alone does not settle the band).
template <class T>
void check(Method m, const Pair& p, double mu, Stats& stats) {
  const auto a = as<T>(p.a), b = as<T>(p.b);
  const Stretched s = stretched(body(a), body(b));
  const double eps = std::numeric_limits<T>::epsilon();
  std::optional<double> gap;
  const auto g = [&] {
    if (!gap) gap = ref::to_double(ref::signed_distance<2>(body(a), body(b)).distance);
    return *gap;
  };
  stats.pairs++;
  for (int n = 0; n <= stats.n_max; ++n) {
    const PolygonalOverlap<T> r = run<T>(m, a, b, n);
    ASSERT_NE(r.verdict, Verdict::invalid_input) << describe(p);
    ASSERT_LE(r.level, n) << describe(p);
    ASSERT_TRUE(m == Method::cover ? r.iterations >= r.level : r.iterations == r.level) << describe(p);
    // Inputs are scaled by a power of two before the test runs, so a scene scaled by one
    // gives the same verdict after the same levels and bisections, bit for bit, and the
    // band scaled by it.
    if (n == 10) {
      const std::vector<T> scales = sizeof(T) == sizeof(double) ? std::vector<T>{T(0x1p-500), T(0x1p-40), T(0x1p40), T(0x1p500)}
                                                                 : std::vector<T>{T(0x1p-40), T(0x1p40)};
      for (const T k : scales) {
        const auto ak = Ellipse2<T>::from_axes(k * a.center(), a.axes(), k * a.radii());
        const auto bk = Ellipse2<T>::from_axes(k * b.center(), b.axes(), k * b.radii());
        const PolygonalOverlap<T> rk = run<T>(m, ak, bk, n);
        ASSERT_TRUE(rk.verdict == r.verdict && rk.level == r.level && rk.iterations == r.iterations &&
                    rk.gap_lo == k * r.gap_lo && rk.gap_hi == k * r.gap_hi)
            << describe(p) << "\n  scale " << k;
      }
    }
    // With the arguments swapped, a stretches into the circle instead; two decided
    // answers are both exact, so they agree (up to the rounding band).
    if (m == Method::ellipses) {
      const PolygonalOverlap<T> swapped = run<T>(m, b, a, n);
      if (swapped.verdict != Verdict::undecided && r.verdict != Verdict::undecided && swapped.verdict != r.verdict) {
        const Stretched t = stretched(body(b), body(a));
        ASSERT_LE(std::abs(mu - 1), std::max(rounding(s, n, eps) / (s.R + s.s_min), rounding(t, n, eps) / (t.R + t.s_min)))
            << describe(p) << "\n  n=" << n << " swapped disagrees";
      }
    }
    // The band holds g. A decided answer whose half-line has mu's sign holds it trivially.
    const bool settled = (r.verdict == Verdict::collision && mu <= 1) || (r.verdict == Verdict::no_collision && mu > 1);
    if (!settled) {
      ASSERT_TRUE(r.gap_lo <= g() && g() <= r.gap_hi)
          << describe(p) << "\n  n=" << n << " " << to_string(r.verdict) << " g=" << g() << " band [" << r.gap_lo
          << ", " << r.gap_hi << "]";
      // How much of the rounding allowance g used (0: inside the exact band).
      const double allowance = rho(a, b, r.level);
      const double excess = std::max(r.gap_lo + allowance - g(), g() - (r.gap_hi - allowance));
      stats.rounding_used = std::max(stats.rounding_used, excess / allowance);
    }
    const double band = m == Method::cover && mu > 1 ? s.s_max * std::sin(M_PI / std::ldexp(1.0, n + 2))
                                                    : niemitalo_error_bound(s.s_max, n);
    if (r.verdict == Verdict::undecided) {
      stats.undecided[n]++;
      ASSERT_EQ(r.level, n) << describe(p);
      if (m != Method::cover) {  // the cover's band reaches sin h * major outside, beyond the bound
        ASSERT_LE(std::max(r.gap_hi, -r.gap_lo), niemitalo_error_bound(a, n) + rho(a, b, n)) << describe(p);
      }
      ASSERT_LE(std::abs(mu - 1), (band + rounding(s, n, eps)) / (s.R + s.s_min))
          << describe(p) << "\n  n=" << n << " mu=" << mu;
      continue;
    }
    stats.decided++;
    if ((r.verdict == Verdict::collision) == (mu <= 1)) continue;
    stats.wrong++;
    stats.worst_wrong = std::max(stats.worst_wrong, std::abs(mu - 1));
    ASSERT_LE(std::abs(mu - 1), rounding(s, n, eps) / (s.R + s.s_min))
        << describe(p) << "\n  n=" << n << " mu=" << mu << " got " << to_string(r.verdict);
  }
}

void print(const char* title, const std::vector<std::pair<Category, Stats>>& rows) {
  std::printf("%s\n  %-14s %8s  undecided at n = 0 / 2 / 5 / 10 / 15 / 20 (of the pairs)  wrong (worst |mu-1|)"
              "  rounding allowance used\n",
              title, "category", "pairs");
  for (const auto& [c, st] : rows) {
    std::printf("  %-14s %8d ", std::string(scenarios::name(c)).c_str(), st.pairs);
    for (int n : {0, 2, 5, 10, 15, 20})
      if (n <= st.n_max) std::printf(" %5d", st.undecided[n]);
      else std::printf("     -");
    std::printf("   %d (%.1e)   %.1e\n", st.wrong, st.worst_wrong, st.rounding_used);
  }
}

template <class MakePair>
void polygonal_against_reference(const char* title, MakePair make, Method method, int per_category) {
  std::vector<std::pair<Category, Stats>> dbl, flt, cover;
  for (const auto category : scenarios::all_categories) {
    Stats sd(20), sf(12), sc(12);
    for (int i = 0; i < per_category; ++i) {
      const Pair p = make(category, static_cast<std::uint64_t>(i));
      const double mu = ref::to_double(ref::pw_scale<2>(body(p.a), body(p.b)));
      check<double>(method, p, mu, sd);
      const double mu_f = ref::to_double(ref::pw_scale<2>(body(as<float>(p.a)), body(as<float>(p.b))));
      check<float>(method, p, mu_f, sf);
      if (method == Method::circle) check<double>(Method::cover, p, mu, sc);
      if (::testing::Test::HasFatalFailure()) return;
    }
    dbl.emplace_back(category, sd);
    flt.emplace_back(category, sf);
    cover.emplace_back(category, sc);
  }
  print((std::string(title) + ", double").c_str(), dbl);
  print((std::string(title) + ", float").c_str(), flt);
  if (method == Method::circle) print("circle cover, ellipse-circle, double", cover);
}

TEST(NiemitaloProperty, PolygonalEllipseCircle) {
  polygonal_against_reference("polygonal, ellipse-circle", circle_pair, Method::circle, cases(1500));
}

TEST(NiemitaloProperty, PolygonalEllipsesRotated) {
  polygonal_against_reference("polygonal, ellipse-ellipse (stretch route)", general_pair, Method::ellipses, cases(1500));
}

TEST(NiemitaloProperty, PolygonalEllipsesParallel) {
  polygonal_against_reference("polygonal, ellipse-ellipse (parallel route)", parallel_pair, Method::ellipses, cases(800));
}

// ----------------------------------------------------------------------------- quartic

struct Failures {
  int points = 0, outside = 0;
  int nan = 0, wrong = 0, inaccurate = 0;
  double worst = 0;  // largest relative point error among outside answers
};

// One route on one pair: the verdict (inside, or distance <= radius) against mu, the point
// against closest_point, relative to max(major radius, |exact point|).
template <class T, class Route>
void tally_route(Route route, const Pair& p, double mu, double tangency, Failures& f) {
  const auto a = as<T>(p.a);
  const Vec2<T> x = p.b.center().cast<T>();
  const T r = T(p.b.radii()[0]);
  const QuarticPoint<T> q = route(a, x);
  f.points++;
  if (q.status == QuarticStatus::failed) {
    f.nan++;
    return;
  }
  ASSERT_TRUE(q.status == QuarticStatus::inside || q.status == QuarticStatus::outside) << describe(p);
  const bool collide = q.status == QuarticStatus::inside || q.distance <= r;
  if (collide != (mu <= 1) && std::abs(mu - 1) > tangency) f.wrong++;
  const auto exact = closest_point(a, x);
  if (exact.signed_distance <= T(0)) return;
  f.outside++;
  if (q.status != QuarticStatus::outside) {  // an outside point declared inside
    f.inaccurate++;
    return;
  }
  ASSERT_TRUE(q.point.allFinite() && std::isfinite(q.distance)) << describe(p);
  const double scale = std::max<double>(a.radii().maxCoeff(), exact.point.norm());
  const double err = (q.point - exact.point).template cast<double>().norm() / scale;
  f.worst = std::max(f.worst, err);
  if (err > 1e-6) f.inaccurate++;
}

std::string percent(int k, int n) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f%%", n > 0 ? 100.0 * k / n : 0.0);
  return s;
}

TEST(NiemitaloProperty, ClosedFormFailureTable) {
  const auto closed = [](const auto& e, const auto& x) { return closest_point_closed_form(e, x); };
  const auto quartic = [](const auto& e, const auto& x) { return closest_point_quartic(e, x); };
  std::printf("closest point of an ellipse to a circle's center, per category: NaN (failed) / wrong verdict "
              "(|mu - 1| > 2e-12, float 1e-5) / point error > 1e-6 of max(major radius, |point|)\n"
              "| category | pairs | closed form, double | quartic, double | closed form, float | quartic, float |\n"
              "|---|---|---|---|---|---|\n");
  Failures total_quartic;
  for (const auto category : scenarios::all_categories) {
    Failures cd, qd, cf, qf;
    for (int i = 0; i < cases(2000); ++i) {
      const Pair p = circle_pair(category, static_cast<std::uint64_t>(i));
      const double mu = ref::to_double(ref::pw_scale<2>(body(p.a), body(p.b)));
      const double mu_f = ref::to_double(ref::pw_scale<2>(body(as<float>(p.a)), body(as<float>(p.b))));
      tally_route<double>(closed, p, mu, 2e-12, cd);
      tally_route<double>(quartic, p, mu, 2e-12, qd);
      tally_route<float>(closed, p, mu_f, 1e-5, cf);
      tally_route<float>(quartic, p, mu_f, 1e-5, qf);
      if (HasFatalFailure()) return;
    }
    auto cell = [](const Failures& f) {
      return percent(f.nan, f.points) + " / " + percent(f.wrong, f.points) + " / " + percent(f.inaccurate, f.outside);
    };
    std::printf("| %s | %d | %s | %s | %s | %s |\n", std::string(scenarios::name(category)).c_str(), cd.points,
                cell(cd).c_str(), cell(qd).c_str(), cell(cf).c_str(), cell(qf).c_str());
    for (const Failures* f : {&qd, &qf}) {
      EXPECT_EQ(f->nan, 0) << scenarios::name(category);
      EXPECT_EQ(f->wrong, 0) << scenarios::name(category);
      EXPECT_EQ(f->inaccurate, 0) << scenarios::name(category);
    }
    EXPECT_LE(qd.worst, 1e-13) << scenarios::name(category);
    total_quartic.worst = std::max(total_quartic.worst, qd.worst);
  }
  std::printf("quartic, double: worst point error %.1e relative\n", total_quartic.worst);
}

// ----------------------------------------------------------------------------- segment-circle

// A segment and a circle: random, or tangent to within a drawn gap (at an end point or
// along the segment), with coordinates up to 10 and radii from 1e-3 to 10.
template <class T>
struct SegmentCase {
  Vec2<T> a, b, c;
  T r;
};

template <class T>
SegmentCase<T> segment_case(scenarios::detail::Rng& rng) {
  using namespace scenarios::detail;
  const Vec2<double> a(uniform(rng, -10, 10), uniform(rng, -10, 10));
  const Vec2<double> b = uniform(rng, 0, 1) < 0.1 ? a : Vec2<double>(uniform(rng, -10, 10), uniform(rng, -10, 10));
  const double r = log_uniform(rng, 1e-3, 10);
  Vec2<double> c(uniform(rng, -10, 10), uniform(rng, -10, 10));
  const double kind = uniform(rng, 0, 1);
  if (kind < 0.7) {  // near tangent: a point of the segment, then r + gap away from it
    const double gap = (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-18, 1e-3);
    const double t = kind < 0.35 ? uniform(rng, 0, 1) : (kind < 0.5 ? 0.0 : 1.0);
    const Vec2<double> foot = a + t * (b - a);
    Vec2<double> out = unit_vector<2>(rng);
    if (t > 0 && t < 1 && b != a) out = Vec2<double>(a.y() - b.y(), b.x() - a.x()).normalized();  // perpendicular
    else if (t == 0 && b != a && out.dot(b - a) > 0) out = -out;                                 // beyond the end
    else if (t == 1 && b != a && out.dot(b - a) < 0) out = -out;
    c = foot + (r + gap) * out;
  } else if (kind < 0.8 && b != a) {  // the center near the segment's line (the side)
    const Vec2<double> perp = Vec2<double>(a.y() - b.y(), b.x() - a.x()).normalized();
    c = a + uniform(rng, -1, 2) * (b - a) + (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-20, 1e-3) * perp;
  }
  return {a.cast<T>(), b.cast<T>(), c.cast<T>(), T(r)};
}

// Distance from c to the segment [a, b] in 50 digits: the clamped projection.
template <class T>
ref::Real segment_distance(const SegmentCase<T>& k) {
  using R = ref::Real;
  const R ax = k.a.x(), ay = k.a.y(), ex = R(k.b.x()) - ax, ey = R(k.b.y()) - ay;
  const R qx = R(k.c.x()) - ax, qy = R(k.c.y()) - ay;
  const R len2 = ex * ex + ey * ey;
  R t = len2 > 0 ? (qx * ex + qy * ey) / len2 : R(0);
  t = t < 0 ? R(0) : (t > 1 ? R(1) : t);
  const R dx = qx - t * ex, dy = qy - t * ey;
  return sqrt(dx * dx + dy * dy);
}

template <class T>
void segment_circle_against_reference(int count) {
  scenarios::detail::Rng rng(0x5e6c17c1e ^ sizeof(T));
  const double eps = std::numeric_limits<T>::epsilon();
  int wrong = 0, wrong_side = 0;
  double used = 0;  // largest |dist - r| / bound of a wrong verdict
  for (int i = 0; i < count; ++i) {
    const SegmentCase<T> k = segment_case<T>(rng);
    const SegmentCircle got = segment_circle<T>(k.a, k.b, make_circle<T>(k.c, k.r));
    const double dist = ref::to_double(segment_distance(k));
    const double excess = ref::to_double(segment_distance(k) - ref::Real(k.r));
    const double bound = 8 * eps * ((k.b - k.a).template cast<double>().norm() + (k.c - k.a).template cast<double>().norm() + k.r);
    if ((got.verdict == Verdict::collision) != (excess <= 0)) {
      wrong++;
      used = std::max(used, std::abs(excess) / bound);
      ASSERT_LE(std::abs(excess), bound) << "case " << i << " dist=" << dist << " r=" << k.r;
    }
    using R = ref::Real;
    const R side = (R(k.b.x()) - R(k.a.x())) * (R(k.c.y()) - R(k.a.y())) - (R(k.b.y()) - R(k.a.y())) * (R(k.c.x()) - R(k.a.x()));
    const Side want = side > 0 ? Side::left : side < 0 ? Side::right : Side::on_line;
    if (got.side != want) {
      wrong_side++;
      const double len = (k.b - k.a).template cast<double>().norm();
      ASSERT_GT(len, 0) << "case " << i;
      ASSERT_LE(std::abs(ref::to_double(side)) / len, 2 * eps * (k.c - k.a).template cast<double>().norm()) << "case " << i;
    }
  }
  std::printf("segment_circle<%s>: %d cases, %d verdicts within rounding of tangency (worst %.2f of the bound), %d sides\n",
              sizeof(T) == sizeof(double) ? "double" : "float", count, wrong, used, wrong_side);
}

TEST(NiemitaloProperty, SegmentCircleWithinTheBound) {
  segment_circle_against_reference<double>(cases(20000));
  segment_circle_against_reference<float>(cases(20000));
}

// Integer inputs small enough that every sum and product of the test is exact: the
// verdict and the side are exact. Reference: exact integer arithmetic (the clamped
// projection, cleared of its division). Tangent cases are built from the right angle of
// the 3-4-5 triangle, so they are exact too.
template <class T>
void segment_circle_exact_on_small_integers(int count, int limit) {
  using I = __int128;
  scenarios::detail::Rng rng(0x1a7e9e5 ^ sizeof(T));
  auto draw = [&](int lo, int hi) { return static_cast<int>(std::floor(scenarios::detail::uniform(rng, lo, hi + 1))); };
  int tangent = 0, collisions = 0;
  for (int i = 0; i < count; ++i) {
    std::int64_t ax = draw(-limit, limit), ay = draw(-limit, limit), bx = draw(-limit, limit), by = draw(-limit, limit);
    std::int64_t cx = draw(-limit, limit), cy = draw(-limit, limit), r = draw(0, limit);
    const int kind = draw(0, 3);
    const int m = draw(1, std::max(1, limit / 8));
    if (kind == 1) {  // tangent to the segment's line: along (4, 3), center 5m away along (-3, 4)
      const std::int64_t t = draw(0, 2);
      ax = draw(-limit / 2, 0), ay = draw(-limit / 2, 0), bx = ax + 4 * m * 2, by = ay + 3 * m * 2;
      cx = ax + 4 * m * t - 3 * m, cy = ay + 3 * m * t + 4 * m, r = 5 * m + draw(-1, 1);
    } else if (kind == 2) {  // an end point on the circle: c = a + (3m, 4m), r = 5m
      cx = ax + 3 * m, cy = ay + 4 * m, r = 5 * m + draw(-1, 1);
    }
    if (std::max({std::abs(ax), std::abs(ay), std::abs(bx), std::abs(by), std::abs(cx), std::abs(cy), r}) > limit || r < 0) continue;
    const I ex = bx - ax, ey = by - ay, qx = cx - ax, qy = cy - ay;
    const I len2 = ex * ex + ey * ey, t = ex * qx + ey * qy, qq = qx * qx + qy * qy, rr = I(r) * r;
    bool hit;
    if (len2 == 0 || t <= 0) hit = qq <= rr;
    else if (t >= len2) hit = (cx - bx) * I(cx - bx) + (cy - by) * I(cy - by) <= rr;
    else hit = qq * len2 - t * t <= rr * len2;  // dist^2 = qq - t^2 / len2
    const I cr = ex * qy - ey * qx;
    const Side side = cr > 0 ? Side::left : cr < 0 ? Side::right : Side::on_line;
    const SegmentCircle got = segment_circle<T>(Vec2<T>(T(ax), T(ay)), Vec2<T>(T(bx), T(by)), make_circle<T>(Vec2<T>(T(cx), T(cy)), T(r)));
    ASSERT_EQ(got.verdict == Verdict::collision, hit) << ax << " " << ay << " " << bx << " " << by << " " << cx << " " << cy << " " << r;
    ASSERT_EQ(got.side, side) << ax << " " << ay << " " << bx << " " << by << " " << cx << " " << cy << " " << r;
    tangent += kind > 0 && ((len2 == 0 || t <= 0) ? qq == rr : (t >= len2 ? false : qq * len2 - t * t == rr * len2));
    collisions += hit;
  }
  std::printf("segment_circle<%s>, integers to %d: %d cases, %d collisions, %d exactly tangent\n",
              sizeof(T) == sizeof(double) ? "double" : "float", limit, count, collisions, tangent);
  EXPECT_GT(tangent, count / 20);
}

TEST(NiemitaloProperty, SegmentCircleExactOnSmallIntegers) {
  segment_circle_exact_on_small_integers<double>(cases(20000), 2048);
  segment_circle_exact_on_small_integers<float>(cases(20000), 16);
}

// Scaling every input by a power of two is exact, so the verdict and the side must not
// change, however large or small the scale (fourth powers of 2^1000 overflow).
template <class T>
void segment_circle_scale_invariant(int count, std::initializer_list<T> scales) {
  scenarios::detail::Rng rng(0x5ca1e ^ sizeof(T));
  int checked = 0;
  for (int i = 0; i < count; ++i) {
    const SegmentCase<T> k = segment_case<T>(rng);
    const SegmentCircle base = segment_circle<T>(k.a, k.b, make_circle<T>(k.c, k.r));
    for (const T s : scales) {
      // Skip inputs the scaling would round (subnormal results).
      auto exact = [s](T v) { return (v * s) / s == v && std::isfinite(v * s); };
      if (!(exact(k.a.x()) && exact(k.a.y()) && exact(k.b.x()) && exact(k.b.y()) && exact(k.c.x()) && exact(k.c.y()) && exact(k.r)))
        continue;
      const SegmentCircle scaled = segment_circle<T>(s * k.a, s * k.b, make_circle<T>(s * k.c, s * k.r));
      ASSERT_EQ(scaled.verdict, base.verdict) << "case " << i << " scale " << s;
      ASSERT_EQ(scaled.side, base.side) << "case " << i << " scale " << s;
      checked++;
    }
  }
  EXPECT_GT(checked, count * int(scales.size()) * 9 / 10);
}

TEST(NiemitaloProperty, SegmentCircleScaleInvariant) {
  segment_circle_scale_invariant<double>(cases(5000), {0x1p-1000, 0x1p-500, 0x1p500, 0x1p1000});
  segment_circle_scale_invariant<float>(cases(5000), {0x1p-100f, 0x1p-60f, 0x1p60f, 0x1p100f});
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
