// Broad phase: which pairs among N bodies may meet, by a uniform grid over axis-aligned
// bounding boxes (cell: the largest box extent; sweep and prune along x where boxes are
// unbounded or the scene is wider than 2^31 cells), about N log N for bodies of similar
// size, slower where a few bodies are much larger than the rest; which pairs overlap
// (candidates, then the exact test); and which pair of N moving bodies touches first
// (candidates, then first_contact), in open space or in a periodic box.
//
// A pair the candidates leave out is certainly separated (for swept boxes: never touches in
// the window): boxes are exact for ellipsoids (with the axes the queries compute with: float
// axes orthonormalized) and padded by 1e-9 of each body's largest radius plus 1e-14 of its
// coordinates (and a few subnormals), far more than the tangency band of classify and the
// rounding of the box. Boxes are computed in double for float bodies too, without
// underflow or overflow at any scale.
#pragma once

#include <ellipsect/batch.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/shapes.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <tuple>
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

// Boxes swept by bodies in rigid motion (contact.hpp) over [t0, t1], as above; a turning
// body's box is the box of its bounding ball (largest radius) about the moving center; a
// growing body's box is that of the body with its radii at t1 (unbounded where t1 is
// infinite). motions.size() must equal bodies.size() (std::invalid_argument otherwise);
// InputError "motions[k].growth" where a growth is negative or not finite, or a body grows
// and t0 < 0.
template <class T, int N>
std::vector<IndexPair> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies,
                                       std::span<const RigidMotion<T, N>> motions, double t0, double t1);

// ---- Periodic box ----------------------------------------------------------------------
//
// Space repeats with period size[k] along axis k: body j also stands at every image
// center_j + m * size (m an integer vector, product taken per axis). A pair meets through
// its image m when body i meets body j translated by m * size. Centers may lie anywhere
// within 2^30 sides of the box [0, size). Each body's box (over the window, for swept
// boxes) must be shorter than half the side on every axis, so that a pair meets through at
// most one image (InputError "box" otherwise). Sizes finite and > 0 (InputError "box.size").
template <int N>
struct PeriodicBox {
  std::array<double, N> size;
};

// A pair (i < j) and the image through which j meets i.
template <int N>
struct ImagePair {
  std::uint32_t i = 0, j = 0;
  std::array<std::int32_t, N> image{};
  friend bool operator==(const ImagePair&, const ImagePair&) = default;
  friend bool operator<(const ImagePair& a, const ImagePair& b) {  // lexicographic: i, j, image
    return std::tie(a.i, a.j, a.image) < std::tie(b.i, b.j, b.image);
  }
};

// Periodic versions of the above, sorted: every (pair, image) whose boxes meet, and every
// (pair, image) whose bodies share a point (the exact test on body i and body j translated
// by image * size, its center summed in double and rounded to T once; an image whose center
// lies beyond the range of T meets nothing).
template <class T, int N>
std::vector<ImagePair<N>> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies, const PeriodicBox<N>& box);
template <class T, int N>
std::vector<ImagePair<N>> candidate_pairs(std::span<const Ellipsoid<T, N>> bodies,
                                          std::span<const RigidMotion<T, N>> motions, double t0, double t1,
                                          const PeriodicBox<N>& box);
template <class T, int N>
std::vector<ImagePair<N>> overlapping_pairs(std::span<const Ellipsoid<T, N>> bodies, const PeriodicBox<N>& box,
                                            const BatchOptions& options = {});

// ---- Earliest contact among N moving bodies -----------------------------------------------

template <class T, int N>
struct PairContact {
  ImagePair<N> pair;  // the pair and, in a periodic box, the image of j it meets (else 0)
  // first_contact(bodies[i], motions[i], bodies[j] translated by image * size, motions[j],
  // ...): its point is near body i. For no_contact_in_window the pair is (0, 0).
  Contact<T, N> contact;
};

// The first contact among all pairs of `bodies` moving with `motions` in [0, t_max] (t_max
// may be +infinity), with the same statuses and guarantees as the pairwise first_contact,
// computed on the candidate pairs of the swept boxes and pruned by the earliest time found:
//   * overlapping_at_start where some pair overlaps at 0 (the first such pair in order),
//     else touching_at_start where some pair touches at 0, else
//   * hit: the earliest contact time of all pairs (ties: the first pair in order); never
//     later than the true first contact, since no pair is left out and each pair's time is
//     never late;
//   * did_not_converge: some pair's search stopped (max_motion_steps) before the earliest
//     time found; `time` is a certified lower bound on the first contact of all pairs and
//     the pair is the one that stopped;
//   * no_contact_in_window: no pair touches in [0, t_max].
// In a periodic box the window is cut into slabs short enough that each swept box stays
// under half a side (bodies must be smaller than a quarter of the side: InputError "box",
// also where a growing body reaches a quarter of the side before the contact);
// more than Options::max_slabs slabs without a contact gives did_not_converge with
// the start of the next slab as the lower bound (pair (0, 0)).
// Throws std::invalid_argument where the sizes of bodies and motions differ, InputError
// naming "motions[k].velocity", "motions[k].angular_velocity" or "motions[k].growth" where
// one is not finite (or a growth is negative);
// invalid_input status where t_max is NaN or negative.
template <class T, int N>
PairContact<T, N> earliest_contact(std::span<const Ellipsoid<T, N>> bodies, std::span<const RigidMotion<T, N>> motions,
                                   T t_max, const Options& options = {});
template <class T, int N>
PairContact<T, N> earliest_contact(std::span<const Ellipsoid<T, N>> bodies, std::span<const RigidMotion<T, N>> motions,
                                   T t_max, const PeriodicBox<N>& box, const Options& options = {});

}  // namespace ellipsect
