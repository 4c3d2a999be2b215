// perram_wertheim and closest_approach against the 50-digit reference (tests/reference/
// contact_function_reference.hpp: golden-section maximization of F(lambda) in the world
// frame; sigma as the root of an overlap test built on the extrema of a's quadric over b's
// boundary, which does not use F).
//
// Claims under test (contact_function.hpp):
//   F relative error <= 1e-12, lambda within 1e-10 min(lambda, 1 - lambda) + 1e-12;
//   sigma relative error <= 1e-12, the point on a's boundary and on b's (b at
//   center(a) + sigma u) within 1e-12 (sigma + radii), the normal parallel to both
//   gradients there within 1e-12 (sigma + radii) / (smallest radius of curvature) rad;
//   sign(F - 1) agrees with classify outside |sqrt(F) - 1| <= 2 tolerance + 1e-12, and a pair
//   classify calls touching has F within that band of 1;
//   swapping a and b gives the same F bit for bit, lambda -> 1 - lambda, and sigma along -u
//   bit for bit;
//   sigma equals L - t, t the first-contact time of b moving with velocity -u from
//   center(a) + L u (L = 4 sigma + the radii), to first_contact's accuracy where the
//   approach is not grazing;
// on the scenario categories random, high_aspect, near_tangent, containment, spheres (equal
// radii, identical and concentric bodies), scaled_small, scaled_large, far_apart, and pairs
// built at F within 1e-12 of 1.
#include <ellipsect/contact_function.hpp>

#include "common.hpp"
#include "tests/reference/contact_function_reference.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using Real = ref::Real;
template <int N> using RVec = Eigen::Matrix<Real, N, 1>;

constexpr std::array<scenarios::Category, 8> categories = {
    scenarios::Category::random,       scenarios::Category::high_aspect,  scenarios::Category::near_tangent,
    scenarios::Category::containment,  scenarios::Category::spheres,      scenarios::Category::scaled_small,
    scenarios::Category::scaled_large, scenarios::Category::far_apart};

// The rounding band of the comparison with classify (the header's claim).
constexpr double band = 2 * Options{}.tolerance + 1e-12;

// Largest errors seen, relative to each claim's scale, printed with the tally.
struct Worst {
  double f = 0, lambda = 0, sigma = 0, point = 0, normal = 0, first_contact = 0;
  int compared_with_first_contact = 0;
  void print() const {
    std::printf("  largest errors: F %.2g, lambda %.2g, sigma %.2g (relative); point %.2g (of sigma + radii), "
                "normal %.2g (of the allowed turn); sigma vs first_contact %.2g (of L), %d pairs\n",
                f, lambda, sigma, point, normal, first_contact, compared_with_first_contact);
  }
};

// A direction drawn from the case's seed.
template <int N>
Vec<double, N> direction_of(const scenarios::Case<N>& c) {
  scenarios::detail::Rng rng(c.seed ^ 0xD1EC7ull);
  return scenarios::detail::unit_vector<N>(rng) * scenarios::detail::log_uniform(rng, 1e-3, 1e3);
}

// Off-boundary distance of p from e (first order) and e's outward unit normal there, in 50 digits.
template <int N>
double off_boundary(const Ellipsoid<double, N>& e, const RVec<N>& center, const Vec<double, N>& p, RVec<N>& normal) {
  const Eigen::Matrix<Real, N, N> axes = e.axes().template cast<Real>();
  const RVec<N> d = axes.transpose() * (p.template cast<Real>() - center);
  const RVec<N> r = e.radii().template cast<Real>();
  const Real q = sqrt(d.cwiseQuotient(r).squaredNorm());
  const RVec<N> grad = axes * (d.cwiseQuotient(r.cwiseAbs2()) / q);
  normal = grad / grad.norm();
  return ref::to_double(abs(q - 1) / grad.norm());
}

template <int N>
void check_consistent_with_classify(const scenarios::Case<N>& c, double f) {
  const double mu = std::sqrt(f);
  const Relation rel = classify(c.a, c.b);
  if (mu > 1 + band) {
    ASSERT_EQ(rel, Relation::separated) << describe(c);
  }
  if (mu < 1 - band) {
    ASSERT_TRUE(rel != Relation::separated && rel != Relation::touching) << describe(c);
  }
  if (rel == Relation::touching) {
    ASSERT_LE(std::abs(mu - 1), band) << describe(c);
  }
}

template <int N>
void check_perram_wertheim(const scenarios::Case<N>& c, Tally& tally, Worst& worst) {
  const auto got = perram_wertheim(c.a, c.b);
  if (c.a.center() == c.b.center()) {
    ASSERT_EQ(got.status, ContactFunctionStatus::concentric) << describe(c);
    ASSERT_EQ(got.f, 0.0);
    ASSERT_TRUE(std::isnan(got.lambda));
    tally.add(scenarios::name(c.category), "concentric");
    return;
  }
  ASSERT_EQ(got.status, ContactFunctionStatus::ok) << describe(c);
  ASSERT_EQ(got.f_upper, got.f);
  const auto r = ref::contact_function<N>(to_ref(c.a), to_ref(c.b));
  const double f = ref::to_double(r.f), lambda = ref::to_double(r.lambda);
  tally.add(scenarios::name(c.category), f > 1 ? "apart" : "overlap");
  ASSERT_LE(std::abs(got.f - f), 1e-12 * f) << describe(c);
  ASSERT_LE(std::abs(got.lambda - lambda), 1e-10 * std::min(lambda, 1 - lambda) + 1e-12) << describe(c);
  worst.f = std::max(worst.f, std::abs(got.f - f) / f);
  worst.lambda = std::max(worst.lambda, std::abs(got.lambda - lambda) / std::min(lambda, 1 - lambda));
  const auto sw = perram_wertheim(c.b, c.a);
  ASSERT_EQ(sw.f, got.f) << describe(c);
  ASSERT_NEAR(sw.lambda, 1 - got.lambda, 4e-16) << describe(c);
  check_consistent_with_classify(c, got.f);
}

template <int N>
void check_closest_approach(const scenarios::Case<N>& c, Worst& worst) {
  const Vec<double, N> dir = direction_of(c);
  const auto got = closest_approach(c.a, c.b, dir);
  ASSERT_EQ(got.status, ContactFunctionStatus::ok) << describe(c);
  ASSERT_EQ(got.distance_lower, got.distance);
  const double sigma = ref::to_double(ref::closest_approach<N>(to_ref(c.a), to_ref(c.b), dir));
  ASSERT_LE(std::abs(got.distance - sigma), 1e-12 * sigma) << describe(c) << "\n  u=" << dir.transpose();
  worst.sigma = std::max(worst.sigma, std::abs(got.distance - sigma) / sigma);

  // The point touches both bodies, with the normal of both surfaces.
  const double size = sigma + c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
  const RVec<N> u = dir.template cast<Real>() / dir.template cast<Real>().norm();
  RVec<N> na, nb;
  const double off_a = off_boundary(c.a, RVec<N>(c.a.center().template cast<Real>()), got.point, na);
  const RVec<N> cb = c.a.center().template cast<Real>() + Real(sigma) * u;
  const double off_b = off_boundary(c.b, cb, got.point, nb);
  ASSERT_LE(off_a, 1e-12 * size) << describe(c);
  ASSERT_LE(off_b, 1e-12 * size) << describe(c);
  // The angle by which a move of the point by 1e-12 size turns the normal: over the
  // smallest radius of curvature r_min^2 / r_max of the two bodies.
  auto curvature = [](const Ellipsoid<double, N>& e) { return e.radii().maxCoeff() / std::pow(e.radii().minCoeff(), 2); };
  const double allowed = 1e-12 * size * std::max(curvature(c.a), curvature(c.b)) + 1e-14;
  const double turn = ref::to_double(std::max((na - got.normal.template cast<Real>()).norm(),
                                              (nb + got.normal.template cast<Real>()).norm()));
  ASSERT_LE(turn, allowed) << describe(c);
  worst.point = std::max(worst.point, std::max(off_a, off_b) / size);
  worst.normal = std::max(worst.normal, turn / allowed);

  // b approaching a along -u from far away first touches it at L - sigma.
  const auto sw = closest_approach(c.b, c.a, Vec<double, N>(-dir));
  ASSERT_EQ(sw.distance, got.distance) << describe(c);
  const double along = got.normal.dot(dir.normalized());
  if (along >= 1e-3) {
    const double L = 4 * sigma + c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
    const Vec<double, N> u_d = dir.normalized();
    const auto moved = c.b.translated(Vec<double, N>(c.a.center() + L * u_d - c.b.center()));
    const auto fc = first_contact(c.a, Vec<double, N>::Zero(), moved, Vec<double, N>(-u_d), 2 * L);
    ASSERT_EQ(fc.status, ContactStatus::hit) << describe(c);
    ASSERT_LE(std::abs((L - fc.time) - got.distance), 1e-12 * L + 1e-12 * sigma) << describe(c);
    worst.first_contact = std::max(worst.first_contact, std::abs((L - fc.time) - got.distance) / L);
    ++worst.compared_with_first_contact;
  }
}

template <int N>
void check_against_reference(int per_category) {
  Tally tally;
  Worst worst;
  for (const auto category : categories)
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_case<N>(category, static_cast<std::uint64_t>(i));
      check_perram_wertheim<N>(c, tally, worst);
      check_closest_approach<N>(c, worst);
      if (::testing::Test::HasFatalFailure()) return;
    }
  tally.print("perram_wertheim vs reference, N=" + std::to_string(N));
  worst.print();
  for (const char* cat : {"random", "high_aspect", "near_tangent", "scaled_small", "scaled_large"}) {
    EXPECT_GT(tally.count(cat, "apart"), per_category / 10) << cat;
    EXPECT_GT(tally.count(cat, "overlap"), per_category / 10) << cat;
  }
  EXPECT_EQ(tally.count("containment", "overlap"), per_category);
  EXPECT_EQ(tally.count("far_apart", "apart"), per_category);
  EXPECT_GT(tally.count("spheres", "concentric"), 0);
}

TEST(ContactFunctionProperty, MatchesReference2D) { check_against_reference<2>(cases(150)); }
TEST(ContactFunctionProperty, MatchesReference3D) { check_against_reference<3>(cases(150)); }

// Pairs at F within 1e-12 of 1: b placed at center(a) + sigma (1 + delta) u, sigma from the
// reference, |delta| in [1e-15, 5e-13]; the reference F of the pair as built decides.
template <int N>
void near_contact(int count) {
  int apart = 0, overlapping = 0;
  for (int i = 0; i < count; ++i) {
    auto c = scenarios::make_case<N>(i % 3 == 0 ? scenarios::Category::high_aspect : scenarios::Category::random,
                                     static_cast<std::uint64_t>(5000 + i));
    scenarios::detail::Rng rng(static_cast<std::uint64_t>(i) * 77 + 1);
    const Vec<double, N> u = scenarios::detail::unit_vector<N>(rng);
    const double delta = (i % 2 == 0 ? -1 : 1) * scenarios::detail::log_uniform(rng, 1e-15, 5e-13);
    const double sigma = ref::to_double(ref::closest_approach<N>(to_ref(c.a), to_ref(c.b), u));
    c.b = c.b.translated(Vec<double, N>(c.a.center() + sigma * (1 + delta) * u - c.b.center()));
    const auto r = ref::contact_function<N>(to_ref(c.a), to_ref(c.b));
    const double f = ref::to_double(r.f);
    ASSERT_LE(std::abs(f - 1), 1.2e-12) << describe(c);
    const auto got = perram_wertheim(c.a, c.b);
    ASSERT_EQ(got.status, ContactFunctionStatus::ok) << describe(c);
    ASSERT_LE(std::abs(got.f - f), 1e-12 * f) << describe(c);
    ASSERT_LE(std::abs(got.lambda - ref::to_double(r.lambda)), 1e-10 * std::min(got.lambda, 1 - got.lambda) + 1e-12)
        << describe(c);
    check_consistent_with_classify(c, got.f);
    (f > 1 ? apart : overlapping)++;
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(apart, count / 4);
  EXPECT_GT(overlapping, count / 4);
}

TEST(ContactFunctionProperty, NearContact2D) { near_contact<2>(cases(60)); }
TEST(ContactFunctionProperty, NearContact3D) { near_contact<3>(cases(60)); }

// Needles and discs of aspect ratio A = 1e4..1e8 (the largest accepted), every pair of the
// two shapes, touching (relative gaps 1e-9..1e-1 either way) or placed at random: F and
// sigma (along a random direction) within 1e-12 + 2 eps A relative (A the larger aspect
// ratio of the two), lambda within 1e-10 min(lambda, 1 - lambda) + 1e-12 up to A = 1e4 and
// 1e-12 A min(lambda, 1 - lambda) + 1e-12 beyond; F bit for bit under swapping
// (contact_function.hpp).
template <int N>
void high_aspect(int per_aspect) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  std::map<std::string, double> worst;
  for (const double aspect : {1e4, 1e5, 1e6, 1e7, 1e8}) {
    const double A = aspect * 0.99;  // within max_aspect_ratio after the draws below
    for (int i = 0; i < per_aspect; ++i) {
      scenarios::detail::Rng rng(static_cast<std::uint64_t>(i) * 131 + static_cast<std::uint64_t>(std::log10(aspect)));
      auto shape = [&](int kind) {
        const double size = scenarios::detail::log_uniform(rng, 0.3, 3);
        Vec<double, N> r = Vec<double, N>::Constant(size);
        r[N - 1] = size / A;  // a disc (3D) or a needle (2D)
        if (kind == 1) r.template head<N - 1>().template tail<1>()[0] = size * 1.001 / A;  // a needle (3D)
        if (kind == 0) r[0] = size * scenarios::detail::log_uniform(rng, 1, 1.0 / 0.99);
        return r;
      };
      const Vec<double, N> ra = shape(i % 2), rb = shape((i / 2) % 2);
      const auto a = Ellipsoid<double, N>::from_axes(scenarios::detail::unit_vector<N>(rng),
                                                     scenarios::detail::rotation<N>(rng), ra);
      const Mat<double, N> axes_b = scenarios::detail::rotation<N>(rng);
      const double gap = (i % 4 < 2 ? -1 : 1) * scenarios::detail::log_uniform(rng, 1e-9, 1e-1);
      const Vec<double, N> cb =
          i % 3 != 0 ? scenarios::detail::tangent_center<N>(a, scenarios::detail::unit_vector<N>(rng), axes_b, rb, gap)
                     : Vec<double, N>(a.center() + scenarios::detail::unit_vector<N>(rng) * (ra.maxCoeff() + rb.maxCoeff()) *
                                                       scenarios::detail::uniform(rng, 0, 1));
      const auto b = Ellipsoid<double, N>::from_axes(cb, axes_b, rb);
      const double largest = std::max(ra.maxCoeff() / ra.minCoeff(), rb.maxCoeff() / rb.minCoeff());
      const double bound = 1e-12 + 2 * eps * largest;
      std::ostringstream what;
      what.precision(17);
      what << "high aspect " << aspect << " case " << i << " (rerun with its seed)\n  a: c=" << a.center().transpose()
           << " r=" << ra.transpose() << "\n  b: c=" << cb.transpose() << " r=" << rb.transpose();
      const auto got = perram_wertheim(a, b);
      ASSERT_EQ(got.status, ContactFunctionStatus::ok) << what.str();
      const auto want = ref::contact_function<N>(to_ref(a), to_ref(b));
      const double f = ref::to_double(want.f), lambda = ref::to_double(want.lambda);
      ASSERT_LE(std::abs(got.f - f), bound * f) << what.str();
      const double lambda_bound = (largest <= 1e4 ? 1e-10 : 1e-12 * largest) * std::min(lambda, 1 - lambda) + 1e-12;
      ASSERT_LE(std::abs(got.lambda - lambda), lambda_bound) << what.str();
      const auto swapped = perram_wertheim(b, a);
      ASSERT_EQ(swapped.f, got.f) << what.str();
      const Vec<double, N> u = scenarios::detail::unit_vector<N>(rng);
      const auto ca = closest_approach(a, b, u);
      const double sigma = ref::to_double(ref::closest_approach<N>(to_ref(a), to_ref(b), u));
      ASSERT_EQ(ca.status, ContactFunctionStatus::ok) << what.str();
      ASSERT_LE(std::abs(ca.distance - sigma), bound * sigma) << what.str();
      const std::string bin = "aspect 1e" + std::to_string(int(std::lround(std::log10(aspect))));
      worst[bin + " F"] = std::max(worst[bin + " F"], std::abs(got.f - f) / f);
      worst[bin + " sigma"] = std::max(worst[bin + " sigma"], std::abs(ca.distance - sigma) / sigma);
      worst[bin + " lambda"] = std::max(worst[bin + " lambda"], std::abs(got.lambda - lambda) / std::min(lambda, 1 - lambda));
    }
  }
  std::printf("high aspect %dD, largest relative errors:", N);
  for (const auto& [what, e] : worst) std::printf(" %s %.2g;", what.c_str(), e);
  std::printf("\n");
}

TEST(ContactFunctionProperty, HighAspect2D) { high_aspect<2>(cases(40)); }
TEST(ContactFunctionProperty, HighAspect3D) { high_aspect<3>(cases(40)); }

// float bodies: computed in double from the float data, so against the reference of the
// float bodies (converted exactly), to the rounding of float axes (orthonormal to ~1e-7).
template <int N>
void floats(int count) {
  for (int i = 0; i < count; ++i) {
    const auto c = scenarios::make_case<N>(scenarios::Category::random, static_cast<std::uint64_t>(i));
    auto to_float = [](const Ellipsoid<double, N>& e) {
      return Ellipsoid<float, N>::from_axes(e.center().template cast<float>(), e.axes().template cast<float>(),
                                            e.radii().template cast<float>());
    };
    auto back = [](const Ellipsoid<float, N>& e) {
      return ref::Body<N>{e.center().template cast<double>(), e.axes().template cast<double>(),
                          e.radii().template cast<double>()};
    };
    const auto a = to_float(c.a), b = to_float(c.b);
    const auto got = perram_wertheim(a, b);
    ASSERT_EQ(got.status, ContactFunctionStatus::ok) << describe(c);
    const double f = ref::to_double(ref::contact_function<N>(back(a), back(b)).f);
    ASSERT_LE(std::abs(got.f - f), 1e-5 * f) << describe(c);
    const Vec<float, N> dir = direction_of(c).template cast<float>();
    const auto ca = closest_approach(a, b, dir);
    const double sigma = ref::to_double(ref::closest_approach<N>(back(a), back(b), dir.template cast<double>()));
    ASSERT_LE(std::abs(ca.distance - sigma), 1e-5 * sigma) << describe(c);
  }
}

TEST(ContactFunctionProperty, Float2D) { floats<2>(20); }
TEST(ContactFunctionProperty, Float3D) { floats<3>(20); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
