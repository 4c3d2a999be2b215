// Fuzz target `niemitalo`: segment_circle, polygonal_overlap (ellipse-circle and two
// ellipses), circle_cover_overlap and the closed-form closest points, double or float, on
// values decoded from the input, checked against polygonal2.hpp and quartic2.hpp:
//   - invalid_input exactly for the inputs each function names;
//   - segment_circle: the verdict is the distance from the center to the segment (in long
//     double) against the radius, and the side the sign of the cross product, away from
//     rounding; swapping the end points gives the same verdict and the mirrored side;
//   - polygonal tests: a decided verdict is wrong only when |mu - 1| <= 16 (n + 2) eps *
//     (frame size) / (R + s_min), undecided happens only when |mu - 1| <= the stated band
//     (niemitalo_error_bound(1, n) * ...), mu the Perram-Wertheim factor; both checked by
//     classify on the bodies scaled to the ends of those intervals; scaling the scene by a
//     power of two gives the same verdict and iteration count, bit for bit;
//   - closest_point_quartic: inside / outside agrees with closest_point's sign away from
//     the boundary; outside: finite point, distance > 0 and within 1e-13 (major radius +
//     distance) of closest_point's (double; 1e-5 in float); closest_point_closed_form:
//     outside only with a finite point and a distance > 0.
#include "fuzz_support.hpp"

#include <ellipsect/classify.hpp>
#include <ellipsect/point.hpp>
#include <ellipsect/polygonal2.hpp>
#include <ellipsect/quartic2.hpp>

#include <algorithm>
#include <numbers>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

template <class T>
constexpr double eps = std::numeric_limits<T>::epsilon();

Side mirrored(Side s) { return s == Side::left ? Side::right : s == Side::right ? Side::left : s; }

template <class T>
void segment(Bytes& in) {
  Vec2<T> a, b, c;
  for (int i = 0; i < 2; ++i) a[i] = static_cast<T>(in.number());
  for (int i = 0; i < 2; ++i) b[i] = static_cast<T>(in.number());
  for (int i = 0; i < 2; ++i) c[i] = static_cast<T>(in.number());
  const T r = static_cast<T>(in.number());
  trace() += "segment " + hex(a) + " " + hex(b) + " center " + hex(c) + " radius " + hex(r);
  const SegmentCircle s = segment_circle<T>(a, b, c, r);
  const SegmentCircle t = segment_circle<T>(b, a, c, r);
  const bool valid = a.allFinite() && b.allFinite() && c.allFinite() && std::isfinite(r) && r >= 0;
  FUZZ_CHECK((s.verdict == Verdict::invalid_input) == !valid, << "verdict " << to_string(s.verdict));
  if (!valid) return;
  FUZZ_CHECK(s.verdict != Verdict::undecided && t.verdict == s.verdict && t.side == mirrored(s.side),
             << "(a, b): " << to_string(s.verdict) << " " << to_string(s.side) << "; (b, a): " << to_string(t.verdict)
             << " " << to_string(t.side));
  using L = long double;
  const L ax = a[0], ay = a[1], dx = L(b[0]) - ax, dy = L(b[1]) - ay, px = L(c[0]) - ax, py = L(c[1]) - ay;
  const L len2 = dx * dx + dy * dy;
  const L u = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, L(0), L(1)) : L(0);
  const L dist = std::hypot(px - u * dx, py - u * dy);
  const L size = std::abs(ax) + std::abs(ay) + std::abs(L(b[0])) + std::abs(L(b[1])) + std::abs(L(c[0])) +
                 std::abs(L(c[1])) + L(r);
  if (std::abs(dist - L(r)) > L(1e-9) * size)
    FUZZ_CHECK((s.verdict == Verdict::collision) == (dist < L(r)),
               << "verdict " << to_string(s.verdict) << ", distance " << double(dist) << ", radius " << double(r));
  const L cross = dx * py - dy * px;
  if (std::abs(cross) > L(1e-12) * std::sqrt(len2) * std::hypot(px, py))
    FUZZ_CHECK(s.side == (cross > 0 ? Side::left : Side::right),
               << "side " << to_string(s.side) << ", cross " << double(cross));
}

// True when a and b, each scaled by s about its own center, share a point (classify).
// With mu the pair's Perram-Wertheim factor (scaled by mu they touch), that is s >= mu for
// s away from mu by more than classify's band.
template <class T>
bool meet_scaled(const Ellipse2<T>& a, const Ellipse2<T>& b, double s) {
  const auto scaled = [s](const Ellipse2<T>& e) {
    return Ellipse2<T>::from_axes(e.center(), e.axes(), (e.radii().template cast<double>() * s).template cast<T>());
  };
  return classify(scaled(a), scaled(b)) != Relation::separated;
}

// A decided verdict is wrong only when |mu - 1| <= rounding, and undecided happens only when
// |mu - 1| <= band: tested at the edges of those intervals, widened by classify's accuracy.
template <class T>
void check_verdict(const char* name, const PolygonalOverlap& v, const Ellipse2<T>& a, const Ellipse2<T>& b, double band,
                   double rounding) {
  const double margin = sizeof(T) >= sizeof(double) ? 1e-9 : 1e-4;
  const double limit = v.verdict == Verdict::undecided ? band : rounding;
  const double up = (1 + limit) * (1 + margin), down = (1 - limit) * (1 - margin);
  const bool scalable =
      up * std::max(a.radii().maxCoeff(), b.radii().maxCoeff()) <= 1e-3 * std::numeric_limits<T>::max() &&
      down * std::min(a.radii().minCoeff(), b.radii().minCoeff()) >= 1e3 * std::numeric_limits<T>::min();
  if (!scalable) return;
  // mu <= 1 + limit: scaled by `up` they meet. mu >= 1 - limit: scaled by `down` they do not.
  const bool upper = v.verdict == Verdict::undecided || v.verdict == Verdict::collision;
  const bool lower = v.verdict == Verdict::undecided || v.verdict == Verdict::no_collision;
  if (upper)
    FUZZ_CHECK(meet_scaled(a, b, up), << name << " " << to_string(v.verdict) << " after " << v.iterations
                                      << ", but apart when scaled by 1 + " << up - 1);
  if (lower && down > 0)
    FUZZ_CHECK(!meet_scaled(a, b, down), << name << " " << to_string(v.verdict) << " after " << v.iterations
                                         << ", but meeting when scaled by 1 - " << 1 - down);
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
  const PolygonalOverlap p = polygonal_overlap<T>(*e, c, r, n);
  const PolygonalOverlap q = circle_cover_overlap<T>(*e, c, r, n);
  const bool valid = c.allFinite() && std::isfinite(r) && r >= 0 && n >= 0 && n <= niemitalo_max_iterations;
  FUZZ_CHECK((p.verdict == Verdict::invalid_input) == !valid, << "polygonal_overlap " << to_string(p.verdict));
  FUZZ_CHECK((q.verdict == Verdict::invalid_input) == !valid, << "circle_cover_overlap " << to_string(q.verdict));
  if (!valid) return;
  const double major = e->radii().maxCoeff(), minor = e->radii().minCoeff();
  const double frame = major + (c - e->center()).template cast<double>().norm() + r;
  if (r > 0 && std::isfinite(frame)) {
    const auto ball = make_ball<T, 2>(c, r);
    const double rounding = 16 * (n + 2) * eps<T> * frame / (double(r) + minor);
    const double band = niemitalo_error_bound(1.0, n) * major / (double(r) + minor);
    check_verdict("polygonal_overlap", p, *e, ball, band, rounding);
    const double cover =
        std::max(niemitalo_error_bound(major, n), major * std::sin(std::numbers::pi / std::ldexp(1.0, n + 2)));
    check_verdict("circle_cover_overlap", q, *e, ball, cover / (double(r) + minor), rounding);
  }
  // Scaled by 2^k where every value stays a normal number: the same answers.
  const auto normal = [&](double x) {
    return x == 0 || (std::abs(std::ldexp(x, k)) >= 1e3 * std::numeric_limits<T>::min() &&
                      std::abs(std::ldexp(x, k)) <= 1e-3 * std::numeric_limits<T>::max());
  };
  bool scalable = normal(r) && normal(frame);
  for (int i = 0; i < 2; ++i) scalable = scalable && normal(c[i]) && normal(e->center()[i]) && normal(e->radii()[i]);
  if (scalable) {
    const T s = std::ldexp(T(1), k);
    const auto es = Ellipse2<T>::from_axes(e->center() * s, e->axes(), e->radii() * s);
    const PolygonalOverlap ps = polygonal_overlap<T>(es, c * s, r * s, n);
    FUZZ_CHECK(ps.verdict == p.verdict && ps.iterations == p.iterations,
               << "scaled: " << to_string(ps.verdict) << " after " << ps.iterations << " vs " << to_string(p.verdict)
               << " after " << p.iterations);
  }
  if (!other) return;
  const PolygonalOverlap two = polygonal_overlap<T>(*e, *other, n);
  FUZZ_CHECK(two.verdict != Verdict::invalid_input, << "two ellipses: invalid_input");
  const auto& ra = e->radii();
  const auto& rb = other->radii();
  const double frame2 = major + rb.maxCoeff() + (other->center() - e->center()).template cast<double>().norm();
  const double denominator = double(rb[0]) * rb[1] + minor * double(rb.minCoeff());
  const double band2 = niemitalo_error_bound(1.0, n) * double(ra.maxCoeff()) * rb.maxCoeff() / denominator;
  // In b's stretched frame the sizes grow by at most rb.max / rb.min.
  const double rounding2 = 16 * (n + 2) * eps<T> * frame2 * (rb.maxCoeff() / rb.minCoeff()) / (rb.minCoeff() + minor);
  if (std::isfinite(band2) && std::isfinite(rounding2))
    check_verdict("polygonal_overlap (two ellipses)", two, *e, *other, band2, rounding2);
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
  if (q.status != QuarticStatus::outside) return;
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
