// Collide and slide (Fauerby, "Improved Collision Detection and Response"; Nettle, "Generic
// Collision Detection for Games Using Ellipsoids"): move a body by a desired displacement
// through a world of half-spaces (floors, walls, ceilings: half_space.hpp), stopping at the
// first contact and sliding along what it touches for the rest of the way.
//
// Method. Each round moves the body along the remaining displacement r to the earliest
// contact with any half-space (half_space.hpp's first_contact, exact), then removes from r
// what pushes into the half-spaces the body now touches (those with r . n < 0, n their
// outward normals): one such plane, r is projected onto it; two (a crease), onto their
// common line in 3D, to nothing in 2D; three in 3D (a corner), to nothing. The body never
// moves into a touched half-space, so it slides along floors and walls and stops in
// corners.
//
// Guarantees:
//   * the body never ends overlapping a half-space: every position is checked with
//     classify (half_space.hpp) before it is taken; a move whose rounding would end inside
//     (a contact time is exact, the moved center is rounded to T) is shortened until it
//     does not, or not made;
//   * the moves add up to `moved` (the body's center is the start center plus `moved`, to
//     the rounding of each move), and the displacement is never exceeded: each round's
//     remaining displacement is the previous one's, minus the move, projected;
//   * at most Options::max_iterations rounds (default 64; `blocked` when displacement is left);
//   * a body that starts overlapping a half-space is not moved (overlapping_at_start); one
//     that starts touching slides along it or leaves it.
// Touching is classify's tangency band (options.hpp).
#pragma once

#include <ellipsect/half_space.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <span>
#include <string_view>
#include <type_traits>

namespace ellipsect {

enum class SlideStatus {
  moved,                 // the whole displacement, in contact with nothing on the way
  slid,                  // stopped at contacts or touched half-spaces and slid along them
                         // until nothing of the displacement was left
  blocked,               // Options::max_iterations rounds, displacement left
  overlapping_at_start,  // the body overlaps a half-space at the start: not moved
  invalid_input,         // a displacement that is not finite or moves the center beyond T
};

std::string_view to_string(SlideStatus s) noexcept;

template <class T, int N>
struct Slide {
  SlideStatus status = SlideStatus::invalid_input;
  Ellipsoid<T, N> body;                        // where it ends (the start body if not moved)
  Vec<T, N> moved = Vec<T, N>::Zero();         // the sum of the moves
  int contacts = 0;                            // rounds that ended at a contact
  int last_contact = -1;                       // index in `world` of the last half-space hit, or -1
};
static_assert(detail::has_plain_layout<Slide<float, 2>, SlideStatus, Ellipsoid<float, 2>, float[2], int, int> &&
              detail::has_plain_layout<Slide<double, 3>, SlideStatus, Ellipsoid<double, 3>, double[3], int, int>);

template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              std::span<const std::type_identity_t<HalfSpace<T, N>>> world,
                              const Options& options = {});

}  // namespace ellipsect
