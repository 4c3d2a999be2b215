// Independent high-precision REFERENCE for distances, penetration depths, and the boundary
// intersection points and overlap area of two ellipses (header templates; builds on reference.hpp).
//
// Routes, all in `Real` (about 50 digits) unless said otherwise, chosen to differ from the
// library's (reduced frame, secular equation, trust-region Newton from one or a few starts):
//
//   * signed distance (separation distance, or minus the penetration depth): the maximum
//     over unit directions n of the support gap g(n) = n.r - sqrt(n^T Pa n) - sqrt(n^T Pb n)
//     (r = cb - ca, P = M^-1 in the WORLD frame), a global search: g is sampled on three
//     dense grids of directions (uniform, and the Gauss maps of both bodies, about 3000
//     directions in 2D and 14000 in 3D, in double), every discrete local maximum is
//     refined by damped Newton in double, the distinct results are ranked, and the best
//     ones are polished by Newton in Real. For convex bodies max g is the signed distance
//     (dist(0, A - B) when apart, minus the distance from 0 to the boundary of A - B when
//     overlapping), so no case distinction is needed.
//   * boundary intersection (2D): the real roots of the quartic obtained by substituting the
//     rational parametrization of a's boundary (tan half-angle) into b's quadric, isolated
//     by recursion on the derivatives (roots of p' split the line into monotone pieces) and
//     bisection/Newton; the parametrization is rotated so its point at infinity is far
//     from b's boundary.
//   * overlap area (2D): adaptive Gauss-Kronrod quadrature (Boost.Math, 31 points) of the
//     length of the common vertical chord over x, split at the x of the crossing points
//     (kinks); on each piece x = x0 + (x1 - x0) sin^2(tau / 2) makes the square-root ends
//     of the common x-range analytic in tau.
#pragma once

#include "reference.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace ellipsect::reference {

template <int N> struct SignedDistance {
  Real distance;     // > 0 separation distance, < 0 minus the penetration depth
  RVec<N> point_a;   // support point of a with outward normal `normal`
  RVec<N> point_b;   // support point of b with outward normal -`normal`
  RVec<N> normal;    // unit, the maximizing direction (from a towards b when apart)
  // The largest g among the other local maxima found (-inf if none): when it is within the
  // test tolerance of `distance`, the witness points are not determined by the distance.
  Real runner_up;
};

namespace detail {

// World-frame data for the support gap, in scalar S (double for the search, Real for the
// polish).
template <class S, int N> struct GapData {
  Eigen::Matrix<S, N, N> Pa, Pb;
  Eigen::Matrix<S, N, 1> r;
};

template <class S, int N> Eigen::Matrix<S, N, N - 1> tangent_basis(const Eigen::Matrix<S, N, 1>& n) {
  using std::abs;
  using std::sqrt;
  Eigen::Matrix<S, N, N - 1> q;
  if constexpr (N == 2) {
    q(0, 0) = -n(1);
    q(1, 0) = n(0);
  } else {
    int i = 0;
    for (int j = 1; j < 3; ++j)
      if (abs(n(j)) < abs(n(i))) i = j;
    Eigen::Matrix<S, 3, 1> t = n * (-n(i));
    t(i) += 1;
    t /= sqrt(t.dot(t));
    q.col(0) = t;
    q.col(1) = n.cross(t);
  }
  return q;
}

template <class S, int N> S gap(const GapData<S, N>& d, const Eigen::Matrix<S, N, 1>& n) {
  using std::sqrt;
  return n.dot(d.r) - sqrt(n.dot(d.Pa * n)) - sqrt(n.dot(d.Pb * n));
}

// Riemannian gradient and Hessian of g on the sphere at n (tangent basis q).
template <class S, int N>
void gap_derivatives(const GapData<S, N>& d, const Eigen::Matrix<S, N, 1>& n, const Eigen::Matrix<S, N, N - 1>& q,
                     Eigen::Matrix<S, N - 1, 1>& grad, Eigen::Matrix<S, N - 1, N - 1>& hess) {
  using std::sqrt;
  using V = Eigen::Matrix<S, N, 1>;
  using M = Eigen::Matrix<S, N, N>;
  const V pa = d.Pa * n, pb = d.Pb * n;
  const S ra = sqrt(n.dot(pa)), rb = sqrt(n.dot(pb));
  const V g = d.r - pa / ra - pb / rb;
  const M h = -(d.Pa / ra - pa * pa.transpose() / (ra * ra * ra)) - (d.Pb / rb - pb * pb.transpose() / (rb * rb * rb));
  grad = q.transpose() * g;
  hess = q.transpose() * h * q - n.dot(g) * Eigen::Matrix<S, N - 1, N - 1>::Identity();
}

// Damped Newton ascent of g on the sphere from n (gradient steps where the Hessian is not
// negative definite, halving until g does not decrease). Stops when the step is below
// `tiny` or after `max_iter` steps.
template <class S, int N>
Eigen::Matrix<S, N, 1> ascend(const GapData<S, N>& d, Eigen::Matrix<S, N, 1> n, int max_iter, const S& tiny) {
  using std::abs;
  using std::sqrt;
  using V = Eigen::Matrix<S, N, 1>;
  using TV = Eigen::Matrix<S, N - 1, 1>;
  using TM = Eigen::Matrix<S, N - 1, N - 1>;
  S value = gap<S, N>(d, n);
  for (int it = 0; it < max_iter; ++it) {
    const Eigen::Matrix<S, N, N - 1> q = tangent_basis<S, N>(n);
    TV grad;
    TM hess;
    gap_derivatives<S, N>(d, n, q, grad, hess);
    // Negative definite test (1x1 or 2x2): then Newton, else a scaled gradient step.
    bool nd = hess(0, 0) < 0;
    if constexpr (N == 3) nd = nd && hess(0, 0) * hess(1, 1) - hess(0, 1) * hess(1, 0) > 0;
    TV t;
    if (nd) {
      t = -hess.inverse() * grad;
    } else {
      S scale = 0;
      for (int i = 0; i < N - 1; ++i)
        for (int j = 0; j < N - 1; ++j) scale = std::max(scale, S(abs(hess(i, j))));
      t = grad / (scale + sqrt(grad.dot(grad)));
    }
    const S len = sqrt(t.dot(t));
    if (len > S(0.5)) t *= S(0.5) / len;
    S step = 1;
    V next = n;
    S next_value = value;
    for (int half = 0; half < 60; ++half, step /= 2) {
      V m = n + q * (t * step);
      m /= sqrt(m.dot(m));
      const S v = gap<S, N>(d, m);
      if (v >= value) {
        next = m;
        next_value = v;
        break;
      }
    }
    const S moved = sqrt((next - n).dot(next - n));
    n = next;
    value = next_value;
    if (moved <= tiny) break;
  }
  return n;
}

template <int N> DVec<N> unit_param(int i, int j, int ni, int nj) {
  DVec<N> u;
  if constexpr (N == 2) {
    (void)j;
    (void)nj;
    const double t = 2 * M_PI * i / ni;
    u << std::cos(t), std::sin(t);
  } else {
    const double th = M_PI * (i + 0.5) / ni, ph = 2 * M_PI * j / nj;
    u << std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th);
  }
  return u;
}

}  // namespace detail

// Signed distance of two bodies (see the top of this file). Polish: ~1e-45 relative for
// isolated maxima; at the merging of two maxima (a degenerate critical point) the value
// is still ~1e-45 but the direction only ~1e-22.
template <int N> SignedDistance<N> signed_distance(const Body<N>& a, const Body<N>& b) {
  using namespace detail;
  const RBody<N> ra = make_rbody<N>(a, "a"), rb = make_rbody<N>(b, "b");
  GapData<Real, N> dr{ra.P, rb.P, RVec<N>(rb.c - ra.c)};
  GapData<double, N> dd;
  for (int i = 0; i < N; ++i) {
    dd.r(i) = to_double(dr.r(i));
    for (int j = 0; j < N; ++j) {
      dd.Pa(i, j) = to_double(ra.P(i, j));
      dd.Pb(i, j) = to_double(rb.P(i, j));
    }
  }
  // Sampling in the body frames (accurate support radii for needles and discs).
  auto g_body = [&](const DVec<N>& n) {
    return n.dot(dd.r) - a.radii.cwiseProduct(a.axes.transpose() * n).norm() -
           b.radii.cwiseProduct(b.axes.transpose() * n).norm();
  };
  constexpr int ni = N == 2 ? 1024 : 48, nj = N == 2 ? 1 : 96;
  std::vector<std::pair<double, DVec<N>>> candidates;
  for (int map = 0; map < 3; ++map) {
    auto direction = [&](int i, int j) {
      const DVec<N> u = unit_param<N>(i, j, ni, nj);
      if (map == 0) return u;
      const Body<N>& body = map == 1 ? a : b;
      return DVec<N>((body.axes * u.cwiseQuotient(body.radii)).normalized());
    };
    std::vector<double> value(ni * nj);
    std::vector<DVec<N>> dir(ni * nj);
    for (int i = 0; i < ni; ++i)
      for (int j = 0; j < nj; ++j) {
        dir[i * nj + j] = direction(i, j);
        value[i * nj + j] = g_body(dir[i * nj + j]);
      }
    for (int i = 0; i < ni; ++i)
      for (int j = 0; j < nj; ++j) {
        const double v = value[i * nj + j];
        bool is_max = true;
        for (int di = -1; di <= 1 && is_max; ++di)
          for (int dj = -1; dj <= 1 && is_max; ++dj) {
            if (di == 0 && dj == 0) continue;
            int ii = i + di, jj = (j + dj + nj) % nj;
            if (N == 2) ii = (ii + ni) % ni;
            if (ii < 0 || ii >= ni) continue;
            if (value[ii * nj + jj] > v) is_max = false;
          }
        if (is_max) candidates.push_back({v, dir[i * nj + j]});
      }
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  if (candidates.size() > 24) candidates.resize(24);

  // Refine in double; keep the distinct local maxima.
  std::vector<std::pair<double, DVec<N>>> maxima;
  for (const auto& c : candidates) {
    const DVec<N> n = ascend<double, N>(dd, c.second, 200, 1e-15);
    const double v = g_body(n);
    bool seen = false;
    for (const auto& m : maxima) seen = seen || (m.second - n).norm() < 1e-7;
    if (!seen) maxima.push_back({v, n});
  }
  std::sort(maxima.begin(), maxima.end(), [](const auto& x, const auto& y) { return x.first > y.first; });

  // Polish the best (and near-ties) in Real.
  const double size = a.radii.maxCoeff() + b.radii.maxCoeff() + std::abs(maxima[0].first);
  SignedDistance<N> out;
  out.distance = -infinity();
  out.runner_up = -infinity();
  for (std::size_t m = 0; m < maxima.size(); ++m) {
    if (m > 0 && maxima[m].first < maxima[0].first - 1e-9 * size) {
      out.runner_up = std::max(out.runner_up, Real(maxima[m].first));
      continue;
    }
    RVec<N> n = to_real<N>(maxima[m].second);
    n /= sqrt(n.dot(n));
    n = ascend<Real, N>(dr, n, 12, Real("1e-44"));
    const Real v = gap<Real, N>(dr, n);
    if (v > out.distance) {
      if (out.distance > -infinity()) out.runner_up = std::max(out.runner_up, out.distance);
      out.distance = v;
      out.normal = n;
    } else {
      out.runner_up = std::max(out.runner_up, v);
    }
  }
  const RVec<N> pa = ra.P * out.normal, pb = rb.P * out.normal;
  out.point_a = ra.c + pa / sqrt(out.normal.dot(pa));
  out.point_b = rb.c - pb / sqrt(out.normal.dot(pb));
  return out;
}

// ------------------------------------------------------------------------------------------
// 2D: boundary intersection points and overlap area
// ------------------------------------------------------------------------------------------

namespace detail {

// p(x) = sum c[i] x^i.
inline Real poly_eval(const std::vector<Real>& c, const Real& x) {
  Real v = c.back();
  for (int i = static_cast<int>(c.size()) - 2; i >= 0; --i) v = v * x + c[i];
  return v;
}

// Real roots of the polynomial c (leading coefficient nonzero), ascending. A root of
// even multiplicity appears once, found as a critical point where |p| is at rounding.
inline std::vector<Real> real_roots(const std::vector<Real>& c) {
  const int deg = static_cast<int>(c.size()) - 1;
  if (deg == 1) return {-c[0] / c[1]};
  std::vector<Real> dc(deg);
  for (int i = 1; i <= deg; ++i) dc[i - 1] = c[i] * i;
  Real bound = 0;
  for (int i = 0; i < deg; ++i) bound = std::max(bound, Real(abs(c[i] / c[deg])));
  bound += 1;
  std::vector<Real> ends{-bound};
  for (const Real& x : real_roots(dc))
    if (x > -bound && x < bound) ends.push_back(x);
  ends.push_back(bound);
  auto magnitude = [&](const Real& x) {  // size of the terms of p at x, for rounding
    Real s = 0, xi = 1;
    for (int i = 0; i <= deg; ++i, xi *= abs(x)) s += abs(c[i]) * xi;
    return s;
  };
  std::vector<Real> roots;
  for (std::size_t k = 1; k + 1 < ends.size(); ++k)  // critical points at rounding level
    if (abs(poly_eval(c, ends[k])) <= Real("1e-40") * magnitude(ends[k])) roots.push_back(ends[k]);
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const Real lo = ends[k], hi = ends[k + 1];
    const Real flo = poly_eval(c, lo), fhi = poly_eval(c, hi);
    if (abs(flo) <= Real("1e-40") * magnitude(lo) || abs(fhi) <= Real("1e-40") * magnitude(hi)) continue;
    if ((flo < 0) == (fhi < 0)) continue;
    const Real sign = flo < 0 ? 1 : -1;
    auto fdf = [&](const Real& x, Real& f, Real& df) {
      f = sign * poly_eval(c, x);
      df = sign * poly_eval(dc, x);
    };
    roots.push_back(newton_increasing(fdf, lo, hi, lo + (hi - lo) / 2, hi - lo));
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

}  // namespace detail

// The points where the boundaries of two ellipses meet (a tangency appears once when it is
// exact to ~1e-40; nearly tangent pairs give two close points or none). Accuracy ~1e-45
// relative to the sizes for transverse crossings.
inline std::vector<RVec<2>> boundary_intersection(const detail::RBody<2>& ra, const detail::RBody<2>& rb) {
  using namespace detail;
  const RVec<2> d = ra.c - rb.c;
  auto level = [&](const RVec<2>& u) {  // q_b at a's boundary point with parameter u, minus 1
    const RVec<2> v = d + ra.L * u;
    return v.dot(rb.M * v) - 1;
  };
  // Put the parametrization's point at infinity where |q_b - 1| is largest among 16 angles.
  RVec<2> u0;
  Real best = -1;
  for (int i = 0; i < 16; ++i) {
    RVec<2> u;
    u << Real(std::cos(M_PI * i / 8)), Real(std::sin(M_PI * i / 8));
    u /= sqrt(u.dot(u));
    const Real v = abs(level(u));
    if (v > best) {
      best = v;
      u0 = u;
    }
  }
  const RVec<2> w = -u0;
  RVec<2> wp;
  wp << -w(1), w(0);
  // u(s) = ((1 - s^2) w + 2 s wp) / (1 + s^2); (1 + s^2)^2 (q_b - 1) is a quartic in s.
  const RMat<2> K = ra.L.transpose() * rb.M * ra.L;
  const RVec<2> bv = ra.L.transpose() * rb.M * d;
  const Real c0 = d.dot(rb.M * d) - 1;
  const Real kww = w.dot(K * w), kwp = w.dot(K * wp), kpp = wp.dot(K * wp), bw = bv.dot(w), bp = bv.dot(wp);
  const std::vector<Real> coeffs{kww + 2 * bw + c0, 4 * kwp + 4 * bp, -2 * kww + 4 * kpp + 2 * c0, -4 * kwp + 4 * bp,
                                 kww - 2 * bw + c0};
  std::vector<RVec<2>> points;
  for (const Real& s : real_roots(coeffs)) {
    const Real den = 1 + s * s;
    const RVec<2> u = (w * (1 - s * s) + wp * (2 * s)) / den;
    points.push_back(ra.c + ra.L * u);
  }
  return points;
}

inline std::vector<RVec<2>> boundary_intersection(const Body<2>& a, const Body<2>& b) {
  return boundary_intersection(detail::make_rbody<2>(a, "a"), detail::make_rbody<2>(b, "b"));
}

// Area of the intersection of two ellipses (~1e-25 relative to the smaller area).
inline Real overlap_area(const detail::RBody<2>& ra, const detail::RBody<2>& rb) {
  using namespace detail;
  struct Chord {
    const RBody<2>& e;
    Real det;  // det M = 1 / (r0 r1)^2
    void at(const Real& x, Real& lo, Real& hi) const {
      const Real dx = x - e.c(0);
      Real disc = e.M(1, 1) - dx * dx * det;
      if (disc < 0) disc = 0;
      const Real mid = e.c(1) - e.M(0, 1) * dx / e.M(1, 1), half = sqrt(disc) / e.M(1, 1);
      lo = mid - half;
      hi = mid + half;
    }
  };
  const Chord ca{ra, 1 / (ra.radii(0) * ra.radii(1) * ra.radii(0) * ra.radii(1))};
  const Chord cb{rb, 1 / (rb.radii(0) * rb.radii(1) * rb.radii(0) * rb.radii(1))};
  const Real wa = sqrt(ra.P(0, 0)), wb = sqrt(rb.P(0, 0));
  const Real lo = std::max(Real(ra.c(0) - wa), Real(rb.c(0) - wb)), hi = std::min(Real(ra.c(0) + wa), Real(rb.c(0) + wb));
  if (!(lo < hi)) return 0;
  std::vector<Real> cuts{lo, hi};
  for (const RVec<2>& p : boundary_intersection(ra, rb))
    if (p(0) > lo && p(0) < hi) cuts.push_back(p(0));
  std::sort(cuts.begin(), cuts.end());
  auto length = [&](const Real& x) {
    Real la, ha, lb, hb;
    ca.at(x, la, ha);
    cb.at(x, lb, hb);
    const Real len = std::min(ha, hb) - std::max(la, lb);
    return len > 0 ? len : Real(0);
  };
  // On each piece x = x0 + (x1 - x0) sin^2(tau / 2), tau in [0, pi]: a square-root end
  // point of the chord becomes analytic in tau, and so does the smooth piece between.
  Real area = 0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const Real x0 = cuts[k], w = cuts[k + 1] - cuts[k];
    if (!(w > 0)) continue;
    auto integrand = [&](const Real& tau) {
      const Real s = sin(tau / 2), c = cos(tau / 2);
      const Real x = s < c ? x0 + w * s * s : cuts[k + 1] - w * c * c;
      return length(x) * w * s * c;  // dx/dtau = w sin(tau / 2) cos(tau / 2)
    };
    area += boost::math::quadrature::gauss_kronrod<Real, 31>::integrate(integrand, Real(0),
                                                                          boost::math::constants::pi<Real>(), 12,
                                                                          Real("1e-24"));
  }
  return area;
}

inline Real overlap_area(const Body<2>& a, const Body<2>& b) {
  return overlap_area(detail::make_rbody<2>(a, "a"), detail::make_rbody<2>(b, "b"));
}

// The maximum of the support gap of two bodies in Real, by the polish of signed_distance
// from the direction n (a local maximum: the global one from signed_distance's normal, for
// bodies moved by much less than their gap to the other local maxima).
template <int N> Real gap_maximum(const detail::RBody<N>& a, const detail::RBody<N>& b, const RVec<N>& n) {
  const detail::GapData<Real, N> d{a.P, b.P, RVec<N>(b.c - a.c)};
  return detail::gap<Real, N>(d, detail::ascend<Real, N>(d, n, 24, Real("1e-44")));
}

// The functions the tests and benchmarks call, for N = 2 and 3: compiled once, in
// distance_reference.cpp (the library ellipsect_reference), not in every program that includes
// this header.
#define ELLIPSECT_DISTANCE_REFERENCE_FUNCTIONS(extern_, N) \
  extern_ template SignedDistance<N> signed_distance<N>(const Body<N>&, const Body<N>&); \
  extern_ template Real gap_maximum<N>(const detail::RBody<N>&, const detail::RBody<N>&, const RVec<N>&);
ELLIPSECT_DISTANCE_REFERENCE_FUNCTIONS(extern, 2)
ELLIPSECT_DISTANCE_REFERENCE_FUNCTIONS(extern, 3)

}  // namespace ellipsect::reference
