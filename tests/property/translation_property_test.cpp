// Translation invariance of the pair queries: a pair moved far from the origin keeps each
// query's stated accuracy, relative to the bodies' size (not to the distance from the origin).
//
// Each pair is put on a grid of 2^-30 of its size and moved by an offset on the same grid,
// 1e3 to 1e6 sizes long in a random direction: both centers stay exactly representable (at
// most 52 significant bits), so the moved pair is the same geometry, exactly. The 50-digit
// references are evaluated on the moved input. Claims under test, with size = the largest
// radii summed (plus |distance| for distances), and `ulp` = eps |x| for a returned point x
// (the rounding of its coordinates, which no answer at 1e6 sizes from the origin can beat):
//   classify, overlap: the reference's relation outside the band (classify.hpp);
//   signed_distance: within 1e-12 size, witness points on their boundaries to 1e-12 size + ulp
//     (also started from a hint near its normal)
//     (distance.hpp);
//   first_contact, rigid with spin: never later than the reference's first contact; linear and
//     rigid, for hits
//     whose approach is not grazing (sine >= 1e-3) the time within 1e-12 max(t, size / speed),
//     the point within 1e-10 size + ulp, the normal within 1e-9 rad (contact.hpp);
//   perram_wertheim: F within 1e-12 relative; closest_approach: sigma within 1e-12 relative
//     (contact_function.hpp);
//   intersect_boundaries: points within 1e-12 size + ulp of both boundaries; overlap_area
//     within 1e-12 of the smaller ellipse's area (intersect2.hpp);
//   batch: classify, overlap and first_contact over Pairs equal the scalar answers bit for bit
//     on the moved pairs (batch.hpp).
#include <ellipsect/batch.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>

#include "common.hpp"
#include "scenarios/rigid.hpp"
#include "tests/reference/contact_function_reference.hpp"
#include "tests/reference/distance_reference.hpp"
#include "tests/reference/rigid_contact_reference.hpp"

#include <cmath>
#include <memory>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using Real = ref::Real;
template <int N> using RVec = Eigen::Matrix<Real, N, 1>;

constexpr double band = 2 * Options{}.tolerance;
constexpr double eps = std::numeric_limits<double>::epsilon();

template <int N>
Ellipsoid<double, N> with_center(const Ellipsoid<double, N>& e, const Vec<double, N>& c) {
  return Ellipsoid<double, N>::from_axes(c, e.axes(), e.radii());
}

// x rounded to the grid of `step` (a power of two).
template <int N>
Vec<double, N> on_grid(const Vec<double, N>& x, double step) {
  return (x / step).array().round().matrix() * step;
}

// A pair on the grid of 2^-30 of its size, and an offset on that grid, 1e3 to 1e6 sizes long.
template <int N>
struct Moved {
  Ellipsoid<double, N> a, b;  // moved by `offset`
  Vec<double, N> offset;
  double size;
};

template <int N>
Moved<N> moved(const Ellipsoid<double, N>& a, const Ellipsoid<double, N>& b, std::uint64_t seed) {
  const double size = a.radii().maxCoeff() + b.radii().maxCoeff();
  const double step = std::ldexp(1.0, std::ilogb(size) - 30);
  scenarios::detail::Rng rng(seed);
  const Vec<double, N> offset =
      on_grid<N>(scenarios::detail::unit_vector<N>(rng) * size * scenarios::detail::log_uniform(rng, 1e3, 1e6), step);
  const Vec<double, N> ca = on_grid<N>(a.center(), step), cb = on_grid<N>(b.center(), step);
  return {with_center<N>(a, ca + offset), with_center<N>(b, cb + offset), offset, size};
}

// Distance of p from e's boundary to first order, in 50 digits.
template <int N>
double off_boundary(const Ellipsoid<double, N>& e, const Vec<double, N>& p) {
  const Eigen::Matrix<Real, N, N> axes = e.axes().template cast<Real>();
  const RVec<N> d = axes.transpose() * (p.template cast<Real>() - e.center().template cast<Real>());
  const RVec<N> r = e.radii().template cast<Real>();
  const Real q = sqrt(d.cwiseQuotient(r).squaredNorm());
  const RVec<N> grad = axes * (d.cwiseQuotient(r.cwiseAbs2()) / q);
  return ref::to_double(abs(q - 1) / grad.norm());
}

double angle_between(double chord) { return 2 * std::asin(std::min(1.0, chord / 2)); }

template <int N>
void check_static(const Moved<N>& m, const std::string& what) {
  const auto& [a, b, offset, size] = m;
  // classify and overlap.
  const auto rc = ref::classify<N>(to_ref(a), to_ref(b), band);
  const Relation relation = classify(a, b);
  if (rc.margin > band) {
    ASSERT_EQ(relation, from_ref(rc.relation)) << what;
    ASSERT_EQ(overlap(a, b), relation != Relation::separated) << what;
  }
  // signed_distance.
  const auto d = signed_distance(a, b);
  const auto rd = ref::signed_distance<N>(to_ref(a), to_ref(b));
  const double scale = size + std::abs(ref::to_double(rd.distance));
  ASSERT_NEAR(d.distance, ref::to_double(rd.distance), 1e-12 * scale) << what;
  if (d.status != DistanceStatus::touching || std::isfinite(d.point_a[0])) {
    ASSERT_LE(off_boundary<N>(a, d.point_a), 1e-12 * scale + eps * d.point_a.norm()) << what;
    ASSERT_LE(off_boundary<N>(b, d.point_b), 1e-12 * scale + eps * d.point_b.norm()) << what;
  }
  // Started from a hint (its own normal turned a little), the same claims.
  if (d.normal.allFinite()) {
    Vec<double, N> turn = Vec<double, N>::Zero();
    turn[0] = 0.03;
    const auto h = signed_distance(a, b, Options{}, Vec<double, N>((d.normal + turn).normalized()));
    ASSERT_EQ(h.status, d.status) << what << " (hint)";
    ASSERT_NEAR(h.distance, ref::to_double(rd.distance), 1e-12 * scale) << what << " (hint)";
    if (h.status != DistanceStatus::touching || std::isfinite(h.point_a[0])) {
      ASSERT_LE(off_boundary<N>(a, h.point_a), 1e-12 * scale + eps * h.point_a.norm()) << what << " (hint)";
      ASSERT_LE(off_boundary<N>(b, h.point_b), 1e-12 * scale + eps * h.point_b.norm()) << what << " (hint)";
    }
  }
  // perram_wertheim and closest_approach.
  const auto pw = perram_wertheim(a, b);
  const auto rpw = ref::contact_function<N>(to_ref(a), to_ref(b));
  const double f = ref::to_double(rpw.f);
  ASSERT_LE(std::abs(pw.f - f), 1e-12 * f) << what;
  const Vec<double, N> dir = (b.center() - a.center()).normalized();
  if (dir.allFinite()) {
    const double sigma = ref::to_double(ref::closest_approach<N>(to_ref(a), to_ref(b), dir));
    ASSERT_LE(std::abs(closest_approach(a, b, dir).distance - sigma), 1e-12 * sigma) << what;
  }
  // intersect_boundaries and overlap_area.
  if constexpr (N == 2) {
    const auto got = intersect_boundaries(a, b);
    for (int i = 0; i < got.count; ++i) {
      const double tol = 1e-12 * size + eps * got.points[i].norm();
      ASSERT_LE(off_boundary<2>(a, got.points[i]), tol) << what << " point " << i;
      ASSERT_LE(off_boundary<2>(b, got.points[i]), tol) << what << " point " << i;
    }
    const double area = overlap_area(a, b).area;
    const double smaller = M_PI * std::min(a.radii().prod(), b.radii().prod());
    ASSERT_NEAR(area, ref::to_double(ref::overlap_area(to_ref(a), to_ref(b))), 1e-12 * smaller) << what;
  }
}

// The linear first_contact of the moved pair against the reference.
template <int N>
void check_linear(const Moved<N>& m, const Vec<double, N>& va, const Vec<double, N>& vb, double t_max,
                  const std::string& what, int& compared) {
  const auto got = first_contact(m.a, va, m.b, vb, t_max);
  const auto r = ref::first_contact<N>(to_ref(m.a), va, to_ref(m.b), vb, t_max, band);
  if (std::abs(ref::to_double(ref::pw_scale<N>(to_ref(m.a), to_ref(m.b))) - 1) <= band) return;
  if (r.kind != ref::ContactKind::hit) return;
  if (std::abs(ref::to_double(r.min_mu) - 1) <= band) return;  // grazing within the band
  ASSERT_EQ(got.status, ContactStatus::hit) << what;
  const Vec<double, N> v = vb - va;
  const Vec<double, N> n_ref = ref::to_double<N>(r.normal).normalized();
  if (std::abs(n_ref.dot(v.normalized())) < 1e-3) return;  // grazing: time sqrt-conditioned
  ++compared;
  const double t_ref = ref::to_double(r.time);
  const double scale = std::max(m.a.radii().maxCoeff(), m.b.radii().maxCoeff());
  ASSERT_LE(std::abs(got.time - t_ref), 1e-12 * std::max(t_ref, scale / v.norm())) << what << " t_ref " << t_ref;
  ASSERT_LE((got.point - ref::to_double<N>(r.point)).norm(), 1e-10 * scale + eps * got.point.norm()) << what;
  ASSERT_LE(angle_between((got.normal - n_ref).norm()), 1e-9) << what;
}

template <int N>
void check_pairs(int per_category) {
  int compared = 0;
  Pairs<double, N> pairs;
  for (const auto category : scenarios::all_categories) {
    if (category == scenarios::Category::zero_velocity) continue;
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_contact_case<N>(category, 620000 + i, 1e-3);
      const Moved<N> m = moved<N>(c.a, c.b, 630000 + i);
      const std::string what = describe(c) + "\n  moved by " + ::testing::PrintToString(m.offset.transpose());
      check_static<N>(m, what);
      check_linear<N>(m, c.va, c.vb, c.t_max, what, compared);
      if (::testing::Test::HasFatalFailure()) return;
      pairs.push_back(m.a, c.va, m.b, c.vb, c.t_max);
    }
  }
  EXPECT_GT(compared, per_category * 3);
  // Batch answers on the moved pairs: the scalar answers, bit for bit.
  const std::size_t n = pairs.size();
  std::vector<Relation> relations(n);
  std::vector<Contact<double, N>> contacts(n);
  std::unique_ptr<bool[]> flags(new bool[n]);
  classify(pairs, std::span<Relation>(relations));
  overlap(pairs, std::span<bool>(flags.get(), n));
  first_contact(pairs, std::span<Contact<double, N>>(contacts));
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(relations[i], classify(pairs.a(i), pairs.b(i))) << "pair " << i;
    ASSERT_EQ(flags[i], overlap(pairs.a(i), pairs.b(i))) << "pair " << i;
    const auto want = first_contact(pairs.a(i), pairs.velocity_a(i), pairs.b(i), pairs.velocity_b(i), pairs.t_max(i));
    ASSERT_EQ(contacts[i].status, want.status) << "pair " << i;
    if (want.status != ContactStatus::hit) continue;
    ASSERT_EQ(contacts[i].time, want.time) << "pair " << i;
    ASSERT_EQ(contacts[i].point, want.point) << "pair " << i;
    ASSERT_EQ(contacts[i].normal, want.normal) << "pair " << i;
  }
}

TEST(TranslationProperty, PairQueriesFarFromOrigin2D) { check_pairs<2>(cases(12)); }
TEST(TranslationProperty, PairQueriesFarFromOrigin3D) { check_pairs<3>(cases(12)); }

// Rigid first_contact of moved pairs, spinning and not (the zero-spin route is the linear query).
template <int N>
void check_rigid(int per_kind) {
  int compared = 0;
  for (const auto kind : {scenarios::Spin::random, scenarios::Spin::slow, scenarios::Spin::needles}) {
    for (int i = 0; i < per_kind; ++i) {
      const auto s = scenarios::make_moving<N>(kind, 640000 + std::uint64_t(i));
      const Moved<N> m = moved<N>(s.a, s.b, 650000 + std::uint64_t(i));
      for (const bool spinning : {true, false}) {
        RigidMotion<double, N> ma = s.ma, mb = s.mb;
        if (!spinning) ma.angular_velocity = mb.angular_velocity = RigidMotion<double, N>{}.angular_velocity;
        const std::string what = scenarios::describe_moving<N>(kind, 640000 + std::uint64_t(i), s) + "\n  moved by " +
                                 ::testing::PrintToString(m.offset.transpose()) + (spinning ? "" : ", no spin");
        const auto got = first_contact(m.a, ma, m.b, mb, s.t_max);
        const auto want = ref::rigid_first_contact<N>(to_ref(m.a), {ma.velocity, ma.angular_velocity}, to_ref(m.b),
                                                      {mb.velocity, mb.angular_velocity}, s.t_max, 1e-30, 6000);
        if (!want.resolved || want.kind != ref::ContactKind::hit) continue;
        ASSERT_EQ(got.status, ContactStatus::hit) << what;
        // Spinning: never late (the axes' rounding included). Without spin the translational
        // query answers, bit for bit, to its own accuracy (below).
        if (spinning) {
          ASSERT_LE(Real(got.time), want.time) << what << ": late by " << ref::to_double(Real(got.time) - want.time);
        }
        if (want.approach_sine < Real(1e-3)) continue;
        ++compared;
        const double t_ref = ref::to_double(want.time);
        ASSERT_LE(std::abs(got.time - t_ref), 1e-12 * std::max(t_ref, s.size / s.speed)) << what << " t_ref " << t_ref;
        ASSERT_LE((got.point - ref::to_double<N>(want.point)).norm(), 1e-10 * s.size + eps * got.point.norm()) << what;
        ASSERT_LE(angle_between((got.normal - ref::to_double<N>(want.normal)).norm()), 1e-9) << what;
      }
    }
  }
  EXPECT_GT(compared, per_kind);
}

TEST(TranslationProperty, RigidContactFarFromOrigin2D) { check_rigid<2>(cases(8)); }
TEST(TranslationProperty, RigidContactFarFromOrigin3D) { check_rigid<3>(cases(8)); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
