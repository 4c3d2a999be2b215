// Broad phase: which pairs among N bodies may meet, by sweep and prune along x over
// axis-aligned bounding boxes, and which pairs overlap (candidates, then the exact test).
//
// A pair the candidates leave out is certainly separated (for swept boxes: never touches in
// the window): boxes are exact for ellipsoids and padded by 1e-9 of each body's largest
// radius plus 1e-14 of its coordinates, far more than the tangency band of classify and the
// rounding of the box. Boxes are computed in double for float bodies too.
#pragma once

#include <ellipsect/batch.hpp>
#include <ellipsect/shapes.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace ellipsect {

// Indices (i, j), i < j, into the bodies given.
using IndexPair = std::pair<std::uint32_t, std::uint32_t>;

// Pairs whose boxes meet, sorted lexicographically. At most 2^32 - 1 bodies.
template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies);

// Swept boxes: body i moves as center + t * velocities[i]; each box is the union of the
// body's boxes over [t0, t1] (t1 may be +infinity: unbounded in the direction of motion;
// t0 == t1 gives the boxes at t0). A coordinate at rest stays put (0 * inf is taken as 0).
// velocities.size() must equal bodies.size() (std::invalid_argument otherwise).
template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies,
                                       std::span<const Vec<T, N>> velocities, double t0, double t1);

// Every pair of closed bodies that share a point (overlap(bodies[i], bodies[j]) is true),
// sorted lexicographically: candidate_pairs, then the batch overlap on all cores
// (options.threads as in batch.hpp).
template <class T, int N>
std::vector<IndexPair> overlapping_pairs(std::span<const Ellipsoid<T, N>> bodies, const BatchOptions& options = {});

}  // namespace ellipsect
