// Fuzz target `queries`: classify, overlap, distance, signed_distance, first_contact and the
// batch functions on two bodies (2D or 3D, double or float) decoded from the input, checked
// against what their headers promise for every pair:
//   classify    swapping the arguments mirrors the relation bit for bit; a body against a
//               copy of itself is `equal`;
//   overlap     exactly classify != separated;
//   distance    same status as classify (separated, touching, overlapping for the others)
//               unless did_not_converge; swapping two distinct bodies gives the same
//               distance, swapped points and the negated normal, bit for bit; separated:
//               distance > 0, overlapping: <= 0 (signed) or 0 with NaN points (distance());
//               a number where one is promised (finite), a unit normal;
//   contact     invalid_input exactly for a non-finite velocity or a NaN / negative t_max;
//               the same status, time and point (normal negated) with a and b swapped; hit:
//               time finite in (0, t_max], finite point, unit normal; touching_at_start:
//               time 0; the start state agrees with classify away from the tangency band;
//   contact function  perram_wertheim: concentric exactly for equal centers (F = 0, lambda
//               NaN), else F >= 0 (not NaN), lambda in [0, 1]; swapping a and b gives the same F
//               bit for bit; F > 1 + 1e-6: classify says separated, F < 1 - 1e-6: an
//               overlapping relation; closest_approach along va: InputError("direction") exactly
//               for a zero or non-finite va, else a finite positive distance, a finite point
//               and a unit normal, and the same distance for (b, a, -va) bit for bit;
//   batch       overlap, classify and first_contact equal the scalar answers bit for bit;
//   half-space  a against the half-space through b's center with normal va: InputError
//               naming the normal exactly for a zero or non-finite va; the relation is one
//               of separated, touching, overlapping, b_contains_a, and b_contains_a exactly
//               where the complement (normal -va) says separated or touching; overlap and
//               signed_distance's status agree with it, the normal is -n bit for bit, the
//               distance finite, > 0 when separated, <= 0 when overlapping; first_contact
//               (velocities vb and 0): invalid_input exactly for bad input, else the start
//               status is the relation's, and a hit is in (0, t_max] at a finite point;
//               collide_and_slide by vb in the world of that half-space: overlapping_at_start
//               exactly where classify says so, invalid_input only for a non-finite end,
//               otherwise an end outside the half-space (separated or touching), moved by at
//               most |vb| (to 1e-12).
//   triangle    a against the triangle (b's center, + va, + vb): InputError naming a vertex
//               exactly for non-finite vertices; overlap is classify != separated; the
//               relation is the same for the vertices in another order unless it is within
//               the tangency band of 1e-6 or the triangle reaches beyond 1e12 radii; a_contains_b: every vertex (as a point triangle)
//               inside or touching; a one-triangle mesh answers as the triangle (classify,
//               first_contact bit for bit, triangle 0 or -1); first_contact (velocities vb and
//               0): invalid_input exactly for bad input, the start status is the relation's
//               (did_not_converge allowed beyond 1e12 radii), a hit is in (0, t_max] at a
//               finite point with a unit normal; collide_and_slide
//               by vb through the mesh: overlapping_at_start exactly where classify says
//               overlapping or a_contains_b, otherwise an end separated or touching, moved by
//               at most |vb|.
//   degenerate  a against the collinear triangle (p, q, m), p b's center, q = p + va, m their
//               midpoint: the relation of the segment (p, q, q) unless within the tangency
//               band of 1e-6; a hit under velocity vb (double) is where the segment, moved
//               there, touches within that band; the triangle (p, q, p + vb) split into its
//               four midpoint triangles, as a mesh: the relation of the whole triangle (same
//               exception), and collide_and_slide by vb through it never ends inside and moves
//               at most |vb|; where every coordinate lies within 1e6 smallest radii of the
//               origin (float: 0.008), so that rounding moves a point by far less than the band.
//   box         a against the box with b's center, axes and radii as half extents: overlap is
//               classify != separated; a_contains_b exactly when every triangle of the box is
//               inside a; b_contains_a only where every face's half-space contains a;
//               first_contact (velocities va and 0) starts as the relation says, a hit is in
//               (0, t_max] and no later than the earliest of the box's triangles' hits;
//               signed_distance's status is classify's (overlapping for containment), its
//               distance >= 0 when separated and <= 0 when overlapping.
//   capsule     a against the capsule along b's first axis (its largest radius either side of
//               b's center, its smallest as the radius): overlap is classify != separated;
//               signed_distance as for the box; first_contact (velocities va and 0):
//               invalid_input exactly for bad input, the start status is the relation's, a
//               hit is in [0, t_max].
#include "fuzz_support.hpp"

#include <ellipsect/batch.hpp>
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
#include <ellipsect/slide.hpp>

#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

Relation mirrored(Relation r) {
  if (r == Relation::a_contains_b) return Relation::b_contains_a;
  if (r == Relation::b_contains_a) return Relation::a_contains_b;
  return r;
}

// Whether first_contact's status is the one the start relation implies (hit or none when
// separated).
bool starts_as(Relation rel, ContactStatus s) {
  return rel == Relation::separated ? s == ContactStatus::hit || s == ContactStatus::no_contact_in_window
         : rel == Relation::touching ? s == ContactStatus::touching_at_start
                                     : s == ContactStatus::overlapping_at_start;
}

DistanceStatus distance_status_of(Relation r) {
  if (r == Relation::separated) return DistanceStatus::separated;
  if (r == Relation::touching) return DistanceStatus::touching;
  return DistanceStatus::overlapping;
}

template <class T>
constexpr T unit_tolerance = sizeof(T) >= sizeof(double) ? T(1e-12) : T(1e-5);

template <class T, int N>
bool unit(const Vec<T, N>& v) {
  return std::abs(v.norm() - T(1)) <= unit_tolerance<T>;
}

template <class T, int N>
void check_distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, Relation rel, bool distinct) {
  for (const bool is_signed : {false, true}) {
    const Distance<T, N> d = is_signed ? signed_distance(a, b) : distance(a, b);
    const Distance<T, N> s = is_signed ? signed_distance(b, a) : distance(b, a);
    const char* name = is_signed ? "signed_distance" : "distance";
    if (d.status == DistanceStatus::did_not_converge) continue;  // a reported status
    FUZZ_CHECK(d.status == distance_status_of(rel),
               << name << " status " << to_string(d.status) << ", classify " << to_string(rel));
    if (distinct && s.status != DistanceStatus::did_not_converge) {
      FUZZ_CHECK(s.status == d.status && same_bits(s.distance, d.distance) && same_bits_or_nan(s.point_a, d.point_b) &&
                     same_bits_or_nan(s.point_b, d.point_a) &&
                     same_bits_or_nan(Vec<T, N>(s.normal), Vec<T, N>(-d.normal)),
                 << name << " (a, b): " << to_string(d.status) << " " << hex(d.distance) << " n " << hex(d.normal)
                 << "; (b, a): " << to_string(s.status) << " " << hex(s.distance) << " n " << hex(s.normal));
    }
    FUZZ_CHECK(std::isfinite(d.distance), << name << " distance " << d.distance);
    if (d.status == DistanceStatus::separated)
      FUZZ_CHECK(d.distance >= 0 && !std::signbit(d.distance), << name << " " << hex(d.distance));
    if (d.status == DistanceStatus::overlapping) FUZZ_CHECK(d.distance <= 0, << name << " " << hex(d.distance));
    if (!is_signed && d.status == DistanceStatus::overlapping) {
      FUZZ_CHECK(d.distance == 0 && d.point_a.hasNaN() && d.point_b.hasNaN() && d.normal.hasNaN(),
                 << "distance() on overlapping bodies: " << hex(d.distance) << " " << hex(d.point_a));
      continue;
    }
    FUZZ_CHECK(all_finite(d.point_a) && all_finite(d.point_b) && all_finite(d.normal),
               << name << " " << to_string(d.status) << " points " << hex(d.point_a) << " " << hex(d.point_b)
               << " normal " << hex(d.normal));
    FUZZ_CHECK(unit(d.normal), << name << " |normal| - 1 = " << d.normal.norm() - T(1));
  }
}

template <class T, int N>
void check_contact(const Ellipsoid<T, N>& a, const Vec<T, N>& va, const Ellipsoid<T, N>& b, const Vec<T, N>& vb,
                   T t_max, Relation rel, Relation rel_wide) {
  const Contact<T, N> c = first_contact(a, va, b, vb, t_max);
  const Contact<T, N> s = first_contact(b, vb, a, va, t_max);
  const bool valid = all_finite(va) && all_finite(vb) && !std::isnan(t_max) && t_max >= 0;
  FUZZ_CHECK((c.status == ContactStatus::invalid_input) == !valid, << "status " << to_string(c.status));
  FUZZ_CHECK(s.status == c.status, << "(a, b): " << to_string(c.status) << ", (b, a): " << to_string(s.status));
  if (c.status == ContactStatus::hit || c.status == ContactStatus::touching_at_start) {
    FUZZ_CHECK(same_bits(s.time, c.time) && same_bits(s.point, c.point) &&
                   same_bits(Vec<T, N>(s.normal), Vec<T, N>(-c.normal)),
               << to_string(c.status) << " (a, b): t " << hex(c.time) << " p " << hex(c.point) << "; (b, a): t "
               << hex(s.time) << " p " << hex(s.point));
    FUZZ_CHECK(all_finite(c.point) && unit(c.normal),
               << to_string(c.status) << " point " << hex(c.point) << " normal " << hex(c.normal));
  }
  if (c.status == ContactStatus::hit)
    FUZZ_CHECK(std::isfinite(c.time) && c.time > 0 && c.time <= t_max,
               << "hit at " << hex(c.time) << ", t_max " << hex(t_max));
  if (c.status == ContactStatus::touching_at_start || c.status == ContactStatus::overlapping_at_start)
    FUZZ_CHECK(c.time == 0, << to_string(c.status) << " time " << hex(c.time));
  if (c.status == ContactStatus::no_contact_in_window) FUZZ_CHECK(std::isnan(c.time), << "time " << hex(c.time));
  // Away from the tangency band (classify with the widest band, 1e3 times the default, is
  // not `touching`), the start state is classify's.
  if (!valid || c.status == ContactStatus::did_not_converge || rel_wide == Relation::touching) return;
  const bool apart = c.status == ContactStatus::hit || c.status == ContactStatus::no_contact_in_window;
  FUZZ_CHECK(apart == (rel == Relation::separated) && c.status != ContactStatus::touching_at_start,
             << "contact " << to_string(c.status) << ", classify " << to_string(rel));
}

template <class T, int N>
void check_contact_function(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Vec<T, N>& u, Relation rel) {
  const ContactFunction<T> f = perram_wertheim(a, b), s = perram_wertheim(b, a);
  if (a.center() == b.center()) {
    FUZZ_CHECK(f.status == ContactFunctionStatus::concentric && f.f == 0 && std::isnan(f.lambda),
               << "perram_wertheim on equal centers: " << to_string(f.status) << " " << hex(f.f));
  } else if (f.status == ContactFunctionStatus::ok) {
    FUZZ_CHECK(f.f >= 0 && f.lambda >= 0 && f.lambda <= 1, << "perram_wertheim " << hex(f.f) << " " << hex(f.lambda));
    FUZZ_CHECK(s.status == f.status && same_bits(s.f, f.f),
               << "perram_wertheim (a, b) " << hex(f.f) << ", (b, a) " << to_string(s.status) << " " << hex(s.f));
    if (std::abs(f.f - 1) > T(1e-6))
      FUZZ_CHECK((f.f > 1) == (rel == Relation::separated) && rel != Relation::touching,
                 << "perram_wertheim F " << hex(f.f) << ", classify " << to_string(rel));
  }
  const bool valid = all_finite(u) && !u.isZero(0);
  try {
    const ClosestApproach<T, N> c = closest_approach(a, b, u);
    FUZZ_CHECK(valid, << "closest_approach accepted the direction " << hex(u));
    if (c.status != ContactFunctionStatus::ok) return;  // a reported status
    FUZZ_CHECK(std::isfinite(c.distance) && c.distance > 0 && all_finite(c.point) && unit(c.normal),
               << "closest_approach " << hex(c.distance) << " point " << hex(c.point) << " normal " << hex(c.normal));
    const ClosestApproach<T, N> r = closest_approach(b, a, Vec<T, N>(-u));
    FUZZ_CHECK(r.status != ContactFunctionStatus::ok || same_bits(r.distance, c.distance),
               << "closest_approach (a, b, u) " << hex(c.distance) << ", (b, a, -u) " << hex(r.distance));
  } catch (const InputError& e) {
    FUZZ_CHECK(!valid && e.field() == "direction", << "closest_approach threw " << e.what());
  }
}

template <class T, int N>
void check_batch(const std::vector<Ellipsoid<T, N>>& as, const std::vector<Ellipsoid<T, N>>& bs,
                 const std::vector<Vec<T, N>>& vas, const std::vector<Vec<T, N>>& vbs, const std::vector<T>& t_maxes) {
  Pairs<T, N> pairs;
  for (std::size_t i = 0; i < as.size(); ++i) pairs.push_back(as[i], vas[i], bs[i], vbs[i], t_maxes[i]);
  const std::size_t n = as.size();
  std::unique_ptr<bool[]> o(new bool[n]);
  std::vector<Relation> r(n);
  std::vector<Contact<T, N>> c(n);
  const BatchOptions one_thread{Options{}, 1};
  overlap<T, N>(pairs, std::span<bool>(o.get(), n), one_thread);
  classify<T, N>(pairs, std::span<Relation>(r), one_thread);
  first_contact<T, N>(pairs, std::span<Contact<T, N>>(c), one_thread);
  // The span overloads (each chunk's columns filled on its thread) and Pairs::assign give
  // the Pairs path's columns and answers.
  std::unique_ptr<bool[]> os(new bool[n]);
  std::vector<Relation> rs(n);
  std::vector<Contact<T, N>> cs(n);
  overlap<T, N>(as, bs, std::span<bool>(os.get(), n), one_thread);
  classify<T, N>(as, bs, std::span<Relation>(rs), one_thread);
  first_contact<T, N>(as, vas, bs, vbs, t_maxes, std::span<Contact<T, N>>(cs), one_thread);
  Pairs<T, N> assigned;
  assigned.assign(as, vas, bs, vbs, t_maxes, 1);
  for (int k = 0; k < Pairs<T, N>::columns; ++k)
    for (std::size_t i = 0; i < n; ++i)
      FUZZ_CHECK(same_bits(assigned.column(k)[i], pairs.column(k)[i]),
                 << "Pairs::assign, column " << k << ", pair " << i);
  for (std::size_t i = 0; i < n; ++i) {
    FUZZ_CHECK(os[i] == o[i] && rs[i] == r[i], << "span overloads, pair " << i);
    FUZZ_CHECK(cs[i].status == c[i].status && same_bits(cs[i].time, c[i].time) && same_bits(cs[i].point, c[i].point) &&
                   same_bits(cs[i].normal, c[i].normal) && cs[i].iterations == c[i].iterations,
               << "span first_contact, pair " << i);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Contact<T, N> sc = first_contact(as[i], vas[i], bs[i], vbs[i], t_maxes[i]);
    FUZZ_CHECK(o[i] == overlap(as[i], bs[i]), << "batch overlap, pair " << i);
    FUZZ_CHECK(r[i] == classify(as[i], bs[i]), << "batch classify, pair " << i << ": " << to_string(r[i]));
    FUZZ_CHECK(c[i].status == sc.status && same_bits(c[i].time, sc.time) && same_bits(c[i].point, sc.point) &&
                   same_bits(c[i].normal, sc.normal) && c[i].iterations == sc.iterations,
               << "batch first_contact, pair " << i << ": " << to_string(c[i].status) << " " << hex(c[i].time)
               << " vs scalar " << to_string(sc.status) << " " << hex(sc.time));
  }
}

template <class T, int N>
void check_half_space(const Ellipsoid<T, N>& a, const Vec<T, N>& point, const Vec<T, N>& normal, const Vec<T, N>& v,
                      T t_max) {
  const bool valid_normal = all_finite(normal) && normal.cwiseAbs().maxCoeff() > T(0);
  std::optional<HalfSpace<T, N>> h, complement;
  try {
    h = make_half_space<T, N>(point, normal);
    complement = make_half_space<T, N>(point, -normal);
  } catch (const InputError& e) {
    FUZZ_CHECK(!valid_normal && e.field().starts_with("normal"), << "InputError " << e.what());
    return;
  }
  FUZZ_CHECK(valid_normal, << "no InputError for the normal " << hex(normal));
  const Relation rel = classify(a, *h), rel_c = classify(a, *complement);
  FUZZ_CHECK(rel != Relation::a_contains_b && rel != Relation::equal, << "relation " << to_string(rel));
  FUZZ_CHECK(overlap(a, *h) == (rel != Relation::separated), << "overlap vs classify " << to_string(rel));
  const auto apart = [](Relation r) { return r == Relation::separated || r == Relation::touching; };
  FUZZ_CHECK((rel == Relation::b_contains_a) == apart(rel_c) && (rel_c == Relation::b_contains_a) == apart(rel),
             << "half-space " << to_string(rel) << ", its complement " << to_string(rel_c));
  const Distance<T, N> d = signed_distance(a, *h);
  FUZZ_CHECK(d.status == distance_status_of(rel) && same_bits(d.normal, Vec<T, N>(-h->normal())) &&
                 std::isfinite(d.distance) && all_finite(d.point_a) && all_finite(d.point_b),
             << "signed_distance " << to_string(d.status) << " " << hex(d.distance) << " normal " << hex(d.normal)
             << ", classify " << to_string(rel));
  if (rel == Relation::separated) FUZZ_CHECK(d.distance > 0, << "separated at " << hex(d.distance));
  if (d.status == DistanceStatus::overlapping) {
    FUZZ_CHECK(d.distance <= 0, << "overlapping at " << hex(d.distance));
    const Distance<T, N> u = distance(a, *h);
    FUZZ_CHECK(u.distance == 0 && std::isnan(u.point_a[0]), << "distance() " << hex(u.distance));
  }
  const Slide<T, N> slide = collide_and_slide(a, v, std::span(&*h, 1));
  const bool inside = rel == Relation::overlapping || rel == Relation::b_contains_a;
  if (slide.status == SlideStatus::invalid_input) {
    FUZZ_CHECK(!all_finite(Vec<T, N>(a.center() + v)), << "invalid_input for the displacement " << hex(v));
  } else {
    FUZZ_CHECK((slide.status == SlideStatus::overlapping_at_start) == inside,
               << "slide " << to_string(slide.status) << ", classify " << to_string(rel));
    const Relation end = classify(slide.body, *h);
    FUZZ_CHECK(inside || end == Relation::separated || end == Relation::touching,
               << "slide ends " << to_string(end) << " at " << hex(Vec<T, N>(slide.body.center())));
    FUZZ_CHECK(slide.moved.norm() <= v.norm() * (1 + T(1e-6)) || !std::isfinite(v.norm()),
               << "moved " << hex(slide.moved) << " for " << hex(v));
  }
  const Contact<T, N> c = first_contact(a, v, *h, Vec<T, N>::Zero(), t_max);
  const bool valid = all_finite(v) && !std::isnan(t_max) && t_max >= 0;
  FUZZ_CHECK((c.status == ContactStatus::invalid_input) == !valid, << "status " << to_string(c.status));
  if (!valid) return;
  const bool start_ok = starts_as(rel, c.status);
  FUZZ_CHECK(start_ok, << "contact " << to_string(c.status) << ", classify " << to_string(rel));
  if (c.status == ContactStatus::hit)
    FUZZ_CHECK(std::isfinite(c.time) && c.time > 0 && c.time <= t_max && all_finite(c.point),
               << "hit at " << hex(c.time) << ", t_max " << hex(t_max) << " point " << hex(c.point));
}

template <class T, int N>
void check_triangle(const Ellipsoid<T, N>& a, const Vec<T, N>& p, const Vec<T, N>& va, const Vec<T, N>& vb, T t_max) {
  const Vec<T, N> q = p + va, r = p + vb;
  const bool finite = all_finite(q) && all_finite(r);
  std::optional<Triangle<T, N>> tri;
  try {
    tri = make_triangle<T, N>(p, q, r);
  } catch (const InputError& e) {
    FUZZ_CHECK(!finite && e.field().starts_with("vertices["), << "InputError " << e.what());
    return;
  }
  FUZZ_CHECK(finite, << "no InputError for the vertices " << hex(q) << " " << hex(r));
  const Relation rel = classify(a, *tri);
  FUZZ_CHECK(rel == Relation::separated || rel == Relation::touching || rel == Relation::overlapping ||
                 rel == Relation::a_contains_b,
             << "relation " << to_string(rel));
  FUZZ_CHECK(overlap(a, *tri) == (rel != Relation::separated), << "overlap vs classify " << to_string(rel));
  Options wide;
  wide.tolerance = Tolerance::max;
  // Within the stated range (triangle.hpp: about 1e15 radii across; beyond, decided to 1e-30
  // of the extent), the same relation with the vertices turned.
  T extent = 0;
  for (const Vec<T, N>& v : {p, q, r}) extent = std::max(extent, T((v - a.center()).norm() / a.radii().minCoeff()));
  const Relation turned = classify(a, make_triangle<T, N>(r, p, q));
  FUZZ_CHECK(turned == rel || classify(a, *tri, wide) == Relation::touching || !(extent <= T(1e12)),
             << "classify " << to_string(rel) << ", with the vertices turned " << to_string(turned));
  if (rel == Relation::a_contains_b)
    for (const Vec<T, N>& v : {p, q, r}) {
      const Relation at = classify(a, make_triangle<T, N>(v, v, v));
      FUZZ_CHECK(at == Relation::a_contains_b || at == Relation::touching,
                 << "contained triangle, its vertex " << hex(v) << " " << to_string(at));
    }
  std::array<T, 3 * N> vertices;
  for (int i = 0; i < N; ++i) vertices[i] = p[i], vertices[N + i] = q[i], vertices[2 * N + i] = r[i];
  const std::array<std::int64_t, 3> indices{0, 1, 2};
  const auto mesh = make_triangle_mesh<T, N>(vertices, indices);
  const MeshRelation mrel = classify(a, mesh);
  FUZZ_CHECK(mrel.relation == rel && mrel.triangle == (rel == Relation::separated ? -1 : 0),
             << "mesh " << to_string(mrel.relation) << " " << mrel.triangle << ", triangle " << to_string(rel));
  const Contact<T, N> c = first_contact(a, vb, *tri, Vec<T, N>::Zero(), t_max);
  const bool valid = all_finite(vb) && !std::isnan(t_max) && t_max >= 0;
  FUZZ_CHECK((c.status == ContactStatus::invalid_input) == !valid, << "status " << to_string(c.status));
  const MeshContact<T, N> mc = first_contact(a, vb, mesh, Vec<T, N>::Zero(), t_max);
  FUZZ_CHECK(mc.contact.status == c.status && same_bits(mc.contact.time, c.time) &&
                 (mc.triangle == 0) == (c.status == ContactStatus::hit || c.status == ContactStatus::touching_at_start ||
                                        c.status == ContactStatus::overlapping_at_start ||
                                        c.status == ContactStatus::did_not_converge),
             << "mesh contact " << to_string(mc.contact.status) << " " << hex(mc.contact.time) << " triangle "
             << mc.triangle << ", triangle's " << to_string(c.status) << " " << hex(c.time));
  const bool inside = rel == Relation::overlapping || rel == Relation::a_contains_b;
  if (valid) {
    // did_not_converge: the closed form's own check failed, only beyond the stated range.
    const bool start_ok = starts_as(rel, c.status) || (rel == Relation::separated &&
                                                       c.status == ContactStatus::did_not_converge && !(extent <= T(1e12)));
    FUZZ_CHECK(start_ok, << "contact " << to_string(c.status) << ", classify " << to_string(rel));
    if (c.status == ContactStatus::hit)
      FUZZ_CHECK(std::isfinite(c.time) && c.time > 0 && c.time <= t_max && all_finite(c.point) &&
                     std::abs(c.normal.norm() - 1) <= T(1e-5),
                 << "hit at " << hex(c.time) << ", t_max " << hex(t_max) << " point " << hex(c.point) << " normal "
                 << hex(c.normal));
  }
  const Slide<T, N> slide = collide_and_slide(a, vb, mesh);
  if (slide.status == SlideStatus::invalid_input) {
    FUZZ_CHECK(!all_finite(Vec<T, N>(a.center() + vb)), << "invalid_input for the displacement " << hex(vb));
    return;
  }
  FUZZ_CHECK((slide.status == SlideStatus::overlapping_at_start) == inside,
             << "slide " << to_string(slide.status) << ", classify " << to_string(rel));
  const Relation end = classify(slide.body, *tri);
  FUZZ_CHECK(inside || end == Relation::separated || end == Relation::touching,
             << "slide ends " << to_string(end) << " at " << hex(Vec<T, N>(slide.body.center())));
  FUZZ_CHECK(slide.moved.norm() <= vb.norm() * (1 + T(1e-6)) || !std::isfinite(vb.norm()),
             << "moved " << hex(slide.moved) << " for " << hex(vb));
}

template <class T, int N>
void check_degenerate(const Ellipsoid<T, N>& a, const Vec<T, N>& p, const Vec<T, N>& va, const Vec<T, N>& vb, T t_max) {
  const Vec<T, N> q = p + va, r = p + vb;
  const Vec<T, N> pq = p + (q - p) / T(2), qr = q + (r - q) / T(2), rp = r + (p - r) / T(2);
  // Every coordinate within min(1e6, 1e-9 / eps) smallest radii of the origin: rounding a
  // point then moves it by at most 1e-9 of that radius.
  const T bound = std::min(T(1e6), T(1e-9) / std::numeric_limits<T>::epsilon()) * a.radii().minCoeff();
  const auto near = [&](const Vec<T, N>& x) { return all_finite(x) && x.cwiseAbs().maxCoeff() <= bound; };
  if (!near(a.center()) || !near(p) || !near(q) || !near(r) || !near(pq) || !near(qr) || !near(rp) || !(t_max >= 0))
    return;
  // Within 1e-6 of the size of touching (a relative gap of 1e-6 moves the boundary by at most
  // that much of the largest radius; 100 eps in float): either answer may stand there.
  const T slack = std::max(T(1e-6), 100 * std::numeric_limits<T>::epsilon()) * a.radii().maxCoeff();
  const auto grazes = [&](const Triangle<T, N>& t) { return std::abs(signed_distance(a, t).distance) <= slack; };
  const auto segment = make_triangle<T, N>(p, q, q), collinear = make_triangle<T, N>(p, q, pq);
  const Relation rel = classify(a, segment);
  FUZZ_CHECK(classify(a, collinear) == rel || grazes(segment),
             << "collinear " << to_string(classify(a, collinear)) << ", its segment " << to_string(rel));
  const Contact<T, N> c = first_contact(a, Vec<T, N>::Zero(), collinear, vb, t_max);
  if constexpr (std::is_same_v<T, double>) {
    if (c.status == ContactStatus::hit && near(Vec<T, N>(p + c.time * vb)) && near(Vec<T, N>(q + c.time * vb)))
      FUZZ_CHECK(grazes(segment.translated(c.time * vb)),
                 << "collinear hit at " << hex(c.time) << ", the segment there "
                 << to_string(classify(a, segment.translated(c.time * vb))));
  }
  std::array<T, 6 * N> vertices;
  const std::array<Vec<T, N>, 6> points{p, q, r, pq, qr, rp};
  for (int k = 0; k < 6; ++k)
    for (int i = 0; i < N; ++i) vertices[k * N + i] = points[k][i];
  const std::array<std::int64_t, 12> indices{0, 3, 5, 3, 1, 4, 5, 4, 2, 3, 4, 5};
  const auto split = make_triangle_mesh<T, N>(vertices, indices);
  const Relation whole = classify(a, make_triangle<T, N>(p, q, r));
  const Relation pieces = classify(a, split).relation;
  FUZZ_CHECK(pieces == whole || grazes(make_triangle<T, N>(p, q, r)),
             << "split triangle " << to_string(pieces) << ", whole " << to_string(whole));
  const Slide<T, N> slide = collide_and_slide(a, vb, split);
  if (slide.status == SlideStatus::invalid_input || slide.status == SlideStatus::overlapping_at_start) return;
  const Relation end = classify(slide.body, split).relation;
  FUZZ_CHECK(end == Relation::separated || end == Relation::touching,
             << "slide over the split triangle ends " << to_string(end) << " at " << hex(Vec<T, N>(slide.body.center())));
  FUZZ_CHECK(slide.moved.norm() <= vb.norm() * (1 + T(1e-6)), << "moved " << hex(slide.moved) << " for " << hex(vb));
}

// signed_distance's status and sign against the relation.
template <class T, int N>
void check_signed_distance(const Distance<T, N>& d, Relation rel, const char* what) {
  const DistanceStatus want = rel == Relation::separated  ? DistanceStatus::separated
                              : rel == Relation::touching ? DistanceStatus::touching
                                                          : DistanceStatus::overlapping;
  FUZZ_CHECK(d.status == want, << what << ": signed_distance " << to_string(d.status) << ", classify " << to_string(rel));
  FUZZ_CHECK(!(d.status == DistanceStatus::separated && d.distance < 0) &&
                 !(d.status == DistanceStatus::overlapping && d.distance > 0),
             << what << ": " << to_string(d.status) << " at distance " << hex(d.distance));
}

template <class T, int N>
void check_box(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Vec<T, N>& va, T t_max) {
  const auto box = make_box<T, N>(b.center(), b.axes(), b.radii());
  const Relation rel = classify(a, box);
  FUZZ_CHECK(overlap(a, box) == (rel != Relation::separated), << "box: overlap vs classify " << to_string(rel));
  // The box's queries run on the pair moved by minus the body's center where the centers'
  // difference is finite (box.hpp): the triangles are the moved box's, met by the moved body.
  const bool moves = !a.center().isZero(0) && Vec<T, N>(box.center() - a.center()).allFinite();
  const auto a_at = moves ? a.translated(Vec<T, N>(-a.center())) : a;
  const auto box_at = moves ? box.translated(Vec<T, N>(-a.center())) : box;
  const auto triangles = box_at.triangles();
  bool all_inside = true;
  for (const auto& t : triangles) all_inside = all_inside && classify(a_at, t) == Relation::a_contains_b;
  FUZZ_CHECK((rel == Relation::a_contains_b) == all_inside, << "box " << to_string(rel) << ", every triangle inside "
                                                              << all_inside);
  if (rel == Relation::b_contains_a)
    for (int i = 0; i < N; ++i)
      for (const T side : {T(-1), T(1)}) {
        const Vec<T, N> normal = side * box.axes().col(i);
        const Relation face =
            classify(a_at, make_half_space<T, N>(box_at.center() + box_at.half_extents()[i] * normal, normal));
        FUZZ_CHECK(face == Relation::b_contains_a, << "box contains a, its face " << i << " says " << to_string(face));
      }
  check_signed_distance<T, N>(signed_distance(a, box), rel, "box");
  const Contact<T, N> c = first_contact(a, va, box, Vec<T, N>::Zero(), t_max);
  if (c.status == ContactStatus::invalid_input) {
    FUZZ_CHECK(!all_finite(va) || !(t_max >= 0), << "box: invalid_input");
    return;
  }
  const bool start_ok = starts_as(rel, c.status);
  FUZZ_CHECK(start_ok, << "box contact " << to_string(c.status) << ", classify " << to_string(rel));
  if (c.status != ContactStatus::hit) return;
  FUZZ_CHECK(std::isfinite(c.time) && c.time > 0 && c.time <= t_max, << "box hit at " << hex(c.time));
  // No triangle of the box hit earlier, to the triangles' accuracy (triangle.hpp: 1e-13 of
  // the time, and T's rounding): the box skips faces that cannot hold the first contact,
  // and where it touches at an edge, the skipped face's triangle may compute the same
  // contact a few ulps earlier. Beyond that, the body must not overlap the box at the
  // box's time (a late hit; grazing contact times are ill-conditioned, their gaps are not).
  const T slack = T(1e-12) + T(8) * std::numeric_limits<T>::epsilon();
  for (const auto& t : triangles) {
    const Contact<T, N> ct = first_contact(a_at, va, t, Vec<T, N>::Zero(), t_max);
    if (ct.status != ContactStatus::hit || ct.time >= c.time * (T(1) - slack)) continue;
    const auto moved = Ellipsoid<T, N>::from_axes(Vec<T, N>(a.center() + c.time * va), a.axes(), a.radii());
    FUZZ_CHECK(classify(moved, box) != Relation::overlapping,
               << "box hit at " << hex(c.time) << ", a triangle's at " << hex(ct.time));
  }
}

template <class T, int N>
void check_capsule(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Vec<T, N>& va, T t_max) {
  const Vec<T, N> along = b.axes().col(0) * b.radii()[0];
  std::optional<Capsule<T, N>> capsule;
  try {
    capsule = make_capsule<T, N>(Vec<T, N>(b.center() - along), Vec<T, N>(b.center() + along), b.radii().minCoeff());
  } catch (const InputError&) {
    return;  // end points beyond the range of T
  }
  const Relation rel = classify(a, *capsule);
  FUZZ_CHECK(overlap(a, *capsule) == (rel != Relation::separated), << "capsule: overlap vs classify " << to_string(rel));
  check_signed_distance<T, N>(signed_distance(a, *capsule), rel, "capsule");
  const Contact<T, N> c = first_contact(a, va, *capsule, Vec<T, N>::Zero(), t_max);
  if (c.status == ContactStatus::invalid_input) {
    FUZZ_CHECK(!all_finite(va) || !(t_max >= 0), << "capsule: invalid_input");
    return;
  }
  const bool start_ok = rel == Relation::separated
                            ? c.status == ContactStatus::hit || c.status == ContactStatus::no_contact_in_window ||
                                  c.status == ContactStatus::did_not_converge
                        : rel == Relation::touching ? c.status == ContactStatus::touching_at_start
                                                    : c.status == ContactStatus::overlapping_at_start;
  FUZZ_CHECK(start_ok, << "capsule contact " << to_string(c.status) << ", classify " << to_string(rel));
  if (c.status == ContactStatus::hit) FUZZ_CHECK(c.time >= 0 && c.time <= t_max, << "capsule hit at " << hex(c.time));
}

template <class T, int N>
void run(Bytes& in) {
  std::vector<Ellipsoid<T, N>> as, bs;
  std::vector<Vec<T, N>> vas, vbs;
  std::vector<T> t_maxes;
  // Up to four pairs: each checked alone, then all of them through the batch functions.
  for (int k = 0; k < 4 && in.remaining() > 0; ++k) {
    const auto a = read_body<T, N>(in);
    if (!a) return;
    const auto b = read_partner<T, N>(in, *a);
    if (!b) return;
    Vec<T, N> va, vb;
    for (int i = 0; i < N; ++i) va[i] = static_cast<T>(in.number());
    for (int i = 0; i < N; ++i) vb[i] = static_cast<T>(in.number());
    const T t_max = in.flag() ? std::numeric_limits<T>::infinity() : static_cast<T>(in.number());
    trace() += "pair " + std::to_string(k) + ": a " + describe(*a) + " b " + describe(*b) + " va " + hex(va) + " vb " +
               hex(vb) + " t_max " + hex(t_max) + "; ";

    const Relation rel = classify(*a, *b);
    FUZZ_CHECK(classify(*b, *a) == mirrored(rel),
               << "classify(a, b) " << to_string(rel) << ", classify(b, a) " << to_string(classify(*b, *a)));
    FUZZ_CHECK(overlap(*a, *b) == (rel != Relation::separated), << "overlap vs classify " << to_string(rel));
    FUZZ_CHECK(classify(*a, *a) == Relation::equal, << "classify(a, a) " << to_string(classify(*a, *a)));
    Options wide;
    wide.tolerance = Tolerance::max;
    const Relation rel_wide = classify(*a, *b, wide);
    const bool distinct =
        !(same_bits(a->center(), b->center()) && same_bits(a->radii(), b->radii()) && same_bits(a->axes(), b->axes()));
    check_distance<T, N>(*a, *b, rel, distinct);
    check_contact<T, N>(*a, va, *b, vb, t_max, rel, rel_wide);
    check_contact_function<T, N>(*a, *b, va, rel);
    check_half_space<T, N>(*a, Vec<T, N>(b->center()), va, vb, t_max);
    check_triangle<T, N>(*a, Vec<T, N>(b->center()), va, vb, t_max);
    check_degenerate<T, N>(*a, Vec<T, N>(b->center()), va, vb, t_max);
    check_box<T, N>(*a, *b, va, t_max);
    check_capsule<T, N>(*a, *b, va, t_max);
    as.push_back(*a);
    bs.push_back(*b);
    vas.push_back(va);
    vbs.push_back(vb);
    t_maxes.push_back(t_max);
  }
  if (!as.empty()) check_batch<T, N>(as, bs, vas, vbs, t_maxes);
}

}  // namespace

// ELLIPSECT_FUZZ_SIMD_TARGET pins the batch functions' instruction set (simd_targets()):
// the coverage of the SIMD code, and with it the inputs a seeded run tries, then does not
// depend on the CPU (scripts/run.sh's CI run pins EMU128, present on every x86-64).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* target = std::getenv("ELLIPSECT_FUZZ_SIMD_TARGET")) set_simd_target(target);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  for_type_and_dim(in, [&]<class T, int N>() { run<T, N>(in); });
  return 0;
}
