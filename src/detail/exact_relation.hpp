// The exact relation of two bodies as stored, for classify at Options::tolerance = 0 where
// the floating-point decision is within its rounding of a threshold (src/pair/exact_relation.cpp).
#pragma once

#include <ellipsect/classify.hpp>

namespace ellipsect::detail {

// The relation of the closed quadrics { x : (x - center)^T M (x - center) <= 1 } with
// M = axes diag(radii)^-2 axes^T formed from the stored numbers (double axes as given,
// orthonormal or not; float axes as every query takes them, their polar factor in double:
// detail/axes.hpp), decided in rational arithmetic: no rounding, no band. Costs tens of
// microseconds to milliseconds (bench/RESULTS.md); meant for the rare undecided pair.
template <class T, int N>
Relation exact_relation(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b);

}  // namespace ellipsect::detail
