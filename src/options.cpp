#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <charconv>
#include <string>

namespace ellipsect::detail {

namespace {

// The shortest decimal that reads back as x ("1e-14", "nan", "-inf").
std::string shortest(double x) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, x).ptr);
}

}  // namespace

void reject_option(const char* field, double value, double low, double high) {
  throw InputError(field, "must be in [" + shortest(low) + ", " + shortest(high) + "] (got " + shortest(value) + ")");
}

void reject_option(const char* field, const char* digits, int low, int high) {
  throw InputError(field, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "] (got " + digits + ")");
}

}  // namespace ellipsect::detail
