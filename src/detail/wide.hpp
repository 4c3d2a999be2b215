// The wider type of the certified fallbacks: answers that rounding in double could flip are
// re-decided in it, and pairs beyond double's range (detail/scale.hpp) run in it. It needs
// at least 64 significand bits (the rounding models give it 11 bits over double) and a
// 15-bit exponent (it holds the squares and cubes of any double).
//   long double  where it has both (x86's 80-bit format; binary128 on aarch64 Linux);
//   emulated     elsewhere (MSVC, Apple arm64, where long double is double), or where the
//                build asks (ELLIPSECT_EMULATED_WIDE, to test that path on any machine):
//                Boost.Multiprecision's binary float with the 80-bit format's significand
//                and exponent range, in software: several times slower than long double,
//                on the paths that reach it (near-ties of the decisions, pairs beyond
//                double's range); the common paths never do.
// Its math functions are called unqualified (detail/math.hpp).
#pragma once

#include "math.hpp"

#include <cfloat>
#include <numbers>
#include <type_traits>

#ifndef ELLIPSECT_EMULATED_WIDE
#if LDBL_MANT_DIG >= 64 && LDBL_MAX_EXP >= 16384
#define ELLIPSECT_EMULATED_WIDE 0
#else
#define ELLIPSECT_EMULATED_WIDE 1
#endif
#endif

#if ELLIPSECT_EMULATED_WIDE
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/eigen.hpp>
#endif

namespace ellipsect::detail {

#if ELLIPSECT_EMULATED_WIDE
using WideFloat = boost::multiprecision::number<
    boost::multiprecision::cpp_bin_float<64, boost::multiprecision::digit_base_2, void, int, -16382, 16383>,
    boost::multiprecision::et_off>;
#else
using WideFloat = long double;
#endif

// pi in F: std's constant for the built-in types, the emulated type's own otherwise.
template <class F>
constexpr F pi() noexcept {
  if constexpr (std::is_floating_point_v<F>) {
    return std::numbers::pi_v<F>;
  } else {
    return acos(F(-1));
  }
}

}  // namespace ellipsect::detail
