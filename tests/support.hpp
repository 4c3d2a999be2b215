// Shared test helpers: case counts and scale, InputError expectations.
#pragma once

#include <ellipsect/shapes.hpp>

#include <gtest/gtest.h>

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

// Whether the property tests run their full case counts (ELLIPSECT_CASE_SCALE unset or
// >= 1): only then are the shares of outcomes in a mix checked, which at the sanitizer pass's
// 20 cases per category depend on the order in which the compiler evaluates the random draws
// in one expression.
inline bool full_case_counts() {
  const char* s = std::getenv("ELLIPSECT_CASE_SCALE");
  return s == nullptr || std::atof(s) >= 1.0;
}

// Runs f, expects InputError whose field() is `field`, named in the message.
template <class F>
void expect_field(F&& f, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "no InputError for " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(": " + field + ": "), std::string::npos) << e.what();
  }
}

}  // namespace ellipsect::testing
