// Classification and overlap of two static bodies.
//
// Accuracy (tested against a 50-digit reference, tests/property/classify_property_test.cpp): the
// relation is exact for every pair whose Perram-Wertheim contact scale factor mu (both
// bodies scaled by mu about their centers just touch) and whose containment scale factors
// differ from 1 by more than 2 * Options::tolerance (default 1e-12); a pair reported
// `touching` has |mu - 1| <= 2 * tolerance. Swapping the arguments gives the mirrored
// answer bit for bit (a_contains_b <-> b_contains_a), at any ratio of sizes. A body and a
// bit-identical copy are `equal` (float and double, any aspect ratio). Scaling both bodies
// by 2^k changes nothing, at any scale the factories accept (docs/method.md, section 7).
//
// Exact relations (Options::tolerance = Tolerance::exact = 0): the relation of the bodies
// as stored, with no band: the closed sets { x : (x - center)^T M (x - center) <= 1 },
// M = axes diag(radii)^-2 axes^T formed exactly from the stored numbers (double axes as
// given; float axes, orthonormal only to 6e-8, as every query takes them: their orthonormal
// polar factor computed in double), float and double, 2D and 3D, every finite scale.
// `touching`: the boundaries meet and the interiors do not; containment includes internal
// tangency; `equal`: the same set (also stored differently: axes permuted or flipped with
// their radii). The floating-point decision answers where every comparison lies beyond its
// rounding plus 1e-14 of the pair's reduced lengths from its threshold; the rest
// (near-tangent pairs only: none of the random benchmark pairs) is decided in rational
// arithmetic from the Perram-Wertheim polynomial and the containment dual (docs/method.md,
// section 10), at about 0.2 ms a pair (bench/RESULTS.md). Tested: exactly tangent pairs
// and their one-ulp moves, scales 2^-500..2^500, far from the origin
// (tests/regression/exact_classify_test.cpp), and random and steered pairs to 1e-20 of
// tangency against a 50-digit referee (tests/property/classify_property_test.cpp).
// overlap(a, b, exact) == (classify(a, b, exact) != separated).
#pragma once

#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <cstdint>
#include <string_view>

namespace ellipsect {

// One byte: batch answers are arrays of it (1 MB per million pairs, and Python's int8 arrays
// hold them as written).
enum class Relation : std::int8_t {
  separated,     // no common point
  touching,      // boundaries meet, interiors disjoint (within the tolerance band, or exactly)
  overlapping,   // interiors intersect, neither contains the other
  a_contains_b,  // b is inside a (boundaries may touch from inside)
  b_contains_a,  // a is inside b
  equal,         // same set (within the tolerance band, or exactly)
};

std::string_view to_string(Relation r) noexcept;

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options = {}) noexcept;

// True when the closed bodies share a point: exactly classify(a, b) != separated, by a
// faster route (no containment test; bounding-ball early outs).
template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options = {}) noexcept;

}  // namespace ellipsect
