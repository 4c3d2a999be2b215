#include "broad_phase.hpp"

#include <ellipsect/broad_phase.hpp>

namespace ellipsect::cli {

template <int N>
std::vector<IndexPair> broad_phase(const std::vector<Body<N>>& bodies, const Window& window, bool swept) {
  std::vector<Ellipsoid<double, N>> shapes;
  std::vector<RigidMotion<double, N>> motions;
  shapes.reserve(bodies.size());
  motions.reserve(bodies.size());
  for (const auto& b : bodies) {
    shapes.push_back(b.shape);
    motions.push_back(b.motion);
  }
  return candidate_pairs<double, N>(shapes, motions, window.t0, swept ? window.t1 : window.t0);
}

template std::vector<IndexPair> broad_phase<2>(const std::vector<Body<2>>&, const Window&, bool);
template std::vector<IndexPair> broad_phase<3>(const std::vector<Body<3>>&, const Window&, bool);

}  // namespace ellipsect::cli
