// Batch pairs from the seeded scenarios (batch_test.cpp, gpu_test.cpp).
#pragma once

#include <ellipsect/batch.hpp>

#include "scenarios/scenarios.hpp"

#include <cstdint>
#include <vector>

namespace ellipsect::testing {

template <class T, int N>
Ellipsoid<T, N> as(const Ellipsoid<double, N>& e) {
  return Ellipsoid<T, N>::from_axes(e.center().template cast<T>(), e.axes().template cast<T>(),
                                    e.radii().template cast<T>());
}

// Every category, `per_category` seeds each (from `first_seed`), with their motions.
template <class T, int N>
Pairs<T, N> scenario_pairs(int per_category, std::uint64_t first_seed = 7000) {
  Pairs<T, N> pairs;
  for (const auto category : scenarios::all_categories)
    for (int i = 0; i < per_category; ++i) {
      const auto c = scenarios::make_case<N>(category, first_seed + std::uint64_t(i));
      pairs.push_back(as<T>(c.a), c.va.template cast<T>(), as<T>(c.b), c.vb.template cast<T>(), T(c.t_max));
    }
  return pairs;
}

// The columns of `pairs`, as batch_kernels.hpp's certify_pairs reads them.
template <class T, int N>
std::vector<const T*> columns_of(const Pairs<T, N>& pairs) {
  std::vector<const T*> columns;
  for (int k = 0; k < Pairs<T, N>::columns; ++k) columns.push_back(pairs.column(k));
  return columns;
}

}  // namespace ellipsect::testing
