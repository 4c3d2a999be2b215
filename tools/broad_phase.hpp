// The program's broad phase: the library's candidate_pairs (ellipsect/broad_phase.hpp) on a
// scene's bodies and time window.
#pragma once

#include "scene.hpp"

#include <vector>

namespace ellipsect::cli {

// Candidate pairs (i < j), sorted lexicographically: ellipsect::candidate_pairs on the
// bodies' boxes at time t0 of the window, or, with `swept`, on the union of their boxes over
// the whole window (unbounded in the direction of motion when the window has no end); a
// turning body's box is that of its bounding ball.
template <int N>
std::vector<IndexPair> broad_phase(const std::vector<Body<N>>& bodies, const Window& window, bool swept);

}  // namespace ellipsect::cli
