// Seeded boxes around a body (box.hpp), shared by the tests: random, around the body, inside
// it, thin, and near tangency at a face, an edge or a corner.
#pragma once

#include <ellipsect/box.hpp>

#include "scenarios/scenarios.hpp"

#include <cmath>
#include <cstdint>

namespace ellipsect::scenarios {

// Boxes: random, around the body, inside it, thin; near tangency at a face, an edge and a
// corner (kinds 4 to 6: the feature placed at a relative gap of 1e-11 to 1e-3, either side,
// from the body's support point along a random direction, the rest of the box beyond it);
// and the same features 0.1 to 10 sizes away (kind 7).
constexpr int box_kinds = 8;

template <int N>
Box<double, N> make_box_case(int kind, int seed, const Ellipsoid<double, N>& a) {
  using namespace detail;
  Rng rng(static_cast<std::uint64_t>(seed) * 7727 + static_cast<std::uint64_t>(kind) * 31 + 5);
  Mat<double, N> axes = rotation<N>(rng);
  using V = Vec<double, N>;
  if (kind == 1) return make_box<double, N>(a.center(), axes, V::Constant(3 * a.radii().maxCoeff()));
  if (kind == 2) return make_box<double, N>(a.center(), axes, V::Constant(0.2 * a.radii().minCoeff()));
  if (kind <= 3) {
    const V c = V::NullaryExpr([&](Eigen::Index) { return uniform(rng, -6, 6); });
    return make_box<double, N>(c, axes, kind == 3 ? radii<N>(rng, 2.0, 1e4) : radii<N>(rng, 2.0, 10));
  }
  const double size = a.radii().maxCoeff();
  const V n = unit_vector<N>(rng);
  const V w = a.radii().cwiseProduct(a.axes().transpose() * n);
  const V support = a.center() + a.axes() * a.radii().cwiseProduct(w) / w.norm();
  const double gap = kind == 7 ? log_uniform(rng, 0.1, 10) * size : (seed % 2 ? -1 : 1) * log_uniform(rng, 1e-11, 1e-3) * size;
  if (kind == 7) kind = 4 + seed % 3;
  const V q = support + gap * n;  // the feature's point nearest the body
  const V h = radii<N>(rng, 2 * size, 100);
  // Face (kind 4) and edge (kind 5, 3D): axis 0 along n, resp. axis 0 orthogonal to n (the
  // edge's direction) with n in the plane of the others; corner (kind 6 and the 2D edge): any.
  if (kind == 4) {
    axes.col(0) = n;
    axes = axes.householderQr().householderQ();
    if (axes.col(0).dot(n) < 0) axes.col(0) = -axes.col(0);
  } else if (kind == 5 && N == 3) {
    axes.col(0) -= axes.col(0).dot(n) * n;
    axes.col(1) = n;
    axes = axes.householderQr().householderQ();
  }
  if (axes.determinant() < 0) axes.col(N - 1) = -axes.col(N - 1);  // a free axis or a corner's
  // The center: q less the offset of the corner with the least n . x, and moved along the
  // free axes (a face's two, an edge's one) to a random point of the feature.
  V center = q;
  for (int i = 0; i < N; ++i) {
    const double along = axes.col(i).dot(n);
    const bool free = (kind == 4 && i > 0) || (kind == 5 && N == 3 && i == 0);
    center += (free ? uniform(rng, -0.9, 0.9) : (along < 0 ? -1.0 : 1.0)) * h[i] * axes.col(i);
  }
  return make_box<double, N>(center, axes, h);
}

template <int N>
struct BoxCase {
  Ellipsoid<double, N> a;
  Box<double, N> b;
};

// The body: near-tangent kinds at scale 1e-6, 1 or 1e6 (by seed) and aspect ratios to 1e4,
// the others at scale 1 and aspect ratios to 10; the box by make_box_case.
template <int N>
BoxCase<N> make_box_pair(int kind, int seed) {
  using namespace detail;
  Rng rng(static_cast<std::uint64_t>(seed) * 104729 + static_cast<std::uint64_t>(kind) + 1);
  const double scale = kind < 4 ? 1.0 : std::pow(1e6, seed % 3 - 1);
  const Vec<double, N> center = Vec<double, N>::NullaryExpr([&](Eigen::Index) { return scale * uniform(rng, -2, 2); });
  const auto a = Ellipsoid<double, N>::from_axes(center, rotation<N>(rng), radii<N>(rng, scale, kind < 4 ? 10 : 1e4));
  return {a, make_box_case<N>(kind, seed, a)};
}

}  // namespace ellipsect::scenarios
