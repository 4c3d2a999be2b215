// Shared by the gradient tests: a body's parameters in gradient.hpp's order, moved in Real,
// and the comparison of derivatives with central differences relative to their units.
#pragma once

#include <ellipsect/gradient.hpp>

#include "tests/property/common.hpp"
#include "tests/reference/reference.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace ellipsect::testing::gradient {

using ref::Real;
template <int N>
using RBody = ref::detail::RBody<N>;
template <int N>
using RVec = ref::RVec<N>;

// A body's parameters in gradient.hpp's order: center (N), orientation (1 in 2D, 3 in 3D),
// radii (N); kind 0, 1, 2.
template <int N>
constexpr int turns = N == 2 ? 1 : 3;
template <int N>
constexpr int params = 2 * N + turns<N>;
template <int N>
int kind_of(int k) {
  return k < N ? 0 : k < N + turns<N> ? 1 : 2;
}

// exp(h [e_j]x): the turn by h about world axis j (2D: counterclockwise, j = 0).
template <int N>
ref::RMat<N> world_turn(int j, const Real& h) {
  const Real c = cos(h), s = sin(h);
  ref::RMat<N> q = ref::RMat<N>::Identity();
  if constexpr (N == 2) {
    q << c, -s, s, c;
  } else {
    const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;  // e_j1 -> e_j2
    q(j1, j1) = c;
    q(j2, j2) = c;
    q(j1, j2) = -s;
    q(j2, j1) = s;
  }
  return q;
}

template <int N>
RBody<N> moved(RBody<N> b, int k, const Real& h) {
  if (kind_of<N>(k) == 0) {
    b.c(k) += h;
  } else if (kind_of<N>(k) == 2) {
    b.radii(k - N - turns<N>) += h;
  } else {
    b.axes = world_turn<N>(k - N, h) * b.axes;
  }
  ref::detail::complete_rbody<N>(b);
  return b;
}

// Component j of a rotation vector (2D: the angle).
template <int N>
double angular_component(const RotationVector<double, N>& w, int j) {
  if constexpr (N == 2) {
    return w;
  } else {
    return w[j];
  }
}

template <int N>
double component(const BodyGradient<double, N>& g, int k) {
  if (kind_of<N>(k) == 0) return g.center[k];
  if (kind_of<N>(k) == 2) return g.radii[k - N - turns<N>];
  return angular_component<N>(g.orientation, k - N);
}

// The derivatives to compare: the library's and the central differences, by kind (center,
// orientation, radii, velocity, angular velocity), over both bodies.
struct Comparison {
  std::array<std::vector<std::pair<double, Real>>, 5> kinds;
  Real scale = 1;  // the pair's length scale: an orientation's derivative is a length times a center's
  Real per_length_floor = 0;  // the least unit of the derivatives by lengths
  Real per_speed_floor = 0;   // the least unit of the derivatives by velocities (kind 3)

  void add(int kind, double library, const Real& reference) { kinds[kind].push_back({library, reference}); }
  Real largest(int kind) const {
    Real m = 0;
    for (const auto& [l, r] : kinds[kind]) m = std::max(m, Real(abs(r)));
    return m;
  }
  // The largest error of a component relative to the largest reference component of its
  // unit: centers and radii together (per length), orientations as that times the scale,
  // velocities, and angular velocities as the velocities' times the scale (a kind that is 0
  // by symmetry, a disk's turn, is measured in the units of the others).
  double worst() const {
    const Real per_length = std::max({largest(0), largest(2), per_length_floor}), per_speed = std::max(largest(3), per_speed_floor);
    const std::array<Real, 5> unit = {per_length, std::max(largest(1), per_length * scale), per_length, per_speed,
                                      std::max(largest(4), per_speed * scale)};
    double worst = 0;
    for (int k = 0; k < 5; ++k) {
      if (unit[k] == 0) continue;
      for (const auto& [l, r] : kinds[k]) worst = std::max(worst, ref::to_double(Real(abs(Real(l) - r) / unit[k])));
    }
    return worst;
  }
  std::string show() const {
    std::string s;
    for (int k = 0; k < 5; ++k)
      for (const auto& [l, r] : kinds[k])
        s += "  kind " + std::to_string(k) + ": " + Real(l).str(17) + " vs " + r.str(20) + "\n";
    return s;
  }
};

}  // namespace ellipsect::testing::gradient
