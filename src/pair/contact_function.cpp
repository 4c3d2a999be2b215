// The Perram-Wertheim contact function and the distance of closest approach
// (contact_function.hpp), in the reduced frame of docs/method.md section 1.
//
// There the sphere body S is the unit ball (S's matrix M_S^-1 = I) and the other body O has
// M_O^-1 = diag(e^2), so C = u I + v diag(e^2) is diagonal, with u the weight of S and v that
// of O (u + v = 1). For O's center at k relative to S's, and D_i = u + v e_i^2:
//   F   = u v sum_i k_i^2 / D_i,
//   F'  = qs - qo,   qs = u^2 sum_i k_i^2 / D_i^2,   qo = v^2 sum_i e_i^2 k_i^2 / D_i^2,
//   F'' = -2 sum_i e_i^2 k_i^2 / D_i^3 < 0                      (derivatives in v),
// where qs and qo are the quadrics of S and O at the Perram-Wertheim point z = u k / D
// (componentwise, relative to S's center), equal to F at the maximizer. F is homogeneous of
// degree 2 in k, so the solve runs on the unit direction of the centers and F is scaled
// by |r|^2 afterwards (no underflow of k^2 for centers 1e-200 apart).
#include <ellipsect/contact_function.hpp>

#include "detail/classify_impl.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"
#include "detail/math.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ellipsect {

std::string_view to_string(ContactFunctionStatus s) noexcept {
  switch (s) {
    case ContactFunctionStatus::ok: return "ok";
    case ContactFunctionStatus::concentric: return "concentric";
    case ContactFunctionStatus::did_not_converge: return "did_not_converge";
  }
  return "unknown";
}

namespace {

// The maximum of F over the weights in the reduced frame, with bounds.
template <class R>
struct Maximum {
  R f, f_upper;  // F at the last iterate and an upper bound of max F (before rounding margins)
  R u, v;        // the weights of S and O there
  int iterations = 0;
  bool converged = false;
};

template <class R>
struct Terms {
  R f, fp, fpp, rounding;  // F, F', F'' and the rounding of F'
};

template <class R, int N>
Terms<R> terms(const Vec<R, N>& e2, const Vec<R, N>& k2, R u, R v) noexcept {
  R s = 0, qs = 0, qo = 0, c = 0;
  for (int i = 0; i < N; ++i) {
    const R inv = R(1) / (u + v * e2[i]);
    const R t = k2[i] * inv;
    s += t;
    qs += t * inv;
    qo += t * inv * e2[i];
    c += t * inv * inv * e2[i];
  }
  qs *= u * u;
  qo *= v * v;
  return {u * v * s, qs - qo, R(-2) * c, R(8) * std::numeric_limits<R>::epsilon() * (qs + qo)};
}

// Newton on F' (terms(u, v) gives F, F', F'' and the rounding of F' at the weights u, v) from
// the maximizer for two balls of the bodies' support radii rho_S, rho_O along the direction,
// v = rho_S / (rho_S + rho_O); a step that leaves the bracket of the root is replaced by
// bisection. Converged when F' vanishes to its rounding or the step is below the weights'
// rounding.
template <class R, class Terms_at>
Maximum<R> maximize(R rho_s, R rho_o, Terms_at&& terms_at, int max_iterations) noexcept {
  const R eps = std::numeric_limits<R>::epsilon();
  Maximum<R> m;
  m.u = rho_o / (rho_s + rho_o);
  m.v = rho_s / (rho_s + rho_o);
  R u_lo = 1, v_lo = 0, u_hi = 0, v_hi = 1;  // F' > 0 at v_lo, < 0 at v_hi
  int outward = 0;  // bisections in a row
  R fp_last = 0;    // F' at the previous iterate (0: none)
  // The bracket of the weight that is small across it, (lo, hi), and whether it is u.
  const auto small_side = [&](R& lo, R& hi) {
    if (v_hi <= R(0.5)) {
      lo = v_lo;
      hi = v_hi;
      return false;
    }
    lo = u_hi;
    hi = u_lo;
    return hi <= R(0.5);
  };
  // A bisection on the scale of that weight: the root can lie many orders of magnitude below
  // where F' starts to change (needles of aspect ratio 1e8: F' constant from 0.3 down to
  // 1e-8, where Newton's steps leave the bracket, and halving took 25 steps; then Newton from
  // the far side gained a factor 1.5 a step). Where its bracket reaches 0, the k-th bisection
  // in a row (k = 0, 1, ...) puts it at 2^-(2^k) times the bracket's other end; where the ends
  // differ by more than a factor 4, at their geometric mean; otherwise both weights go to their
  // midpoints.
  const auto bisect = [&](R& u, R& v) {
    R lo, hi;
    const bool is_u = small_side(lo, hi);
    if (hi > R(0.5)) {
      u = (u_lo + u_hi) / 2;
      v = (v_lo + v_hi) / 2;
      return;
    }
    R x = lo == R(0) ? hi * ldexp(R(1), -(1 << std::min(outward, 9)))
                     : (hi > R(4) * lo ? sqrt(lo) * sqrt(hi) : (lo + hi) / 2);
    if (!(x > R(0))) x = hi / 2;
    (is_u ? u : v) = x;
    (is_u ? v : u) = R(1) - x;
  };
  for (;;) {
    const Terms<R> t = terms_at(m.u, m.v);
    m.f = t.f;
    ++m.iterations;
    if (t.fp > 0) {
      u_lo = m.u;
      v_lo = m.v;
    } else {
      u_hi = m.u;
      v_hi = m.v;
    }
    if (abs(t.fp) <= t.rounding) {
      m.converged = true;
      break;
    }
    if (m.iterations >= max_iterations) {
      // Concavity: max F <= F + F' (v* - v) with v* in the bracket.
      m.f_upper = t.f + (t.fp > 0 ? t.fp * (v_hi - m.v) : t.fp * (v_lo - m.v));
      return m;
    }
    // The Newton step, judged on the smaller weight (the other may not change at all); a
    // bisection instead where it leaves the bracket, or where Newton is slow (F' of the same
    // sign, down by less than 4 times) across a bracket of more than 16 times.
    const R step = t.fp / t.fpp;
    R u = m.u + step, v = m.v - step;
    R lo, hi;
    small_side(lo, hi);
    const bool slow = (t.fp > 0) == (fp_last > 0) && fp_last != R(0) && abs(t.fp) > abs(fp_last) / 4 &&
                      hi <= R(0.5) && hi > R(16) * lo;
    fp_last = t.fp;
    if (slow || !(v <= u ? v > v_lo && v < v_hi : u > u_hi && u < u_lo)) {
      bisect(u, v);
      ++outward;
    } else {
      outward = 0;
    }
    const bool small = (v <= u ? abs(v - m.v) : abs(u - m.u)) <= R(4) * eps * std::min(u, v);
    m.u = u;
    m.v = v;
    if (small) {
      m.converged = true;
      break;
    }
  }
  m.f_upper = m.f;
  return m;
}

// C(v) = u P_S + v P_O (P_X = B_X^T B_X, B_X = diag(r_X) A_X^T) applied through the
// Householder QR, with column pivoting, of the stacked factors [sqrt(u) B_S; sqrt(v) B_O]
// (C = Q^T Q), rows sorted by decreasing norm: row-wise backward stable (Cox and Higham), so
// every computed quantity is that of bodies whose axes and radii are moved by a few units of
// their last bit, whatever the spread of the radii. half(x) = R^-T Pi^T x, with x^T C^-1 x =
// |half(x)|^2 and C^-1 x = Pi R^-1 half(x).
template <class R, int N>
class WeightedInverse {
public:
  WeightedInverse(const Mat<R, N>& bs, const Mat<R, N>& bo, R u, R v) noexcept {
    Eigen::Matrix<R, 2 * N, N> rows;
    rows.template topRows<N>() = sqrt(u) * bs;
    rows.template bottomRows<N>() = sqrt(v) * bo;
    std::array<int, 2 * N> order;
    std::array<R, 2 * N> norm;
    for (int i = 0; i < 2 * N; ++i) {
      order[std::size_t(i)] = i;
      norm[std::size_t(i)] = rows.row(i).squaredNorm();
    }
    std::sort(order.begin(), order.end(), [&](int x, int y) { return norm[std::size_t(x)] > norm[std::size_t(y)]; });
    Eigen::Matrix<R, 2 * N, N> sorted;
    for (int i = 0; i < 2 * N; ++i) sorted.row(i) = rows.row(order[std::size_t(i)]);
    qr_.compute(sorted);
  }
  Vec<R, N> half(const Vec<R, N>& x) const noexcept {
    const Vec<R, N> p = qr_.colsPermutation().transpose() * x;
    return qr_.matrixR().template topLeftCorner<N, N>().template triangularView<Eigen::Upper>().transpose().solve(p);
  }
  Vec<R, N> full(const Vec<R, N>& h) const noexcept {
    const Vec<R, N> y = qr_.matrixR().template topLeftCorner<N, N>().template triangularView<Eigen::Upper>().solve(h);
    return qr_.colsPermutation() * y;
  }

private:
  Eigen::ColPivHouseholderQR<Eigen::Matrix<R, 2 * N, N>> qr_;
};

// The maximizer's vectors, per unit of |r| (world frame): y = C(lambda)^-1 r, M_S^-1 y and
// M_O^-1 y, and `level`, the factor that puts M_S^-1 y on S's boundary (|B_S y|).
template <class R, int N>
struct Maximizer {
  Vec<R, N> y, ms_y, mo_y;
  R level;
};

// F along the unit direction `dir` in the world frame, where C's factors keep every radius:
// y = C^-1 dir, F = u v dir . y, and with S = |B_S y|^2, O = |B_O y|^2 (so that
// dir . y = u S + v O), F' = u^2 S - v^2 O (qs - qo above) and
// F'' = -2 (P_S y)^T C^-1 (P_O y) (derivatives in v).
template <class R, int N>
struct WorldFrame {
  Mat<R, N> bs, bo;
  Vec<R, N> dir;
  R aspect;  // the larger aspect ratio: F' is computed to about eps times it
  Terms<R> terms(R u, R v, Maximizer<R, N>* at = nullptr) const noexcept {
    const WeightedInverse<R, N> c(bs, bo, u, v);
    const Vec<R, N> h = c.half(dir), y = c.full(h);
    const Vec<R, N> sy = bs * y, oy = bo * y;
    const Vec<R, N> ms_y = bs.transpose() * sy, mo_y = bo.transpose() * oy;
    if (at != nullptr) *at = {y, ms_y, mo_y, detail::stable_norm<R, N>(sy)};
    const R qs = u * u * sy.squaredNorm(), qo = v * v * oy.squaredNorm();
    return {u * v * h.squaredNorm(), qs - qo, R(-2) * c.half(ms_y).dot(c.half(mo_y)),
            R(8) * std::numeric_limits<R>::epsilon() * aspect * (qs + qo)};
  }
};

template <class R, class T, int N>
Mat<R, N> factor(const Ellipsoid<T, N>& x) noexcept {
  return x.radii().template cast<R>().asDiagonal() * detail::work_axes<R>(x).transpose();
}

// Pairs whose aspect ratios multiply beyond this are solved in the world frame: in the
// reduced frame O's semi-axes spread over up to that product, and its rounding, relative to
// the largest, reached the thinnest (two needles of aspect ratio 1e8: F off by 28%, where
// the world frame's error is 5e-10).
inline constexpr double reduced_frame_aspect_limit = 1e12;

// The maximum for the world direction `dir` of O's center from S's (unit), and its vectors.
template <class R, int N>
struct Solved {
  Maximum<R> max;
  Maximizer<R, N> at;
  R rounding;  // relative rounding of F from the frame: S's aspect (reduced), both (world)
};

template <class R, class T, int N>
Solved<R, N> solve(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const Vec<R, N>& dir,
                   const Options& options) noexcept {
  const R eps = std::numeric_limits<R>::epsilon();
  Solved<R, N> out;
  const R aspect_s = R(s.radii().maxCoeff()) / R(s.radii().minCoeff());
  const R aspect_o = R(o.radii().maxCoeff()) / R(o.radii().minCoeff());
  if (aspect_s * aspect_o > R(reduced_frame_aspect_limit)) {
    const WorldFrame<R, N> world{factor<R>(s), factor<R>(o), dir, std::max(aspect_s, aspect_o)};
    out.max = maximize<R>((world.bs * dir).norm(), (world.bo * dir).norm(),
                          [&](R u, R v) { return world.terms(u, v); }, options.max_contact_function_iterations);
    world.terms(out.max.u, out.max.v, &out.at);
    out.rounding = R(4 * detail::reduced_frame_ulps) * eps * std::max(aspect_s, aspect_o);
    return out;
  }
  const detail::Reduced<R, N> red = detail::reduce<R>(s, o);
  const Vec<R, N> k = red.to_z * dir;
  const Vec<R, N> e2 = red.e.cwiseAbs2(), k2 = k.cwiseAbs2();
  out.max = maximize<R>(k.norm(), red.e.cwiseProduct(k).norm(), [&](R u, R v) { return terms<R, N>(e2, k2, u, v); },
                        options.max_contact_function_iterations);
  // In the Z frame y = k / D (D_i = u + v e_i^2); in the world y = to_z^T (k / D),
  // M_S^-1 y = to_world (k / D), M_O^-1 y = to_world (e^2 k / D), and |k / D| is S's level.
  Vec<R, N> z;
  for (int i = 0; i < N; ++i) z[i] = k[i] / (out.max.u + out.max.v * e2[i]);
  out.at = {red.to_z.transpose() * z, red.to_world * z, red.to_world * Vec<R, N>(e2.cwiseProduct(z)),
            detail::stable_norm<R, N>(z)};
  out.rounding = R(4 * detail::reduced_frame_ulps) * eps * aspect_s;
  return out;
}

// x rounded to T towards -inf (+inf when `up`).
template <class T, class R>
T directed(R x, bool up) noexcept {
  T y = T(x);
  if (up ? R(y) < x : R(y) > x) y = nextafter(y, up ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity());
  return y;
}

// perram_wertheim's value from the solve, for r = center(o) - center(s) of length `norm`.
template <class T, class R, int N>
ContactFunction<T> value_of(const Solved<R, N>& sol, bool a_is_s, R norm) noexcept {
  ContactFunction<T> out;
  const Maximum<R>& m = sol.max;
  const R f = norm * (norm * m.f);
  out.iterations = m.iterations;
  out.lambda = T(a_is_s ? m.v : m.u);
  if (m.converged) {
    out.status = ContactFunctionStatus::ok;
    out.f = out.f_upper = T(f);
  } else {
    out.status = ContactFunctionStatus::did_not_converge;
    out.f = directed<T>(f * (R(1) - sol.rounding), false);
    out.f_upper = directed<T>(norm * (norm * m.f_upper) * (R(1) + sol.rounding), true);
  }
  return out;
}

// The pair in query order (detail::order_pair): the sphere body s, the other body o, and
// r = center(o) - center(s) as a unit direction and its length.
template <class R, class T, int N>
ContactFunction<T> contact_function(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s,
                                    const Vec<R, N>& direction, R norm, const Options& options) noexcept {
  return value_of<T>(solve<R>(s, o, direction, options), a_is_s, norm);
}

// F and its gradient (contact_function.hpp) for the pair scaled by 2^-e, from the
// maximizer's y, M_S^-1 y and M_O^-1 y (per unit of |r|).
template <class R, class T, int N>
ContactFunctionGradient<T, N> contact_function_gradient(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o,
                                                        bool a_is_s, const Vec<R, N>& direction, R norm, int e,
                                                        const Options& options) noexcept {
  const Solved<R, N> sol = solve<R>(s, o, direction, options);
  const BodyGradient<T, N> unknown = detail::constant_gradient<T, N>(std::numeric_limits<T>::quiet_NaN());
  ContactFunctionGradient<T, N> out{value_of<T>(sol, a_is_s, norm), unknown, unknown};
  const Maximum<R>& m = sol.max;
  if (!m.converged) return out;
  const Vec<R, N>& y = sol.at.y;
  const R uv2 = R(2) * m.u * m.v * norm;  // 2 lambda (1 - lambda) |r|
  // The body X with weight w and M_X^-1 y = my: d/d radii and d/d phi, in the scaled frame.
  auto body = [&](const Ellipsoid<T, N>& x, R w, const Vec<R, N>& my, const Vec<R, N>& center) {
    const Vec<R, N> q = detail::work_axes<R>(x).transpose() * y;
    BodyGradient<R, N> g;
    g.center = center;
    g.radii = -(uv2 * norm * w) * x.radii().template cast<R>().cwiseProduct(q.cwiseAbs2());
    g.orientation = detail::times<R, N>(detail::turn_rate<R, N>(my, y), -uv2 * norm * w);
    return g;
  };
  BodyGradient<R, N> gs = body(s, m.u, sol.at.ms_y, Vec<R, N>(-uv2 * y));
  BodyGradient<R, N> go = body(o, m.v, sol.at.mo_y, Vec<R, N>(uv2 * y));
  // Lengths of the pair scaled by 2^-e: the derivatives by a length scale by 2^-e.
  for (BodyGradient<R, N>* g : {&gs, &go}) {
    g->center = detail::times_pow2(g->center, -e);
    g->radii = detail::times_pow2(g->radii, -e);
  }
  out.a = detail::gradient_in<T>(a_is_s ? gs : go, R(1));
  out.b = detail::gradient_in<T>(a_is_s ? go : gs, R(1));
  return out;
}

// The same with b moving from a's center along the unit direction u.
template <class R, class T, int N>
ClosestApproach<T, N> approach(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s, const Vec<R, N>& u,
                               const Options& options) noexcept {
  ClosestApproach<T, N> out;
  // O's center relative to S's, per unit of sigma.
  const Solved<R, N> sol = solve<R>(s, o, a_is_s ? u : Vec<R, N>(-u), options);
  const Maximum<R>& m = sol.max;
  out.iterations = m.iterations;
  out.lambda = T(a_is_s ? m.v : m.u);
  const R sigma = R(1) / sqrt(m.f);
  // The contact point M_S^-1 y brought to S's boundary, where S's outward normal is along y.
  const Vec<R, N> center_s = a_is_s ? Vec<R, N>(s.center().template cast<R>())
                                    : Vec<R, N>(o.center().template cast<R>() + sigma * u);
  out.point = (center_s + sol.at.ms_y / sol.at.level).template cast<T>();
  const Vec<R, N> n = detail::unit_vector<R, N>(sol.at.y);
  out.normal = (a_is_s ? n : Vec<R, N>(-n)).template cast<T>();
  if (m.converged) {
    out.status = ContactFunctionStatus::ok;
    out.distance = out.distance_lower = T(sigma);
  } else {
    out.status = ContactFunctionStatus::did_not_converge;
    out.distance = directed<T>(R(1) / sqrt(m.f * (R(1) - sol.rounding)), true);
    out.distance_lower = directed<T>(R(1) / sqrt(m.f_upper * (R(1) + sol.rounding)), false);
  }
  return out;
}

// F is dimensionless: the pair runs at its scale (detail/scale.hpp). The sphere body is
// chosen before rescaling (rescaling can merge bodies that differ only below the smallest
// subnormal; swap symmetry needs the order they had). `finish(s, o, a_is_s, direction, norm,
// e)` solves the pair in query order, scaled by 2^-e, with r = norm * direction in the
// working type of direction.
template <class T, int N, class Finish>
auto with_direction(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, Finish finish) noexcept {
  using R = detail::Work<T>;
  const auto pair = detail::order_pair(a, b);
  auto difference = [](const auto& x, const auto& y, auto type) {
    using S = decltype(type);
    return Vec<S, N>(y.center().template cast<S>() - x.center().template cast<S>());
  };
  return detail::at_scale<R>(detail::scale_of(a, b), [&]<class W>(auto units) {
    decltype(auto) s = units.body(pair.s);
    decltype(auto) o = units.body(pair.o);
    Vec<W, N> r = difference(s, o, W());
    W norm = detail::stable_norm<W, N>(r);
    if (units.rescaled && !(norm >= std::numeric_limits<W>::min())) {
      // The rescaled centers are too close to keep the direction's digits (r subnormal or
      // zero): r comes from the given centers in the wide type.
      using L = detail::WideFloat;
      const Vec<L, N> wide = difference(pair.s, pair.o, L());
      r = detail::unit_vector<L, N>(wide).template cast<W>();
      norm = W(ldexp(detail::stable_norm<L, N>(wide), -units.exponent));
    }
    return finish(s, o, pair.a_is_s, detail::unit_vector<W, N>(r), norm, units.exponent);
  });
}

template <class T>
ContactFunction<T> concentric() noexcept {
  ContactFunction<T> out;
  out.status = ContactFunctionStatus::concentric;
  out.f = out.f_upper = T(0);
  out.lambda = std::numeric_limits<T>::quiet_NaN();
  return out;
}

}  // namespace

template <class T, int N>
ContactFunction<T> perram_wertheim(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options) noexcept {
  if (a.center() == b.center()) return concentric<T>();
  return with_direction(a, b, [&](const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s, const auto& direction,
                            auto norm, int) { return contact_function(s, o, a_is_s, direction, norm, options); });
}

template <class T, int N>
ContactFunctionGradient<T, N> perram_wertheim_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                       const Options& options) noexcept {
  if (a.center() == b.center()) {
    // F vanishes to second order in r: every derivative is 0.
    return {concentric<T>(), detail::constant_gradient<T, N>(T(0)), detail::constant_gradient<T, N>(T(0))};
  }
  return with_direction(a, b, [&](const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, bool a_is_s, const auto& direction,
                            auto norm, int e) {
    return contact_function_gradient(s, o, a_is_s, direction, norm, e, options);
  });
}

template <class T, int N>
ClosestApproach<T, N> closest_approach(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                       const VecArg<T, N>& direction, const Options& options) {
  if (!direction.allFinite()) throw InputError("direction", "must be finite");
  if (direction.isZero(0)) throw InputError("direction", "must be nonzero");
  const auto pair = detail::order_pair(a, b);
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    const Vec<W, N> u = detail::unit_vector<W, N>(direction.template cast<W>());
    ClosestApproach<T, N> out = approach<W>(units.body(pair.s), units.body(pair.o), pair.a_is_s, u, options);
    units.lengths_out(out.distance, out.distance_lower, out.point);
    return out;
  });
}

template <class T, int N>
ClosestApproachGradient<T, N> closest_approach_gradient(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                        const VecArg<T, N>& direction, const Options& options) {
  using R = detail::Work<T>;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const BodyGradient<T, N> unknown = detail::constant_gradient<T, N>(nan);
  ClosestApproachGradient<T, N> out{closest_approach(a, b, direction, options), unknown, unknown,
                                    Vec<T, N>::Constant(nan)};
  if (out.value.status != ContactFunctionStatus::ok) return out;
  const Vec<R, N> n = out.value.normal.template cast<R>();
  const Vec<R, N> d = direction.template cast<R>();
  const Vec<R, N> u = detail::unit_vector<R, N>(d);
  const R along = n.dot(u);
  if (!(along > R(0))) return out;
  // sigma grows with either support radius along n, at 1 / (n . u).
  out.a = detail::gradient_in<T>(detail::support_radius_gradient<R>(a, n), R(1) / along);
  out.b = detail::gradient_in<T>(detail::support_radius_gradient<R>(b, n), R(1) / along);
  const R largest = d.cwiseAbs().maxCoeff(), length = largest * (d / largest).norm();  // |d|, without overflow
  out.direction = (Vec<R, N>(n - along * u) * (-R(out.value.distance) / (along * length))).template cast<T>();
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                   \
  template ClosestApproachGradient<T, N> closest_approach_gradient<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, \
                                                                         const VecArg<T, N>&, const Options&);        \
  template ContactFunction<T> perram_wertheim<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&,                   \
                                                    const Options&) noexcept;                                         \
  template ContactFunctionGradient<T, N> perram_wertheim_gradient<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, \
                                                                        const Options&) noexcept;                     \
  template ClosestApproach<T, N> closest_approach<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&,               \
                                                        const VecArg<T, N>&, const Options&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
