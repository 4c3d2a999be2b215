// Broad phase: the pairs of bodies whose axis-aligned bounding boxes meet, by sweep and
// prune along x. A pair it leaves out is certainly separated (and, for swept boxes, never
// touches in the window): boxes are exact for ellipsoids and padded by 1e-9 of each body's
// size plus rounding of its coordinates, far more than the tangency band of classify.
#pragma once

#include "scene.hpp"

#include <vector>

namespace ellipsect::cli {

// Candidate pairs (i < j), sorted lexicographically. Boxes are the bodies' boxes at time
// t0 of the window, or, with `swept`, the union of their boxes over the whole window
// (unbounded in the direction of motion when the window has no end).
template <int N>
std::vector<IndexPair> broad_phase(const std::vector<Body<N>>& bodies, const Window& window, bool swept);

}  // namespace ellipsect::cli
