// Seeded bodies against triangles (triangle.hpp), shared by the tests and the benchmarks.
// Each case is built in the body's unit-ball frame, where its nearest point is known: a
// triangle inside the half-space { y : n . y >= d } through the point p = d n touches the
// sphere of radius d at p, so it lies at relative gap d - 1 with its nearest point on the
// chosen feature (face, edge or vertex); then mapped to world coordinates
// (x = c + A diag(r) u) and given a motion towards, along or away from the body.
#pragma once

#include <ellipsect/triangle.hpp>

#include "scenarios/scenarios.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace ellipsect::scenarios {

enum class TriangleKind {
  random,
  aspect,
  near_face,
  near_edge,
  near_vertex,
  contained,
  large,
  needle,
  small,
  huge,
  grazing,
  still
};
constexpr std::array<TriangleKind, 12> triangle_kinds = {
    TriangleKind::random,    TriangleKind::aspect, TriangleKind::near_face, TriangleKind::near_edge,
    TriangleKind::near_vertex, TriangleKind::contained, TriangleKind::large, TriangleKind::needle,
    TriangleKind::small,     TriangleKind::huge,   TriangleKind::grazing,   TriangleKind::still};

inline const char* name(TriangleKind k) {
  switch (k) {
    case TriangleKind::random: return "random";
    case TriangleKind::aspect: return "aspect_1e4";
    case TriangleKind::near_face: return "near_tangent_face";
    case TriangleKind::near_edge: return "near_tangent_edge";
    case TriangleKind::near_vertex: return "near_tangent_vertex";
    case TriangleKind::contained: return "contained";
    case TriangleKind::large: return "large_triangle";
    case TriangleKind::needle: return "needle";
    case TriangleKind::small: return "scale_1e-6";
    case TriangleKind::huge: return "scale_1e6";
    case TriangleKind::grazing: return "grazing";
    case TriangleKind::still: return "zero_relative_velocity";
  }
  return "?";
}

template <int N>
struct TriangleCase {
  TriangleKind kind;
  int seed;
  Ellipsoid<double, N> a;
  Triangle<double, N> b;
  Vec<double, N> va, vb;
  double t_max;
  double window;  // t_max, or where t_max is infinite a time after which the gap only grows
  double gap;     // the relative gap aimed at (before rounding to double)
};

template <int N>
std::string describe(const TriangleCase<N>& c) {
  std::ostringstream s;
  s.precision(17);
  s << "N=" << N << " kind=" << name(c.kind) << " seed=" << c.seed << " gap=" << c.gap << "\n  a: c=" << c.a.center().transpose()
    << " r=" << c.a.radii().transpose() << "\n  b:";
  for (int k = 0; k < 3; ++k) s << " (" << c.b.vertex(k).transpose() << ")";
  s << "\n  va=" << c.va.transpose() << " vb=" << c.vb.transpose() << " t_max=" << c.t_max;
  return s.str();
}

// random: vertices anywhere within 3 radii; aspect_1e4: radii ratios to 1e4; near_tangent_*:
// the relative gap log-uniform in [1e-13, 1e-3], either sign, at a face (3D; an edge in 2D),
// an edge or a vertex; contained: vertices within 0.9 of the ball; large_triangle: 1e3 to
// 1e12 radii across (every other one near tangency); needle: a segment, a point, two equal
// vertices, or a sliver 1e-12 to 1e-6 thick; scale_1e-6 / 1e6: everything scaled; grazing:
// the approach 1e-9 of the speed; zero_relative_velocity: equal velocities. The others: gaps
// in [-0.5, 2].
template <int N>
TriangleCase<N> make_triangle_case(TriangleKind kind, int seed) {
  using namespace detail;
  using V = Vec<double, N>;
  Rng rng(static_cast<std::uint64_t>(seed) * 7919 + static_cast<std::uint64_t>(kind) * 104729 + 17);
  const Mat<double, N> axes = rotation<N>(rng);
  const V r = radii<N>(rng, 1.0, kind == TriangleKind::aspect ? 1e4 : 10);
  const V c = V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -3, 3); });
  const V n = unit_vector<N>(rng);
  V e1 = unit_vector<N>(rng);
  e1 = (e1 - e1.dot(n) * n).normalized();
  V e2 = e1;  // a second tangent in 3D
  if constexpr (N == 3) e2 = n.cross(e1);
  const bool near = kind == TriangleKind::near_face || kind == TriangleKind::near_edge ||
                    kind == TriangleKind::near_vertex || (kind == TriangleKind::large && seed % 2 == 0);
  const double gap =
      near ? (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-13, 1e-3) : uniform(rng, -0.5, 2);
  const V p = (1 + gap) * n;
  const double R = kind == TriangleKind::large ? log_uniform(rng, 1e3, 1e12) : log_uniform(rng, 0.1, 3);
  // 0 face, 1 edge, 2 vertex
  int feature = kind == TriangleKind::near_face ? 0 : kind == TriangleKind::near_edge ? 1 : kind == TriangleKind::near_vertex ? 2
                                                                                                                   : static_cast<int>(uniform(rng, 0, 3));
  if (N == 2 && feature == 0) feature = 1;
  std::array<V, 3> u;
  if (feature == 0) {
    const double a1 = uniform(rng, 1.8, 2.4), a2 = uniform(rng, 1.8, 2.4), t0 = uniform(rng, -M_PI, M_PI);
    const double angle[3] = {t0, t0 + a1, t0 + a1 + a2};
    for (int k = 0; k < 3; ++k)
      u[k] = p + R * uniform(rng, 0.5, 1.5) * (std::cos(angle[k]) * e1 + std::sin(angle[k]) * e2);
  } else if (feature == 1) {
    u[0] = p - R * uniform(rng, 0.2, 1) * e1;
    u[1] = p + R * uniform(rng, 0.2, 1) * e1;
    u[2] = p + R * uniform(rng, 0.2, 1.5) * n + R * uniform(rng, -1, 1) * e2;
  } else {
    u[0] = p;
    for (int k = 1; k < 3; ++k)
      u[k] = p + R * (uniform(rng, 0.2, 1) * n + uniform(rng, -1, 1) * e1 + uniform(rng, -1, 1) * e2);
  }
  if (kind == TriangleKind::needle) {
    // Along the edge u0 u1 (which passes through p), or the point p.
    const int shape = static_cast<int>(uniform(rng, 0, 4));
    u[0] = p - R * uniform(rng, 0.2, 1) * e1;
    u[1] = p + R * uniform(rng, 0.2, 1) * e1;
    const V along = u[0] + uniform(rng, 0, 1) * (u[1] - u[0]);
    if (shape == 0) u[2] = along;                                              // a segment
    if (shape == 1) u[0] = u[1] = u[2] = p;                                    // a point
    if (shape == 2) u[2] = u[0];                                               // two equal vertices
    if (shape == 3) u[2] = along + R * log_uniform(rng, 1e-12, 1e-6) * n;      // a sliver
  }
  if (kind == TriangleKind::contained)
    for (V& x : u) x = unit_vector<N>(rng) * uniform(rng, 0, 0.9);
  if (kind == TriangleKind::random)
    for (V& x : u) x = V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -3, 3); });
  const double size = kind == TriangleKind::small ? 1e-6 : kind == TriangleKind::huge ? 1e6 : 1;
  const auto world = [&](const V& x) { return V(size * (c + axes * r.cwiseProduct(x))); };
  TriangleCase<N> out{kind, seed, Ellipsoid<double, N>::from_axes(c * size, axes, r * size),
                      make_triangle<double, N>(world(u[0]), world(u[1]), world(u[2])), V::Zero(), V::Zero(), 0, 0, gap};
  // The triangle moves towards the body's center in the ball frame (along -n), sideways, or away.
  const double speed = log_uniform(rng, 0.1, 10);  // ball radii per unit time
  const double sin_angle = kind == TriangleKind::grazing ? 1e-9 : uniform(rng, -0.3, 1);
  const V w = speed * (-sin_angle * n + std::sqrt(1 - sin_angle * sin_angle) * e1);
  const V relative = size * axes * r.cwiseProduct(w);
  out.va = unit_vector<N>(rng) * relative.norm() * uniform(rng, 0, 0.5);
  out.vb = kind == TriangleKind::still ? out.va : V(out.va + relative);
  double extent = 0;
  for (const V& x : u) extent = std::max(extent, x.norm());
  out.t_max = uniform(rng, 0, 1) < 0.3 ? std::numeric_limits<double>::infinity()
                                        : log_uniform(rng, 0.1, 10) * (std::abs(gap) + 1) / speed;
  // After 2 (extent + 2) / speed every point of the triangle is farther than at t = 0.
  out.window = std::isfinite(out.t_max) ? out.t_max : 2 * (extent + 2) / speed;
  return out;
}

}  // namespace ellipsect::scenarios
