// Shared test helpers: case counts and scale.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <string>

namespace ellipsect::testing {

// Number of random cases for a property test: `n` scaled by ELLIPSECT_CASE_SCALE (the
// sanitizer pass runs a fraction), at least 20.
inline int cases(int n) {
  const char* s = std::getenv("ELLIPSECT_CASE_SCALE");
  const double scale = s != nullptr ? std::atof(s) : 1.0;
  return std::max(20, static_cast<int>(n * scale));
}

}  // namespace ellipsect::testing
