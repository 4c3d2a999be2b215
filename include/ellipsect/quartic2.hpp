// The closed-form closest point of an ellipse to a point (an ellipse-circle test: the
// circle collides when its center is inside the ellipse or within its radius of that
// point), in two versions. Derivations and measurements: docs/niemitalo.md.
//
// Frame. The point is moved into the ellipse's axes and folded into the first quadrant
// (the closest point stays in that quadrant), then scaled so the major radius is 1 and
// lies along x: the ellipse is x^2 + b^2 y^2 = 1 with b = major / minor >= 1, the point
// is (c, d), c, d >= 0. The foot (x, y) of a normal through (c, d) satisfies
//   (1 - x^2) (b^2 c - (b^2 - 1) x)^2 = b^2 d^2 x^2,        y = d x / (b^2 c - (b^2 - 1) x),
// a quartic in x.
//
// closest_point_closed_form: O. Niemitalo's closed-form root of that quartic ("Ellipse-
//   circle and ellipse-ellipse collision detection"), evaluated as published, with its
//   intermediate variables e, f, g, h, i, j, k, s, q, m, n, o, s3, p, s2 and its one early
//   out (the point inside the ellipse). Kept as a documented alternative: it is
//   numerically unstable (intermediates growing like b^24, a division by b^2 - 1, a
//   cancellation in k, which equals g^2), and the square root of s = j^2 - 4 k^3 needs
//   complex arithmetic where the resolvent cubic has three real roots, so the formula is
//   evaluated in std::complex<T> (principal square and cube roots, the real part of x),
//   as the computer-algebra result it is. A non-finite result is reported as `failed`; a
//   finite wrong one cannot be detected. docs/niemitalo.md tabulates its failure rate per
//   scenario category (tests/property/niemitalo_property_test.cpp prints the table).
//
// closest_point_quartic: the same geometry through a numerically careful closed form.
//   With the multiplier t of the Lagrange condition (point P = (a^2 c / (a^2 + t),
//   b^2 d / (b^2 + t)) on the ellipse of radii a >= b), t is the largest real root of a
//   quartic that, shifted by its mean, reads (sigma^2 - delta^2)^2 = C^2 (sigma - delta)^2 +
//   D^2 (sigma + delta)^2; Ferrari's resolvent of that form has no linear term, and every
//   step avoids the cancellations of the published formula. The root is then polished by
//   the library's bracketed Newton/bisection on the secular equation (point.hpp), which
//   cannot fail. Float input is computed in double.
//
// Accuracy (tested against closest_point on the scenario categories,
// tests/property/niemitalo_property_test.cpp, and on points with a known foot,
// tests/unit/quartic2_test.cpp): closest_point_quartic returns the point within 1e-13 of
// max(major radius, |point|) and the distance within 1e-13 of (major radius + distance),
// for every outside point, in double and float; its closed-form root alone (before the
// polish) gives the point to 1e-12 of the major radius up to aspect ratio 10 and to about
// 1e-16 aspect^3 beyond (near a needle's flat side the quartic is ill-conditioned).
// closest_point_closed_form: see the failure table in docs/niemitalo.md. Both report a
// point whose distance rounds to 0 in T (on the ellipse, to rounding) as `inside`, never
// as `outside` at distance 0 (tests/regression/niemitalo_test.cpp).
#pragma once

#include <ellipsect/shapes.hpp>

#include <string_view>

namespace ellipsect {

enum class QuarticStatus {
  outside,        // the point is outside the ellipse; `point` and `distance` are set
  inside,         // the point is inside or on the ellipse (a circle centered there collides);
                  // a point within rounding of the boundary may be either, never outside at distance 0
  failed,         // the closed form produced a non-finite value (closest_point_closed_form only)
  invalid_input,  // the point is not finite
};

std::string_view to_string(QuarticStatus s) noexcept;

template <class T>
struct QuarticPoint {
  QuarticStatus status = QuarticStatus::invalid_input;
  Vec2<T> point;  // outside: the closest boundary point, world frame; NaN otherwise
  T distance;     // outside: |x - point| > 0 (also after rounding to T); NaN otherwise
};
static_assert(detail::has_plain_layout<QuarticPoint<float>, QuarticStatus, float[2], float> &&
              detail::has_plain_layout<QuarticPoint<double>, QuarticStatus, double[2], double>);

// The published closed form, evaluated in T.
template <class T>
QuarticPoint<T> closest_point_closed_form(const Ellipse2<T>& ellipse, const VecArg<T, 2>& x) noexcept;

// The careful closed form plus polishing.
template <class T>
QuarticPoint<T> closest_point_quartic(const Ellipse2<T>& ellipse, const VecArg<T, 2>& x) noexcept;

}  // namespace ellipsect
