// First contact of two bodies moving with constant linear velocities (Eberly's method:
// unit ball plus axis-aligned ellipsoid, closest point by Newton on the convex secular
// function, contact time by Newton on the convex distance function; see docs/method.md).
//
// Accuracy (tested against a 50-digit reference, tests/property/contact_test.cpp), for
// pairs whose paths are not grazing (the relative velocity makes an angle theta with the
// contact plane's tangent, sin(theta) >= 1e-3):
//   time   relative error <= 1e-12, or absolute 1e-12 * scale / speed when near 0;
//   point  within 1e-10 * scale of the exact contact point;
//   normal within 1e-9 rad.
// For grazing paths the contact time is ill-conditioned (a double root): the status is
// right outside the tolerance band and the time is accurate to about sqrt(tolerance).
// Scaling bodies and velocities by 2^k leaves status, time and normal unchanged and
// multiplies the point by exactly 2^k, at any scale (docs/method.md, section 7). Where one
// body is smaller than the rounding of the other's coordinates (radius ratios beyond
// about 1e16), the normal is the large body's at the small one's center and the point the
// small body's support point along it: off by about the small body's size over the large
// one's radius of curvature (tests/regression/scales_test.cpp).
#pragma once

#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <string_view>

namespace ellipsect {

enum class ContactStatus {
  hit,                   // separated at t = 0, first touch at `time` in (0, t_max]
  touching_at_start,     // touching at t = 0 (within the tolerance band); time = 0
  overlapping_at_start,  // interiors already intersect at t = 0; no point or normal
  no_contact_in_window,  // separated throughout [0, t_max] (includes "never touch" and a
                         // contact time beyond the largest finite T)
  did_not_converge,      // Options::max_iterations reached; time is the last iterate
  invalid_input,         // a velocity is not finite, or t_max is NaN or negative
};

std::string_view to_string(ContactStatus s) noexcept;

template <class T, int N>
struct Contact {
  ContactStatus status = ContactStatus::invalid_input;
  // Contact time, in the units of the velocities; 0 for the *_at_start statuses, NaN for
  // no_contact_in_window and invalid_input.
  T time;
  // World-frame contact point at `time` (hit, touching_at_start); NaN otherwise.
  Vec<T, N> point;
  // Unit normal at the contact point, outward from a, pointing from a towards b (hit,
  // touching_at_start); NaN otherwise.
  Vec<T, N> normal;
  // Newton steps taken on the contact time.
  int iterations = 0;
};
static_assert(detail::has_plain_layout<Contact<float, 2>, ContactStatus, float, float[2], float[2], int> &&
              detail::has_plain_layout<Contact<double, 3>, ContactStatus, double, double[3], double[3], int>);

// Bodies a and b move as center + t * velocity; contact is searched in [0, t_max]
// (t_max may be +infinity).
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Ellipsoid<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options = {}) noexcept;

}  // namespace ellipsect
