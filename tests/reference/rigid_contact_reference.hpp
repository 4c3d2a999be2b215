// Independent 50-digit REFERENCE for the first contact of two bodies in rigid motion
// (constant linear velocity of the centre, constant angular velocity about it), header templates.
//
// Route, all in Real (reference.hpp), chosen to differ from the library's (signed distance
// by trust-region Newton, slab gap along its normal with first- and second-order bounds):
//   * the bodies at time t are built in Real: centre c + t v, axes exp(t [omega]x) axes_0
//     (Rodrigues' formula with Real sine and cosine);
//   * a certified lower bound on their distance: the larger of (mu - 1)(r_a + r_b), mu the
//     Perram-Wertheim scale factor (mu A and mu B touch, and mu X contains X grown by
//     (mu - 1) times its smallest radius r_x), and the support gap n . r - sqrt(n^T Pa n) -
//     sqrt(n^T Pb n) in Real (every direction gives a lower bound) along the PW normal and
//     along the direction a damped Newton ascent of the gap from it reaches in double;
//   * dense certified sampling: no point of A moves faster than |omega_a| R_a relative to
//     A's centre, none of B faster than |v_b - v_a| + |omega_b| R_b relative to it, so the
//     distance falls at most at W = |v_b - v_a| + |omega_a| R_a + |omega_b| R_b; the slab
//     along the PW normal n closes at most at V_n = -n . (v_b - v_a) + R_a |omega_a x n| +
//     R_b |omega_b x n|. Time advances by the larger of (distance bound) / W and
//     (gap along n) / V_n: no contact is skipped. Sampling stops where the lower bound is
//     below 1e-8 of the bodies' size;
//   * bracketing: from there, steps doubling from the last certified one until mu < 1, then
//     bisection on the sign of mu - 1 to the full precision of Real. (Only a contact
//     shorter than the doubling's reach, within 1e-8 of the size of the bodies, could be
//     stepped over; such pairs are grazing, which the tests treat apart.)
// Precision: time ~1e-40 relative for transversal contacts; point and normal ~1e-40.
#pragma once

#include "distance_reference.hpp"
#include "reference.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>

namespace ellipsect::reference {

template <int N> using AngularRate = std::conditional_t<N == 2, double, Eigen::Matrix<double, 3, 1>>;

template <int N> struct RigidMotionRef {
  Eigen::Matrix<double, N, 1> velocity;
  AngularRate<N> omega;
  double growth = 0;  // radii times (1 + growth t)
};

template <int N> struct RigidContact {
  ContactKind kind = ContactKind::none;
  bool resolved = true;  // false: the step cap was reached, or no bracket was found
  Real time;             // hit: contact time; *_at_start: 0; none: +infinity
  RVec<N> point;         // PW point at `time` (hit and touching_at_start)
  RVec<N> normal;        // unit Ma (x - ca(t)), A -> B
  Real approach_sine;    // |n . u| / |u|, u the relative velocity of the material points at the contact point
  long steps = 0;        // certified samples taken
};

namespace detail {

template <int N> RMat<N> rotation(const AngularRate<N>& omega, const Real& t) {
  RMat<N> rot;
  if constexpr (N == 2) {
    const Real angle = Real(omega) * t, c = cos(angle), s = sin(angle);
    rot << c, -s, s, c;
  } else {
    RVec<3> w = to_real<3>(omega);
    const Real rate = sqrt(dot<3>(w, w));
    if (rate == 0) return RMat<3>::Identity();
    w /= rate;
    const Real angle = rate * t, c = cos(angle), s = sin(angle);
    RMat<3> k;
    k << 0, -w(2), w(1), w(2), 0, -w(0), -w(1), w(0), 0;
    rot = RMat<3>::Identity() + k * s + (k * k) * (1 - c);
  }
  return rot;
}

template <int N> Real rate_of(const AngularRate<N>& omega) {
  if constexpr (N == 2) return abs(Real(omega));
  else return sqrt(dot<3>(to_real<3>(omega), to_real<3>(omega)));
}

// omega x u in Real (2D: omega about the plane's normal).
template <int N> RVec<N> cross(const AngularRate<N>& omega, const RVec<N>& u) {
  if constexpr (N == 2) {
    const Real w(omega);
    return RVec<2>(-w * u(1), w * u(0));
  } else {
    const RVec<3> w = to_real<3>(omega);
    return RVec<3>(w(1) * u(2) - w(2) * u(1), w(2) * u(0) - w(0) * u(2), w(0) * u(1) - w(1) * u(0));
  }
}

template <int N> RBody<N> body_at(const RBody<N>& b0, const RigidMotionRef<N>& m, const Real& t) {
  RBody<N> b = b0;
  b.c = b0.c + to_real<N>(m.velocity) * t;
  b.axes = rotation<N>(m.omega, t) * b0.axes;
  if (m.growth != 0) b.radii = b0.radii * (1 + Real(m.growth) * t);
  complete_rbody<N>(b);
  return b;
}

}  // namespace detail

// kind: overlapping_at_start if mu(0) < 1 - band, touching_at_start if |mu(0) - 1| <= band,
// hit at the first t in [0, t_max] with mu(t) = 1, none otherwise. max_steps caps the
// samples, certified and bracketing (resolved = false beyond it: in the tests, paths that
// run along each other within 1e-8 of the bodies' size).
template <int N>
RigidContact<N> rigid_first_contact(const Body<N>& a, const RigidMotionRef<N>& ma, const Body<N>& b,
                                    const RigidMotionRef<N>& mb, double t_max, double band, long max_steps = 20000) {
  using namespace detail;
  const RBody<N> ra = make_rbody<N>(a, "a"), rb = make_rbody<N>(b, "b");
  const Real size = ra.rmax + rb.rmax;
  const RVec<N> vrel = to_real<N>(mb.velocity) - to_real<N>(ma.velocity);
  // The fastest any point of either body moves relative to a's center up to time s: the
  // relative velocity, the turn (|omega| R(s), R(s) = R (1 + g s)) and the growth (g R).
  const Real ga(ma.growth), gb(mb.growth);
  auto W_at = [&](const Real& s) {
    return sqrt(dot<N>(vrel, vrel)) + rate_of<N>(ma.omega) * ra.rmax * (1 + ga * s) + ga * ra.rmax +
           rate_of<N>(mb.omega) * rb.rmax * (1 + gb * s) + gb * rb.rmax;
  };
  const Real W = W_at(Real(0));

  struct Sample {
    RBody<N> a, b;
    PwState<N> s;
    Real mu;
  };
  Real lam = -1;
  auto sample = [&](const Real& t) {
    Sample x{body_at<N>(ra, ma, t), body_at<N>(rb, mb, t), {}, 0};
    x.s = pw_solve<N>(x.a.P, x.b.P, RVec<N>(x.b.c - x.a.c), lam);
    if (!x.s.centres_coincide) lam = x.s.lambda;
    x.mu = sqrt(x.s.F);
    return x;
  };
  auto normal_at = [&](const Sample& x, const RVec<N>& p) {
    RVec<N> n = matvec<N>(x.a.M, RVec<N>(p - x.a.c));
    const Real nn = sqrt(dot<N>(n, n));
    if (nn > 0) n /= nn;
    return n;
  };
  // A certified step from the sample's time t: the larger of the distance bound over W and
  // the support gap along the PW normal n over the fastest its slab can close, V_n = -n . v +
  // R_a |w_a x n| + R_b |w_b x n| + g_a R_a + g_b R_b (a body turning about its centre and
  // growing moves its support plane along n at most that fast). With growth the rates rise
  // with time: each is taken at the end of the step it gives (that step, shortened, stays
  // within it). Returns the lower bound on the distance, the step in `step`.
  auto lower_bound = [&](const Sample& x, const Real& t, Real& step) {
    Real lo = (x.mu - 1) * (x.a.rmin + x.b.rmin);
    auto certified = [&](const Real& gap, auto&& rate) {
      if (!(gap > 0)) return Real(0);
      const Real r0 = rate(t);
      if (!(r0 > 0)) return infinity();
      const Real r1 = rate(t + gap / r0);
      return r1 > 0 ? Real(gap / r1) : infinity();
    };
    step = certified(lo, W_at);
    if (x.s.centres_coincide) return lo;
    auto along = [&](const RVec<N>& n) {
      const Real gap = dot<N>(n, RVec<N>(x.b.c - x.a.c)) - sqrt(dot<N>(n, matvec<N>(x.a.P, n))) -
                       sqrt(dot<N>(n, matvec<N>(x.b.P, n)));
      const RVec<N> wa = cross<N>(ma.omega, n), wb = cross<N>(mb.omega, n);
      const Real across_a = sqrt(dot<N>(wa, wa)), across_b = sqrt(dot<N>(wb, wb));
      auto vn = [&](const Real& s) {
        return -dot<N>(n, vrel) + ra.rmax * ((1 + ga * s) * across_a + ga) + rb.rmax * ((1 + gb * s) * across_b + gb);
      };
      if (gap > 0) step = std::max(step, certified(gap, vn));
      lo = std::max(lo, gap);
    };
    const RVec<N> n_pw = normal_at(x, pw_point<N>(x.a, x.s));
    along(n_pw);
    // The PW normal is a poor direction for thin bodies far from contact: a damped Newton
    // ascent of the gap in double (distance_reference.hpp) gives a better one.
    GapData<double, N> g{x.a.P.template cast<double>(), x.b.P.template cast<double>(),
                         RVec<N>(x.b.c - x.a.c).template cast<double>()};
    const DVec<N> n_up = ascend<double, N>(g, n_pw.template cast<double>(), 40, 1e-15);
    RVec<N> n = to_real<N>(n_up);
    n /= sqrt(dot<N>(n, n));
    along(n);
    return lo;
  };
  RigidContact<N> out;
  auto finish = [&](ContactKind kind, const Real& t, const Sample& x) {
    out.kind = kind;
    out.time = t;
    out.point = pw_point<N>(x.a, x.s);
    out.normal = normal_at(x, out.point);
    const RVec<N> u = to_real<N>(mb.velocity) + cross<N>(mb.omega, RVec<N>(out.point - x.b.c)) -
                      to_real<N>(ma.velocity) - cross<N>(ma.omega, RVec<N>(out.point - x.a.c));
    const Real uu = sqrt(dot<N>(u, u));
    out.approach_sine = uu > 0 ? Real(abs(dot<N>(out.normal, u)) / uu) : Real(0);
    return out;
  };

  Sample x = sample(Real(0));
  const Real bd(band);
  if (x.mu < 1 - bd) return finish(ContactKind::overlapping_at_start, Real(0), x);
  if (abs(x.mu - 1) <= bd) return finish(ContactKind::touching_at_start, Real(0), x);
  out.time = infinity();
  if (!(W > 0)) return out;
  const Real tmax = std::isfinite(t_max) ? Real(t_max) : infinity();
  Real t = 0;
  const Real close = size * Real("1e-8");
  while (true) {
    // Certified sampling down to `close`.
    Real step;
    Real lo = lower_bound(x, t, step);
    while (lo > close) {
      if (++out.steps > max_steps) {
        out.resolved = false;
        return out;
      }
      t += step;
      if (t > tmax) return out;
      x = sample(t);
      lo = lower_bound(x, t, step);
    }
    // Bracket by doubling steps from the certified one, then bisect.
    Real h = std::max(lo, Real(0)) / W;
    if (h == 0) h = size * eps() / W;
    Real hi = -1;
    for (int k = 1; k <= 80; ++k, ++out.steps) {
      const Real tk = t + h * pow(Real(2), k);
      if (tk > tmax * 2 + size / W) break;
      if (sample(tk).mu < 1) {
        hi = tk;
        break;
      }
    }
    if (hi < 0) {  // no contact in reach: a near miss; go on sampling past it
      if (lo <= 0) {
        out.resolved = false;
        return out;
      }
      t += step;
      if (t > tmax) return out;
      x = sample(t);
      if (++out.steps > max_steps) {
        out.resolved = false;
        return out;
      }
      continue;
    }
    Real left = t;
    for (int i = 0; i < 400 && hi - left > eps() * 16 * hi; ++i) {
      const Real mid = (left + hi) / 2;
      if (sample(mid).mu < 1) hi = mid; else left = mid;
    }
    if (left > tmax) return out;
    return finish(ContactKind::hit, left, sample(left));
  }
}

// The functions the tests and benchmarks call, for N = 2 and 3: compiled once, in
// rigid_contact_reference.cpp (the library ellipsect_reference), not in every program that includes
// this header.
#define ELLIPSECT_RIGID_CONTACT_REFERENCE_FUNCTIONS(extern_, N) \
  extern_ template detail::RBody<N> detail::body_at<N>(const detail::RBody<N>&, const RigidMotionRef<N>&, const Real&); \
  extern_ template RigidContact<N> rigid_first_contact<N>(const Body<N>&, const RigidMotionRef<N>&, const Body<N>&, \
                                                          const RigidMotionRef<N>&, double, double, long);
ELLIPSECT_RIGID_CONTACT_REFERENCE_FUNCTIONS(extern, 2)
ELLIPSECT_RIGID_CONTACT_REFERENCE_FUNCTIONS(extern, 3)

}  // namespace ellipsect::reference
