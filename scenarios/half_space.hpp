// Seeded bodies against half-spaces (half_space.hpp), shared by the tests and the
// benchmarks: a body and a plane at a chosen relative offset s / rho along a random normal
// (rho the body's support radius), and a motion towards, along or away from the plane.
#pragma once

#include <ellipsect/half_space.hpp>

#include "scenarios/scenarios.hpp"

#include <array>
#include <sstream>
#include <string>

namespace ellipsect::scenarios {

enum class Plane { random, aspect, near_outside, near_inside, contained, far, far_along, small, large, grazing, still };
constexpr std::array<Plane, 11> planes = {Plane::random,    Plane::aspect, Plane::near_outside, Plane::near_inside,
                                          Plane::contained, Plane::far,    Plane::far_along,    Plane::small,
                                          Plane::large,     Plane::grazing, Plane::still};

inline const char* name(Plane p) {
  switch (p) {
    case Plane::random: return "random";
    case Plane::aspect: return "aspect_1e4";
    case Plane::near_outside: return "near_tangent";
    case Plane::near_inside: return "near_tangent_inside";
    case Plane::contained: return "contained";
    case Plane::far: return "far";
    case Plane::far_along: return "far_along_plane";
    case Plane::small: return "scale_1e-6";
    case Plane::large: return "scale_1e6";
    case Plane::grazing: return "grazing";
    case Plane::still: return "zero_closing_speed";
  }
  return "?";
}

template <int N>
struct PlaneCase {
  Plane kind;
  int seed;
  Ellipsoid<double, N> a;
  HalfSpace<double, N> b;
  Vec<double, N> va, vb;
  double t_max;
};

template <int N>
std::string describe(const PlaneCase<N>& c) {
  std::ostringstream s;
  s.precision(17);
  s << "N=" << N << " kind=" << name(c.kind) << " seed=" << c.seed << "\n  a: c=" << c.a.center().transpose()
    << " r=" << c.a.radii().transpose() << "\n  b: p=" << c.b.point().transpose() << " n=" << c.b.normal().transpose()
    << "\n  va=" << c.va.transpose() << " vb=" << c.vb.transpose() << " t_max=" << c.t_max;
  return s.str();
}

// random: offsets in [-3, 3], aspect ratios to 10; aspect: to 1e4; near_tangent(_inside):
// the relative gap of the lower (upper) side log-uniform in [1e-13, 1e-3], either sign;
// contained: offsets in [-5, -1]; far: |offset| in [1e3, 1e8]; far_along_plane: the plane's
// point 1e3 to 1e15 sizes away along the plane; scale_1e-6 / 1e6: everything scaled;
// grazing: a closing speed 1e-9 of the speed; zero_closing_speed: equal velocities.
template <int N>
PlaneCase<N> make_plane_case(Plane kind, int seed) {
  using namespace detail;
  Rng rng(static_cast<std::uint64_t>(seed) * 7919 + static_cast<std::uint64_t>(kind));
  const double aspect = kind == Plane::aspect ? 1e4 : 10;
  const Mat<double, N> axes = rotation<N>(rng);
  const Vec<double, N> r = radii<N>(rng, 1.0, aspect);
  const Vec<double, N> c = Vec<double, N>::NullaryExpr([&](Eigen::Index) { return uniform(rng, -3, 3); });
  const Vec<double, N> n = unit_vector<N>(rng);
  const double rho = (r.asDiagonal() * axes.transpose() * n).norm();
  double offset = uniform(rng, -3, 3);
  if (kind == Plane::near_outside || kind == Plane::near_inside) {
    const double gap = log_uniform(rng, 1e-13, 1e-3) * (uniform(rng, 0, 1) < 0.5 ? -1 : 1);
    offset = (kind == Plane::near_outside ? 1 : -1) * (1 + gap);
  }
  if (kind == Plane::contained) offset = -uniform(rng, 1, 5);
  if (kind == Plane::far) offset = log_uniform(rng, 1e3, 1e8) * (uniform(rng, 0, 1) < 0.5 ? -1 : 1);
  Vec<double, N> tangent = unit_vector<N>(rng);
  tangent = (tangent - tangent.dot(n) * n).normalized();
  Vec<double, N> p = c - offset * rho * n;
  if (kind == Plane::far_along) p += log_uniform(rng, 1e3, 1e15) * tangent;
  const double size = kind == Plane::small ? 1e-6 : kind == Plane::large ? 1e6 : 1;
  PlaneCase<N> out{kind, seed, Ellipsoid<double, N>::from_axes(c * size, axes, r * size),
                   make_half_space<double, N>(p * size, n), {}, {}, 0};
  const double speed = log_uniform(rng, 0.1, 10) * size;
  const double sin_angle = kind == Plane::grazing ? 1e-9 : uniform(rng, -0.3, 1);
  out.vb = unit_vector<N>(rng) * speed * uniform(rng, 0, 0.5);
  out.va = out.vb + speed * (-sin_angle * n + std::sqrt(1 - sin_angle * sin_angle) * tangent);
  if (kind == Plane::still) out.va = out.vb;
  out.t_max = uniform(rng, 0, 1) < 0.3 ? std::numeric_limits<double>::infinity()
                                        : log_uniform(rng, 0.1, 10) * (std::abs(offset) + 1) * rho * size / speed;
  return out;
}

}  // namespace ellipsect::scenarios
