// First contact of two bodies moving with constant linear velocities (Eberly's method:
// unit ball plus axis-aligned ellipsoid, closest point by Newton on the convex secular
// function, contact time by Newton on the convex distance function; see docs/method.md).
//
// The pair is solved in coordinates relative to one body (its center, and its velocity), so
// the accuracy does not depend on the distance from the origin: a pair moved by an offset of
// 1e6 sizes keeps it (tests/property/translation_property_test.cpp).
// Accuracy (tested against a 50-digit reference, tests/property/contact_property_test.cpp), for
// pairs whose paths are not grazing (the relative velocity makes an angle theta with the
// contact plane's tangent, sin(theta) >= 1e-3):
//   time   relative error <= 1e-12, or absolute 1e-12 * scale / speed when near 0 (the
//          converged Newton iterate: it may lie after the exact contact by its rounding, a
//          few ulps);
//   point  within 1e-10 * scale of the exact contact point, plus the rounding of its
//          coordinates (eps |point|: half an ulp is 6e-11 at 1e6 from the origin);
//   normal within 1e-9 rad.
// For grazing paths the contact time is ill-conditioned (a double root): the status is
// right outside the tolerance band and the time is accurate to about sqrt(tolerance).
// Scaling bodies and velocities by 2^k leaves status, time and normal unchanged and
// multiplies the point by exactly 2^k, at any scale (docs/method.md, section 7). Where one
// body is smaller than the rounding of the other's coordinates (radius ratios beyond
// about 1e16), the normal is the large body's at the small one's center and the point the
// small body's support point along it: off by about the small body's size over the large
// one's radius of curvature (tests/regression/scales_test.cpp).
// At Options::tolerance = 0 (exact) the status at t = 0 is classify's exact relation:
// touching_at_start only for bodies that touch exactly, overlapping_at_start for every
// other common point; bodies apart by less than the narrowest band (1e-14) that close are a
// hit at -gap / slope (at least the smallest positive time), within the accuracy above.
// The rigid-motion first_contact below treats 0 as the narrowest band.
#pragma once

#include <ellipsect/gradient.hpp>
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
  did_not_converge,      // Options::max_contact_iterations reached; time is the last iterate
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

// ---- Gradient (gradient.hpp's parameters) ---------------------------------------------
//
// first_contact(a, velocity_a, b, velocity_b, t_max) and the derivatives of its time t and
// point x; the rigid form below has the same fields. Implicit differentiation of g(t) = 0, g the signed
// distance of the moved bodies (its derivatives as in distance.hpp's
// signed_distance_gradient, at the contact normal n and the bodies' poses at t):
// dt/dtheta = (dg/dtheta) / s with the closing speed
//     s = -dg/dt = n . (v_a - v_b) + (p_a x n) . omega_a + (p_b x n) . omega_b
// (p_X the support point of body X along +-n less its center, at t):
//     dt/d center(a) = -n / s = -dt/d center(b),   dt/d velocity_X = t dt/d center(X),
//     dt/d radii(X)_i = -r_i (A_X(t)^T n)_i^2 / (rho_X(n) s),
//     dt/d phi_X = -Q_X(t)^T (p_X x n) / s   (the orientation at time 0; Q_X(t) = exp(t [omega_X]x)),
//     dt/d omega_X = -t J(t omega_X)^T (p_X x n) / s   (J the left Jacobian of the rotation
//                                                      group; 2D: Q = J = 1).
// The linear form differentiates at omega = 0 (the angular velocities' derivatives then tell
// how the time changes as the bodies start to turn). Differentiable where status is hit with
// s > 0; the derivatives grow as 1 / s towards a grazing contact (s = 0, a double root of g:
// no derivative). overlapping_at_start: t = 0 for every nearby input, the derivatives are 0.
// Every other status, and hit with s <= 0 in rounding: NaN (touching_at_start and a graze
// have one-sided derivatives only; no_contact_in_window has no time).
// The point's derivatives (field `point`, a Jacobian per parameter group) by implicit
// differentiation of the touching itself: at the hit, c_b - c_a = p_a(n) + p_b(n), with
// p_X(n) = M_X n / rho_X(n) the support offset of X along n (M_X its shape matrix), whose
// derivative by n is H_X = (M_X - p_X p_X^T) / rho_X. A change of the parameters moves the
// offset as dp_X = (the parameters' own change of p_X at fixed n) + H_X dn, so the normal moves
// by (H_a + H_b) dn = the tangential part of d(c_b - c_a) - (the parameters' change of p_a and
// p_b) (its normal part is the time's equation above), and the point c_a(t) + p_a(n) by
//     dx = d c_a + t d v_a + v_a dt + (a's own change of p_a) + H_a dn
// (a turn u moves p_X at fixed n by u x p_X - H_X (u x n); the time moves it as the turn
// dt omega_X). Where the time's derivatives are 0 or NaN, so is every entry.
// Both are formed at the contact normal polished by one Newton step on the support gap's
// maximum at t (value.normal is left as first_contact returns it).
// Accuracy (tests/property/gradient_property_test.cpp, against 50-digit central differences of
// the time at which the support gap's maximum in the world frame vanishes and of a's support
// point there, the bodies turned in Real), of each component relative to its unit (the largest
// derivative by a center or a radius, times the pair's largest radius for the orientations;
// the largest by a velocity, times that radius for the angular velocities; the point's entries
// likewise over the whole Jacobian):
//   linear motion  within 2e-12 + 1e-13 / alpha^2, alpha the closing angle
//                  |n . (v_a - v_b)| / |v_a - v_b|: the derivatives grow as 1 / alpha towards a
//                  graze, and the rounding of the hit's time reaches them divided by alpha^2
//                  (1e-9 at alpha >= 0.01); measured, on random pairs, aspect ratios to 1e4,
//                  scale 1e-6 and 1e6, far apart and far from the origin with alpha from 1e-3
//                  to 1, the error times alpha^2 up to 8e-14 for the time and 4e-13 for the
//                  point (1.1e-9 at alpha = 1e-3);
//   rigid motion   within 1e-11; measured up to 3e-13 (spins to 10 turns).
template <class T, int N>
struct ContactPointJacobian {
  BodyJacobian<T, N> a, b;                                       // by the bodies at time 0
  Mat<T, N> velocity_a, velocity_b;                              // column j by velocity_j
  TurnJacobian<T, N> angular_velocity_a, angular_velocity_b;     // column j by omega_j
};
static_assert(detail::has_plain_layout<ContactPointJacobian<float, 2>, BodyJacobian<float, 2>, BodyJacobian<float, 2>,
                                        float[4], float[4], float[2], float[2]> &&
              detail::has_plain_layout<ContactPointJacobian<double, 3>, BodyJacobian<double, 3>,
                                        BodyJacobian<double, 3>, double[9], double[9], double[9], double[9]>);

template <class T, int N>
struct ContactGradient {
  Contact<T, N> value;                                     // first_contact(...)
  BodyGradient<T, N> a, b;                                 // of value.time, by the bodies at time 0
  Vec<T, N> velocity_a, velocity_b;                        // of value.time
  RotationVector<T, N> angular_velocity_a, angular_velocity_b;  // of value.time
  ContactPointJacobian<T, N> point;                        // of value.point
};
static_assert(detail::has_plain_layout<ContactGradient<float, 2>, Contact<float, 2>, BodyGradient<float, 2>,
                                        BodyGradient<float, 2>, float[2], float[2], float, float,
                                        ContactPointJacobian<float, 2>> &&
              detail::has_plain_layout<ContactGradient<double, 3>, Contact<double, 3>, BodyGradient<double, 3>,
                                        BodyGradient<double, 3>, double[3], double[3], double[3], double[3],
                                        ContactPointJacobian<double, 3>>);

template <class T, int N>
ContactGradient<T, N> first_contact_gradient(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a,
                                             const Ellipsoid<T, N>& b, const VecArg<T, N>& velocity_b, T t_max,
                                             const Options& options = {}) noexcept;

// ---- Rigid motion: constant linear and angular velocity, and growth ------------------
//
// The center moves as center + t * velocity and the body turns about its center with a
// constant angular velocity: its axes at time t are exp(t [omega]x) * axes (3D: omega is a
// vector, axis times rate in radians per unit time; 2D: a scalar rate, counterclockwise).
// Its radii scale as (1 + growth * t) about the center (growth >= 0, per unit time; 0: a
// rigid body). The body at t grows on at the rate growth / (1 + growth * t) of its radii
// then: restarting a motion from body_at(body, motion, t) takes that rate.
template <class T, int N>
struct RigidMotion;
template <class T>
struct RigidMotion<T, 2> {
  Vec<T, 2> velocity = Vec<T, 2>::Zero();
  T angular_velocity = T(0);
  T growth = T(0);
};
template <class T>
struct RigidMotion<T, 3> {
  Vec<T, 3> velocity = Vec<T, 3>::Zero();
  Vec<T, 3> angular_velocity = Vec<T, 3>::Zero();
  T growth = T(0);
};
static_assert(detail::has_plain_layout<RigidMotion<float, 2>, float[2], float, float> &&
              detail::has_plain_layout<RigidMotion<double, 3>, double[3], double[3], double>);

// The body at time t of its motion: center + t * velocity, axes rotated by exp(t [omega]x)
// (Rodrigues' formula, to a few ulps; the angle |omega| t is reduced by the sine and cosine
// exactly), radii times (1 + growth * t) (rounded once). Throws InputError naming
// "velocity", "angular_velocity", "growth" or "time" where the motion or t is not finite,
// growth is negative, or the moved center, the angle |omega| t or the grown radii overflow.
template <class T, int N>
Ellipsoid<T, N> body_at(const Ellipsoid<T, N>& body, const RigidMotion<T, N>& motion, T t);

// First contact of two bodies in rigid motion, in [0, t_max] (t_max may be +infinity), with
// the same statuses and fields as above; `iterations` counts advancement steps.
//
// Method (docs/method.md, section 9): conservative advancement. At the current time t the
// distance (distance.hpp) gives the direction n of closest approach (the direction between
// the centers while the bodies are more than their largest radii apart, or while the slab
// along it is open by an eighth of the radii, at the first step by 1e-6 of them); the slab gap
//     g_n(s) = n . (c_b(s) - c_a(s)) - rho_a(n, s) - rho_b(n, s)
// (rho_X the support radius of body X along n at time s) is a lower bound on the distance
// at every s, and for s >= t
//     g_n(s) >= g_n(t) - V (s - t)   and   g_n(s) >= g_n(t) + g_n'(t) (s - t) - K (s - t)^2 / 2,
// with V = -n . (v_b - v_a) + S_a |omega_a x n| + S_b |omega_b x n|, S = min(R, (R^2 - r^2) /
// (2 r)) (R, r the largest and smallest radius; S = 0 for a ball), and K = sum over the
// bodies of R^2 |omega x n|^2 / r + R |omega| |omega x n|: bounds on the rate at which a body
// turning about its center can move its support plane. Time advances to the first zero of
// the larger of the two bounds, so no contact is skipped; the second bound makes the steps
// Newton-like near a transversal contact. Where V <= 0 the slab never closes, and where the
// balls of radius R about the centers never meet from t on, neither do the bodies: no
// contact, ever.
// Growth: a body whose radii are (1 + g s) times those at 0 has support radius (1 + g s)
// rho^0(n, s) (rho^0 that of the body turning without growth); at t, with gamma = g / (1 +
// g t), it is (1 + gamma (s - t)) times that of the body at t turning on, so each body adds
// g R_0 to V (R_0 its largest radius at 0), gamma rho to the gap's rate at t, and over steps
// of at most 1 / (8 gamma) its K becomes 9/8 of the one at t plus 2 gamma |rho_turn'| (the
// turn's part of the rate); the balls grow at g R_0.
//
// Guarantees (tested against a 50-digit reference by another route, tests/property/
// rigid_contact_property_test.cpp):
//   * the reported time is never later than the first contact of the exact motion: each
//     step keeps a margin for the rounding of the bodies it forms at time t (a few ulps of
//     T of the centers, of t times the speeds and of the radii times (8 + |omega| t)) and of
//     the gap: a contact in the window is never missed, and no_contact_in_window is
//     certified (both spins zero: see the last item);
//   * hit: time within 1e-12 relative (or 1e-12 * scale / speed near 0), point within
//     1e-10 * scale (plus the rounding of its coordinates, as above), normal within 1e-9 rad,
//     for contacts that are not grazing (as above); the last steps run in long double along
//     the hit's normal (the double steps stop about 70 ulps of the size short of contact);
//   * translation invariant: the bodies are formed in a's frame (c_b - c_a, v_b - v_a), and
//     the accuracy holds at any distance from the origin (tested to 1e6 sizes);
//   * did_not_converge (Options::max_motion_steps reached, or the scene's coordinates at the
//     current time no longer resolve the bodies: far in the future of an unbounded window,
//     or speeds near the range of the type): `time` is a certified lower bound on the first
//     contact time, point and normal NaN;
//   * growth: the same guarantees and accuracy (tested against a 50-digit reference whose
//     bounds include the growth, tests/property/rigid_contact_property_test.cpp); bodies that
//     neither turn nor move apart still get their time from the advancement, then one step
//     to the root of the slab gap along the hit's normal (linear in time);
//   * both angular velocities and growths exactly zero: the answer of the translational first_contact
//     above (whose time is not certified early: it may lie a few ulps after the contact), its
//     point and normal bit for bit, a hit's time certified early: the smaller of its time and
//     the root, less its rounding, of the slab gap along its normal, which is linear in time
//     when nothing turns (where that slab does not close, the advancement above).
// invalid_input where a velocity or angular velocity is not finite, a growth is negative or
// not finite, or t_max is NaN or negative. Range: radii and speeds at any scale (rescaled by powers of two); pairs that
// need more than double (radius ratios beyond 2^160 or the centers' offset beyond 2^340
// radii, shapes.hpp; the offset, not the coordinates: the pair is solved in a's frame) and
// angular velocities or growths whose magnitude overflows (given, or in the time unit in
// which bodies beyond 2^+-64 move about a radius where their speeds leave 2^+-960 radii) get
// their start state (overlapping_at_start, touching_at_start) or did_not_converge at time 0.
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Ellipsoid<T, N>& b,
                            const RigidMotion<T, N>& motion_b, T t_max, const Options& options = {}) noexcept;

// first_contact under rigid motion and the derivatives of its time (the linear form's
// ContactGradient above). Growing bodies (either growth nonzero) get the value only, their
// derivatives NaN.
template <class T, int N>
ContactGradient<T, N> first_contact_gradient(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a,
                                             const Ellipsoid<T, N>& b, const RigidMotion<T, N>& motion_b, T t_max,
                                             const Options& options = {}) noexcept;

// ---- Rigid motion against shapes ---------------------------------------------------------
//
// first_contact(body, RigidMotion, shape, velocity_b, t_max, options) for the half-spaces,
// triangles, boxes, capsules and meshes of half_space.hpp, triangle.hpp, box.hpp,
// capsule.hpp and mesh.hpp (declared there): the shape moves at a constant velocity and does
// not turn; the body may grow. The same advancement as above in the shape's frame (the body moving at v_a - v_b),
// the slab gap along the normal n of the shape's distance at t taken as
//     g_n(s) = min over the shape of n . x  -  n . c(s)  -  rho(n, s)
// (the least over its vertices, its plane along its normal, its segment less the radius:
// exact for the shape as stored, a lower bound on the distance for any n), with the body's
// bounds V and K of above and none for the shape. No contact ever where the body's ball of
// radius R lies beyond the shape's slab and its center does not close on it. Statuses, the
// never-late guarantee and did_not_converge as above; the contact point in world coordinates
// at the contact time. Accuracy (tests/property/rigid_shapes_property_test.cpp, against the
// shapes' 50-digit static references at the reported time and before it): a hit at a time
// where the reference's relative gap is within 1e-9 of 0 and positive at earlier sampled
// times; no contact reported where the reference finds the shape touched; balls and bodies
// spinning about a symmetry axis give the translational time. As in the pair query, the
// advancement runs in the body's frame at time 0 (the shape moved by minus the body's
// center), so the answer does not depend on the distance from the origin: moved 1e6 sizes
// from it (exactly), the hit times are the same to 1e-12 of size / speed
// (tests/property/shape_translation_property_test.cpp; 4.7e-9 when the bodies were formed in
// world coordinates; float shapes are taken as given, their moved vertices would round).
// A hit whose point lies beyond the range of T (both moving at 1e305) is did_not_converge,
// its time a certified lower bound. Range: pairs within the native range (shapes.hpp,
// "Range", of the shape moved into the body's frame); beyond it the start state, else
// did_not_converge at 0.

}  // namespace ellipsect
