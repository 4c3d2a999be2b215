// Collide and slide (Fauerby, "Improved Collision Detection and Response"; Nettle, "Generic
// Collision Detection for Games Using Ellipsoids"): move a body by a desired displacement
// through a world of half-spaces (floors, walls, ceilings: half_space.hpp) or a triangle mesh
// (mesh.hpp), stopping at the first contact and sliding along what it touches for the rest of
// the way.
//
// Method. Each round moves the body along the remaining displacement r to the earliest
// contact with any obstacle (the exact first_contact of half_space.hpp or triangle.hpp), then
// removes from r what pushes into the obstacles the body now touches: each contributes the
// plane tangent to the body at the contact point, with the normal n facing the body (a
// half-space's own outward normal; for a triangle, minus the body's outward normal at the
// point of its face, edge or vertex touched), and pushes when r . n < 0. One such plane, r
// is projected onto it; two (a crease), onto their common line in 3D, to nothing in 2D;
// three in 3D (a corner), to nothing; normals within 1e-12 of each other count as one plane
// (the triangles around a vertex or along an edge touched at one point). A touch counts,
// at the start of a round or hit on the way, only where the move would take the body into
// the obstacle deeper than half the tangency band (the body shrunk about its center by half
// the band meets it on the way): otherwise it is a graze, as where a floor or wall split into
// coplanar (in 2D collinear) pieces is slid across, the next piece's edge or vertex level
// with the body's resting place within the band, whose tangent plane the band alone tilts by
// up to the square root of the band over the body's curvature there (float bodies, whose
// radii cannot be shrunk by so little, count every touch). So a split floor slides as the
// whole one; the body never moves into a touched obstacle beyond half the band, so it
// slides along floors and walls, around a mesh's edges and vertices (whose tangent plane
// turns as the body moves), and stops in corners.
// Steps are walls: a riser stops the body or turns it along itself; climbing a step is the
// caller's (a move up, one forward, one down), as in the controllers cited.
//
// Frame. The slide runs in the start body's frame (the obstacles moved by minus its center;
// double and long double worlds), as the pair queries do, so its rounding is relative to the
// body's size and not to the magnitude of the coordinates: moved together by 1e6 sizes, a
// body and its world slide the same path (tests/property/shape_translation_property_test.cpp).
// The end comes back to world coordinates rounded; where that rounded end overlaps an
// obstacle (the exact end touches it within the band), it is moved off along the normals of
// the obstacles it touches by 1, 2, 4, ... units of its coordinates' last bit (at most 64
// such steps). float worlds are slid as given (their moved vertices would round).
//
// Guarantees:
//   * the body never ends overlapping an obstacle (a half-space, or any triangle of the
//     mesh: a mesh is a surface, the body never passes through it): every position is
//     checked with classify before it is taken; a move whose rounding would end inside
//     (a contact time is exact, the moved center is rounded to T) is shortened until it
//     does not, or not made; where no step clears the rounded end (a gap narrower than the
//     coordinates' rounding), the body is left at the start, blocked;
//   * the moves add up to `moved` (the body's center is the start center plus `moved`, to
//     the rounding of each move and of the end), and the displacement is never exceeded
//     beyond that rounding: each round's remaining displacement is the previous one's,
//     minus the move, projected;
//   * at most Options::max_slide_rounds rounds (default 64; `blocked` when displacement is left);
//   * a body that starts overlapping an obstacle is not moved (overlapping_at_start); one
//     that starts touching slides along it or leaves it.
// Touching is classify's tangency band (options.hpp).
#pragma once

#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
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
  blocked,               // Options::max_slide_rounds rounds, displacement left
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
  int last_contact = -1;                       // index in `world` of the last obstacle hit, or -1
};
static_assert(detail::has_plain_layout<Slide<float, 2>, SlideStatus, Ellipsoid<float, 2>, float[2], int, int> &&
              detail::has_plain_layout<Slide<double, 3>, SlideStatus, Ellipsoid<double, 3>, double[3], int, int>);

template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              std::span<const std::type_identity_t<HalfSpace<T, N>>> world,
                              const Options& options = {});

// The same through a triangle mesh (mesh.hpp): the contacts are the triangles' (faces, edges
// and vertices), the plane slid along at each is the one tangent to the body at the contact
// point; last_contact is a triangle index.
template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              const TriangleMesh<T, N>& world, const Options& options = {});

}  // namespace ellipsect
