// Fuzz target `niemitalo`: make_circle, segment_circle, polygonal_overlap (ellipse-circle
// and two ellipses), circle_cover_overlap and the closed-form closest points, double or
// float, on values decoded from the input, checked against polygonal2.hpp and quartic2.hpp:
//   - make_circle throws InputError exactly for invalid values, naming the field;
//     invalid_input exactly for the inputs each function names (max_level outside
//     [0, niemitalo_max_level]: band NaN);
//   - segment_circle: the verdict is the distance from the center to the segment (long
//     double, on inputs scaled by an exact power of two) against the radius, outside the
//     header's band 8 eps (|b - a| + |center - a| + radius); the side is the sign of the
//     cross product outside 2 eps |center - a| of the line; swapping the end points gives
//     the same verdict and the mirrored side;
//   - polygonal tests: the band [gap_lo, gap_hi] contains the signed gap of distance.hpp's
//     signed_distance (within its accuracy, 1e-12 of its scale; float 1e-6); collision has
//     gap_lo = -inf, no_collision gap_hi = +inf, undecided a finite band around 0 at level
//     max_level (polygonal_overlap: within niemitalo_error_bound + rho of 0); iterations ==
//     level for polygonal_overlap, at most 2^(n+1) - 1 for circle_cover_overlap; scaling the
//     scene by a power of two gives the same verdict, level and iterations and the band
//     scaled, bit for bit;
//   - closest_point_quartic: inside / outside agrees with closest_point's sign away from
//     the boundary; outside: finite point, distance > 0 (a distance rounding to 0 is
//     inside) and within 1e-13 (major radius + distance) of closest_point's (double; 1e-5
//     in float); otherwise NaN point and distance; closest_point_closed_form: outside only
//     with a finite point and a distance > 0.
#include "fuzz_support.hpp"

#include <ellipsect/distance.hpp>
#include <ellipsect/point.hpp>
#include <ellipsect/polygonal2.hpp>
#include <ellipsect/quartic2.hpp>

#include <algorithm>
#include <numbers>
#include <optional>
#include <string_view>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

template <class T>
constexpr double eps = std::numeric_limits<T>::epsilon();

Side mirrored(Side s) { return s == Side::left ? Side::right : s == Side::right ? Side::left : s; }

// make_circle throws exactly for invalid values, naming the first invalid field.
template <class T>
std::optional<Circle<T>> circle_of(const Vec2<T>& c, T r) {
  const char* expected = !std::isfinite(c[0]) ? "center[0]"
                         : !std::isfinite(c[1]) ? "center[1]"
                         : !(std::isfinite(r) && r >= 0) ? "radius"
                                                          : nullptr;
  try {
    const Circle<T> circle = make_circle<T>(c, r);
    FUZZ_CHECK(!expected, << "make_circle accepted an invalid " << expected);
    FUZZ_CHECK(same_bits(circle.center(), c) && same_bits(circle.radius(), r), << "make_circle changed its values");
    return circle;
  } catch (const InputError& e) {
    FUZZ_CHECK(expected && std::string_view(e.what()).find(expected) != std::string_view::npos,
               << "make_circle threw \"" << e.what() << "\", expected " << (expected ? expected : "no error"));
    return std::nullopt;
  }
}

template <class T>
void segment(Bytes& in) {
  Vec2<T> a, b, c;
  for (int i = 0; i < 2; ++i) a[i] = static_cast<T>(in.number());
  for (int i = 0; i < 2; ++i) b[i] = static_cast<T>(in.number());
  for (int i = 0; i < 2; ++i) c[i] = static_cast<T>(in.number());
  const T r = static_cast<T>(in.number());
  trace() += "segment " + hex(a) + " " + hex(b) + " center " + hex(c) + " radius " + hex(r);
  const auto circle = circle_of(c, r);
  if (!circle) return;
  const SegmentCircle s = segment_circle<T>(a, b, *circle);
  const SegmentCircle t = segment_circle<T>(b, a, *circle);
  const bool valid = a.allFinite() && b.allFinite();
  FUZZ_CHECK((s.verdict == Verdict::invalid_input) == !valid, << "verdict " << to_string(s.verdict));
  FUZZ_CHECK((t.verdict == Verdict::invalid_input) == !valid, << "swapped verdict " << to_string(t.verdict));
  if (!valid) {
    FUZZ_CHECK(s.side == Side::on_line && t.side == Side::on_line, << "invalid_input with side " << to_string(s.side));
    return;
  }
  FUZZ_CHECK(s.verdict != Verdict::undecided && t.verdict != Verdict::undecided,
             << "(a, b): " << to_string(s.verdict) << "; (b, a): " << to_string(t.verdict));
  // Reference in long double, on the inputs scaled by an exact power of two (no overflow).
  using L = long double;
  const L bigger = std::max({L(a.cwiseAbs().maxCoeff()), L(b.cwiseAbs().maxCoeff()), L(c.cwiseAbs().maxCoeff()), L(r)});
  int ex = 0;
  if (bigger > 0) (void)std::frexp(bigger, &ex);
  const auto sc = [ex](T x) { return std::ldexp(L(x), -ex); };
  const L ax = sc(a[0]), ay = sc(a[1]), dx = sc(b[0]) - ax, dy = sc(b[1]) - ay, px = sc(c[0]) - ax, py = sc(c[1]) - ay;
  const L rr = sc(r);
  const L len2 = dx * dx + dy * dy;
  const L u = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, L(0), L(1)) : L(0);
  const L dist = std::hypot(px - u * dx, py - u * dy);
  // The header's band: 8 eps_T (|b - a| + |center - a| + radius), widened by the reference's
  // rounding; for (b, a) with |center - b|. Outside it both orders give the exact verdict
  // (hence the same one); within it either is allowed.
  const L to_a = std::hypot(px, py), to_b = std::hypot(px - dx, py - dy), len = std::sqrt(len2);
  const auto outside_band = [&](L to_start) {
    return std::abs(dist - rr) > L(8 * eps<T>) * (len + to_start + rr) * L(1.01);
  };
  const std::string swapped = "; (b, a): " + std::string(to_string(t.verdict)) + " " + std::string(to_string(t.side));
  if (outside_band(to_a))
    FUZZ_CHECK((s.verdict == Verdict::collision) == (dist < rr),
               << "verdict " << to_string(s.verdict) << ", distance " << double(dist) << ", radius " << double(rr)
               << " (scaled by 2^" << -ex << ")" << swapped);
  if (outside_band(to_b))
    FUZZ_CHECK((t.verdict == Verdict::collision) == (dist < rr),
               << "(b, a): verdict " << to_string(t.verdict) << ", distance " << double(dist) << ", radius "
               << double(rr) << " (scaled by 2^" << -ex << "); (a, b): " << to_string(s.verdict));
  // side: exact except for a center within 2 eps_T |center - a| of the line (|center - b|
  // for (b, a), which gives the mirrored side).
  const L cross = dx * py - dy * px;
  const Side expected = cross > 0 ? Side::left : Side::right;
  if (std::abs(cross) > L(2 * eps<T>) * L(1.01) * len * to_a)
    FUZZ_CHECK(s.side == expected, << "side " << to_string(s.side) << ", cross " << double(cross) << swapped);
  if (std::abs(cross) > L(2 * eps<T>) * L(1.01) * len * to_b)
    FUZZ_CHECK(t.side == mirrored(expected), << "(b, a): side " << to_string(t.side) << ", cross " << double(cross)
                                                 << "; (a, b): " << to_string(s.side));
}

// The certified band [gap_lo, gap_hi] against the signed gap g of the exact query
// (distance.hpp's signed_distance, accurate to 1e-12 * its scale).
template <class T>
void check_band(const char* name, const PolygonalOverlap<T>& v, const Ellipse2<T>& a, const Ellipse2<T>& b, int n,
                T bound_side) {
  FUZZ_CHECK(v.verdict != Verdict::invalid_input, << name << ": invalid_input");
  FUZZ_CHECK(v.level >= 0 && v.level <= n && v.iterations >= 0, << name << ": level " << v.level << " iterations "
                                                                     << v.iterations);
  FUZZ_CHECK(!std::isnan(v.gap_lo) && !std::isnan(v.gap_hi) && v.gap_lo <= v.gap_hi,
             << name << ": band [" << v.gap_lo << ", " << v.gap_hi << "]");
  constexpr T inf = std::numeric_limits<T>::infinity();
  // Decided: open on one side (the other, rho, is infinite only where the scene's size is).
  if (v.verdict == Verdict::collision)
    FUZZ_CHECK(v.gap_lo == -inf, << name << ": collision with band [" << v.gap_lo << ", " << v.gap_hi << "]");
  if (v.verdict == Verdict::no_collision)
    FUZZ_CHECK(v.gap_hi == inf, << name << ": no_collision with band [" << v.gap_lo << ", " << v.gap_hi << "]");
  if (v.verdict == Verdict::undecided) {
    FUZZ_CHECK(v.level == n && v.gap_lo <= 0 && v.gap_hi >= 0,
               << name << ": undecided at level " << v.level << " with band [" << v.gap_lo << ", " << v.gap_hi << "]");
    if (bound_side >= 0)
      FUZZ_CHECK(-v.gap_lo <= bound_side && v.gap_hi <= bound_side,
                 << name << ": undecided band [" << v.gap_lo << ", " << v.gap_hi << "] beyond bound + rho " << bound_side);
  }
  const auto d = signed_distance(a, b);
  const double g = double(d.distance);
  if (!std::isfinite(g)) return;
  if (d.status == DistanceStatus::did_not_converge) return;
  // distance.hpp's accuracy: 1e-12 * scale (float: 1e-6), scale = the largest radii plus |g|.
  const double scale = double(a.radii().maxCoeff()) + double(b.radii().maxCoeff()) + std::abs(g);
  if (!std::isfinite(scale)) return;
  const double slack = (sizeof(T) >= sizeof(double) ? 1e-12 : 1e-6) * scale + 4 * std::numeric_limits<T>::denorm_min();
  FUZZ_CHECK(double(v.gap_lo) <= g + slack && g - slack <= double(v.gap_hi),
             << name << ": " << to_string(v.verdict) << " at level " << v.level << ", band [" << hex(v.gap_lo) << ", "
             << hex(v.gap_hi) << "], signed gap " << g);
}

// The same answer, the band scaled by s (bit for bit where both ends are normal numbers or
// infinite: a subnormal rounding allowance, tiny scenes, cannot scale exactly).
template <class T>
bool same_result(const PolygonalOverlap<T>& x, const PolygonalOverlap<T>& y, T s) {
  const auto exact = [](T v) { return std::isinf(v) || std::isnormal(v); };
  const auto same = [&](T u, T v) { return !(exact(u) && exact(v)) || same_bits(T(u * s), v); };
  return x.verdict == y.verdict && x.level == y.level && x.iterations == y.iterations && same(x.gap_lo, y.gap_lo) &&
         same(x.gap_hi, y.gap_hi);
}

template <class T>
std::string show(const PolygonalOverlap<T>& v) {
  return std::string(to_string(v.verdict)) + " level " + std::to_string(v.level) + " iterations " +
         std::to_string(v.iterations) + " [" + hex(v.gap_lo) + ", " + hex(v.gap_hi) + "]";
}

template <class T>
void polygons(Bytes& in) {
  const auto e = read_body<T, 2>(in);
  if (!e) return;
  Vec2<T> c;
  for (int i = 0; i < 2; ++i) c[i] = static_cast<T>(in.number());
  const T r = static_cast<T>(in.number());
  const int n = static_cast<int>(in.byte() % 34) - 2;   // -2 .. 31: both ends invalid
  const int k = static_cast<int>(in.byte() % 41) - 20;  // scale by 2^k
  const auto other = read_body<T, 2>(in);
  trace() += "ellipse " + describe(*e) + " circle " + hex(c) + " radius " + hex(r) + " n " + std::to_string(n) +
             " scale 2^" + std::to_string(k) + (other ? " other " + describe(*other) : "");
  const bool valid_n = n >= 0 && n <= niemitalo_max_level;
  if (other) {
    const PolygonalOverlap<T> two = polygonal_overlap<T>(*e, *other, n);
    FUZZ_CHECK((two.verdict == Verdict::invalid_input) == !valid_n, << "two ellipses: " << to_string(two.verdict));
    if (!valid_n)
      FUZZ_CHECK(std::isnan(two.gap_lo) && std::isnan(two.gap_hi), << "invalid_input with a band");
    // Known gap: b's stretch multiplies one direction by r_b,min / r_b,max, whose square
    // underflows for aspect ratios beyond about 2^500 (2^60 in float); the band is checked
    // only where the stretched frame stays in range.
    const auto ratio = [](const Ellipse2<T>& x) {
      return double(x.radii().maxCoeff()) / double(x.radii().minCoeff());
    };
    const double frame = double(e->radii().maxCoeff()) + double(other->radii().maxCoeff()) +
                         (other->center() - e->center()).template cast<double>().norm();
    const double limit = sizeof(T) >= sizeof(double) ? 0x1p200 : 0x1p20;
    if (valid_n && ratio(*other) <= limit && ratio(*e) <= limit && frame / other->radii().minCoeff() <= limit &&
        frame / e->radii().minCoeff() <= limit)
      check_band<T>("polygonal_overlap (two ellipses)", two, *e, *other, n, T(-1));
  }
  const auto circle = circle_of(c, r);
  if (!circle) return;
  const PolygonalOverlap<T> p = polygonal_overlap<T>(*e, *circle, n);
  const PolygonalOverlap<T> q = circle_cover_overlap<T>(*e, *circle, n);
  FUZZ_CHECK((p.verdict == Verdict::invalid_input) == !valid_n, << "polygonal_overlap " << to_string(p.verdict));
  FUZZ_CHECK((q.verdict == Verdict::invalid_input) == !valid_n, << "circle_cover_overlap " << to_string(q.verdict));
  if (!valid_n) {
    FUZZ_CHECK(std::isnan(p.gap_lo) && std::isnan(p.gap_hi) && std::isnan(q.gap_lo) && std::isnan(q.gap_hi),
               << "invalid_input with a band");
    return;
  }
  FUZZ_CHECK(p.iterations == p.level, << "polygonal_overlap: " << show(p));
  FUZZ_CHECK((long long)q.iterations <= (1LL << (n + 1)) - 1 && q.iterations >= q.level, << "circle_cover_overlap: " << show(q));
  const double major = e->radii().maxCoeff();
  const Vec2<double> off = (c - e->center()).template cast<double>();
  const double size = std::abs(off[0]) + std::abs(off[1]) + major + double(r);
  // polygonal_overlap's undecided band: within niemitalo_error_bound + rho of 0.
  const double rho = 16.0 * (n + 2) * eps<T> * size;
  const double bound = double(niemitalo_error_bound(*e, n)) + rho;
  if (r > 0) {
    const Ellipse2<T> ball = circle->ellipse();
    check_band<T>("polygonal_overlap", p, *e, ball, n, std::isfinite(bound) ? T(bound * (1 + 1e-6)) : T(-1));
    check_band<T>("circle_cover_overlap", q, *e, ball, n, T(-1));
  }
  // Scaled by 2^k where every value stays a normal number: the same answers, the band scaled.
  const auto normal = [&](double x) {
    return x == 0 || (std::abs(std::ldexp(x, k)) >= 1e3 * std::numeric_limits<T>::min() &&
                      std::abs(std::ldexp(x, k)) <= 1e-3 * std::numeric_limits<T>::max() &&
                      std::abs(x) >= 1e3 * std::numeric_limits<T>::min());
  };
  bool scalable = normal(r) && normal(size) && std::isfinite(size);
  for (int i = 0; i < 2; ++i) scalable = scalable && normal(c[i]) && normal(e->center()[i]) && normal(e->radii()[i]);
  if (scalable) {
    const T s = std::ldexp(T(1), k);
    const auto es = Ellipse2<T>::from_axes(e->center() * s, e->axes(), e->radii() * s);
    const Circle<T> cs = make_circle<T>(c * s, r * s);
    const PolygonalOverlap<T> ps = polygonal_overlap<T>(es, cs, n);
    const PolygonalOverlap<T> qs = circle_cover_overlap<T>(es, cs, n);
    FUZZ_CHECK(same_result(p, ps, s), << "polygonal_overlap scaled: " << show(ps) << " vs " << show(p));
    FUZZ_CHECK(same_result(q, qs, s), << "circle_cover_overlap scaled: " << show(qs) << " vs " << show(q));
  }
}

template <class T>
void closest(Bytes& in) {
  const auto e = read_body<T, 2>(in);
  if (!e) return;
  Vec2<T> x;
  for (int i = 0; i < 2; ++i) x[i] = static_cast<T>(in.number());
  trace() += "ellipse " + describe(*e) + " point " + hex(x);
  const QuarticPoint<T> q = closest_point_quartic<T>(*e, x);
  const QuarticPoint<T> f = closest_point_closed_form<T>(*e, x);
  FUZZ_CHECK((q.status == QuarticStatus::invalid_input) == !x.allFinite(), << "quartic " << to_string(q.status));
  FUZZ_CHECK((f.status == QuarticStatus::invalid_input) == !x.allFinite(), << "closed form " << to_string(f.status));
  if (!x.allFinite()) return;
  FUZZ_CHECK(q.status != QuarticStatus::failed, << "closest_point_quartic failed");
  if (f.status == QuarticStatus::outside)
    FUZZ_CHECK(all_finite(f.point) && f.distance > 0, << "closed form outside: " << hex(f.point) << " " << f.distance);
  const ClosestPoint<T, 2> cp = closest_point(*e, x);
  const double major = e->radii().maxCoeff();
  const double scale = major + (x - e->center()).template cast<double>().norm();
  if (!std::isfinite(scale) || !std::isfinite(double(cp.signed_distance))) return;
  if (std::abs(double(cp.signed_distance)) > 1e-12 * scale)
    FUZZ_CHECK((q.status == QuarticStatus::outside) == (cp.signed_distance > 0),
               << "quartic " << to_string(q.status) << ", closest_point signed distance " << cp.signed_distance);
  if (q.status != QuarticStatus::outside) {
    FUZZ_CHECK(!all_finite(q.point) && std::isnan(q.distance), << "quartic " << to_string(q.status) << " with a point");
    return;
  }
  FUZZ_CHECK(all_finite(q.point) && q.distance > 0, << "quartic outside: " << hex(q.point) << " " << q.distance);
  const double tol = (sizeof(T) >= sizeof(double) ? 1e-13 : 1e-5) * (major + double(q.distance));
  FUZZ_CHECK(std::abs(double(q.distance) - double(cp.signed_distance)) <= tol,
             << "quartic distance " << hex(q.distance) << ", closest_point " << hex(cp.signed_distance));
}

template <class T>
void run(Bytes& in, int which) {
  if (which == 0) segment<T>(in);
  if (which == 1) polygons<T>(in);
  if (which == 2) closest<T>(in);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::uint8_t kind = in.byte();
  const int which = (kind >> 1) % 3;
  trace() = std::string(kind & 1 ? "float " : "double ");
  if (kind & 1) {
    run<float>(in, which);
  } else {
    run<double>(in, which);
  }
  return 0;
}
