// 50-digit reference for a body against a triangle (header templates, never includes the library).
//
// Route, different from the library's (the unit-ball frame, the nearest of seven candidates
// as barycentric weights, a certified bracket in double and double-length arithmetic, the
// contact time from closed-form entering roots per feature):
//   * world coordinates: the quadric f(x) = (x - c)^T M (x - c), M = A diag(r)^-2 A^T with
//     the axes exactly as stored, minimized over the triangle in Real as a convex quadratic
//     program: the face's stationary point (a 2x2 system in M's metric), each edge's (one
//     unknown), each vertex, the least admissible value; the winner is verified against the
//     optimality condition of a convex program over a polytope, (y - x)^T M (x - c) >= 0 for
//     every vertex y, to 1e-30 (a violation throws);
//   * d = sqrt(min f), D = sqrt(max over the vertices of f);
//   * the first contact time by searching the convex function d(t), evaluated afresh at each
//     time from the moved center and vertices: bisection on d(t) <= 1 when d(window end) <= 1,
//     otherwise the minimizer by golden section first, then bisection before it.
#pragma once

#include "tests/reference/reference.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace ellipsect::reference {

template <int N>
struct TriangleGaps {
  Real d;            // min over the triangle of sqrt((x - c)^T M (x - c))
  Real D;            // max over the vertices
  RVec<N> nearest;   // the triangle's point where d is reached
  RVec<N> gradient;  // M (nearest - c): the body's outward normal direction there
};

template <int N>
using RTriangle = std::array<RVec<N>, 3>;

template <int N>
RMat<N> quadric_of(const Body<N>& body) {
  RMat<N> M = RMat<N>::Zero();
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < N; ++k)
        M(i, j) += Real(body.axes(i, k)) * Real(body.axes(j, k)) / (Real(body.radii(k)) * Real(body.radii(k)));
  return M;
}

template <int N>
TriangleGaps<N> triangle_gaps(const RMat<N>& M, const RVec<N>& center, const RTriangle<N>& v) {
  const auto form = [&](const RVec<N>& x, const RVec<N>& y) { return detail::dot<N>(x, detail::matvec<N>(M, y)); };
  RVec<N> best = v[0];
  Real best_f = form(RVec<N>(v[0] - center), RVec<N>(v[0] - center));
  const auto consider = [&](const RVec<N>& x) {
    const RVec<N> e = x - center;
    const Real f = form(e, e);
    if (f < best_f) {
      best_f = f;
      best = x;
    }
  };
  Real far = best_f;
  for (int k = 1; k < 3; ++k) {
    consider(v[k]);
    const RVec<N> e = v[k] - center;
    if (form(e, e) > far) far = form(e, e);
  }
  for (int i = 0; i < 3; ++i) {
    const RVec<N> e = v[i] - center, g = v[(i + 1) % 3] - v[i];
    const Real gg = form(g, g);
    if (gg == 0) continue;
    const Real s = -form(g, e) / gg;
    if (s > 0 && s < 1) consider(RVec<N>(v[i] + s * g));
  }
  const RVec<N> e0 = v[0] - center, g1 = v[1] - v[0], g2 = v[2] - v[0];
  const Real a = form(g1, g1), b = form(g1, g2), c = form(g2, g2), det = a * c - b * b;
  if (det > 0) {
    const Real p = -form(g1, e0), q = -form(g2, e0);
    const Real s = (p * c - q * b) / det, t = (a * q - b * p) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) consider(RVec<N>(v[0] + s * g1 + t * g2));
  }
  TriangleGaps<N> out;
  out.d = sqrt(best_f);
  out.D = sqrt(far);
  out.nearest = best;
  out.gradient = detail::matvec<N>(M, RVec<N>(best - center));
  // Optimality over the polytope: no vertex lies on the descending side of the gradient.
  Real scale = 0;
  for (int k = 0; k < 3; ++k) scale = std::max(scale, Real(sqrt(form(RVec<N>(v[k] - center), RVec<N>(v[k] - center)))));
  for (int k = 0; k < 3; ++k) {
    const Real slope = detail::dot<N>(RVec<N>(v[k] - best), out.gradient);
    if (slope < -Real(1e-30) * (1 + scale * scale))
      throw std::logic_error("triangle_gaps: the minimizer fails its optimality condition (" + slope.str(3) + ")");
  }
  return out;
}

template <int N>
TriangleGaps<N> triangle_gaps(const Body<N>& body, const std::array<DVec<N>, 3>& vertices) {
  RTriangle<N> v;
  for (int k = 0; k < 3; ++k) v[k] = to_real<N>(vertices[k]);
  return triangle_gaps<N>(quadric_of<N>(body), to_real<N>(body.center), v);
}

// d at time t of the body moving with velocity_a and the triangle with velocity_b.
template <int N>
struct MovingTriangle {
  RMat<N> M;
  RVec<N> center, va, vb;
  RTriangle<N> v;
  TriangleGaps<N> at(const Real& t) const {
    RTriangle<N> moved;
    for (int k = 0; k < 3; ++k) moved[k] = v[k] + t * vb;
    return triangle_gaps<N>(M, RVec<N>(center + t * va), moved);
  }
};

template <int N>
MovingTriangle<N> moving_triangle(const Body<N>& body, const std::array<DVec<N>, 3>& vertices, const DVec<N>& velocity_a,
                                  const DVec<N>& velocity_b) {
  MovingTriangle<N> m{quadric_of<N>(body), to_real<N>(body.center), to_real<N>(velocity_a), to_real<N>(velocity_b), {}};
  for (int k = 0; k < 3; ++k) m.v[k] = to_real<N>(vertices[k]);
  return m;
}

struct TriangleContact {
  Real time;     // the first t in [0, window] with d(t) <= 1; +infinity when none
  Real minimum;  // min of d over the window (at the searched minimizer)
};

// `window` is t_max, or for t_max = infinity a time after which d only grows (the caller's).
template <int N>
TriangleContact triangle_contact_time(const MovingTriangle<N>& m, const Real& window) {
  const auto d = [&](const Real& t) { return m.at(t).d; };
  TriangleContact out{detail::infinity(), d(Real(0))};
  if (out.minimum <= 1) {
    out.time = 0;
    return out;
  }
  Real hi = window;
  const Real d_end = d(hi);
  out.minimum = std::min(out.minimum, d_end);
  if (d_end > 1) {
    // Golden section for the minimizer of the convex d on [0, window].
    const Real ratio = (sqrt(Real(5)) - 1) / 2;
    Real lo = 0, top = window;
    Real x1 = top - ratio * (top - lo), x2 = lo + ratio * (top - lo), f1 = d(x1), f2 = d(x2);
    for (int k = 0; k < 200 && top - lo > Real(1e-30) * window; ++k) {
      if (f1 <= 1 || f2 <= 1) break;
      if (f1 < f2) {
        top = x2, x2 = x1, f2 = f1, x1 = top - ratio * (top - lo), f1 = d(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + ratio * (top - lo), f2 = d(x2);
      }
    }
    out.minimum = std::min({out.minimum, f1, f2});
    if (f1 > 1 && f2 > 1) return out;
    hi = f1 <= 1 ? x1 : x2;
  }
  Real lo = 0;
  for (int k = 0; k < 200 && hi - lo > Real(1e-24) * hi; ++k) {
    const Real mid = (lo + hi) / 2;
    (d(mid) > 1 ? lo : hi) = mid;
  }
  out.time = hi;
  return out;
}

// The functions the tests and benchmarks call, for N = 2 and 3: compiled once, in
// triangle_reference.cpp (the library ellipsect_reference), not in every program that includes
// this header.
#define ELLIPSECT_TRIANGLE_REFERENCE_FUNCTIONS(extern_, N) \
  extern_ template RMat<N> quadric_of<N>(const Body<N>&); \
  extern_ template TriangleGaps<N> triangle_gaps<N>(const RMat<N>&, const RVec<N>&, const RTriangle<N>&); \
  extern_ template TriangleGaps<N> triangle_gaps<N>(const Body<N>&, const std::array<DVec<N>, 3>&); \
  extern_ template struct MovingTriangle<N>; \
  extern_ template MovingTriangle<N> moving_triangle<N>(const Body<N>&, const std::array<DVec<N>, 3>&, const DVec<N>&, \
                                                        const DVec<N>&); \
  extern_ template TriangleContact triangle_contact_time<N>(const MovingTriangle<N>&, const Real&);
ELLIPSECT_TRIANGLE_REFERENCE_FUNCTIONS(extern, 2)
ELLIPSECT_TRIANGLE_REFERENCE_FUNCTIONS(extern, 3)

}  // namespace ellipsect::reference
