#include <ellipsect/half_space.hpp>

#include "detail/axes.hpp"
#include "detail/compensated.hpp"
#include "detail/contact_start.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/reduce.hpp"
#include "detail/scale.hpp"
#include "detail/math.hpp"
#include "detail/obstacle_motion.hpp"
#include "detail/validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace ellipsect {
namespace {

using detail::CompensatedDot;
using detail::Double;

// x times 2^e; most pairs run at e = 0, where this is free (std::ldexp is a library call).
template <class F>
F pow2(F x, int e) noexcept {
  return e == 0 ? x : ldexp(x, e);
}

// The body against the plane in the working type F, every length times 2^-exponent
// (half_space.hpp, "Math"): the lower gap L = s - rho, the upper gap U = -s - rho, the support
// radius rho, the lowest point and the unit normal n; `error` bounds |L - exact| and
// |U - exact| (0: computed in compensated arithmetic, taken as exact), `size` is the
// largest radius.
template <class F, int N>
struct Gaps {
  using Scalar = F;
  F lower, upper, rho, error, size;
  // The lowest point c - support, support = A diag(r) w the support offset along n, with
  // w = diag(r) q / rho and q = A^T n.
  Vec<F, N> lowest, normal, support, w, q;
  Vec<F, N> offset;  // c - p, rounded
  int exponent;
};

// Plain arithmetic when `compensated` is false, with the error bound
//   (N + 4) eps (sum |n_i (c_i - p_i)| + rho + r_max),
// twice the first-order bound u ((N + 2) sum |n_i (c_i - p_i)| + (N + 4) rho + N^1.5 r_max)
// (u = eps / 2: the differences and the dot product s; rho's own rounding; the rounding of
// A^T n, at most gamma_N sqrt(N) per entry, times r_max; the final difference).
// Compensated: s and A^T n by compensated dot products, c - p split exactly, and L, U from
// (s^2 - rho^2) / (s + rho) in double length where they cancel.
template <class F, class T, int N>
Gaps<F, N> gaps_in(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, int exponent, bool compensated) noexcept {
  const Mat<F, N> axes = detail::work_axes<F>(a);
  Vec<F, N> c, p, r, n;
  for (int i = 0; i < N; ++i) {
    c[i] = pow2(F(a.center()[i]), -exponent);
    p[i] = pow2(F(b.point()[i]), -exponent);
    r[i] = pow2(F(a.radii()[i]), -exponent);
    n[i] = F(b.normal()[i]);
  }
  Gaps<F, N> g;
  g.offset = c - p;
  Vec<F, N> t;  // t_k = r_k (A^T n)_k, rho = |t|
  if (!compensated) {
    F s = 0, spread = 0;
    for (int i = 0; i < N; ++i) {
      const F term = n[i] * g.offset[i];
      s += term;
      spread += abs(term);
    }
    g.q = axes.transpose() * n;
    t = r.cwiseProduct(g.q);
    g.rho = t.norm();
    g.lower = s - g.rho;
    g.upper = -s - g.rho;
    g.error = F(N + 4) * std::numeric_limits<F>::epsilon() * (spread + g.rho + r.maxCoeff());
  } else {
    CompensatedDot<F> sd;
    for (int i = 0; i < N; ++i) {
      const Double<F> d = detail::two_sum(c[i], -p[i]);
      sd.add(n[i], d.hi);
      sd.add(n[i], d.lo);
    }
    const Double<F> s = sd.value();
    Double<F> rho2{};
    for (int k = 0; k < N; ++k) {
      CompensatedDot<F> ud;
      for (int i = 0; i < N; ++i) ud.add(axes(i, k), n[i]);
      g.q[k] = ud.value().hi;
      const Double<F> tk = detail::times(ud.value(), r[k]);
      t[k] = tk.hi;
      rho2 = detail::add(rho2, detail::square(tk));
    }
    g.rho = sqrt(rho2.hi);
    // s^2 - rho^2 = (s - rho)(s + rho): L and U where they cancel, directly where they do not.
    const F q = detail::add(detail::square(s), Double<F>{-rho2.hi, -rho2.lo}).hi;
    g.lower = s.hi > F(0) ? q / (s.hi + g.rho) : s.hi - g.rho;
    g.upper = s.hi < F(0) ? q / (g.rho - s.hi) : -(s.hi + g.rho);
    g.error = 0;
  }
  g.size = r.maxCoeff();
  g.w = t / g.rho;
  g.support = axes * r.cwiseProduct(g.w);
  g.lowest = c - g.support;
  g.normal = n;
  g.exponent = exponent;
  return g;
}

// Whether the relation is certain: each gap farther than its error from the band's edges.
template <class F, int N>
bool decided(const Gaps<F, N>& g, const Options& options) noexcept {
  const F band = F(double(options.tolerance)) * g.rho;
  const F margin = g.error * (F(1) + F(double(options.tolerance)));
  return abs(g.lower - band) > margin && abs(g.lower + band) > margin && abs(g.upper + band) > margin;
}

// Calls then(gaps), the gaps computed at the pair's scale (detail/scale.hpp): in the working
// type, rescaled by a power of two where needed, or in the wide type; in plain arithmetic
// where accept(gaps) holds, else compensated.
template <class T, int N, class Accept, class Then>
auto with_gaps(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, Accept&& accept, Then&& then) noexcept {
  const detail::Scale scale = detail::scale_of<T>(a.radii().maxCoeff(), a.radii().minCoeff(),
                                                  std::max(detail::max_abs(a.center()), detail::max_abs(b.point())));
  // The gaps scale the inputs by 2^-exponent themselves and keep the exponent.
  return detail::in_type<detail::Work<T>>(scale, [&]<class F>(int exponent) {
    if constexpr (!std::is_same_v<F, detail::Work<T>>) {
      return then(gaps_in<F>(a, b, exponent, true));
    } else {
      const Gaps<F, N> quick = gaps_in<F>(a, b, exponent, false);
      return then(accept(quick) ? quick : gaps_in<F>(a, b, exponent, true));
    }
  });
}

// The stated accuracy of lengths (half_space.hpp: 1e-14 scale) with a margin: plain results
// are kept where their error bound is below 5e-15 of scale.
template <class F, int N>
bool accurate(const Gaps<F, N>& g, F length) noexcept {
  return g.error <= F(5e-15) * (g.size + abs(length));
}

template <class F, int N>
Relation relation_of(const Gaps<F, N>& g, const Options& options) noexcept {
  const F band = F(double(options.tolerance)) * g.rho;
  if (g.lower > band) return Relation::separated;
  if (g.lower >= -band) return Relation::touching;
  if (g.upper >= -band) return Relation::b_contains_a;
  return Relation::overlapping;
}

template <class T, class F, int N>
Vec<T, N> world(const Vec<F, N>& v, int exponent) noexcept {
  Vec<T, N> out;
  for (int i = 0; i < N; ++i) out[i] = T(pow2(v[i], exponent));
  return out;
}

template <class T, class F, int N>
Distance<T, N> distance_from(const Gaps<F, N>& g, const HalfSpace<T, N>& b, const Options& options,
                             bool penetration) noexcept {
  Distance<T, N> d;
  const Relation rel = relation_of(g, options);
  d.status = rel == Relation::separated  ? DistanceStatus::separated
             : rel == Relation::touching ? DistanceStatus::touching
                                         : DistanceStatus::overlapping;
  if (d.status == DistanceStatus::overlapping && !penetration) {
    d.distance = T(0);
    d.point_a = d.point_b = d.normal = detail::nan_vec<T, N>();
    return d;
  }
  d.distance = T(pow2(g.lower, g.exponent));
  d.point_a = world<T>(g.lowest, g.exponent);
  d.point_b = world<T>(Vec<F, N>(g.lowest - g.lower * g.normal), g.exponent);
  d.normal = -b.normal();
  return d;
}

// The gaps that distance and signed_distance accept.
auto distance_accepts(const Options& options) noexcept {
  return [&options](const auto& g) { return decided(g, options) && accurate(g, g.lower); };
}

template <class T, int N>
Distance<T, N> distance_of(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options,
                           bool penetration) noexcept {
  return with_gaps(a, b, distance_accepts(options),
                   [&](const auto& g) { return distance_from<T>(g, b, options, penetration); });
}

// signed_distance_gradient from the gaps (half_space.hpp; n_H = g.normal, s = g.support):
//   dL/dc = n_H,   dL/dr_i = -w_i q_i,   dL/dphi = -(s x n_H),
//   dL/dp = -n_H,  the plane's turn (x - p) x n = -(lever x n_H) with lever = c - p - s.
// Where the plane's point lies beyond 1024 radii of the center, the lever's part along n_H
// cancels in the cross product: c - p is split exactly and the products compensated;
// otherwise the plain products' rounding stays below 1e-13 of the body's size.
template <class T, class F, int N>
DistanceGradient<T, N, HalfSpaceGradient<T, N>> gradient_from(const Gaps<F, N>& g, const Ellipsoid<T, N>& a,
                                                               const HalfSpace<T, N>& b, const Options& options) noexcept {
  DistanceGradient<T, N, HalfSpaceGradient<T, N>> out;
  out.value = distance_from<T>(g, b, options, true);
  const Vec<F, N>& n = g.normal;
  const F length = pow2(F(1), g.exponent);
  out.a.center = n.template cast<T>();
  out.a.radii = (-g.w.cwiseProduct(g.q)).template cast<T>();
  out.a.orientation = detail::rotation_in<T, F, N>(detail::turn_rate<F, N>(Vec<F, N>(-length * g.support), n));
  out.b.point = (-n).template cast<T>();
  if (!(g.offset.cwiseAbs().maxCoeff() > F(1024) * g.size)) {
    out.b.normal = detail::rotation_in<T, F, N>(detail::turn_rate<F, N>(Vec<F, N>(length * (g.support - g.offset)), n));
    return out;
  }
  std::array<Vec<F, N>, 3> lever{g.offset, g.offset, Vec<F, N>(-g.support)};
  for (int i = 0; i < N; ++i)
    lever[1][i] = detail::two_sum(pow2(F(a.center()[i]), -g.exponent), -pow2(F(b.point()[i]), -g.exponent)).lo;
  const auto turn = [&](int j, int k) {  // -(lever x n_H) . e with e_j x e_k = e
    CompensatedDot<F> dot;
    for (const auto& x : lever) {
      dot.add(-x[j], n[k]);
      dot.add(x[k], n[j]);
    }
    return T(pow2(dot.value().hi, g.exponent));
  };
  if constexpr (N == 2) {
    out.b.normal = turn(0, 1);
  } else {
    out.b.normal = Vec<T, 3>(turn(1, 2), turn(2, 0), turn(0, 1));
  }
  return out;
}

}  // namespace

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options) noexcept {
  return with_gaps(
      a, b, [&](const auto& g) { return decided(g, options); }, [&](const auto& g) { return relation_of(g, options); });
}

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options) noexcept {
  return classify(a, b, options) != Relation::separated;
}

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options) noexcept {
  return distance_of(a, b, options, false);
}

template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a, const HalfSpace<T, N>& b, const Options& options) noexcept {
  return distance_of(a, b, options, true);
}

template <class T, int N>
DistanceGradient<T, N, HalfSpaceGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a,
                                                                         const HalfSpace<T, N>& b,
                                                                         const Options& options) noexcept {
  return with_gaps(a, b, distance_accepts(options),
                   [&](const auto& g) { return gradient_from<T>(g, a, b, options); });
}

// L(t) = L(0) - t sigma: the hit at L(0) / sigma. The velocities are rescaled by 2^-v (v the
// exponent of the largest speed, or 0), and the time comes back times 2^(exponent - v).
template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const HalfSpace<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  Contact<T, N> out = detail::unanswered_contact<T, N>();
  if (!detail::valid_motion<T, N>(velocity_a, velocity_b, t_max)) return out;
  // The hit time is L / sigma: L to within 2e-15 relative (the stated 1e-14 with a margin).
  const auto accept = [&](const auto& g) {
    return decided(g, options) && (relation_of(g, options) != Relation::separated || g.error <= 2e-15 * g.lower);
  };
  return with_gaps(a, b, accept, [&](const auto& g) {
    using F = typename std::decay_t<decltype(g)>::Scalar;
    const Relation rel = relation_of(g, options);
    if (rel != Relation::separated) {
      out.time = T(0);
      if (rel != Relation::touching) {
        out.status = ContactStatus::overlapping_at_start;
        return out;
      }
      out.status = ContactStatus::touching_at_start;
      out.point = world<T>(g.lowest, g.exponent);
      out.normal = -b.normal();
      return out;
    }
    out.status = ContactStatus::no_contact_in_window;
    const T speed = std::max(detail::max_abs(velocity_a), detail::max_abs(velocity_b));
    if (!(speed > T(0))) return out;
    const int v = detail::speed_exponent(speed);
    CompensatedDot<F> sd;  // sigma = -n . (v_a - v_b)
    for (int i = 0; i < N; ++i) {
      const Double<F> w = detail::two_sum(pow2(F(velocity_a[i]), -v), -pow2(F(velocity_b[i]), -v));
      sd.add(-g.normal[i], w.hi);
      sd.add(-g.normal[i], w.lo);
    }
    const F sigma = sd.value().hi;
    if (!(sigma > F(0))) return out;
    const F time = std::max(pow2(g.lower / sigma, g.exponent - v), F(std::numeric_limits<T>::denorm_min()));
    if (!(isfinite(T(time)) && T(time) <= t_max)) return out;
    out.time = T(time);
    Vec<F, N> point;
    for (int i = 0; i < N; ++i) point[i] = pow2(g.lowest[i], g.exponent) + time * F(velocity_a[i]);
    if (!point.template cast<T>().allFinite()) {  // the body has left the range of T by then
      out.status = ContactStatus::did_not_converge;
      return out;
    }
    out.status = ContactStatus::hit;
    out.point = point.template cast<T>();
    out.normal = -b.normal();
    return out;
  });
}

// ---- Rigid motion (detail/obstacle_motion.hpp) --------------------------------------------

namespace detail::obstacle {
template <class T, int N>
struct ObstacleTraits<HalfSpace<T, N>> {
  // The distance's normal is exactly -normal (half_space.hpp); along any other direction the
  // half-space reaches -infinity.
  static Lowest lowest(const Vec<R, N>& n, const HalfSpace<T, N>& h) noexcept {
    const Vec<R, N> outward = h.normal().template cast<R>();
    if (n != -outward) return {-std::numeric_limits<R>::infinity(), 0};
    const R x = n.dot(h.point().template cast<R>());
    return {x, abs(x)};
  }
  // None: the half-space's distance costs no solve.
  static std::optional<Vec<R, N>> inner_point(const HalfSpace<T, N>&) noexcept { return std::nullopt; }
  static T coordinate(const HalfSpace<T, N>& h) noexcept { return detail::max_abs(h.point()); }
};
}  // namespace detail::obstacle

ELLIPSECT_RIGID_OBSTACLE_CONTACT(HalfSpace)

// ---- The factories -----------------------------------------------------------------------

template <class T, int N>
HalfSpace<T, N> HalfSpace<T, N>::from_point_normal(const Vec<T, N>& point, const Vec<T, N>& normal) {
  detail::require_finite(point, "point");
  detail::require_finite(normal, "normal");
  if (!(normal.cwiseAbs().maxCoeff() > T(0))) throw InputError("normal", "must not be zero");
  HalfSpace h;
  Eigen::Map<Vec<T, N>>(h.point_.data()) = point;
  Eigen::Map<Vec<T, N>>(h.normal_.data()) = detail::unit_vector<T, N>(normal);
  return h;
}

template <class T, int N>
HalfSpace<T, N> HalfSpace<T, N>::translated(const Vec<T, N>& offset) const {
  HalfSpace h = *this;
  Eigen::Map<Vec<T, N>>(h.point_.data()) = detail::moved<T, N>(point(), offset, "the point");
  return h;
}

#define ELLIPSECT_INSTANTIATE(T, N) ELLIPSECT_INSTANTIATE_OBSTACLE(HalfSpace, HalfSpaceGradient, T, N)
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
