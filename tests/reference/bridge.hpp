// Conversions between the library's types and the reference's (the reference itself never
// includes the library; this header is where the two meet, for tests and benchmarks).
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/shapes.hpp>

#include "tests/reference/reference.hpp"

namespace ellipsect::reference {

template <int N>
Body<N> to_ref(const Ellipsoid<double, N>& e) {
  return {e.center(), e.axes(), e.radii()};
}

inline ellipsect::Relation from_ref(Relation r) {
  switch (r) {
    case Relation::separated: return ellipsect::Relation::separated;
    case Relation::touching: return ellipsect::Relation::touching;
    case Relation::overlapping: return ellipsect::Relation::overlapping;
    case Relation::a_contains_b: return ellipsect::Relation::a_contains_b;
    case Relation::b_contains_a: return ellipsect::Relation::b_contains_a;
    case Relation::equal: return ellipsect::Relation::equal;
  }
  return ellipsect::Relation::overlapping;
}

}  // namespace ellipsect::reference
