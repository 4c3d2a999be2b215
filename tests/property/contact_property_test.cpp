// first_contact against the 50-digit reference: the first t with Perram-Wertheim factor
// mu(t) = 1, found by golden-section minimization of the quasi-convex mu(t) and bracketed
// root finding; contact point from the PW construction. Independent of the library's
// Newton on the reduced distance.
//
// Claims under test (contact.hpp), for non-grazing approach (sin of the angle between the
// relative velocity and the contact plane >= 1e-3):
//   status exact outside the 2 * tolerance band; time error <= 1e-12 * max(t, scale / speed);
//   point within 1e-10 * scale; normal within 1e-9 rad.
// Grazing paths: status exact outside the band (on min mu over the window).
#include "common.hpp"

#include <cmath>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;

constexpr double band = 2 * Options{}.tolerance;

ContactStatus from_ref(ref::ContactKind k) {
  switch (k) {
    case ref::ContactKind::hit: return ContactStatus::hit;
    case ref::ContactKind::touching_at_start: return ContactStatus::touching_at_start;
    case ref::ContactKind::overlapping_at_start: return ContactStatus::overlapping_at_start;
    case ref::ContactKind::none: return ContactStatus::no_contact_in_window;
  }
  return ContactStatus::invalid_input;
}

template <int N>
Ellipsoid<double, N> at_time(const Ellipsoid<double, N>& e, const Vec<double, N>& v, double t) {
  return e.translated(v * t);
}

template <int N>
void check_case(const scenarios::Case<N>& c, Tally& tally) {
  const auto got = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
  const auto r = ref::first_contact<N>(to_ref(c.a), c.va, to_ref(c.b), c.vb, c.t_max, band);
  const ContactStatus want = from_ref(r.kind);
  const std::string cat(scenarios::name(c.category));
  ASSERT_NE(got.status, ContactStatus::did_not_converge) << describe(c);
  ASSERT_NE(got.status, ContactStatus::invalid_input) << describe(c);

  // Swapping the bodies: identical time and point, reversed normal.
  const auto sw = first_contact(c.b, c.vb, c.a, c.va, c.t_max);
  ASSERT_EQ(sw.status, got.status) << describe(c);
  if (got.status == ContactStatus::hit) {
    ASSERT_EQ(sw.time, got.time) << describe(c);
    ASSERT_EQ(sw.point, got.point) << describe(c);
    ASSERT_EQ(sw.normal, (Vec<double, N>(-got.normal))) << describe(c);
  }

  // Start state undecidable inside the band; "none" vs "hit" undecidable when the
  // smallest mu over the window is inside it.
  const double mu0 = ref::to_double(ref::pw_scale<N>(to_ref(c.a), to_ref(c.b)));
  if (std::abs(mu0 - 1) <= band) {
    tally.add(cat, "in_band_at_start");
    return;
  }
  if (want == ContactStatus::no_contact_in_window || want == ContactStatus::hit) {
    if (std::abs(ref::to_double(r.min_mu) - 1) <= band) {
      tally.add(cat, "in_band_grazing");
      return;
    }
  }
  tally.add(cat, std::string(to_string(want)));
  ASSERT_EQ(got.status, want) << describe(c) << "\n  ref time=" << ref::to_double(r.time)
                              << " min_mu=" << ref::to_double(r.min_mu) << " got time=" << got.time;
  if (want != ContactStatus::hit) return;

  const Vec<double, N> v = c.vb - c.va;
  const double scale = std::max(c.a.radii().maxCoeff(), c.b.radii().maxCoeff());
  const double t_ref = ref::to_double(r.time);
  const Vec<double, N> n_ref = ref::to_double<N>(r.normal);
  const double sin_angle = std::abs(n_ref.dot(v.normalized()));
  if (sin_angle < 1e-3) {  // grazing: time is sqrt-conditioned; status checked above
    tally.add(cat, "grazing_hit");
    return;
  }
  const double time_tol = 1e-12 * std::max(t_ref, scale / v.norm());
  EXPECT_LE(std::abs(got.time - t_ref), time_tol) << describe(c) << "\n  t_ref=" << t_ref << " got=" << got.time;
  EXPECT_LE((got.point - ref::to_double<N>(r.point)).norm(), 1e-10 * scale) << describe(c);
  const double angle = 2 * std::asin(std::min(1.0, (got.normal - n_ref.normalized()).norm() / 2));
  EXPECT_LE(std::abs(angle), 1e-9) << describe(c);
}

template <int N>
void run(int per_category) {
  Tally tally;
  for (const auto category : scenarios::all_categories)
    for (int i = 0; i < per_category; ++i) {
      check_case(scenarios::make_case<N>(category, 300000 + i), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  tally.print("first_contact vs reference (scenario mix), N=" + std::to_string(N));
}

// Constructed contacts: each pair touches at a chosen time t0 under a chosen approach
// angle (down to sin = 1e-3), so most cases are hits and the accuracy claims are
// exercised on every category.
template <int N>
void run_constructed(int per_category) {
  Tally tally;
  for (const auto category : scenarios::all_categories) {
    if (category == scenarios::Category::grazing || category == scenarios::Category::zero_velocity) continue;
    for (int i = 0; i < per_category; ++i) {
      check_case(scenarios::make_contact_case<N>(category, 400000 + i, 1e-3), tally);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  tally.print("first_contact vs reference (constructed contacts), N=" + std::to_string(N));
}

TEST(ContactProperty, ScenarioMix2D) { run<2>(cases(500)); }
TEST(ContactProperty, ScenarioMix3D) { run<3>(cases(500)); }
TEST(ContactProperty, ConstructedContacts2D) { run_constructed<2>(cases(200)); }
TEST(ContactProperty, ConstructedContacts3D) { run_constructed<3>(cases(200)); }

// Just before the reported time the bodies are apart, just after they overlap.
template <int N>
void check_flip(int n) {
  int checked = 0;
  for (int i = 0; i < n; ++i) {
    const auto c = scenarios::make_contact_case<N>(scenarios::Category::random, 500000 + i, 0.1);
    const auto got = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
    if (got.status != ContactStatus::hit) continue;
    const double eps = 1e-8 * std::max(c.a.radii().maxCoeff(), c.b.radii().maxCoeff()) / (c.vb - c.va).norm();
    if (got.time < 2 * eps) continue;
    ++checked;
    EXPECT_FALSE(overlap(at_time(c.a, c.va, got.time - eps), at_time(c.b, c.vb, got.time - eps))) << describe(c);
    EXPECT_TRUE(overlap(at_time(c.a, c.va, got.time + eps), at_time(c.b, c.vb, got.time + eps))) << describe(c);
  }
  EXPECT_GT(checked, n / 2);
}

TEST(ContactProperty, OverlapFlipsAtContactTime2D) { check_flip<2>(cases(300)); }
TEST(ContactProperty, OverlapFlipsAtContactTime3D) { check_flip<3>(cases(300)); }

// Scaling space by a power of two (positions, radii, velocities) leaves the time and
// status identical and scales the point exactly; a rigid motion of the whole scene
// moves the point and normal with it, the time unchanged (to the stated accuracy).
template <int N>
void check_invariance(int n) {
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    const auto c = scenarios::make_contact_case<N>(scenarios::Category::random, 600000 + i, 0.05);
    const auto got = first_contact(c.a, c.va, c.b, c.vb, c.t_max);
    ASSERT_NE(got.status, ContactStatus::did_not_converge) << describe(c);
    for (double s : {0x1p-30, 0x1p30}) {
      auto scale = [s](const Ellipsoid<double, N>& e) {
        return Ellipsoid<double, N>::from_axes(e.center() * s, e.axes(), e.radii() * s);
      };
      const auto sc = first_contact(scale(c.a), Vec<double, N>(c.va * s), scale(c.b), Vec<double, N>(c.vb * s), c.t_max);
      ASSERT_EQ(sc.status, got.status) << describe(c);
      if (got.status != ContactStatus::hit) continue;
      ASSERT_EQ(sc.time, got.time) << describe(c);
      ASSERT_EQ(sc.point, (Vec<double, N>(got.point * s))) << describe(c);
      ASSERT_EQ(sc.normal, got.normal) << describe(c);
    }
    if (got.status != ContactStatus::hit) continue;
    ++hits;
    scenarios::detail::Rng rng(i);
    const Mat<double, N> q = scenarios::detail::rotation<N>(rng);
    const Vec<double, N> t = scenarios::detail::unit_vector<N>(rng) * 3.0;
    auto move = [&](const Ellipsoid<double, N>& e) {
      return Ellipsoid<double, N>::from_axes(q * e.center() + t, q * e.axes(), e.radii());
    };
    const auto mv = first_contact(move(c.a), Vec<double, N>(q * c.va), move(c.b), Vec<double, N>(q * c.vb), c.t_max);
    ASSERT_EQ(mv.status, ContactStatus::hit) << describe(c);
    const double scale = std::max(c.a.radii().maxCoeff(), c.b.radii().maxCoeff());
    const double speed = (c.vb - c.va).norm();
    EXPECT_LE(std::abs(mv.time - got.time), 1e-12 * std::max(got.time, scale / speed)) << describe(c);
    EXPECT_LE((mv.point - (q * got.point + t)).norm(), 1e-10 * (scale + got.point.norm())) << describe(c);
    EXPECT_LE((mv.normal - q * got.normal).norm(), 1e-9) << describe(c);
  }
  EXPECT_GT(hits, n / 2);
}

TEST(ContactProperty, ScaleAndRigidMotionInvariance2D) { check_invariance<2>(cases(300)); }
TEST(ContactProperty, ScaleAndRigidMotionInvariance3D) { check_invariance<3>(cases(300)); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
