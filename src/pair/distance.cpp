// Separation distance and penetration depth (docs/distance.md):
//
// * The signed distance is max over unit n of the support gap g(n) = -phi(n)
//   (detail/distance_gap.hpp), found by trust-region Newton on the sphere. On the cone
//   {g > 0} the maximum is unique (g is concave and positively homogeneous), so a descent
//   that converges with g > 0 has found the separation distance, wherever it started.
// * The status agrees with classify. Far from touching it is certain without the
//   reduction: F(l) >= 1.01^2 in the Perram-Wertheim test (separated; the direction it
//   implies separates the bodies), classify's overlap certificate, or a converged descent
//   whose gap exceeds the tangency band of the reduced frame with its rounding (the
//   sphere body scaled by 1 + gap reaches at most gap * its largest radius further, so
//   gap >= distance / that radius). Otherwise the reduced frame decides as classify does:
//   the origin outside O and the gap |P| - 1 of O's closest point P against the band,
//   re-decided in the wider type when rounding could flip it; the world normal of the
//   sphere body at P starts the descent (the ball scaled by |P| touches O there, so that
//   plane separates the bodies when |P| > 1).
// * Overlapping bodies: penetration is not convex. The first descent's minimum is the
//   global one where the depth of r in an ellipsoid inside the Minkowski sum, fitted at
//   that minimum, reaches it (detail/depth_bound.hpp); otherwise the descent also starts
//   from the reduced-frame direction and the best sampled directions of both Gauss maps,
//   and the deepest converged descent wins.
// * The computation is written with the sphere body first, so swapping the arguments
//   swaps the points and negates the normal without changing a bit.
#include <ellipsect/distance.hpp>

#include "detail/certificates-inl.hpp"
#include "detail/classify_impl.hpp"
#include "detail/depth_bound.hpp"
#include "detail/distance_gap.hpp"
#include "detail/exact_relation.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace ellipsect {

std::string_view to_string(DistanceStatus s) noexcept {
  switch (s) {
    case DistanceStatus::separated: return "separated";
    case DistanceStatus::touching: return "touching";
    case DistanceStatus::overlapping: return "overlapping";
    case DistanceStatus::did_not_converge: return "did_not_converge";
  }
  return "unknown";
}

namespace {

// The reduced-frame start: the status and the world normal of S at the reduced closest
// point of O (pointing from S towards O), or a zero vector where there is none.
template <class R, int N>
struct Start {
  DistanceStatus status;
  Vec<R, N> normal;
};

template <class W, class R, class T, int N>
Start<R, N> start(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, W tol, bool& doubt) noexcept {
  const auto red = detail::reduce<W>(s, o);
  const W rounding = detail::reduced_rounding<W>(s, o, red.e, red.k);
  const W q0 = detail::level_at_origin<W, N>(red.e, red.k);
  Start<R, N> st;
  st.normal.setZero();
  doubt = abs(q0) <= rounding;
  const auto p = q0 > W(0) ? detail::closest_from_outside<W, N>(red.e, red.k) : detail::closest_from_inside<W, N>(red.e, red.k);
  if (p.norm > W(0)) st.normal = detail::unit_vector<W, N>(red.normal_map * p.point).template cast<R>();
  if (q0 <= W(0)) {
    st.status = DistanceStatus::overlapping;
    return st;
  }
  const W gap = p.norm - W(1);
  doubt = doubt || abs(gap - tol) <= rounding || abs(gap + tol) <= rounding;
  st.status = gap > tol ? DistanceStatus::separated : gap >= -tol ? DistanceStatus::touching : DistanceStatus::overlapping;
  return st;
}

// The start before any reduction: the better separating of the Perram-Wertheim
// direction y and the line of centers (nearly the answer for bodies far apart, where y
// is the normal of the hugely scaled bodies), and the status when it is already certain.
template <class R, int N>
struct QuickStart {
  std::optional<DistanceStatus> status;
  Vec<R, N> normal;
};

template <class R, class T, int N>
QuickStart<R, N> quick_start(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const detail::GapBodies<R, N>& g) noexcept {
  if (g.r_norm == R(0)) {  // common center: overlapping; start along S's shortest axis
    int i;
    s.radii().minCoeff(&i);
    return {DistanceStatus::overlapping, g.axes1.col(i).normalized()};  // float axes: unit to rounding only
  }
  const auto pw = detail::pw_direction<R, N>(g);
  const Vec<R, N> line = g.r / g.r_norm;
  // y is NaN where C is singular in working precision (two needles: the sum of two matrices
  // of rank 1 to rounding); the comparison is false then and keeps the line.
  const Vec<R, N> n = detail::gap_value<R, N>(g, pw.n) <= detail::gap_value<R, N>(g, line) ? pw.n : line;
  // F >= 1.01^2 puts y, and then n, in {g > 0}.
  if (pw.f >= R(1.01 * 1.01)) return {DistanceStatus::separated, n};
  namespace hw = detail::HWY_NAMESPACE;  // a certain common point
  if (hw::certificate_code<false>(s, o, 0.0) > 0) return {DistanceStatus::overlapping, n};
  return {std::nullopt, n};
}

// A separation distance above which classify certainly says separated: the tangency band
// times the sphere body's largest radius, plus the rounding of the reduced frame
// (detail::reduced_rounding, in world units) and of the distance itself.
template <class R, class T, int N>
R separation_margin(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const detail::GapBodies<R, N>& g, R tol) noexcept {
  const R a_max = R(s.radii().maxCoeff()), aspect = a_max / R(s.radii().minCoeff());
  const R size = g.r_norm + a_max + R(o.radii().maxCoeff()) + R(s.center().norm()) + R(o.center().norm());
  return tol * a_max + R(4 * detail::reduced_frame_ulps) * std::numeric_limits<R>::epsilon() * aspect * size;
}

// The status from classify's exact relation (Options::tolerance = 0).
template <class T, int N>
DistanceStatus exact_status(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) {
  const Relation rel = detail::exact_relation(a, b);
  return rel == Relation::touching    ? DistanceStatus::touching
         : rel == Relation::separated ? DistanceStatus::separated
                                      : DistanceStatus::overlapping;
}

// Directions sampled for the penetration search, in addition to the other starts.
template <int N>
constexpr int penetration_starts = N == 2 ? 3 : 4;

// Whether the depth phi at `at` is within depth_certificate of the global minimum of phi: the
// lower bound of detail/depth_bound.hpp reaches it less the margin (which also holds the
// bound's rounding, a few dozen ulps of the size), scale = the largest radii plus the depth.
inline constexpr double depth_certificate = 1e-13;

// The bound where it certifies `at`, else -infinity.
template <class R, int N>
R certified_depth(const detail::GapBodies<R, N>& g, const detail::GapAt<R, N>& at) noexcept {
  const R scale = g.radii1.maxCoeff() + g.radii2.maxCoeff() + abs(at.phi);
  const R bound = detail::depth_lower_bound<R, N>(g, at);
  return bound >= at.phi - R(depth_certificate) * scale ? bound : -std::numeric_limits<R>::infinity();
}

// The answer from the descent `best` (status set), s the sphere body.
template <class R, class T, int N>
Distance<T, N> answer(Distance<T, N>& out, const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o,
                      const detail::GapBodies<R, N>& g, const detail::Descent<R, N>& best, bool a_is_s) noexcept {
  const Vec<R, N> point_s = s.center().template cast<R>() + best.at.s1;
  const Vec<R, N> point_o = o.center().template cast<R>() - best.at.s2;
  out.distance = T(-best.at.phi);
  if (!best.converged) {
    // g at the last iterate is at most max g; less a bound on its rounding (each |B n| is off
    // by a few ulps of the body's largest radius, n . r by a few of |r|), rounded down to T.
    out.status = DistanceStatus::did_not_converge;
    const R margin = R(16) * std::numeric_limits<R>::epsilon() * (g.r_norm + g.radii1.maxCoeff() + g.radii2.maxCoeff());
    const R lower = -(best.at.phi + margin);
    out.distance = T(lower);
    if (R(out.distance) > lower) out.distance = nextafter(out.distance, -std::numeric_limits<T>::infinity());
  }
  // The status is certified; rounding within the stated accuracy may leave the distance on
  // the wrong side of 0 (or at -0), and clamping only moves it towards the true value.
  if (out.status == DistanceStatus::separated && !(out.distance > T(0))) out.distance = T(0);
  if (out.status == DistanceStatus::overlapping && out.distance > T(0)) out.distance = T(0);
  out.point_a = (a_is_s ? point_s : point_o).template cast<T>();
  out.point_b = (a_is_s ? point_o : point_s).template cast<T>();
  out.normal = (a_is_s ? best.at.n : Vec<R, N>(-best.at.n)).template cast<T>();
  return out;
}

// The solve in working precision R, s the sphere body (detail::order_pair). `hint`: a unit
// direction from s towards o to descend from first, or null. Its descent settles the answer
// alone where it certifies it: separated by more than the band (a converged descent with
// g > 0 has the unique maximum), or, for the penetration, a depth that the inner-ellipsoid
// bound proves global and beyond the band (twice the separation margin: the depth of a pair
// within the band is at most tol / (1 - tol) times the sphere body's largest radius).
// Otherwise the solve goes on as without it, the hint's descent one candidate more.
template <class R, class T, int N>
Distance<T, N> solve(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s, const Options& options,
                     bool penetration, const Vec<R, N>* hint = nullptr) noexcept {
  constexpr T nan = std::numeric_limits<T>::quiet_NaN();
  Distance<T, N> out;
  out.distance = nan;
  out.point_a.setConstant(nan);
  out.point_b.setConstant(nan);
  out.normal.setConstant(nan);

  const auto g = detail::gap_bodies<R>(s, o);
  std::optional<detail::Descent<R, N>> hinted;
  if (hint != nullptr) {
    hinted = detail::descend<R, N>(g, *hint, options.max_distance_iterations);
    const R margin = separation_margin<R>(s, o, g, R(double(options.tolerance)));
    if (hinted->converged && -hinted->at.phi > margin) {
      out.status = DistanceStatus::separated;
      out.iterations = hinted->iterations;
      return answer<R>(out, s, o, g, *hinted, a_is_s);
    }
    if (penetration && hinted->converged && hinted->at.phi > 2 * margin && certified_depth(g, hinted->at) > 2 * margin) {
      out.status = DistanceStatus::overlapping;
      out.iterations = hinted->iterations;
      return answer<R>(out, s, o, g, *hinted, a_is_s);
    }
  }
  const QuickStart<R, N> quick = quick_start<R>(s, o, g);

  if (quick.status == DistanceStatus::overlapping && !penetration) {
    out.status = DistanceStatus::overlapping;
    out.distance = T(0);
    return out;
  }
  // The first descent starts from the quick direction; `starts` holds the others.
  auto best = detail::descend<R, N>(g, quick.normal, options.max_distance_iterations);
  out.iterations = best.iterations;
  if (hinted) {  // the smaller phi, converged first
    out.iterations += hinted->iterations;
    if ((hinted->converged && !best.converged) || (hinted->converged == best.converged && hinted->at.phi < best.at.phi))
      best = *hinted;
  }
  std::array<Vec<R, N>, 1 + penetration_starts<N>> starts;
  int count = 0;
  if (quick.status) {
    out.status = *quick.status;
  } else if (best.converged && -best.at.phi > separation_margin<R>(s, o, g, R(double(options.tolerance)))) {
    out.status = DistanceStatus::separated;
  } else {
    bool doubt;
    Start<R, N> st = start<R, R>(s, o, R(double(options.tolerance)), doubt);
    if (doubt) st = start<detail::Wide<R>, R>(s, o, detail::Wide<R>(double(options.tolerance)), doubt);
    if (st.status == DistanceStatus::touching && options.tolerance.is_exact()) {  // the exact relation decides
      st.status = exact_status(s, o);
    }
    out.status = st.status;
    // Absent only when S's center lies exactly on O's boundary (the bodies overlap).
    if (st.normal.squaredNorm() > R(0) && st.normal.allFinite()) starts[count++] = st.normal;
  }
  if (out.status == DistanceStatus::overlapping) {
    if (!penetration) {
      out.distance = T(0);
      return out;
    }
    if (best.converged && certified_depth(g, best.at) > -std::numeric_limits<R>::infinity()) {
      count = 0;
    } else {
      std::array<Vec<R, N>, penetration_starts<N>> sampled;
      const int found = detail::sampled_starts<R, N, penetration_starts<N>>(g, sampled);
      for (int i = 0; i < found; ++i) starts[count++] = sampled[i];
    }
  }
  for (int i = 0; i < count; ++i) {
    const auto d = detail::descend<R, N>(g, starts[i], options.max_distance_iterations);
    out.iterations += d.iterations;
    // The smallest phi wins (an unconverged one lower than every converged one makes the
    // answer uncertain); within rounding, a converged descent wins.
    const R noise = std::max(d.at.noise, best.at.noise);
    if (d.at.phi < best.at.phi - noise || (d.at.phi <= best.at.phi + noise && d.converged && !best.converged)) best = d;
  }
  return answer<R>(out, s, o, g, best, a_is_s);
}

// The solve at the pair's scale (detail/scale.hpp): as given, rescaled by 2^-e with the
// lengths scaled back, or in the wide type. The sphere body is chosen before rescaling:
// rescaling can merge two bodies that differ only below the smallest subnormal, and swap
// symmetry needs the order they had.
// `hint`: a direction from a towards b, or null (a zero or non-finite one is none).
template <class T, int N>
Distance<T, N> solve_at_scale(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options,
                              bool penetration, const Vec<T, N>* hint = nullptr) noexcept {
  const auto pair = detail::order_pair(a, b);
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    std::optional<Vec<W, N>> start;  // from s towards o, unit
    if (hint != nullptr && hint->allFinite()) {
      const Vec<W, N> h = (pair.a_is_s ? Vec<T, N>(*hint) : Vec<T, N>(-*hint)).template cast<W>();
      const W length = h.norm();
      if (length > W(0) && isfinite(length)) start = Vec<W, N>(h / length);
    }
    Distance<T, N> d = solve<W>(units.body(pair.s), units.body(pair.o), pair.a_is_s, options, penetration,
                                start ? &*start : nullptr);
    units.lengths_out(d.distance, d.point_a, d.point_b);
    if (options.tolerance.is_exact() && d.status != DistanceStatus::did_not_converge &&
        units.loses(a, b)) {  // the status of the pair as given, not of the scaled one
      d.status = exact_status(a, b);
      if (d.status == DistanceStatus::separated && !(d.distance > T(0))) d.distance = T(0);
      if (d.status == DistanceStatus::overlapping && d.distance > T(0)) d.distance = T(0);
    }
    return d;
  });
}

}  // namespace

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options) noexcept {
  return solve_at_scale(a, b, options, false);
}

template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options) noexcept {
  return solve_at_scale(a, b, options, true);
}

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options,
                        const VecArg<T, N>& hint) noexcept {
  return solve_at_scale(a, b, options, false, &hint);
}

template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options,
                               const VecArg<T, N>& hint) noexcept {
  return solve_at_scale(a, b, options, true, &hint);
}

template <class T, int N>
DistanceGradient<T, N> signed_distance_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                const Options& options) noexcept {
  using R = detail::Work<T>;
  const BodyGradient<T, N> unknown = detail::constant_gradient<T, N>(std::numeric_limits<T>::quiet_NaN());
  DistanceGradient<T, N> out{signed_distance(a, b, options), unknown, unknown};
  if (out.value.status == DistanceStatus::did_not_converge) return out;
  // d = max over n of n . (center(b) - center(a)) - rho_a(n) - rho_b(n), at the returned n.
  const Vec<R, N> n = out.value.normal.template cast<R>();
  BodyGradient<R, N> ga = detail::support_radius_gradient<R>(a, n), gb = detail::support_radius_gradient<R>(b, n);
  ga.center = n;
  gb.center = -n;
  out.a = detail::gradient_in<T>(ga, R(-1));
  out.b = detail::gradient_in<T>(gb, R(-1));
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                              \
  template Distance<T, N> distance<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, const Options&) noexcept; \
  template Distance<T, N> signed_distance<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, const Options&) noexcept; \
  template Distance<T, N> distance<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, const Options&,          \
                                         const Vec<T, N>&) noexcept;                                              \
  template Distance<T, N> signed_distance<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, const Options&,   \
                                                const Vec<T, N>&) noexcept;                                       \
  template DistanceGradient<T, N> signed_distance_gradient<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&,      \
                                                                 const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
