#include <ellipsect/quartic2.hpp>

#include "detail/instantiate.hpp"
#include "detail/niemitalo_quartic.hpp"
#include "detail/reduce.hpp"
#include "detail/scale.hpp"
#include "detail/secular.hpp"
#include "detail/math.hpp"

#include <cmath>
#include <complex>
#include <limits>

namespace ellipsect {

std::string_view to_string(QuarticStatus s) noexcept {
  switch (s) {
    case QuarticStatus::outside: return "outside";
    case QuarticStatus::inside: return "inside";
    case QuarticStatus::failed: return "failed";
    case QuarticStatus::invalid_input: return "invalid_input";
  }
  return "unknown";
}

namespace {

// The document's frame, in precision R: the point in the ellipse's axes, folded into the
// first quadrant, with the major axis first (`major` is its index).
template <class R>
struct Frame {
  Vec2<R> local;   // the point in the ellipse's axes (signed)
  R a, b;          // major and minor radius
  R c, d;          // |coordinate| along the major and the minor axis
  int major;
};

template <class R, class T>
Frame<R> frame(const Ellipse2<T>& e, const Vec2<T>& x) noexcept {
  Frame<R> f;
  f.local = detail::work_axes<R>(e).transpose() * (x.template cast<R>() - e.center().template cast<R>());
  f.major = e.radii()[0] >= e.radii()[1] ? 0 : 1;
  f.a = R(e.radii()[f.major]);
  f.b = R(e.radii()[1 - f.major]);
  f.c = abs(f.local[f.major]);
  f.d = abs(f.local[1 - f.major]);
  return f;
}

template <class T>
QuarticPoint<T> no_point(QuarticStatus s) noexcept {
  constexpr T nan = std::numeric_limits<T>::quiet_NaN();
  return {s, Vec2<T>(nan, nan), nan};
}

// The world point for (major, minor) coordinates in the first quadrant. A distance that is
// 0 in T (a point on the boundary, which the inside test missed by rounding) is `inside`:
// `outside` promises a positive distance.
template <class R, class T>
QuarticPoint<T> outside(const Ellipse2<T>& e, const Frame<R>& f, R along_major, R along_minor, R distance) noexcept {
  if (!(T(distance) > T(0))) return no_point<T>(QuarticStatus::inside);
  Vec2<R> local;
  local[f.major] = copysign(along_major, f.local[f.major]);
  local[1 - f.major] = copysign(along_minor, f.local[1 - f.major]);
  const Vec2<R> world = e.center().template cast<R>() + detail::work_axes<R>(e) * local;
  return {QuarticStatus::outside, world.template cast<T>(), T(distance)};
}

}  // namespace

template <class T>
QuarticPoint<T> closest_point_closed_form(const Ellipse2<T>& ellipse, const VecArg<T, 2>& x) noexcept {
  using C = std::complex<T>;
  if (!x.allFinite()) return no_point<T>(QuarticStatus::invalid_input);
  const Frame<T> fr = frame<T>(ellipse, x);
  // Horizontal radius 1, b = 1 / vertical radius > 1, circle center (c, d).
  const T b = fr.a / fr.b, c = fr.c / fr.a, d = fr.d / fr.a;
  if (c * c + b * b * d * d <= T(1)) return no_point<T>(QuarticStatus::inside);
  // e .. k and s are real; s < 0 (three real roots of the resolvent) makes the rest complex,
  // as in the computer-algebra result the formula comes from (principal roots).
  const T e = b * b * b * b * c * c;
  const T f = b * b * b * b - 2 * b * b + 1;
  const T g = e - f + d * d * b * b;
  const T h = b * b * c;
  const T i = b * b * h - h;
  const T j = 72 * f * e * g + 2 * g * g * g + (108 * (f - e) + 36 * g) * i * i;
  const T k = 12 * i * i + g * g - 12 * f * e;
  const T s = j * j - 4 * k * k * k;
  const C q = pow(j + sqrt(C(s)), T(1) / 3);
  const T m = b * b - 1;
  const T n = 1 / m;
  const C o = g / (3 * f) + g * g * n * n * cbrt(T(2)) / (T(3) * q) + (n * n * q * cbrt(T(4))) / T(6);
  const C s3 = (e - g) * n * n + o;
  const C p = sqrt(s3);
  const C s2 = (2 * e - g) * n * n - o - (2 * h * ((e - g) * n * n * n - 2 / m)) / p;
  const T xx = std::real(h / (2 * m) - p / T(2) + sqrt(s2) / T(2));
  const T yy = sqrt(1 - xx * xx) / b;
  if (!isfinite(xx) || !isfinite(yy)) return no_point<T>(QuarticStatus::failed);
  return outside<T>(ellipse, fr, xx * fr.a, yy * fr.a, hypot(fr.c - xx * fr.a, fr.d - yy * fr.a));
}

namespace {

// closest_point_quartic in precision R, on a body and point whose squares stay in range.
template <class R, class T>
QuarticPoint<T> quartic_in(const Ellipse2<T>& ellipse, const Vec2<T>& x) noexcept {
  const Frame<R> fr = frame<R>(ellipse, x);
  const R u = fr.c / fr.a, v = fr.d / fr.b;
  if (u * u + v * v <= R(1)) return no_point<T>(QuarticStatus::inside);
  const R ratio = fr.b / fr.a;
  const R tau = detail::secular_quartic_root<R>(ratio * ratio, u, ratio * fr.d / fr.a);
  // Polish: the secular equation in the library's convention (origin at the point, the
  // ellipse's center at k), warm-started at t = a^2 tau.
  const Vec2<R> e = ellipse.radii().template cast<R>();
  const Vec2<R> k(-fr.local.cwiseAbs()[0], -fr.local.cwiseAbs()[1]);
  const auto p = detail::closest_from_outside<R, 2>(e, k, fr.a * fr.a * tau);
  const Vec2<R> foot = p.offset.cwiseAbs();  // center to the point, first quadrant
  return outside<R>(ellipse, fr, foot[fr.major], foot[1 - fr.major], p.norm);
}

}  // namespace

// At the scale of the body and the point (detail/scale.hpp), as closest_point: as given,
// rescaled by 2^-e with the lengths scaled back, or in the wide type. A major radius near
// the top of the range made a^2 (the polish's start a^2 tau) overflow: a NaN point.
template <class T>
QuarticPoint<T> closest_point_quartic(const Ellipse2<T>& ellipse, const VecArg<T, 2>& x) noexcept {
  using R = detail::Work<T>;
  if (!x.allFinite()) return no_point<T>(QuarticStatus::invalid_input);
  const detail::Scale scale = detail::scale_of<T>(ellipse.radii().maxCoeff(), ellipse.radii().minCoeff(),
                                                  std::max(detail::max_abs(ellipse.center()), detail::max_abs(x)));
  return detail::at_scale<R>(scale, [&]<class W>(auto units) {
    QuarticPoint<T> q = quartic_in<W>(units.body(ellipse), Vec2<T>(units.length(x)));
    if (q.status != QuarticStatus::outside) return q;
    units.lengths_out(q.point, q.distance);
    if (!(q.distance > T(0))) return no_point<T>(QuarticStatus::inside);
    return q;
  });
}

#define ELLIPSECT_INSTANTIATE(T)                                                                         \
  template QuarticPoint<T> closest_point_closed_form<T>(const Ellipse2<T>&, const Vec2<T>&) noexcept; \
  template QuarticPoint<T> closest_point_quartic<T>(const Ellipse2<T>&, const Vec2<T>&) noexcept;
ELLIPSECT_FOR_EACH_TYPE(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
