// Fuzz target `rigid`: first_contact under rigid motion and body_at on two bodies (2D or 3D,
// double or float) and motions decoded from the input, and of the first body against a box,
// half-space and capsule made from the second (moving at its velocity), checked against what
// contact.hpp promises for every input:
//   invalid_input exactly for a non-finite velocity or angular velocity, or a NaN or
//   negative t_max; both angular velocities zero: the translational first_contact bit for
//   bit, but a hit's time, which may be stepped back (certified early), never later (or
//   the advancement's answer, where that hit's slab along its normal does not close); hit: time finite in (0, t_max], finite point, unit normal; touching_at_start: time
//   0; overlapping_at_start exactly where the bodies overlap at 0 (distance's status);
//   a small step cap chosen by the input: the same answer, or did_not_converge with a time
//   in [0, t_max] not later than the uncapped hit's, or (the cap reached inside the tangency
//   band) a hit not later than it (to 1e-12 relative: both are refined); iterations within
//   the cap;
//   body_at: InputError naming "velocity", "angular_velocity" or "time" for non-finite
//   input, else a body with the same radii, finite axes and the center moved by t * velocity;
//   translation (an input flag at the end): the pair with its centers on a grid of 2^-(p - 23)
//   of its largest radius (p the type's digits: 2^-30 for double) and moved by an offset of up
//   to 2^(p - 3) grid steps (2^20 radii), both exact: the same status, time and normal
//   bit for bit, the point moved by the offset to its rounding (the queries compute relative to
//   one body);
//   growth (a flag after that): both growths from the input, the pair and the first body
//   against a zero-length capsule and a collinear triangle made from the second, with the
//   promises above (invalid_input also exactly for a negative or non-finite growth).
#include "fuzz_support.hpp"

#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/triangle.hpp>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

template <class T>
constexpr T unit_tolerance = sizeof(T) >= sizeof(double) ? T(1e-12) : T(1e-5);

template <class T, int N>
void check_body_at(const Ellipsoid<T, N>& body, const RigidMotion<T, N>& m, T t) {
  const char* want = !m.velocity.allFinite() ? "velocity" : !finite_spin(m) ? "angular_velocity"
                                                           : !std::isfinite(t) ? "time" : nullptr;
  try {
    const Ellipsoid<T, N> at = body_at(body, m, t);
    FUZZ_CHECK(want == nullptr, "body_at accepted bad input " << want);
    FUZZ_CHECK(same_bits(at.radii(), body.radii()), "radii changed");
    const Vec<T, N> moved = body.center() + t * m.velocity;  // to a rounding, however contracted
    const T size = body.center().cwiseAbs().maxCoeff() + (t * m.velocity).cwiseAbs().maxCoeff();
    FUZZ_CHECK((at.center() - moved).cwiseAbs().maxCoeff() <= 4 * std::numeric_limits<T>::epsilon() * size,
               "center not moved by t v");
    FUZZ_CHECK(at.axes().allFinite(), "axes not finite");
  } catch (const InputError& e) {
    // A finite motion may still move or turn the body beyond the type's range ("time").
    FUZZ_CHECK(want != nullptr ? e.field() == want : e.field() == "time", "body_at threw for field " << e.field());
  }
}

// The promises above for one query: `query(options)` the rigid first contact, `linear()` the
// translational one (asked where `still`: no party turns), `start` the distance's status at 0.
template <class T, int N, class Query, class Linear>
void check_contact(Query&& query, Linear&& linear, bool bad, bool still, DistanceStatus start, T t_max,
                   const Options& capped) {
  const Contact<T, N> c = query(Options{});
  FUZZ_CHECK((c.status == ContactStatus::invalid_input) == bad, "invalid_input " << int(c.status));
  if (bad) return;
  if (still) {
    const Contact<T, N> d = linear();
    // The translational answer, a hit's time stepped back (certified early), not on; or,
    // where the translational hit's slab along its normal does not close, the advancement's
    // answer, checked below as any rigid answer.
    if (c.status == d.status && same_bits_or_nan(c.point, d.point) && same_bits_or_nan(c.normal, d.normal)) {
      FUZZ_CHECK(c.status == ContactStatus::hit ? c.time >= T(0) && c.time <= d.time : same_bits(c.time, d.time),
                 "zero spin: time " << c.time << " after the translational " << d.time);
      return;
    }
    FUZZ_CHECK(d.status == ContactStatus::hit, "zero spin differs from the translational answer");
  }
  FUZZ_CHECK(c.iterations >= 0 && c.iterations <= Options{}.max_motion_steps, "iterations " << c.iterations);
  FUZZ_CHECK((c.status == ContactStatus::overlapping_at_start) == (start == DistanceStatus::overlapping),
             "overlapping_at_start " << int(c.status) << " vs start " << int(start));
  switch (c.status) {
    case ContactStatus::hit:
      FUZZ_CHECK(std::isfinite(c.time) && c.time > T(0) && c.time <= t_max, "hit time " << c.time);
      FUZZ_CHECK(all_finite(c.point), "hit point not finite");
      FUZZ_CHECK(std::abs(c.normal.norm() - T(1)) <= unit_tolerance<T>, "normal not unit");
      break;
    case ContactStatus::touching_at_start: FUZZ_CHECK(c.time == T(0), "touching time " << c.time); break;
    case ContactStatus::did_not_converge:
      FUZZ_CHECK(c.time >= T(0) && c.time <= t_max, "lower bound " << c.time << " outside the window");
      break;
    default: break;
  }
  const Contact<T, N> k = query(capped);
  FUZZ_CHECK(k.iterations <= capped.max_motion_steps, "capped iterations " << k.iterations);
  if (k.status == ContactStatus::did_not_converge) {
    FUZZ_CHECK(k.time >= T(0) && k.time <= t_max, "capped lower bound " << k.time);
    if (c.status == ContactStatus::hit) FUZZ_CHECK(k.time <= c.time, "lower bound " << k.time << " after " << c.time);
  } else if (!(k.status == c.status && same_bits(k.time, c.time))) {
    // The cap reached inside the tangency band: a hit at an earlier time in the band (each
    // hit's time then refined along its own normal: both lower bounds of the same contact,
    // equal to rounding where the refinement reaches it).
    FUZZ_CHECK(k.status == ContactStatus::hit && c.status == ContactStatus::hit &&
                   k.time <= c.time + std::max(T(1e-12), 4 * std::numeric_limits<T>::epsilon()) * c.time,
               "capped answer " << int(k.status) << " at " << k.time << " vs " << int(c.status) << " at " << c.time);
  }
}

// Whether x + y is exact (Knuth's two-sum has no error).
template <class T>
bool exact_sum(T x, T y) {
  const T s = x + y, z = s - x;
  return (x - (s - z)) + (y - z) == T(0) && std::isfinite(s);
}

template <class T, int N>
void check_translated(Bytes& in, const Ellipsoid<T, N>& a, const RigidMotion<T, N>& ma, const Ellipsoid<T, N>& b,
                      const RigidMotion<T, N>& mb, T t_max) {
  constexpr int p = std::numeric_limits<T>::digits;
  const int e = std::ilogb(std::max(a.radii().maxCoeff(), b.radii().maxCoeff()));
  const T grid = std::ldexp(T(1), e - (p - 23)), limit = std::ldexp(T(1), p - 3);
  Vec<T, N> offset;
  for (int i = 0; i < N; ++i)
    offset[i] = T(static_cast<std::int64_t>(in.u64() >> (64 - (p - 2))) - (std::int64_t(1) << (p - 3))) * grid;
  auto on_grid = [&](const Ellipsoid<T, N>& x, const Vec<T, N>& by, std::optional<Ellipsoid<T, N>>& out) {
    Vec<T, N> c;
    for (int i = 0; i < N; ++i) {
      c[i] = std::round(x.center()[i] / grid) * grid;
      if (!(std::abs(c[i] / grid) < limit) || !exact_sum(c[i], by[i])) return;
      c[i] += by[i];
    }
    try {
      out = Ellipsoid<T, N>::from_axes(c, x.axes(), x.radii());
    } catch (const InputError&) {
    }
  };
  std::optional<Ellipsoid<T, N>> a0, b0, a1, b1;
  const Vec<T, N> zero = Vec<T, N>::Zero();
  on_grid(a, zero, a0);
  on_grid(b, zero, b0);
  on_grid(a, offset, a1);
  on_grid(b, offset, b1);
  if (!a0 || !b0 || !a1 || !b1) return;
  const Contact<T, N> c0 = first_contact(*a0, ma, *b0, mb, t_max), c1 = first_contact(*a1, ma, *b1, mb, t_max);
  FUZZ_CHECK(c0.status == c1.status && same_bits(c0.time, c1.time) && same_bits_or_nan(c0.normal, c1.normal),
             "moved by " << hex(offset) << ": " << int(c1.status) << " at " << c1.time << " vs " << int(c0.status)
                         << " at " << c0.time);
  if (!all_finite(c0.point)) return;
  constexpr T eps = std::numeric_limits<T>::epsilon();
  const T rounding = 8 * eps * (c0.point.cwiseAbs().maxCoeff() + c1.point.cwiseAbs().maxCoeff());
  FUZZ_CHECK((c1.point - offset - c0.point).cwiseAbs().maxCoeff() <= rounding + std::numeric_limits<T>::denorm_min(),
             "moved point " << hex(c1.point) << " vs " << hex(c0.point) << " + " << hex(offset));
}

// Growth (a flag after the translation's): both bodies' growths from the input (any double:
// invalid_input exactly where one is negative or not finite, or the motions or window are
// bad), the pair and the first body against degenerate shapes made from the second: a
// zero-length capsule at its center (its smallest radius) and a collinear triangle along
// its first axis (a segment with a vertex at its midpoint). A growing body never gets the
// translational answer's shortcut.
template <class T, int N>
void check_growing(Bytes& in, const Ellipsoid<T, N>& a, RigidMotion<T, N> ma, const Ellipsoid<T, N>& b,
                   RigidMotion<T, N> mb, T t_max, const Options& capped) {
  ma.growth = static_cast<T>(in.number());
  mb.growth = static_cast<T>(in.number());
  trace() += " growth " + hex(ma.growth) + " " + hex(mb.growth);
  auto bad_growth = [](T g) { return !(g >= T(0)) || !std::isfinite(g); };
  const bool bad_window = std::isnan(t_max) || t_max < T(0);
  const bool bad_a = !ma.velocity.allFinite() || !finite_spin(ma) || bad_growth(ma.growth) || bad_window;
  check_contact<T, N>([&](const Options& o) { return first_contact(a, ma, b, mb, t_max, o); },
                      [&] { return first_contact(a, ma.velocity, b, mb.velocity, t_max); },
                      bad_a || !mb.velocity.allFinite() || !finite_spin(mb) || bad_growth(mb.growth),
                      zero_spin(ma) && zero_spin(mb) && ma.growth == T(0) && mb.growth == T(0), distance(a, b).status,
                      t_max, capped);
  const auto shape = [&](const auto& s) {
    check_contact<T, N>([&](const Options& o) { return first_contact(a, ma, s, mb.velocity, t_max, o); },
                        [&] { return first_contact(a, ma.velocity, s, mb.velocity, t_max); },
                        bad_a || !mb.velocity.allFinite(), zero_spin(ma) && ma.growth == T(0), distance(a, s).status,
                        t_max, capped);
  };
  try {
    const Vec<T, N> axis = b.axes().col(0) * b.radii()[0];
    shape(make_capsule<T, N>(b.center(), b.center(), b.radii().minCoeff()));
    shape(make_triangle<T, N>(Vec<T, N>(b.center() - axis), Vec<T, N>(b.center() + axis), b.center()));
  } catch (const InputError&) {
  }
}

template <class T, int N>
void run(Bytes& in) {
  const auto a = read_body<T, N>(in);
  if (!a) return;
  const auto b = read_partner<T, N>(in, *a);
  if (!b) return;
  const RigidMotion<T, N> ma = read_motion<T, N>(in), mb = read_motion<T, N>(in);
  const T t_max = in.flag() ? std::numeric_limits<T>::infinity() : static_cast<T>(in.number());
  Options capped;
  capped.max_motion_steps = 1 + in.byte() % 16;
  auto spin = [](const RigidMotion<T, N>& m) {
    if constexpr (N == 2) return hex(m.angular_velocity);
    else return hex(m.angular_velocity);
  };
  trace() += describe(*a) + " " + describe(*b) + " va " + hex(ma.velocity) + " wa " + spin(ma) + " vb " +
             hex(mb.velocity) + " wb " + spin(mb) + " t_max " + hex(t_max) + " cap " +
             std::to_string(capped.max_motion_steps);

  check_body_at(*a, ma, t_max);

  const bool bad_window = std::isnan(t_max) || t_max < T(0);
  check_contact<T, N>([&](const Options& o) { return first_contact(*a, ma, *b, mb, t_max, o); },
                      [&] { return first_contact(*a, ma.velocity, *b, mb.velocity, t_max); },
                      !ma.velocity.allFinite() || !mb.velocity.allFinite() || !finite_spin(ma) || !finite_spin(mb) ||
                          bad_window,
                      zero_spin(ma) && zero_spin(mb), distance(*a, *b).status, t_max, capped);

  // The partner's frame as shapes moving at its velocity: the box of its radii, the
  // half-space below the plane through its center normal to its first axis, the capsule along
  // that axis (its smallest radius); a shape beyond the type's range is skipped.
  const bool bad = !ma.velocity.allFinite() || !mb.velocity.allFinite() || !finite_spin(ma) || bad_window;
  const auto shape = [&](const auto& s) {
    check_contact<T, N>([&](const Options& o) { return first_contact(*a, ma, s, mb.velocity, t_max, o); },
                        [&] { return first_contact(*a, ma.velocity, s, mb.velocity, t_max); }, bad, zero_spin(ma),
                        distance(*a, s).status, t_max, capped);
  };
  try {
    const Vec<T, N> axis = b->axes().col(0);
    shape(make_box<T, N>(b->center(), b->axes(), b->radii()));
    shape(make_half_space<T, N>(b->center(), axis));
    shape(make_capsule<T, N>(Vec<T, N>(b->center() - b->radii()[0] * axis), Vec<T, N>(b->center() + b->radii()[0] * axis),
                             b->radii().minCoeff()));
  } catch (const InputError&) {
  }
  if (in.flag() && !bad && mb.velocity.allFinite() && finite_spin(mb)) check_translated<T, N>(in, *a, ma, *b, mb, t_max);
  if (in.flag()) check_growing<T, N>(in, *a, ma, *b, mb, t_max, capped);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  for_type_and_dim(in, [&]<class T, int N>() { run<T, N>(in); });
  return 0;
}
