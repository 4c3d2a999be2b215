// ellipsect as MuJoCo's ellipsoid narrow phase (docs/engines.md).
//
// MuJoCo finds contacts through a public table of collision functions,
// mjCOLLISIONFUNC[type1][type2] (mujoco.h), called by mj_collision for every geom pair that
// passes its filters, with the geoms ordered by type (type1 <= type2). install() puts
// collide() there for the ellipsoid against ellipsoid, sphere, plane, capsule and box, in both
// orders; everything else — the broad phase, the filters, margins and gaps, the solver,
// sensors, mj_contactForce — stays MuJoCo's and works unchanged. MuJoCo's own functions for
// these pairs (libccd's MPR on the ellipsoid's support; the plane's is exact) are put back by
// uninstall(). Meshes, cylinders and height fields keep MuJoCo's functions: MuJoCo collides a
// mesh as the solid convex hull of its vertices, which ellipsect has no query for.
//
// The table is global: install() affects every model and thread of the process. Call it
// before simulating, not while another thread is inside mj_collision. Built and tested with
// MuJoCo 2.2.2 (Debian 12's libmujoco-dev); the module compiles against the headers it finds,
// so a later MuJoCo needs a build against its own headers.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>

namespace ellipsect::mujoco {

// Puts collide() into mjCOLLISIONFUNC for the pairs above, remembering the entries it
// replaces; a second call changes nothing.
void install() noexcept;

// Puts back the entries install() replaced; nothing where install() was not called.
void uninstall() noexcept;

// Whether collide() is in the table (install() called last).
bool installed() noexcept;

// An mjfCollision for two geoms of which one at least is an ellipsoid and the other an
// ellipsoid, sphere, plane, capsule or box (either order). Fills con[0] as MuJoCo's own
// functions do and returns 1 when the signed distance d of the two geoms is at most margin,
// else returns 0:
//   con->dist     d: the separation, or minus the penetration depth (the minimum
//                 translation that separates them; containment included), as
//                 signed_distance (distance.hpp, and box.hpp, capsule.hpp, half_space.hpp)
//                 answers it, with its accuracy: within a few ulps of the bodies' size.
//   con->pos      the midpoint of the two witness points, one on each surface;
//   con->frame    the unit normal from geom g1 to geom g2 in [0..2] (from the plane into the
//                 other geom for a plane), [3..8] zero: mj_collision completes the frame.
// One contact for every pair: the bodies are smooth and strictly convex, so their contact
// is a point (docs/engines.md: the measured resting ellipsoid on a box face).
// A geom whose size ellipsect refuses (radii not finite and positive, an aspect ratio beyond
// Ellipsoid::max_aspect_ratio) calls mju_error with a message naming the geom and the field.
// A descent that exhausts its iteration cap (not seen on the tested pairs) still gives a
// certified lower bound on d (distance.hpp's did_not_converge), so its contact is never
// missed; it is counted in counters().not_converged.
int collide(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2, mjtNum margin);

// Calls of collide(), contacts it returned, and answers whose descent did not converge,
// summed over every thread since the last reset_counters().
struct Counters {
  std::uint64_t calls = 0;
  std::uint64_t contacts = 0;
  std::uint64_t not_converged = 0;
};
Counters counters() noexcept;
void reset_counters() noexcept;

}  // namespace ellipsect::mujoco
