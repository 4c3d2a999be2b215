// classify and overlap against the 50-digit reference (Perram-Wertheim contact function
// and the extrema of one body's quadric over the other's boundary, computed in the other
// body's frame): a route independent of the library's reduction and secular solver.
//
// Claim under test (classify.hpp): the relation is exact whenever every tangency measure
// of the reference (margin) is farther than 2 * tolerance from 1, and a pair reported
// touching has |mu - 1| <= 2 * tolerance; at tolerance 0 (the exact mode, last tests) the
// relation of the stored bodies is exact for every pair the reference decides (margin above
// 1e-40), at relative gaps down to 1e-20.
#include <ellipsect/batch.hpp>
#include <ellipsect/intersect2.hpp>

#include "common.hpp"
#include "detail/axes.hpp"
#include "detail/batch_kernels.hpp"
#include "tests/unit/scenario_pairs.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;

constexpr double band = 2 * Options{}.tolerance;

template <int N>
void check_against_reference(int per_category) {
  Tally tally;
  int decided = 0;
  for (const auto category : scenarios::all_categories) {
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_case<N>(category, static_cast<std::uint64_t>(i));
      const Relation got = classify(c.a, c.b);
      const auto r = ref::classify<N>(to_ref(c.a), to_ref(c.b), band);
      const Relation want = from_ref(r.relation);
      const bool decidable = r.margin > band;
      // Equal bodies sit on every tangency at once (margin 0): the answer must be equal.
      if (want == Relation::equal) {
        ASSERT_EQ(got, Relation::equal) << describe(c);
      }
      tally.add(scenarios::name(category), decidable || want == Relation::equal ? std::string(to_string(want)) : "in_band");
      if (decidable) {
        ++decided;
        ASSERT_EQ(got, want) << describe(c) << "\n  mu=" << ref::to_double(r.mu) << " margin=" << ref::to_double(r.margin);
      }
      if (got == Relation::touching) {
        ASSERT_LE(ref::to_double(abs(r.mu - 1)), band) << describe(c);
      }
      ASSERT_EQ(overlap(c.a, c.b), got != Relation::separated) << describe(c);
      ASSERT_EQ(classify(c.b, c.a), mirrored(got)) << describe(c);
      ASSERT_EQ(overlap(c.b, c.a), got != Relation::separated) << describe(c);
    }
  }
  tally.print("classify vs reference, N=" + std::to_string(N));
  // The mix must exercise every relation, and near-tangent cases must mostly be decidable
  // (their gaps, 1e-9 .. 1e-6, are far outside the band).
  EXPECT_GT(decided, per_category * 9);
  EXPECT_GT(tally.count("near_tangent", "separated"), per_category / 5);
  EXPECT_GT(tally.count("near_tangent", "overlapping"), per_category / 5);
  EXPECT_GT(tally.count("containment", "a_contains_b") + tally.count("containment", "b_contains_a"), per_category / 3);
  EXPECT_GT(tally.count("spheres", "equal"), 0);
}

TEST(ClassifyProperty, MatchesReference2D) { check_against_reference<2>(cases(1000)); }
TEST(ClassifyProperty, MatchesReference3D) { check_against_reference<3>(cases(1000)); }

// Pairs placed just outside and inside the certificates' margins: both bodies scaled
// about their centers so that the reference contact scale mu becomes 1 + delta, with
// |delta| from 1e-8 to 1e-2 (the Perram-Wertheim margin is about 2.4e-5), over random
// and high-aspect shapes. classify and overlap must match the reference on each.
template <int N>
void check_at_certificate_margins(int n) {
  scenarios::detail::Rng rng(4242);
  int decided = 0;
  for (int i = 0; i < n; ++i) {
    const auto category = i % 2 == 0 ? scenarios::Category::random : scenarios::Category::high_aspect;
    const auto c = scenarios::make_case<N>(category, 300000 + std::uint64_t(i));
    const double mu = ref::to_double(ref::pw_scale<N>(to_ref(c.a), to_ref(c.b)));
    const double delta = (i % 4 < 2 ? 1 : -1) * std::pow(10.0, scenarios::detail::uniform(rng, -8, -2));
    const double s = mu / (1 + delta);
    const auto a = Ellipsoid<double, N>::from_axes(c.a.center(), c.a.axes(), c.a.radii() * s);
    const auto b = Ellipsoid<double, N>::from_axes(c.b.center(), c.b.axes(), c.b.radii() * s);
    const auto r = ref::classify<N>(to_ref(a), to_ref(b), band);
    if (r.margin <= band) continue;
    ++decided;
    ASSERT_EQ(classify(a, b), from_ref(r.relation)) << describe(c) << " delta=" << delta;
    ASSERT_EQ(overlap(a, b), from_ref(r.relation) != Relation::separated) << describe(c) << " delta=" << delta;
  }
  EXPECT_GT(decided, n * 9 / 10);
}

TEST(ClassifyProperty, MatchesReferenceAtCertificateMargins2D) { check_at_certificate_margins<2>(cases(1000)); }
TEST(ClassifyProperty, MatchesReferenceAtCertificateMargins3D) { check_at_certificate_margins<3>(cases(1000)); }

// Rigid motions and scaling by powers of two change no answer (the tolerance model is
// relative; powers of two are exact, so the answer is identical, not just close).
template <int N>
void check_invariance(int n) {
  for (int i = 0; i < n; ++i) {
    for (const auto category : {scenarios::Category::random, scenarios::Category::high_aspect, scenarios::Category::containment}) {
      const auto c = scenarios::make_case<N>(category, 100000 + i);
      const Relation got = classify(c.a, c.b);
      for (double s : {0x1p-40, 0x1p40}) {
        const auto as = Ellipsoid<double, N>::from_axes(c.a.center() * s, c.a.axes(), c.a.radii() * s);
        const auto bs = Ellipsoid<double, N>::from_axes(c.b.center() * s, c.b.axes(), c.b.radii() * s);
        ASSERT_EQ(classify(as, bs), got) << describe(c);
      }
      // A rigid motion moves the bodies by rounding only: same answer unless in the band.
      const auto r = ref::classify<N>(to_ref(c.a), to_ref(c.b), band);
      if (r.margin < 1e-9) continue;
      scenarios::detail::Rng rng(i);
      const Mat<double, N> q = scenarios::detail::rotation<N>(rng);
      const Vec<double, N> t = scenarios::detail::unit_vector<N>(rng) * 7.0;
      const auto am = Ellipsoid<double, N>::from_axes(q * c.a.center() + t, q * c.a.axes(), c.a.radii());
      const auto bm = Ellipsoid<double, N>::from_axes(q * c.b.center() + t, q * c.b.axes(), c.b.radii());
      ASSERT_EQ(classify(am, bm), got) << describe(c);
    }
  }
}

TEST(ClassifyProperty, ScaleAndRigidMotionInvariance2D) { check_invariance<2>(cases(200)); }
TEST(ClassifyProperty, ScaleAndRigidMotionInvariance3D) { check_invariance<3>(cases(200)); }

// float instantiation: computed in double from the float data; the float rounding of the
// inputs (axes orthonormal only to ~1e-7) moves the bodies by ~1e-7 relative, so the
// answer is exact outside a 1e-5 band of the reference on those rounded bodies.
TEST(ClassifyProperty, FloatMatchesReferenceOutsideFloatBand) {
  for (int i = 0; i < cases(500); ++i) {
    const auto c = scenarios::make_case<3>(scenarios::Category::random, 200000 + i);
    const auto af = Ellipsoid3<float>::from_axes(c.a.center().cast<float>(), c.a.axes().cast<float>(), c.a.radii().cast<float>());
    const auto bf = Ellipsoid3<float>::from_axes(c.b.center().cast<float>(), c.b.axes().cast<float>(), c.b.radii().cast<float>());
    auto as_ref = [](const Ellipsoid3<float>& e) {
      return ref::Body<3>{e.center().cast<double>(), e.axes().cast<double>(), e.radii().cast<double>()};
    };
    const auto r = ref::classify<3>(as_ref(af), as_ref(bf), band);
    if (r.margin > 1e-5) {
      ASSERT_EQ(classify(af, bf), from_ref(r.relation)) << describe(c);
    }
  }
}

// The body as every query takes it: its axes replaced by their orthonormal polar factor
// (for float data), here U V^T of Eigen's SVD in double.
template <class T, int N>
ref::Body<N> polar_ref(const Ellipsoid<T, N>& e) {
  const Mat<double, N> axes = e.axes().template cast<double>();
  const Eigen::JacobiSVD<Mat<double, N>> svd(axes, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return ref::Body<N>{e.center().template cast<double>(), svd.matrixU() * svd.matrixV().transpose(),
                      e.radii().template cast<double>()};
}

// Pairs<float, N> (float columns, the float filter, the scalar functions for the pairs it
// leaves open) against the reference at the certificates' margins: float bodies scaled so
// that mu = 1 + delta, |delta| from 1e-8 to 1e-2 (float's rounding is 6e-8), over random
// and high-aspect shapes; the reference takes each float body by polar_ref.
template <int N>
void check_float_batch_at_margins(int n) {
  using E = Ellipsoid<float, N>;
  scenarios::detail::Rng rng(4343);
  Pairs<float, N> pairs;
  std::vector<ref::Classification<N>> want;
  for (int i = 0; i < n; ++i) {
    const auto category = i % 2 == 0 ? scenarios::Category::random : scenarios::Category::high_aspect;
    const auto c = scenarios::make_case<N>(category, 310000 + std::uint64_t(i));
    const E a0 = ellipsect::testing::as<float>(c.a), b0 = ellipsect::testing::as<float>(c.b);
    const double mu = ref::to_double(ref::pw_scale<N>(polar_ref(a0), polar_ref(b0)));
    const double delta = (i % 4 < 2 ? 1 : -1) * std::pow(10.0, scenarios::detail::uniform(rng, -8, -2));
    const double s = mu / (1 + delta);
    const E a = E::from_axes(a0.center(), a0.axes(), (a0.radii().template cast<double>() * s).template cast<float>());
    const E b = E::from_axes(b0.center(), b0.axes(), (b0.radii().template cast<double>() * s).template cast<float>());
    pairs.push_back(a, b);
    want.push_back(ref::classify<N>(polar_ref(a), polar_ref(b), band));
  }
  const std::size_t count = pairs.size();
  const auto overlaps = std::make_unique<bool[]>(count);
  std::vector<Relation> relations(count);
  overlap(pairs, std::span<bool>(overlaps.get(), count));
  classify(pairs, std::span<Relation>(relations));
  const auto columns = ellipsect::testing::columns_of(pairs);
  std::vector<signed char> codes(count);
  detail::certify_pairs(N, detail::BatchQuery::classify, columns.data(), 0, count, Options{}.tolerance, codes.data());
  int decided = 0, by_filter = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (want[i].margin <= band) continue;
    ++decided;
    by_filter += codes[i] != 0;
    const Relation r = from_ref(want[i].relation);
    ASSERT_EQ(relations[i], r) << "pair " << i << " mu=" << ref::to_double(want[i].mu);
    ASSERT_EQ(overlaps[i], r != Relation::separated) << "pair " << i << " mu=" << ref::to_double(want[i].mu);
  }
  EXPECT_GT(decided, n * 9 / 10);
  EXPECT_GT(by_filter, n / 4);  // the filter's own answers are among those checked
}

TEST(ClassifyProperty, FloatBatchMatchesReferenceAtMargins2D) { check_float_batch_at_margins<2>(cases(1000)); }
TEST(ClassifyProperty, FloatBatchMatchesReferenceAtMargins3D) { check_float_batch_at_margins<3>(cases(1000)); }

// Containment at the certificates' margins: containment pairs (b inside a) with a scaled
// about its center so that the reference's containment measure max over b of sqrt(qa)
// becomes 1 - delta, |delta| from 1e-8 to 1e-2 (either side of containment). classify (one
// pair), the batch on double Pairs and the batch on float Pairs (float bodies, the
// reference taking them by polar_ref) must each match the reference.
template <class T, int N>
void check_containment_at_margins(int n) {
  using E = Ellipsoid<T, N>;
  scenarios::detail::Rng rng(4444);
  Pairs<T, N> pairs;
  std::vector<Relation> want;
  for (int i = 0; i < n; ++i) {
    const auto c = scenarios::make_case<N>(scenarios::Category::containment, 320000 + std::uint64_t(i));
    const E a0 = ellipsect::testing::as<T>(c.a), b = ellipsect::testing::as<T>(c.b);
    const double inside = ref::to_double(ref::classify<N>(polar_ref(a0), polar_ref(b), band).b_in_a);
    const double delta = (i % 4 < 2 ? 1 : -1) * std::pow(10.0, scenarios::detail::uniform(rng, -8, -2));
    const auto radii = (a0.radii().template cast<double>() * (inside / (1 - delta))).template cast<T>();
    const E a = E::from_axes(a0.center(), a0.axes(), radii);
    const auto r = ref::classify<N>(polar_ref(a), polar_ref(b), band);
    if (r.margin <= band) continue;
    const Relation expected = from_ref(r.relation);
    ASSERT_EQ(classify(a, b), expected) << describe(c) << " delta=" << delta;
    ASSERT_EQ(classify(b, a), mirrored(expected)) << describe(c) << " delta=" << delta;
    pairs.push_back(a, b);
    want.push_back(expected);
  }
  ASSERT_GT(pairs.size(), std::size_t(n) * 9 / 10);
  std::vector<Relation> relations(pairs.size());
  classify(pairs, std::span<Relation>(relations));
  int contained = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    ASSERT_EQ(relations[i], want[i]) << "pair " << i;
    contained += want[i] == Relation::a_contains_b;
  }
  EXPECT_GT(contained, n / 4);  // both sides of containment occur
  EXPECT_LT(contained, n * 3 / 4);
}

TEST(ClassifyProperty, ContainmentAtMargins2D) { check_containment_at_margins<double, 2>(cases(500)); }
TEST(ClassifyProperty, ContainmentAtMargins3D) { check_containment_at_margins<double, 3>(cases(500)); }
TEST(ClassifyProperty, ContainmentAtMarginsFloatBatch) {
  check_containment_at_margins<float, 2>(cases(300));
  check_containment_at_margins<float, 3>(cases(300));
}

// A body and a bit-identical copy of it are equal, for every valid body: float and double,
// 2D and 3D, random poses and aspect ratios to 1e8; overlap agrees, and in 2D the boundaries
// are reported equal and the overlap is the body's area.
template <class T, int N>
void check_equal_to_itself(int n, std::uint64_t seed) {
  scenarios::detail::Rng rng(seed);
  using namespace scenarios::detail;
  for (int i = 0; i < n; ++i) {
    const Vec<double, N> r = radii<N>(rng, log_uniform(rng, 1e-3, 1e3), log_uniform(rng, 1, 1e8));
    const Vec<double, N> c = unit_vector<N>(rng) * uniform(rng, 0, 100);
    const auto body =
        Ellipsoid<T, N>::from_axes(c.template cast<T>(), rotation<N>(rng).template cast<T>(), r.template cast<T>());
    const Ellipsoid<T, N> copy = body;
    std::ostringstream what;
    what.precision(17);
    what << "i=" << i << " c=" << c.transpose() << " r=" << r.transpose();
    ASSERT_EQ(classify(body, body), Relation::equal) << what.str();
    ASSERT_EQ(classify(body, copy), Relation::equal) << what.str();
    ASSERT_TRUE(overlap(body, copy)) << what.str();
    if constexpr (N == 2) {
      ASSERT_EQ(intersect_boundaries(body, copy).status, BoundaryStatus::equal) << what.str();
      const double area = M_PI * double(body.radii()[0]) * double(body.radii()[1]);
      const double tol = 4 * std::numeric_limits<T>::epsilon() * area;
      ASSERT_NEAR(double(overlap_area(body, copy).area), area, tol) << what.str();
    }
  }
}

TEST(ClassifyProperty, BodyEqualsItself) {
  check_equal_to_itself<double, 2>(cases(500), 11);
  check_equal_to_itself<double, 3>(cases(500), 12);
  check_equal_to_itself<float, 2>(cases(500), 13);
  check_equal_to_itself<float, 3>(cases(500), 14);
}

// Radius ratios from 1e3 to 1e150: a small body at 1e-12, 0.5, 1 -+ 1e-6 or 3 times the
// large body's smallest radius from its center (for balls: near the center, just inside,
// just outside, far away). Swapping the arguments mirrors the answer and
// overlap agrees; up to a ratio of 1e30 the answer matches the reference (beyond, the
// reference's own 50 digits cannot represent 1 - lambda), and for two balls the closed form
// (distance of the centers against the sum and the difference of the radii) at any ratio.
template <int N>
void check_extreme_radius_ratios(int n) {
  scenarios::detail::Rng rng(31415);
  using namespace scenarios::detail;
  for (int i = 0; i < n; ++i) {
    const bool balls = i % 3 == 0;
    const double ratio = std::pow(10.0, uniform(rng, 3, i % 2 == 0 ? 30 : 150));
    const Vec<double, N> ra = balls ? Vec<double, N>::Constant(1) : radii<N>(rng, 1, 10);
    const Vec<double, N> rb = balls ? Vec<double, N>::Constant(1 / ratio) : radii<N>(rng, 1 / ratio, 10);
    const Vec<double, N> dir = unit_vector<N>(rng);
    const double where[] = {1e-12, 0.5, 1 - 1e-6, 1 + 1e-6, 3};
    const double dist = where[i % 5] * (balls ? 1.0 : ra.minCoeff());
    const auto a = Ellipsoid<double, N>::from_axes(Vec<double, N>::Constant(-7.5), rotation<N>(rng), ra);
    const auto b = Ellipsoid<double, N>::from_axes(a.center() + dir * dist, rotation<N>(rng), rb);
    std::ostringstream what;
    what.precision(17);
    what << "i=" << i << " ratio=" << ratio << " dist=" << dist << " a.c=" << a.center().transpose()
         << " b.c=" << b.center().transpose() << " ra=" << ra.transpose() << " rb=" << rb.transpose();
    const Relation got = classify(a, b);
    ASSERT_EQ(classify(b, a), mirrored(got)) << what.str();
    ASSERT_EQ(overlap(a, b), got != Relation::separated) << what.str();
    ASSERT_EQ(overlap(b, a), got != Relation::separated) << what.str();
    if (balls) {
      const double d = (b.center() - a.center()).norm();
      if (d + rb[0] < 1 - 1e-9) {
        ASSERT_EQ(got, Relation::a_contains_b) << what.str();
      } else if (d - rb[0] > 1 + 1e-9) {
        ASSERT_EQ(got, Relation::separated) << what.str();
      } else if (d - rb[0] < 1 - 1e-9 && d + rb[0] > 1 + 1e-9) {
        ASSERT_EQ(got, Relation::overlapping) << what.str();
      }
    } else if (ratio <= 1e30) {
      const auto r = ref::classify<N>(to_ref(a), to_ref(b), band);
      if (r.margin > band) {
        ASSERT_EQ(got, from_ref(r.relation)) << what.str();
      }
    }
  }
}

TEST(ClassifyProperty, SwapSymmetricAtExtremeRadiusRatios2D) { check_extreme_radius_ratios<2>(cases(300)); }
TEST(ClassifyProperty, SwapSymmetricAtExtremeRadiusRatios3D) { check_extreme_radius_ratios<3>(cases(300)); }


// ---- The exact mode: Options::tolerance = 0 ----------------------------------------------
//
// Claim under test (options.hpp, classify.hpp): at tolerance 0, classify and overlap answer
// the exact relation of the bodies as stored (the quadrics of the stored centers, axes as
// given (float: their polar factor in double) and radii), float and double, either argument order, and the batch classify the
// same. Referee: ref::classify_stored, the stored quadrics in 50 digits (not the
// re-orthonormalised axes of ref::classify, which move a body by about an ulp). A pair is
// decided where the referee's margin exceeds 1e-40, or where it finds the bodies equal
// (identical copies); the others, exact tangencies that 50 digits cannot tell from 1, are
// counted. Pairs: every scenario category (aspect ratios to 1e4), and pairs steered from
// the random, high-aspect and containment scenarios to relative gaps of +-1e-15, 1e-17 and
// 1e-20 (float data: 1e-9, 1e-11, 1e-13) from external or internal tangency.

constexpr double referee_floor = 1e-40;

// The stored body in double; float axes as the exact mode defines them (classify.hpp):
// their orthonormal polar factor in double, the axes every query computes with.
template <class T, int N>
ref::Body<N> stored(const Ellipsoid<T, N>& e) {
  return {e.center().template cast<double>(), detail::work_axes<double>(e), e.radii().template cast<double>()};
}

// The tangency a steered pair approaches: from outside (the contact scale mu of the stored
// bodies) or b inside a (the largest value of a's gauge on b's boundary).
enum class Tangency { external, internal };

template <class T, int N>
ref::Real tangency_measure(Tangency t, const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) {
  const auto ra = ref::detail::make_stored_rbody<N>(stored(a)), rb = ref::detail::make_stored_rbody<N>(stored(b));
  if (t == Tangency::internal) return ref::detail::metric_range_impl<N>(ra, rb).max;
  return sqrt(ref::detail::pw_solve<N>(ra.P, rb.P, ref::RVec<N>(rb.c - ra.c)).F);
}

// The pair (a, b) with centers and radii moved by a few ulps each, chosen so that the
// tangency measure is about 1 + target: the measure is linear in ulp steps to about 1e-31
// (double), so its first differences, one reference evaluation per value, predict every
// combination of steps, and a meet in the middle over steps in [-m, m] (m = 3 in 2D, 2 in
// 3D: 7^8 and 5^12 combinations) finds the one closest to the target.
template <class T, int N>
std::pair<Ellipsoid<T, N>, Ellipsoid<T, N>> steered(Tangency t, const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                    double target) {
  using E = Ellipsoid<T, N>;
  std::vector<T> p;
  for (int i = 0; i < N; ++i) p.push_back(a.center()[i]);
  for (int i = 0; i < N; ++i) p.push_back(a.radii()[i]);
  for (int i = 0; i < N; ++i) p.push_back(b.center()[i]);
  for (int i = 0; i < N; ++i) p.push_back(b.radii()[i]);
  auto pair_of = [&](const std::vector<T>& q) {
    auto v = [&](int k) { return Vec<T, N>(Eigen::Map<const Vec<T, N>>(q.data() + k * N)); };
    return std::pair<E, E>(E::from_axes(v(0), a.axes(), v(1)), E::from_axes(v(2), b.axes(), v(3)));
  };
  auto gap = [&](const std::vector<T>& q) {
    const auto [qa, qb] = pair_of(q);
    return tangency_measure<T, N>(t, qa, qb) - 1;
  };
  const int m = N == 2 ? 3 : 2;
  const ref::Real g0 = gap(p);
  // Usable values: nonzero, and m ulps either way on one uniform grid (no power of 2 crossed).
  std::vector<int> index;
  std::vector<double> slope;
  std::vector<T> ulp;
  for (int i = 0; i < int(p.size()); ++i) {
    const T u = std::nextafter(p[i], std::numeric_limits<T>::infinity()) - p[i];
    T lo = p[i], hi = p[i];
    for (int k = 0; k < m; ++k) {
      lo = std::nextafter(lo, -std::numeric_limits<T>::infinity());
      hi = std::nextafter(hi, std::numeric_limits<T>::infinity());
    }
    if (p[i] == 0 || hi - p[i] != m * u || p[i] - lo != m * u) continue;
    std::vector<T> q = p;
    q[i] += u;
    index.push_back(i);
    ulp.push_back(u);
    slope.push_back(ref::to_double(gap(q) - g0));
  }
  // Sums of the predicted changes over the steps of one half of the values.
  const int count = int(index.size()), half = count / 2;
  auto sums = [&](int from, int to) {
    std::vector<std::pair<double, std::vector<int>>> out{{0.0, {}}};
    for (int i = from; i < to; ++i) {
      std::vector<std::pair<double, std::vector<int>>> next;
      for (const auto& [s, steps] : out)
        for (int k = -m; k <= m; ++k) {
          auto with = steps;
          with.push_back(k);
          next.emplace_back(s + k * slope[std::size_t(i)], std::move(with));
        }
      out = std::move(next);
    }
    return out;
  };
  const auto first = sums(0, half);
  auto second = sums(half, count);
  std::sort(second.begin(), second.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  const double want = target - ref::to_double(g0);
  double best = std::numeric_limits<double>::infinity();
  const std::vector<int>*best_first = nullptr, *best_second = nullptr;
  for (const auto& f : first) {
    auto it = std::lower_bound(second.begin(), second.end(), want - f.first,
                               [](const auto& x, double v) { return x.first < v; });
    for (auto j = it == second.begin() ? it : it - 1; j != second.end() && j <= it; ++j) {
      const double miss = std::abs(f.first + j->first - want);
      if (miss < best) best = miss, best_first = &f.second, best_second = &j->second;
    }
  }
  std::vector<T> q = p;
  for (int i = 0; i < count; ++i) {
    const int k = i < half ? (*best_first)[std::size_t(i)] : (*best_second)[std::size_t(i - half)];
    q[std::size_t(index[std::size_t(i)])] += T(k) * ulp[std::size_t(i)];
  }
  return pair_of(q);
}

// Checks one pair at tolerance 0 against the referee (both orders, classify and overlap)
// where it decides; returns the referee's classification.
template <class T, int N>
ref::Classification<N> check_exact_pair(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& exact,
                                        const std::string& where, AnswerCount& answers) {
  const auto r = ref::classify_stored<N>(stored(a), stored(b), referee_floor);
  const Relation want = from_ref(r.relation);
  if (!(r.margin > referee_floor) && want != Relation::equal) return r;
  std::ostringstream w;
  w.precision(3);
  w << where << "\n  (mu - 1 = " << ref::to_double(r.mu - 1) << ", b in a - 1 = " << ref::to_double(r.b_in_a - 1)
    << ", a in b - 1 = " << ref::to_double(r.a_in_b - 1) << ", margin " << ref::to_double(r.margin) << ")";
  answers.check(w.str(), "classify(a, b)", want, classify(a, b, exact));
  answers.check(w.str(), "classify(b, a)", mirrored(want), classify(b, a, exact));
  answers.check(w.str(), "overlap(a, b)", want != Relation::separated, overlap(a, b, exact));
  answers.check(w.str(), "overlap(b, a)", want != Relation::separated, overlap(b, a, exact));
  return r;
}

template <class T, int N>
void check_exact_against_reference(int per_category, int steered_bases) {
  using E = Ellipsoid<T, N>;
  const Options exact = exact_options;
  const std::string type = sizeof(T) == sizeof(double) ? "double" : "float";
  AnswerCount answers;
  Tally tally;
  Pairs<T, N> pairs;
  std::vector<Relation> wants;
  std::vector<std::string> wheres;
  // group: the category, or for a steered pair the tangency and the decade of its gap.
  auto check = [&](const E& a, const E& b, std::optional<Tangency> t, std::string group, const std::string& where) {
    const auto r = check_exact_pair<T, N>(a, b, exact, where, answers);
    const Relation want = from_ref(r.relation);
    if (t) {
      const double gap = ref::to_double((*t == Tangency::external ? r.mu : r.b_in_a) - 1);
      group += gap == 0 ? "0" : "1e" + std::to_string(int(std::floor(std::log10(std::abs(gap)))));
    }
    const bool decided = r.margin > referee_floor || want == Relation::equal;
    tally.add(group, decided ? std::string(to_string(want)) : "undecided");
    if (!decided) return;
    pairs.push_back(a, b);
    wants.push_back(want);
    wheres.push_back(where);
  };
  for (const auto category : scenarios::all_categories)
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_case<N>(category, 400000 + std::uint64_t(i));
      check(as<T>(c.a), as<T>(c.b), std::nullopt, std::string(scenarios::name(category)), describe(c));
    }
  const std::vector<double> targets =
      sizeof(T) == sizeof(double) ? std::vector<double>{1e-15, 1e-17, 1e-20} : std::vector<double>{1e-9, 1e-11, 1e-13};
  for (int i = 0; i < steered_bases; ++i) {
    const Tangency t = i % 2 == 0 ? Tangency::external : Tangency::internal;
    const auto category = t == Tangency::internal ? scenarios::Category::containment
                          : i % 4 == 0            ? scenarios::Category::random
                                                  : scenarios::Category::high_aspect;
    const auto c = scenarios::make_case<N>(category, 410000 + std::uint64_t(i));
    const E a0 = as<T>(c.a), b0 = as<T>(c.b);
    // Onto the tangency, to the rounding of T: both bodies scaled by mu about their centers
    // (external), or a by its measure of b (internal).
    const double s = ref::to_double(tangency_measure<T, N>(t, a0, b0));
    auto scaled = [&](const E& e) {
      return E::from_axes(e.center(), e.axes(), (e.radii().template cast<double>() * s).template cast<T>());
    };
    const E a1 = scaled(a0), b1 = t == Tangency::external ? scaled(b0) : b0;
    for (const double target : targets)
      for (const double sign : {1.0, -1.0}) {
        const auto [a, b] = steered<T, N>(t, a1, b1, sign * target);
        std::ostringstream where;
        where << describe(c) << "\n  steered to " << (t == Tangency::external ? "mu" : "b's measure in a")
              << " = 1 + " << sign * target << ":";
        where.precision(std::numeric_limits<T>::max_digits10);
        where << "\n  a: c=" << a.center().transpose() << " r=" << a.radii().transpose()
              << "\n  b: c=" << b.center().transpose() << " r=" << b.radii().transpose();
        check(a, b, t, t == Tangency::external ? "steered external, gap " : "steered internal, gap ", where.str());
      }
  }
  std::vector<Relation> got(pairs.size());
  classify(pairs, std::span<Relation>(got), BatchOptions{.query = exact});
  for (std::size_t i = 0; i < pairs.size(); ++i) answers.check(wheres[i], "batch classify", wants[i], got[i]);
  tally.print("exact classify vs the stored-body reference, " + type + " N=" + std::to_string(N));
  answers.report("exact classify vs the stored-body reference, " + type + " N=" + std::to_string(N));
  EXPECT_GT(int(pairs.size()), (per_category * 10 + steered_bases * 6) * 8 / 10);  // most are decided
}

TEST(ClassifyProperty, ExactModeMatchesStoredReference2D) {
  check_exact_against_reference<double, 2>(cases(60), cases(30));
  check_exact_against_reference<float, 2>(cases(60), cases(30));
}
TEST(ClassifyProperty, ExactModeMatchesStoredReference3D) {
  check_exact_against_reference<double, 3>(cases(60), cases(30));
  check_exact_against_reference<float, 3>(cases(60), cases(30));
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
