// Tolerances and iteration caps: the one place they are defined.
//
// Tolerance model. Every query reduces the pair to the frame in which one body (the
// "sphere body", chosen by a rule that does not depend on argument order) is the unit
// ball. Gaps measured there are dimensionless: a gap g means the sphere body would have to
// be scaled by (1 + g) about its center to just touch the other body. Scaling a whole
// scene, or moving it rigidly, leaves these numbers unchanged, so the answers do not
// depend on units. `tolerance` is that relative gap below which two bodies count as
// touching (and containment within which counts as tangent from inside).
//
// Range. The model holds at every scale: a pair whose largest radius lies outside 2^+-64 is
// rescaled by a power of two (exact) before the query, so scaling a scene by 2^k changes no
// answer beyond multiplying lengths by exactly 2^k. Within one pair, radii within a ratio
// of 2^160 and coordinates within 2^340 times the largest radius are computed in double;
// pairs beyond that in long double (docs/method.md, section 7).
//
// Validation. Options are input: each field is a value type that checks its value when it
// is constructed or assigned and throws InputError naming the field ("tolerance",
// "max_contact_iterations", ...) with the value and the accepted range. So an
// Options cannot hold an invalid value, and the queries, which read the fields through
// their implicit conversions to double and int, need no check. Designated initializers
// (Options{.tolerance = 1e-9, .max_motion_steps = 100}) and assignments (o.tolerance = 1e-9)
// work as for plain members.
#pragma once

#include <charconv>
#include <concepts>
#include <cstdint>
#include <limits>
#include <utility>

namespace ellipsect {

namespace detail {
// Throw InputError("tolerance", "must be 0 or in [low, high] (got value)"), and
// InputError(field, "must be in [low, high] (got value)") for an integer given by its
// decimal digits (src/options.cpp).
[[noreturn]] void reject_tolerance(double value, double low, double high);
[[noreturn]] void reject_option(const char* field, const char* digits, std::uintmax_t low, std::uintmax_t high);
inline constexpr char max_contact_iterations_field[] = "max_contact_iterations";
inline constexpr char max_distance_iterations_field[] = "max_distance_iterations";
inline constexpr char max_contact_function_iterations_field[] = "max_contact_function_iterations";
inline constexpr char max_slide_rounds_field[] = "max_slide_rounds";
inline constexpr char max_motion_steps_field[] = "max_motion_steps";
inline constexpr char max_slabs_field[] = "max_slabs";
}  // namespace detail

// Options::tolerance: a relative gap in [min, max]; NaN, infinities, 0, negative values and
// values outside the range throw InputError("tolerance"). Why these ends:
//   min = 1e-14 (45 ulps): near its edges the band is decided in long double (or compensated
//        arithmetic), whose rounding, 32 ulps (3.5e-18) of the reduced frame's lengths,
//        stays below it while those lengths are within about 3000 of the sphere body's size;
//        a narrower band would be decided by rounding, differently by each query.
//   max = 1e-9: the early outs prove answers beyond a fixed relative margin of 1e-9 (the
//        inscribed balls of classify's certificates, the broad phase's boxes padded by 1e-9
//        of each radius); in a wider band they contradict the exact path (1e-6: unit balls
//        2 - 1e-8 apart are overlapping for classify, touching_at_start for first_contact).
//   exact = 0: no band. classify and overlap answer the relation of the bodies as stored,
//        settling the pairs within the narrowest band (min) and within rounding of it in
//        rational arithmetic (classify.hpp); first_contact (linear motion) and
//        signed_distance take their statuses at the start from that relation (contact.hpp,
//        distance.hpp). The other queries use the narrowest band, min.
class Tolerance {
public:
  static constexpr double exact = 0;
  static constexpr double min = 1e-14;
  static constexpr double max = 1e-9;

  constexpr Tolerance(double value) : value_(value) {
    if (!(value == exact || (value >= min && value <= max))) detail::reject_tolerance(value, min, max);
  }
  // The band the computations use: `min` for exact, whose queries then settle the pairs
  // inside it exactly.
  constexpr operator double() const noexcept { return value_ == exact ? min : value_; }
  // The value as given (0 for exact).
  constexpr double value() const noexcept { return value_; }
  constexpr bool is_exact() const noexcept { return value_ == exact; }

private:
  double value_;
};

// An iteration cap: an integer in [1, Max], stored in Max's type, given in any integer type
// (out of range, the value as given is rejected: InputError(Field)). The maximum bounds a
// query's time; every loop so capped converges well inside the default caps on the tested
// pairs.
template <const char* Field, auto Max>
  requires std::integral<decltype(Max)>
class IterationCap {
public:
  using value_type = decltype(Max);
  static constexpr const char* field = Field;
  static constexpr value_type min = 1;
  static constexpr value_type max = Max;

  template <std::integral I>
  constexpr IterationCap(I value) : value_(static_cast<value_type>(value)) {
    if (!(std::cmp_greater_equal(value, min) && std::cmp_less_equal(value, max))) reject(value);
  }
  constexpr operator value_type() const noexcept { return value_; }

private:
  template <class I>
  [[noreturn]] static void reject(I value) {
    char digits[24] = {};  // 20 digits and a sign at most
    std::to_chars(digits, digits + sizeof digits - 1, value);
    detail::reject_option(Field, digits, min, max);
  }
  value_type value_;
};

// The interval a real option must lie in: finite, between low and high, each end open or
// closed (high may be infinite: then only finiteness bounds it).
struct RealRange {
  const char* field;
  double low, high;
  bool low_closed, high_closed;

  constexpr bool contains(double v) const noexcept {
    const bool finite = v == v && v != std::numeric_limits<double>::infinity() &&
                        v != -std::numeric_limits<double>::infinity();
    return finite && (low_closed ? v >= low : v > low) && (high_closed ? v <= high : v < high);
  }
};

namespace detail {
// Throw InputError(range.field, "must be finite and in (low, high) (got value)") with the
// range's brackets (src/options.cpp).
[[noreturn]] void reject_real(double value, const RealRange& range);
}  // namespace detail

// A real option validated as the caps are: constructed or assigned outside Range, it throws
// InputError(Range.field) with the value and the interval; it reads as a double.
template <const RealRange& Range>
class RealOption {
public:
  static constexpr const RealRange& range = Range;

  constexpr RealOption(double value) : value_(value) {
    if (!Range.contains(value)) detail::reject_real(value, Range);
  }
  constexpr operator double() const noexcept { return value_; }

private:
  double value_;
};

// One cap per algorithm, named by what it caps; each loop so capped is bounded by it alone.
// Reaching a cap is a status, never an answer: did_not_converge for the solvers (with what
// the status's documentation says of the values), blocked for the slide's rounds. The caps
// outside Options are reported as statuses too: PackingStatus::collision_limit
// (PackingOptions::max_collisions, packing.hpp) and Verdict::undecided (the Niemitalo
// tests' max_level, polygonal2.hpp). Every status named here is tested at a small cap in its
// family's unit tests.
struct Options {
  // Relative tangency band (see above), in [Tolerance::min, Tolerance::max] = [1e-14, 1e-9],
  // or Tolerance::exact = 0. Pairs whose gap lies within the band are reported as touching;
  // outside it, answers are exact up to the accuracy stated per query.
  Tolerance tolerance = 1e-12;
  // Newton's iterations on the contact time's convex h(t) (Eberly): first_contact under
  // linear motion of two bodies (contact.hpp) and of a body and a capsule (capsule.hpp), in
  // [1, 100000]. Reached: ContactStatus::did_not_converge, the time the last iterate.
  IterationCap<detail::max_contact_iterations_field, 100000> max_contact_iterations = 64;
  // The evaluations of each descent on the sphere of directions of distance and
  // signed_distance of two bodies (distance.hpp), in [1, 100000]. Reached:
  // DistanceStatus::did_not_converge.
  IterationCap<detail::max_distance_iterations_field, 100000> max_distance_iterations = 64;
  // The iterations of the Perram-Wertheim maximization: perram_wertheim, closest_approach
  // and their gradients (contact_function.hpp), in [1, 100000]. Reached:
  // ContactFunctionStatus::did_not_converge, with certified bounds.
  IterationCap<detail::max_contact_function_iterations_field, 100000> max_contact_function_iterations = 64;
  // The rounds of collide_and_slide, one contact and one slide each (slide.hpp), in
  // [1, 100000]. Reached with displacement left: SlideStatus::blocked.
  IterationCap<detail::max_slide_rounds_field, 100000> max_slide_rounds = 64;
  // The advancement steps of first_contact under rigid motion, each one signed distance:
  // two bodies (contact.hpp), a body and an obstacle, and each pair of earliest_contact's
  // search (broad_phase.hpp), in [1, 1000000]. Reached: ContactStatus::did_not_converge, with
  // a certified lower bound on the contact time.
  IterationCap<detail::max_motion_steps_field, 1000000> max_motion_steps = 10000;
  // The slabs of earliest_contact's search in a periodic box (broad_phase.hpp), each a time
  // window of the swept candidates, in [1, 1000000]. Reached: PairContact's status
  // did_not_converge, its time a lower bound.
  IterationCap<detail::max_slabs_field, 1000000> max_slabs = 10000;
};

}  // namespace ellipsect
