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
  touching,      // boundaries meet, interiors disjoint (within the tolerance band)
  overlapping,   // interiors intersect, neither contains the other
  a_contains_b,  // b is inside a (boundaries may touch from inside)
  b_contains_a,  // a is inside b
  equal,         // same set (within the tolerance band)
};

std::string_view to_string(Relation r) noexcept;

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options = {}) noexcept;

// True when the closed bodies share a point: exactly classify(a, b) != separated, by a
// faster route (no containment test; bounding-ball early outs).
template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options = {}) noexcept;

}  // namespace ellipsect
