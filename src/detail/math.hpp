// The math functions for every arithmetic type the library computes in: called unqualified
// under these using-declarations, so that the emulated wide type's own overloads
// (detail/wide.hpp) are found by argument-dependent lookup, and std's for the built-in types.
#pragma once

#include <cmath>
#include <cstdlib>

namespace ellipsect {

using std::abs;
using std::acos;
using std::asin;
using std::atan2;
using std::cbrt;
using std::copysign;
using std::cos;
using std::floor;
using std::fma;
using std::frexp;
using std::hypot;
using std::ilogb;
using std::isfinite;
using std::isnan;
using std::ldexp;
using std::nextafter;
using std::pow;
using std::round;
using std::signbit;
using std::sin;
using std::sqrt;

}  // namespace ellipsect
