#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace ellipsect::detail {

namespace {

// The shortest decimal that reads back as x ("1e-14", "0.001", "nan", "-inf"). (printf, not
// std::to_chars: the wasm build's standard library has no floating-point to_chars.)
std::string shortest(double x) {
  char buffer[32];
  for (int digits = 1;; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (digits == 17 || std::strtod(buffer, nullptr) == x) return buffer;
  }
}

}  // namespace

void reject_tolerance(double value, double low, double high) {
  throw InputError("tolerance", "must be 0 or in [" + shortest(low) + ", " + shortest(high) + "] (got " + shortest(value) + ")");
}

void reject_option(const char* field, const char* digits, std::uintmax_t low, std::uintmax_t high) {
  throw InputError(field, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "] (got " + digits + ")");
}

void reject_real(double value, const RealRange& range) {
  throw InputError(range.field, "must be finite and in " + std::string(range.low_closed ? "[" : "(") +
                                    shortest(range.low) + ", " + shortest(range.high) +
                                    (range.high_closed ? "]" : ")") + " (got " + shortest(value) + ")");
}

}  // namespace ellipsect::detail
