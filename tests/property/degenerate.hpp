// Degenerate triangles for the property tests (and the relation a triangle reference implies):
// each scenario triangle (scenarios/triangle.hpp) made, in world coordinates, collinear (v2 on the segment v0 v1,
// to the rounding of double), nearly collinear (that v2 moved 1 to 4 ulps per coordinate off
// the segment), a point, or nearly a point (v1 and v2 1 to 4 ulps per coordinate from v0).
// The scenario's edge u0 u1 (near_tangent_edge) and vertex u0 (near_tangent_vertex) carry
// its gap, so the segment and the point stay near tangency.
#pragma once

#include "scenarios/triangle.hpp"
#include "tests/reference/reference.hpp"

#include <ellipsect/classify.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace ellipsect::testing {

enum class Degenerate { collinear, nearly_collinear, point, nearly_point };
constexpr std::array<Degenerate, 4> degenerate_kinds{Degenerate::collinear, Degenerate::nearly_collinear,
                                                     Degenerate::point, Degenerate::nearly_point};

inline const char* name(Degenerate d) {
  return d == Degenerate::collinear ? "collinear" : d == Degenerate::nearly_collinear ? "nearly_collinear"
                                                : d == Degenerate::point            ? "point"
                                                                                    : "nearly_point";
}

// x moved by 1 to 4 ulps, up or down, in each coordinate.
template <int N>
Vec<double, N> ulps_from(const Vec<double, N>& x, scenarios::detail::Rng& rng) {
  Vec<double, N> y = x;
  for (int i = 0; i < N; ++i) {
    const double towards = scenarios::detail::uniform(rng, 0, 1) < 0.5 ? -1e300 : 1e300;
    const int steps = 1 + static_cast<int>(scenarios::detail::uniform(rng, 0, 4));
    for (int k = 0; k < steps; ++k) y[i] = std::nextafter(y[i], towards);
  }
  return y;
}

template <int N>
scenarios::TriangleCase<N> degenerate(scenarios::TriangleCase<N> c, Degenerate d) {
  scenarios::detail::Rng rng(static_cast<std::uint64_t>(c.seed) * 31 + static_cast<std::uint64_t>(d) * 7 + 3);
  const Vec<double, N> v0 = c.b.vertex(0), v1 = c.b.vertex(1);
  const Vec<double, N> along = v0 + scenarios::detail::uniform(rng, 0, 1) * (v1 - v0);
  switch (d) {
    case Degenerate::collinear: c.b = make_triangle<double, N>(v0, v1, along); break;
    case Degenerate::nearly_collinear: c.b = make_triangle<double, N>(v0, v1, ulps_from<N>(along, rng)); break;
    case Degenerate::point: c.b = make_triangle<double, N>(v0, v0, v0); break;
    case Degenerate::nearly_point: c.b = make_triangle<double, N>(v0, ulps_from<N>(v0, rng), ulps_from<N>(v0, rng)); break;
  }
  return c;
}

// The relation that a triangle reference's gaps imply (tests/reference/triangle_reference.hpp:
// d the least, D the greatest scaled distance of the triangle from the body's center, 1 on its
// boundary) with the tangency band `tolerance`; nullopt within 1e-14 of a band edge, where
// the query may answer either side.
inline std::optional<Relation> expected_relation(const reference::Real& d, const reference::Real& D,
                                                 double tolerance) {
  using reference::Real;
  const Real band = Real(tolerance), margin = Real(1e-14);
  for (const Real& edge : {Real(d - 1 - band), Real(d - 1 + band), Real(D - 1 - band)})
    if (abs(edge) <= margin) return std::nullopt;
  if (d - 1 > band) return Relation::separated;
  if (d - 1 >= -band) return Relation::touching;
  if (D - 1 <= band) return Relation::a_contains_b;
  return Relation::overlapping;
}

}  // namespace ellipsect::testing
