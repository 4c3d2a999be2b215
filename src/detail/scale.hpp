// The range of scales every query supports, and the power-of-two rescaling that gives it
// (docs/method.md, section 7).
//
// The methods form squares and cubes of lengths (quadric matrices, the secular equation,
// the determinants of the Perram-Wertheim matrix), so in double they overflow beyond about
// 1e51 to 1e154 and underflow below the reciprocals. A query therefore measures its pair:
//   native  the largest radius r_max is within 2^+-native_exponent and the pair is
//           representable (below): the query runs on the bodies as given;
//   scaled  representable, r_max outside that window: the query runs on the bodies scaled
//           by 2^-E, E = ilogb(r_max) (so r_max lands in [1, 2)), and its lengths are scaled
//           back by 2^E. Multiplying by a power of two is exact (no result is in the
//           subnormal range of a representable pair), so the answers are exactly those of
//           the pair at unit scale, and scaling a scene by 2^k scales every length answer by
//           exactly 2^k;
//   wide    not representable in double: some radius of the pair is below about
//           2^-ratio_bits r_max, or a center or query point coordinate above about
//           2^offset_bits r_max. The query runs in the wide type (detail/wide.hpp: its 15-bit exponent holds
//           the squares of any double) on the bodies as given.
// first_contact also rescales time where the speeds leave the window (time_exponent).
// float bodies are always native: their squares and cubes fit in double, the working type.
//
// This is the one range mechanism: a query measures its inputs (scale_of, time_exponent)
// and runs through at_scale, which picks the working type and hands the query the Units
// that convert its inputs into the frame it runs in and its answers back; a query states
// only how its answers scale (lengths, areas, times). Queries whose arithmetic handles the
// scaled range itself (the half-space gaps, the polytope support, the triangle pair) go
// through in_type, which picks the type alone; the rigid advancement between bodies, which
// has no wide path, rescales through Units alone; the advancements against shapes at rest
// and the batch filter leave every pair that is not as_given to their start state and to
// the scalar functions.
// Niemitalo's division-free tests (polygonal2.cpp) are outside it: as published, they run
// in T itself, each scene brought to unit size by its own power of two.
#pragma once

#include <ellipsect/shapes.hpp>

#include "shape_access.hpp"
#include "math.hpp"
#include "wide.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace ellipsect::detail {

// Pairs whose largest radius lies in [2^-native_exponent, 2^(native_exponent + 1)) run as
// given, so answers there are those of the code without rescaling, bit for bit.
inline constexpr int native_exponent = 64;
// Representable pairs: every radius >= 2^-ratio_bits r_max (the reduced frame forms
// (r_max / r_min)^2 and the distance its cube), every center coordinate and query point
// coordinate <= 2^offset_bits r_max (offsets over the smallest radius stay below 2^500).
inline constexpr int ratio_bits = 160;
inline constexpr int offset_bits = 340;

enum class Range : std::uint8_t { native, scaled, wide };

// Eight bytes, so that it returns in one register (|F| < 2^15).
struct Scale {
  Range range = Range::native;
  std::int16_t time = 0;  // F: and on times times 2^F (first contact: time_exponent)
  int exponent = 0;       // E: the query runs on the bodies times 2^-E (Range::scaled)
  // Whether the query runs on its inputs as given, in the working type.
  bool as_given() const noexcept { return range == Range::native && time == 0; }
  // Whether the working type holds the query's squares and cubes (else the wide type).
  bool representable() const noexcept { return range != Range::wide; }
};
static_assert(sizeof(Scale) == 8);

// Largest magnitude of a vector's coordinates.
template <class D>
typename D::Scalar max_abs(const Eigen::MatrixBase<D>& v) noexcept {
  return v.cwiseAbs().maxCoeff();
}

// The range of a set of lengths given as the largest and smallest radius and the largest
// coordinate magnitude (centers, query points).
template <class T>
Scale scale_of(T r_max, T r_min, T coordinate) noexcept {
  if constexpr (!std::is_same_v<T, double>) {
    return {};
  } else {
    // Most pairs: native by comparisons alone (the products by powers of two are exact).
    if (r_max >= 0x1p-64 && r_max < 0x1p65 && r_min >= r_max * 0x1p-160 && coordinate <= r_max * 0x1p340) return {};
    const int e = ilogb(r_max);
    if (ilogb(r_min) < e - ratio_bits || (coordinate > 0 && ilogb(coordinate) > e + offset_bits))
      return {Range::wide};
    if (e >= -native_exponent && e <= native_exponent) return {};
    return {Range::scaled, 0, e};
  }
}

template <class T, int N>
Scale scale_of(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) noexcept {
  return scale_of<T>(std::max(a.radii().maxCoeff(), b.radii().maxCoeff()),
                     std::min(a.radii().minCoeff(), b.radii().minCoeff()),
                     std::max(max_abs(a.center()), max_abs(b.center())));
}

// first_contact also rescales time where the speeds, in the rescaled lengths, leave a
// window of 2^+-window: F = their exponent (velocities times 2^-(E + F), times and t_max
// times 2^F), else 0. The linear contact forms squares and products of speeds with
// lengths, so its window is the native one; the rigid advancement forms only speed times
// time and its motion bounds, so it rescales time only where the speeds approach the
// type's range (rigid_time_window).
inline constexpr int rigid_time_window = 960;

template <class T, int N>
int time_exponent(const Scale& scale, const Vec<T, N>& velocity_a, const Vec<T, N>& velocity_b,
                  int window = native_exponent) noexcept {
  if constexpr (!std::is_same_v<T, double>) {
    return 0;
  } else {
    const T speed = std::max(max_abs(velocity_a), max_abs(velocity_b));
    if (scale.range == Range::wide || !(speed > 0) || !isfinite(speed)) return 0;
    const int f = ilogb(speed) - scale.exponent;
    return f >= -window && f <= window ? 0 : f;
  }
}

// The exponent by which the compensated contact times against shapes at rest (half-space,
// triangle) scale the velocities: 0 within 2^+-500, where their differences cannot
// overflow nor the error terms of their products underflow, else that of the speed.
template <class T>
int speed_exponent(T speed) noexcept {
  return double(speed) >= 0x1p-500 && double(speed) <= 0x1p500 ? 0 : ilogb(speed);
}

// 2^-e for the binary exponent e of `size` (finite, > 0): multiplying by it is exact and
// brings `size` into [1, 2), so squares and fourth powers of lengths up to `size` stay in
// range. Read off the exponent field (libm's frexp and ldexp cost more than the tests that
// use it: a level of the polygonal tests, the spheres' pre-test of capsules).
template <class T>
T unit_scale(T size) noexcept {
  using U = std::conditional_t<sizeof(T) == sizeof(std::uint64_t), std::uint64_t, std::uint32_t>;
  static_assert(std::numeric_limits<T>::is_iec559 && sizeof(T) == sizeof(U));
  constexpr int mantissa = std::numeric_limits<T>::digits - 1;
  constexpr U bias = std::numeric_limits<T>::max_exponent - 1;
  const U field = (std::bit_cast<U>(size) >> mantissa) & (2 * bias + 1);
  if (field == 0 || field >= 2 * bias) {  // size subnormal, or 2^-e would be: the nearest finite power
    int e;
    (void)frexp(size, &e);
    return ldexp(T(1), std::min(1 - e, std::numeric_limits<T>::max_exponent - 1));
  }
  return std::bit_cast<T>(static_cast<U>((2 * bias - field) << mantissa));
}

// A vector times 2^k (exact where the result is normal).
template <class D>
Vec<typename D::Scalar, D::RowsAtCompileTime> times_pow2(const Eigen::MatrixBase<D>& v, int k) noexcept {
  Vec<typename D::Scalar, D::RowsAtCompileTime> out;
  for (int i = 0; i < D::RowsAtCompileTime; ++i) out[i] = ldexp(v[i], k);
  return out;
}

// The body scaled about the origin by 2^k: center and radii times 2^k, the same axes.
template <class T, int N>
Ellipsoid<T, N> scaled(const Ellipsoid<T, N>& e, int k) noexcept {
  return ShapeAccess::unchecked<T, N>(times_pow2(e.center(), k), e.axes(), times_pow2(e.radii(), k));
}

// Whether scaled(e, k) keeps every number (no center coordinate or radius underflows), so
// that the exact relation (Options::tolerance = 0) of the scaled pair is the given pair's.
template <class T, int N>
bool scales_exactly(const Ellipsoid<T, N>& e, int k) noexcept {
  const Ellipsoid<T, N> s = scaled(e, k);
  return times_pow2(s.center(), -k) == e.center() && times_pow2(s.radii(), -k) == e.radii();
}

// The conversions of a query run at a scale (at_scale): inputs into the frame the query
// runs in (lengths times 2^-E, velocities 2^-(E + F), times 2^F, rates per time 2^-F),
// answers back to the caller's. Rescaled = false: the inputs as given (no copies) and the
// answers untouched, so native answers are those of the query alone, bit for bit.
template <bool Rescaled>
struct Units {
  static constexpr bool rescaled = Rescaled;
  int exponent = 0;       // E
  int time_exponent = 0;  // F

  template <class T, int N>
  decltype(auto) body(const Ellipsoid<T, N>& e) const noexcept {
    if constexpr (rescaled) return scaled(e, -exponent); else return (e);
  }
  template <class X>
  decltype(auto) length(const X& x) const noexcept { return in(x, -exponent); }
  template <class X>
  decltype(auto) velocity(const X& v) const noexcept { return in(v, -exponent - time_exponent); }
  template <class X>
  decltype(auto) time(const X& t) const noexcept { return in(t, time_exponent); }
  template <class X>
  decltype(auto) rate(const X& w) const noexcept { return in(w, -time_exponent); }

  template <class... X>
  void lengths_out(X&... x) const noexcept { (out(x, exponent), ...); }
  template <class... X>
  void areas_out(X&... x) const noexcept { (out(x, 2 * exponent), ...); }
  template <class... X>
  void per_lengths_out(X&... x) const noexcept { (out(x, -exponent), ...); }
  template <class... X>
  void times_out(X&... x) const noexcept { (out(x, -time_exponent), ...); }

  // Whether rescaling lost a digit of a body (a coordinate or radius below the normal
  // range): then the exact relation (Options::tolerance = 0) of the rescaled bodies need
  // not be that of the given ones.
  template <class... Bodies>
  bool loses(const Bodies&... bodies) const noexcept {
    if constexpr (rescaled) return (!scales_exactly(bodies, -exponent) || ...); else return false;
  }

 private:
  template <class X>
  static decltype(auto) in(const X& x, int k) noexcept {
    if constexpr (!rescaled) return (x);
    else if constexpr (std::is_arithmetic_v<X>) return ldexp(x, k);
    else return times_pow2(x, k);
  }
  template <class X>
  static void out(X& x, int k) noexcept {
    if constexpr (!rescaled) return;
    else if constexpr (std::is_arithmetic_v<X>) x = ldexp(x, k);
    else x = times_pow2(x, k);
  }
};

// Runs the query at the scale: query.template operator()<W>(units, args...) with W = R and
// the inputs as given (native), W = R and rescaled Units (lengths beyond the native window,
// or time rescaled), or W the wide type and the inputs as given (wide). The query converts
// its inputs and answers through the Units it is given. A query that captures its inputs
// passes no args; one whose native path is only a few dozen instructions (overlap) passes
// them as args to a function object instead, so that nothing is built before the branch.
template <class R, class Query, class... Args>
[[gnu::always_inline]] inline auto at_scale(const Scale& scale, Query&& query, const Args&... args) {
  if (scale.as_given()) [[likely]] return query.template operator()<R>(Units<false>{}, args...);
  if (scale.range == Range::wide) return query.template operator()<WideFloat>(Units<false>{}, args...);
  return query.template operator()<R>(Units<true>{scale.exponent, scale.time}, args...);
}

// For a query that scales its inputs itself (the half-space gaps, the polytope support, the
// triangle pair: their arithmetic carries the exponent): query.template operator()<W>(E)
// with W = R, or the wide type (E = 0) beyond the representable range.
template <class R, class Query>
auto in_type(const Scale& scale, Query&& query) {
  if (scale.representable()) return query.template operator()<R>(scale.exponent);
  return query.template operator()<WideFloat>(0);
}

}  // namespace ellipsect::detail
