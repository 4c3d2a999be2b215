// First contact time (seed section 6), with the changes documented in docs/method.md:
//
// * Newton runs on delta(t) = |P(t)| - 1, the distance from the ball to the moving
//   ellipsoid minus 1, instead of the seed's h(t) = |P(t)|^2 - 1. The distance from a
//   point to a translating convex set is convex in t, so Newton from t = 0 (where
//   delta > 0) never passes the first root, exactly as for h; but delta is nearly linear
//   while the bodies are far apart, where Newton on the quadratic h only halves the
//   distance per step. Its slope is W.P / |P| (envelope theorem); the seed's equation
//   (29) and code use 4 W.P for h'(t) where the true value is 2 W.P, which halves every
//   step and costs the quadratic convergence.
// * Every exit is a status: overlapping and touching at start, no contact in [0, t_max]
//   (slope >= 0: the seed's W.P >= 0 quick-out, applied at every iterate), converged hit,
//   or did_not_converge at the iteration cap.
// * Tolerances are relative (Options::tolerance for tangency, ulps for the time).
#include <ellipsect/contact.hpp>

#include "detail/certificates-inl.hpp"
#include "detail/classify_impl.hpp"
#include "detail/compensated.hpp"
#include "detail/contact_start.hpp"
#include "detail/exact_relation.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"
#include "detail/math.hpp"

#include <cmath>
#include <limits>

namespace ellipsect {

std::string_view to_string(ContactStatus s) noexcept {
  switch (s) {
    case ContactStatus::hit: return "hit";
    case ContactStatus::touching_at_start: return "touching_at_start";
    case ContactStatus::overlapping_at_start: return "overlapping_at_start";
    case ContactStatus::no_contact_in_window: return "no_contact_in_window";
    case ContactStatus::did_not_converge: return "did_not_converge";
    case ContactStatus::invalid_input: return "invalid_input";
  }
  return "unknown";
}

// One solve in working precision R, the contact of S (the sphere body) and O moving at vs
// and vo: the reduced frame at t = 0, O's center relative to S's as a function of time,
// and its rounding, shared by the start decision, Newton's loop and the answer's point
// and normal.
//
// After run, `doubt` is the estimated error of the outcome relative to what the caller's
// accuracy claim allows: > 1 means the answer may be wrong (a status within rounding of the
// tolerance band, or a time error above 2.5e-13 of the time scale, or a normal error above
// 2.5e-10 rad) and the caller repeats the solve in a wider type; `resume` is then a time to
// start that solve from (0 when unknown): the hit's time less 64 times its estimated error.
//
// Starting at `from` > 0 instead of 0: where delta(from) is above the band by more than its
// rounding and closing (slope < 0), convexity makes delta decrease on [0, from], so the pair
// is apart beyond the band on all of it and the first root lies after `from`; the loop goes
// on from there. Otherwise the solve starts at 0. The start needs no trust in its source.
template <class R, class T, int N>
class ContactSolve {
 public:
  R doubt = 0, resume = 0;

  ContactSolve(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const Vec<T, N>& vs_in, const Vec<T, N>& vo_in,
               bool a_is_s, const Options& options) noexcept
      : s_(s), o_(o), a_is_s_(a_is_s), options_(options), tol_(R(double(options.tolerance))),
        red_(detail::reduce<R>(s, o)), vs_(vs_in.template cast<R>()), ks_(s.center().template cast<R>()),
        w_(red_.to_z * (vo_in.template cast<R>() - vs_)) {
    out_.time = T(nan);
    out_.point.setConstant(T(nan));
    out_.normal.setConstant(T(nan));
    // O's center relative to S's at time t, from the exact differences of the centers and of
    // the velocities (two-sums; no product, so contraction cannot spoil them): r(t) = (d + t u)
    // + (d_lo + t u_lo), the first part formed with one rounding (mul_add). Its error is
    // about eps |r(t)| + eps^2 (|d| + t |u|): relative to the pair's separation, not to the
    // distance from the origin nor to how far the pair travels before it meets.
    for (int i = 0; i < N; ++i) {
      d_[i] = detail::two_sum(R(o.center()[i]), -ks_[i]);
      u_[i] = detail::two_sum(R(vo_in[i]), -vs_[i]);
    }
    for (int i = 0; i < N; ++i) {
      d_norm_ += d_[i].hi * d_[i].hi;
      u_norm_ += u_[i].hi * u_[i].hi;
    }
    d_norm_ = sqrt(d_norm_);
    u_norm_ = sqrt(u_norm_);
    e_max_ = red_.e.maxCoeff();
    inv_a_min_ = R(1) / R(s.radii().minCoeff());
  }

  Contact<T, N> run(R tmax, R from) noexcept {
    detail::BranchPoint<R, N> p;
    p.root = -1;
    R t = 0, delta;
    if (from > R(0) && from <= tmax && closest_at(from, p) && p.norm - R(1) - tol_ > rounding(from) &&
        w_.dot(p.point) < R(0)) {
      t = from;
      delta = p.norm - R(1);
    } else {
      p.root = -1;
      if (!closest_at(0, p)) return finish(ContactStatus::overlapping_at_start, 0, nullptr);
      delta = p.norm - R(1);
    }
    if (t == R(0) && near_band_edge(delta, 0)) doubt = 2;
    if (delta < -tol_) return finish(ContactStatus::overlapping_at_start, 0, nullptr);
    if (delta <= tol_ && !options_.tolerance.is_exact()) return finish(ContactStatus::touching_at_start, 0, &p);
    if (delta <= tol_) return within_band(delta, tmax, p);
    return newton(t, delta, tmax, p);
  }

 private:
  const R nan = std::numeric_limits<R>::quiet_NaN();
  const R eps = std::numeric_limits<R>::epsilon();

  // Exact tolerance, apart by less than the band at t = 0: the relation at t = 0 decides;
  // closing, they touch within rounding of -delta / slope (the first positive time at
  // least); else never, as in Newton's loop.
  Contact<T, N> within_band(R delta, R tmax, const detail::BranchPoint<R, N>& p) noexcept {
    const Relation start = detail::exact_relation(s_, o_);
    if (start == Relation::touching) return finish(ContactStatus::touching_at_start, 0, &p);
    if (start != Relation::separated) return finish(ContactStatus::overlapping_at_start, 0, nullptr);
    const R slope = w_.dot(p.point) / p.norm;
    if (!(slope < R(0))) return finish(ContactStatus::no_contact_in_window, nan, nullptr);
    const R t1 = std::max(-delta / slope, R(std::numeric_limits<T>::denorm_min()));
    if (t1 > tmax) return finish(ContactStatus::no_contact_in_window, nan, nullptr);
    out_.iterations = 1;
    return finish(ContactStatus::hit, t1, &p);
  }

  // Newton on delta(t) = |P(t)| - 1 from the left, from t where delta > tol: convexity keeps
  // every step before the first root.
  Contact<T, N> newton(R t, R delta, R tmax, detail::BranchPoint<R, N> p) noexcept {
    for (int it = 1; it <= options_.max_contact_iterations; ++it) {
      out_.iterations = it;
      const R slope = w_.dot(p.point) / p.norm;
      if (!(slope < R(0))) {  // moving apart from here on: the minimum of delta is behind us
        if (near_band_edge(delta, t)) doubt = 2;
        return delta <= tol_ ? finish(ContactStatus::hit, t, &p)
                             : finish(ContactStatus::no_contact_in_window, nan, nullptr);
      }
      const R tn = t - delta / slope;
      if (tn > tmax) return finish(ContactStatus::no_contact_in_window, nan, nullptr);
      detail::BranchPoint<R, N> pn = p;
      const bool outside = closest_at(tn, pn);
      if (!outside || pn.norm < R(1)) {
        // Newton from the left cannot pass the root in exact arithmetic: landing inside
        // means tn is within rounding of it. Report the end nearer to touching; if the depth
        // exceeds the rounding model, bisect [t, tn] to adjacent floats instead.
        const R depth = R(1) - pn.norm;
        if (outside && depth <= rounding(tn)) return depth < delta ? hit(tn, pn) : hit(t, p);
        return bisected(t, tn, p);
      }
      // A step of a few ulps of t: Newton from the left has reached the root.
      const bool converged = tn - t <= 4 * eps * tn;
      t = tn;
      p = pn;
      delta = p.norm - R(1);
      if (converged) return hit(t, p);
    }
    return delta <= tol_ ? finish(ContactStatus::hit, t, &p) : finish(ContactStatus::did_not_converge, t, nullptr);
  }

  // [lo, hi] with the pair apart at lo (p its closest point) and not at hi, bisected to
  // adjacent floats: the hit at its left end, the last time the bodies are apart.
  Contact<T, N> bisected(R lo, R hi, detail::BranchPoint<R, N> p) noexcept {
    while (true) {
      const R mid = lo + (hi - lo) / 2;
      if (mid <= lo || mid >= hi) break;
      detail::BranchPoint<R, N> pm = p;
      if (closest_at(mid, pm) && pm.norm >= R(1)) {
        lo = mid;
        p = pm;
      } else {
        hi = mid;
      }
    }
    return hit(lo, p);
  }

  Vec<R, N> relative_at(R t) const noexcept {
    Vec<R, N> rel;
    for (int i = 0; i < N; ++i) rel[i] = detail::mul_add(t, u_[i].hi, d_[i].hi) + (t * u_[i].lo + d_[i].lo);
    return rel;
  }

  // The reduced frame's rounding: 32 ulps of |k|, of O's largest semi-axis and of the
  // relative position in S's units (with its own rounding), none of the world coordinates.
  R rounding(R t) const noexcept {
    const Vec<R, N> rel = relative_at(t);
    const R apart = rel.norm() + eps * (d_norm_ + t * u_norm_);
    return R(detail::reduced_frame_ulps) * eps * ((red_.to_z * rel).norm() + e_max_ + apart * inv_a_min_);
  }

  // A decision "delta versus +-tol" that rounding could flip.
  bool near_band_edge(R delta, R t) const noexcept {
    const R r = rounding(t);
    return abs(delta - tol_) <= r || abs(delta + tol_) <= r;
  }

  // The closest point of O(t) to the origin, or false when the origin is inside O(t).
  // `p` comes in holding a nearby solution whose multiplier warm-starts the solve.
  bool closest_at(R t, detail::BranchPoint<R, N>& p) const noexcept {
    const Vec<R, N> k = red_.to_z * relative_at(t);
    if (detail::level_at_origin<R, N>(red_.e, k) <= R(0)) return false;
    p = detail::closest_from_outside<R, N>(red_.e, k, p.root);
    return true;
  }

  // A converged hit, its errors against a quarter of the claims: the time error is the
  // rounding of delta over the slope, relative to max(t, the time to cross the unit ball);
  // the normal turns by the point's rounding times the sphere body's aspect ratio (the map
  // back to the world stretches directions by up to a_max / a_min).
  Contact<T, N> hit(R t, const detail::BranchPoint<R, N>& q) noexcept {
    const R aspect_s = R(s_.radii().maxCoeff()) / R(s_.radii().minCoeff());
    const R r = rounding(t), slope = w_.dot(q.point) / q.norm;
    const R scale = std::max(t, R(1) / w_.norm());
    doubt = std::max({doubt, r / (abs(slope) * scale) / R(2.5e-13), r * aspect_s / R(2.5e-10)});
    resume = std::max(R(0), t - 64 * r / abs(slope));
    return finish(ContactStatus::hit, t, &q);
  }

  Contact<T, N> finish(ContactStatus status, R t, const detail::BranchPoint<R, N>* p) noexcept {
    out_.status = status;
    out_.time = T(t);
    if (p != nullptr && p->norm > R(0) && rounding(t) <= R(1)) {
      const Vec<R, N> z = p->point / p->norm;  // on the unit ball, i.e. on S's boundary
      const Vec<R, N> offset = red_.to_world * z;
      for (int i = 0; i < N; ++i) out_.point[i] = T(detail::mul_add(t, vs_[i], ks_[i]) + offset[i]);
      const Vec<R, N> n = detail::unit_vector<R, N>(red_.normal_map * z);
      out_.normal = (a_is_s_ ? n : Vec<R, N>(-n)).template cast<T>();
    } else if (p != nullptr) {
      // S is smaller than the rounding of O's coordinates in the reduced frame (radius
      // ratios beyond 1/eps), where P's direction is noise: the normal is O's at S's
      // center, -grad q_O (off by about S's size over O's radius of curvature), and the
      // point S's support point along it.
      Vec<R, N> cs;
      for (int i = 0; i < N; ++i) cs[i] = detail::mul_add(t, vs_[i], ks_[i]);
      const Vec<R, N> offset = -relative_at(t);
      const Mat<R, N> axes_o = detail::work_axes<R>(o_), axes_s = detail::work_axes<R>(s_);
      const Vec<R, N> radii_o = o_.radii().template cast<R>(), radii_s = s_.radii().template cast<R>();
      const Vec<R, N> local = (axes_o.transpose() * offset).cwiseQuotient(radii_o).cwiseQuotient(radii_o);
      const Vec<R, N> n = detail::unit_vector<R, N>(-(axes_o * local));
      const Vec<R, N> w = radii_s.cwiseProduct(axes_s.transpose() * n);
      out_.point = (cs + axes_s * radii_s.cwiseProduct(w / w.norm())).template cast<T>();
      out_.normal = (a_is_s_ ? n : Vec<R, N>(-n)).template cast<T>();
    }
    return out_;
  }

  const Ellipsoid<T, N>& s_;
  const Ellipsoid<T, N>& o_;
  bool a_is_s_;
  const Options& options_;
  R tol_;
  detail::Reduced<R, N> red_;  // S the unit ball at the origin, O axis-aligned, at t = 0
  Vec<R, N> vs_, ks_;          // S's velocity and center
  Vec<R, N> w_;                // O's velocity relative to S, in the reduced frame
  detail::Double<R> d_[N], u_[N];
  R d_norm_ = 0, u_norm_ = 0, e_max_, inv_a_min_;
  Contact<T, N> out_;
};

template <class R, class T, int N>
Contact<T, N> solve_contact(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const Vec<T, N>& vs,
                            const Vec<T, N>& vo, R tmax, bool a_is_s, const Options& options, R& doubt,
                            R& resume, R from = 0) noexcept {
  ContactSolve<R, T, N> solve(s, o, vs, vo, a_is_s, options);
  const Contact<T, N> c = solve.run(tmax, from);
  doubt = solve.doubt;
  resume = solve.resume;
  return c;
}

// The answer for a pair whose exact relation at t = 0 is `rel`, given the answer `c` for the
// pair rescaled with a subnormal difference lost: a start status from rel; a separated pair
// that the rescaled one saw touching is a hit at the first positive time when closing along
// c's normal (relative velocity u), else never.
template <class T, int N>
void exact_start(Contact<T, N>& c, Relation rel, const Vec<T, N>& u, T t_max) noexcept {
  const bool at_start = c.status == ContactStatus::touching_at_start || c.status == ContactStatus::overlapping_at_start;
  if (rel == Relation::separated && !at_start) return;
  if (rel == Relation::touching && c.status == ContactStatus::touching_at_start) return;
  const bool closing = c.normal.allFinite() && c.normal.dot(u) < T(0);
  const T first = std::numeric_limits<T>::denorm_min();
  if (rel == Relation::separated && closing && first <= t_max) {
    c.status = ContactStatus::hit;
    c.time = first;
    return;
  }
  c = detail::unanswered_contact<T, N>();
  c.status = rel == Relation::separated ? ContactStatus::no_contact_in_window
             : rel == Relation::touching ? ContactStatus::touching_at_start
                                         : ContactStatus::overlapping_at_start;
  if (rel != Relation::separated) c.time = T(0);
}

// first_contact of a pair run as given in the working type: the certificates' quick outs,
// the solve, and the wide type from just before R's hit where R is in doubt.
template <class T, int N>
Contact<T, N> contact_in(const Ellipsoid<T, N>& a, const Vec<T, N>& velocity_a, const Ellipsoid<T, N>& b,
                         const Vec<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  using R = detail::Work<T>;
  Contact<T, N> out = detail::unanswered_contact<T, N>();
  namespace hw = detail::HWY_NAMESPACE;
  double va[N], vb[N];
  for (int i = 0; i < N; ++i) {
    va[i] = double(velocity_a[i]);
    vb[i] = double(velocity_b[i]);
  }
  if (hw::swept_code<double, N>(hw::lanes_of(a, hw::Fill::balls), va, hw::lanes_of(b, hw::Fill::balls), vb, double(t_max), options.tolerance) > 0) {
    out.status = ContactStatus::no_contact_in_window;
    return out;
  }
  // overlap's certificate of a common point is at least 1e-9 deep: the inscribed balls
  // overlap by 1e-9 of their radii, or a point lies at quadric level 1 - 2e-5 or below in
  // both bodies. Either makes the Perram-Wertheim scale mu < 1 - 1e-9, and the sphere body
  // scaled by mu about its center meets the other body scaled by mu, hence the other body:
  // the relative gap at t = 0 is at most mu - 1, below the band of any tolerance <= 1e-10.
  if (options.tolerance <= 1e-10 && hw::certificate_code<false>(a, b, options.tolerance) > 0) {
    out.status = ContactStatus::overlapping_at_start;
    out.time = 0;
    return out;
  }
  const auto [s, o, a_is_s] = detail::order_pair(a, b);
  const Vec<T, N>& vs = a_is_s ? velocity_a : velocity_b;
  const Vec<T, N>& vo = a_is_s ? velocity_b : velocity_a;
  R doubt, resume;
  out = solve_contact<R, T, N>(s, o, vs, vo, R(t_max), a_is_s, options, doubt, resume);
  if (doubt > R(1)) {  // too close to call in R: certify in the wider type, from just before R's hit
    using W = detail::Wide<R>;
    W wide_doubt, wide_resume;
    out = solve_contact<W, T, N>(s, o, vs, vo, W(t_max), a_is_s, options, wide_doubt, wide_resume, W(resume));
  }
  return out;
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a, const Ellipsoid<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  using R = detail::Work<T>;
  if (!detail::valid_motion<T, N>(velocity_a, velocity_b, t_max)) return detail::unanswered_contact<T, N>();
  // Lengths and times rescaled by powers of two (detail/scale.hpp): lengths by 2^-e, times
  // by 2^f where the speeds in the rescaled lengths (2^f) leave the window, so velocities
  // by 2^-(e + f). The sphere body is chosen before rescaling, which can merge two bodies
  // that differ only below the smallest subnormal (swap symmetry needs the order they had).
  detail::Scale scale = detail::scale_of(a, b);
  scale.time = detail::time_exponent(scale, velocity_a, velocity_b);
  const auto pair = detail::order_pair(a, b);
  const Vec<T, N>& vs = pair.a_is_s ? velocity_a : velocity_b;
  const Vec<T, N>& vo = pair.a_is_s ? velocity_b : velocity_a;
  Contact<T, N> c = detail::at_scale<R>(scale, [&]<class W>(auto units) {
    if constexpr (!std::is_same_v<W, R>) {  // the wide type throughout, without the double-precision quick out
      W doubt, resume;
      return solve_contact<W, T, N>(pair.s, pair.o, vs, vo, W(t_max), pair.a_is_s, options, doubt, resume);
    } else if constexpr (units.rescaled) {
      Contact<T, N> r = contact_in(units.body(pair.s), units.velocity(vs), units.body(pair.o), units.velocity(vo),
                                   units.time(t_max), options);
      if (!pair.a_is_s) r.normal = -r.normal;
      units.times_out(r.time);
      units.lengths_out(r.point);
      if (options.tolerance.is_exact() && units.loses(a, b))
        exact_start(r, detail::exact_relation(a, b), Vec<T, N>(velocity_b - velocity_a), t_max);
      return r;
    } else {
      return contact_in(a, velocity_a, b, velocity_b, t_max, options);
    }
  });
  // A contact time beyond the largest finite T is outside every window; speeds of any size
  // can close at a subnormal relative speed, which time rescaling (by the larger speed)
  // leaves alone.
  if (c.status == ContactStatus::hit && !isfinite(c.time)) {
    c.status = ContactStatus::no_contact_in_window;
    c.time = std::numeric_limits<T>::quiet_NaN();
    c.point.setConstant(c.time);
    c.normal.setConstant(c.time);
  }
  return c;
}

template <class T, int N>
ContactGradient<T, N> first_contact_gradient(const Ellipsoid<T, N>& a, const VecArg<T, N>& velocity_a,
                                             const Ellipsoid<T, N>& b, const VecArg<T, N>& velocity_b, T t_max,
                                             const Options& options) noexcept {
  using R = detail::Work<T>;
  ContactGradient<T, N> out = detail::unanswered_gradient(first_contact(a, velocity_a, b, velocity_b, t_max, options));
  if (out.value.status != ContactStatus::hit) return out;
  // The bodies only translate: their support radii at the hit are those at time 0.
  const RotationVector<R, N> still = detail::constant_gradient<R, N>(R(0)).orientation;
  detail::contact_time_gradient<T, N, R>(out, a, b, Vec<R, N>(b.center().template cast<R>() - a.center().template cast<R>()),
                                         velocity_a.template cast<R>(), velocity_b.template cast<R>(), still,
                                         still);
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                            \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const Vec<T, N>&, const Ellipsoid<T, N>&, \
                                             const Vec<T, N>&, T, const Options&) noexcept;                     \
  template ContactGradient<T, N> first_contact_gradient<T, N>(const Ellipsoid<T, N>&, const Vec<T, N>&,         \
                                                              const Ellipsoid<T, N>&, const Vec<T, N>&, T,      \
                                                              const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
