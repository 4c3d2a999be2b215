#include "broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ellipsect::cli {

namespace {

template <int N>
struct Box {
  double lo[N], hi[N];
};

// Position of one coordinate at time t, with 0 * inf taken as 0 (a body at rest stays put).
double at_time(double c, double v, double t) { return v == 0.0 ? c : c + v * t; }

template <int N>
Box<N> box_of(const Body<N>& b, const Window& w, bool swept) {
  const auto& A = b.shape.axes();
  const auto& r = b.shape.radii();
  const auto& c = b.shape.center();
  Box<N> box;
  for (int k = 0; k < N; ++k) {
    double h2 = 0.0;
    for (int j = 0; j < N; ++j) h2 += (A(k, j) * r[j]) * (A(k, j) * r[j]);
    double lo = at_time(c[k], b.velocity[k], w.t0), hi = lo;
    if (swept) {
      const double end = at_time(c[k], b.velocity[k], w.t1);
      lo = std::min(lo, end);
      hi = std::max(hi, end);
    }
    const double h = std::sqrt(h2);
    const double pad = 1e-9 * r.maxCoeff() + 1e-14 * (std::abs(c[k]) + (std::isfinite(lo) ? std::abs(lo) : 0.0) +
                                                      (std::isfinite(hi) ? std::abs(hi) : 0.0));
    box.lo[k] = lo - h - pad;
    box.hi[k] = hi + h + pad;
  }
  return box;
}

}  // namespace

template <int N>
std::vector<IndexPair> broad_phase(const std::vector<Body<N>>& bodies, const Window& window, bool swept) {
  const std::size_t n = bodies.size();
  std::vector<Box<N>> boxes;
  boxes.reserve(n);
  for (const auto& b : bodies) boxes.push_back(box_of<N>(b, window, swept));
  std::vector<std::uint32_t> order(n);
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

template std::vector<IndexPair> broad_phase<2>(const std::vector<Body<2>>&, const Window&, bool);
template std::vector<IndexPair> broad_phase<3>(const std::vector<Body<3>>&, const Window&, bool);

}  // namespace ellipsect::cli
