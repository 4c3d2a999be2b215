#include <ellipsect/broad_phase.hpp>

#include "detail/instantiate.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>

namespace ellipsect {

namespace {

template <int N>
struct Box {
  double lo[N], hi[N];
};

// Position of one coordinate at time t, with 0 * inf taken as 0 (a body at rest stays put).
double at_time(double c, double v, double t) { return v == 0.0 ? c : c + v * t; }

// The box of `body` moving with `velocity` over [t0, t1].
template <class T, int N>
Box<N> box_of(const Ellipsoid<T, N>& body, const Vec<T, N>& velocity, double t0, double t1) {
  const auto A = body.axes();
  const auto r = body.radii();
  const auto c = body.center();
  const double r_max = double(r.maxCoeff());
  Box<N> box;
  for (int k = 0; k < N; ++k) {
    double h2 = 0.0;
    for (int j = 0; j < N; ++j) {
      const double e = double(A(k, j)) * double(r[j]);
      h2 += e * e;
    }
    const double start = at_time(double(c[k]), double(velocity[k]), t0);
    const double end = at_time(double(c[k]), double(velocity[k]), t1);
    const double lo = std::min(start, end), hi = std::max(start, end);
    const double h = std::sqrt(h2);
    const double pad = 1e-9 * r_max + 1e-14 * (std::abs(double(c[k])) + (std::isfinite(lo) ? std::abs(lo) : 0.0) +
                                               (std::isfinite(hi) ? std::abs(hi) : 0.0));
    box.lo[k] = lo - h - pad;
    box.hi[k] = hi + h + pad;
  }
  return box;
}

// Sweep and prune along x: pairs whose boxes meet, sorted.
template <int N>
std::vector<IndexPair> sweep(const std::vector<Box<N>>& boxes) {
  std::vector<std::uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
    return boxes[p].lo[0] < boxes[q].lo[0] || (boxes[p].lo[0] == boxes[q].lo[0] && p < q);
  });
  std::vector<IndexPair> pairs;
  std::vector<std::uint32_t> active;
  for (const std::uint32_t i : order) {
    const Box<N>& bi = boxes[i];
    // Drop boxes that end before this one starts.
    std::size_t keep = 0;
    for (const std::uint32_t j : active)
      if (boxes[j].hi[0] >= bi.lo[0]) active[keep++] = j;
    active.resize(keep);
    for (const std::uint32_t j : active) {
      const Box<N>& bj = boxes[j];
      bool meet = true;
      for (int k = 1; k < N && meet; ++k) meet = bi.lo[k] <= bj.hi[k] && bj.lo[k] <= bi.hi[k];
      if (meet) pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
    active.push_back(i);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies,
                                       std::span<const Vec<T, N>> velocities, double t0, double t1) {
  if (velocities.size() != bodies.size())
    throw std::invalid_argument("ellipsect: velocities and bodies must have equal sizes");
  std::vector<Box<N>> boxes;
  boxes.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) boxes.push_back(box_of(bodies[i], velocities[i], t0, t1));
  return sweep(boxes);
}

template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies) {
  std::vector<Box<N>> boxes;
  boxes.reserve(bodies.size());
  const Vec<T, N> rest = Vec<T, N>::Zero();
  for (const auto& b : bodies) boxes.push_back(box_of(b, rest, 0.0, 0.0));
  return sweep(boxes);
}

template <class T, int N>
std::vector<IndexPair> overlapping_pairs(std::span<const Ellipsoid<T, N>> bodies, const BatchOptions& options) {
  const std::vector<IndexPair> candidates = candidate_pairs(bodies);
  Pairs<T, N> pairs;
  pairs.reserve(candidates.size());
  for (const auto& [i, j] : candidates) pairs.push_back(bodies[i], bodies[j]);
  const auto hit = std::make_unique<bool[]>(candidates.size());
  overlap(pairs, std::span<bool>(hit.get(), candidates.size()), options);
  std::vector<IndexPair> out;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (hit[k]) out.push_back(candidates[k]);
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                 \
  template std::vector<IndexPair> candidate_pairs<T, N>(std::span<const Ellipsoid<T, N>>);                          \
  template std::vector<IndexPair> candidate_pairs<T, N>(std::span<const Ellipsoid<T, N>>,                           \
                                                        std::span<const Vec<T, N>>, double, double);                \
  template std::vector<IndexPair> overlapping_pairs<T, N>(std::span<const Ellipsoid<T, N>>, const BatchOptions&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
