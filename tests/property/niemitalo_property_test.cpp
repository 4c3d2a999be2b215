// Niemitalo's methods (polygonal2.hpp, quartic2.hpp) against the 50-digit reference on the
// scenario categories: seeded random pairs, aspect ratios to 1e4, near tangency,
// containment, scenes scaled by 1e-6 and 1e6, far apart; rotated and axis-parallel.
//
// Claims under test:
// * Polygonal and circle-cover tests: a decided answer disagrees with the exact one only
//   within rounding of tangency, and `undecided` only happens within the polygon's band.
//   Both bands are stated on the Perram-Wertheim factor mu (affine invariant, so the same
//   in the stretched frame where the test runs): there the circle has radius R and the
//   ellipse the singular values s_max >= s_min, and a signed gap g between them (distance,
//   or minus the penetration depth) satisfies g / (R + s_max) <= mu - 1 <= g / (R + s_min)
//   (the support functions of the scaled bodies grow by between R + s_min and R + s_max
//   per unit of scale). Undecided means |g| <= niemitalo_error_bound(s_max, n), so
//       |mu - 1| <= (niemitalo_error_bound(s_max, n) + rounding) / (R + s_min).
//   The rounding term allows 16 ulps per level on the frame's coordinates.
// * closest_point_quartic: every outside point to 1e-13 relative; the table of
//   closest_point_closed_form's failures is printed (docs/niemitalo.md).
#include <ellipsect/point.hpp>
#include <ellipsect/polygonal2.hpp>
#include <ellipsect/quartic2.hpp>

#include "common.hpp"

#include <Eigen/SVD>

#include <cstdio>
#include <limits>
#include <vector>

namespace {

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
  int n_max;
  explicit Stats(int n) : undecided(n + 1, 0), n_max(n) {}
};

template <class T>
PolygonalOverlap run(Method m, const Ellipse2<T>& a, const Ellipse2<T>& b, int n) {
  switch (m) {
    case Method::circle: return polygonal_overlap(a, Vec2<T>(b.center()), b.radii()[0], n);
    case Method::ellipses: return polygonal_overlap(a, b, n);
    case Method::cover: return circle_cover_overlap(a, Vec2<T>(b.center()), b.radii()[0], n);
  }
  return {Verdict::invalid_input, 0};
}

// Checks one pair at every n against mu (of the pair as rounded to T).
template <class T>
void check(Method m, const Pair& p, double mu, Stats& stats) {
  const auto a = as<T>(p.a), b = as<T>(p.b);
  const Stretched s = stretched(body(a), body(b));
  const double eps = std::numeric_limits<T>::epsilon();
  stats.pairs++;
  for (int n = 0; n <= stats.n_max; ++n) {
    const PolygonalOverlap r = run<T>(m, a, b, n);
    ASSERT_NE(r.verdict, Verdict::invalid_input) << describe(p);
    ASSERT_LE(r.iterations, n) << describe(p);
    // Inputs are scaled by a power of two before the test runs, so a scene scaled by one
    // gives the same verdict after the same number of iterations, bit for bit.
    if (n == 10) {
      for (const T k : {T(0x1p-40), T(0x1p40)}) {
        const auto ak = Ellipse2<T>::from_axes(k * a.center(), a.axes(), k * a.radii());
        const auto bk = Ellipse2<T>::from_axes(k * b.center(), b.axes(), k * b.radii());
        const PolygonalOverlap rk = run<T>(m, ak, bk, n);
        ASSERT_TRUE(rk.verdict == r.verdict && rk.iterations == r.iterations) << describe(p);
      }
    }
    // With the arguments swapped, a stretches into the circle instead; two decided
    // answers are both exact, so they agree (up to the rounding band).
    if (m == Method::ellipses) {
      const PolygonalOverlap swapped = run<T>(m, b, a, n);
      if (swapped.verdict != Verdict::undecided && r.verdict != Verdict::undecided && swapped.verdict != r.verdict) {
        const Stretched t = stretched(body(b), body(a));
        ASSERT_LE(std::abs(mu - 1), std::max(rounding(s, n, eps) / (s.R + s.s_min), rounding(t, n, eps) / (t.R + t.s_min)))
            << describe(p) << "\n  n=" << n << " swapped disagrees";
      }
    }
    const double band = m == Method::cover && mu > 1 ? s.s_max * std::sin(M_PI / std::ldexp(1.0, n + 2))
                                                    : niemitalo_error_bound(s.s_max, n);
    if (r.verdict == Verdict::undecided) {
      stats.undecided[n]++;
      ASSERT_EQ(r.iterations, n) << describe(p);
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
  std::printf("%s\n  %-14s %8s  undecided at n = 0 / 2 / 5 / 10 / 15 / 20 (of the pairs)  wrong (worst |mu-1|)\n", title,
              "category", "pairs");
  for (const auto& [c, st] : rows) {
    std::printf("  %-14s %8d ", std::string(scenarios::name(c)).c_str(), st.pairs);
    for (int n : {0, 2, 5, 10, 15, 20})
      if (n <= st.n_max) std::printf(" %5d", st.undecided[n]);
      else std::printf("     -");
    std::printf("   %d (%.1e)\n", st.wrong, st.worst_wrong);
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

}  // namespace
