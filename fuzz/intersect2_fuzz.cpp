// Fuzz target `intersect2`: intersect_boundaries and overlap_area on two ellipses (double or
// float) decoded from the input, checked against intersect2.hpp:
//   - status equal exactly when classify says equal (then count 0); count in [0, 4]; the
//     listed points finite; separated: no point; touching: exactly one, tangent;
//     containment: no transverse crossing;
//   - swapping a and b gives the same points (as a set) and kinds, and the same area, bit
//     for bit;
//   - area finite, 0 when separated or touching, the smaller ellipse's area (pi r0 r1) under
//     containment, otherwise in [0, the smaller area]; relation is classify(a, b).
#include "fuzz_support.hpp"

#include <ellipsect/classify.hpp>
#include <ellipsect/intersect2.hpp>

#include <algorithm>
#include <numbers>
#include <tuple>
#include <vector>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

// The listed points and kinds, sorted by their bits (order-free comparison).
template <class T>
std::vector<std::tuple<std::uint64_t, std::uint64_t, int>> point_set(const BoundaryIntersection<T>& r) {
  std::vector<std::tuple<std::uint64_t, std::uint64_t, int>> s;
  for (int i = 0; i < r.count; ++i) {
    std::uint64_t x = 0, y = 0;
    const double px = r.points[i][0], py = r.points[i][1];
    std::memcpy(&x, &px, sizeof x);
    std::memcpy(&y, &py, sizeof y);
    s.emplace_back(x, y, static_cast<int>(r.kinds[i]));
  }
  std::sort(s.begin(), s.end());
  return s;
}

template <class T>
void run(Bytes& in) {
  const auto a = read_body<T, 2>(in);
  if (!a) return;
  const auto b = read_partner<T, 2>(in, *a);
  if (!b) return;
  trace() += "a " + describe(*a) + " b " + describe(*b);
  const Relation rel = classify(*a, *b);
  const auto r = intersect_boundaries(*a, *b);
  const auto s = intersect_boundaries(*b, *a);
  FUZZ_CHECK(r.count >= 0 && r.count <= 4, << "count " << r.count);
  FUZZ_CHECK((r.status == BoundaryStatus::equal) == (rel == Relation::equal),
             << to_string(r.status) << " vs classify " << to_string(rel));
  if (r.status == BoundaryStatus::equal) FUZZ_CHECK(r.count == 0, << "equal with count " << r.count);
  int transverse = 0;
  for (int i = 0; i < r.count; ++i) {
    FUZZ_CHECK(all_finite(r.points[i]), << "point " << i << " " << hex(r.points[i]));
    transverse += r.kinds[i] == CrossingKind::transverse;
  }
  if (rel == Relation::separated) FUZZ_CHECK(r.count == 0, << "separated with " << r.count << " points");
  if (rel == Relation::touching)
    FUZZ_CHECK(r.count == 1 && r.kinds[0] == CrossingKind::tangent,
               << "touching: " << r.count << " points, " << transverse << " transverse");
  if (rel == Relation::a_contains_b || rel == Relation::b_contains_a)
    FUZZ_CHECK(transverse == 0, << to_string(rel) << " with " << transverse << " transverse crossings");
  FUZZ_CHECK(s.status == r.status && point_set(s) == point_set(r),
             << "swap: " << r.count << " vs " << s.count << " points (" << to_string(r.status) << ")");

  const auto area = overlap_area(*a, *b);
  const auto area_swapped = overlap_area(*b, *a);
  FUZZ_CHECK(area.relation == rel, << to_string(area.relation) << " vs classify " << to_string(rel));
  FUZZ_CHECK(same_bits(area.area, area_swapped.area),
             << "swap: area " << hex(area.area) << " vs " << hex(area_swapped.area));
  const double area_a = std::numbers::pi * double(a->radii()[0]) * double(a->radii()[1]);
  const double area_b = std::numbers::pi * double(b->radii()[0]) * double(b->radii()[1]);
  // Rounded to T: a float area below float's range is 0, one beyond it +inf.
  const double smaller = static_cast<T>(std::min(area_a, area_b));
  // +inf only where the smaller ellipse's area itself exceeds the largest T (overlap_area).
  FUZZ_CHECK(area.area >= 0 && (std::isfinite(area.area) || !std::isfinite(smaller)), << "area " << area.area);
  constexpr double rel_tol = sizeof(T) >= sizeof(double) ? 1e-12 : 1e-5;
  if (rel == Relation::separated || rel == Relation::touching) FUZZ_CHECK(area.area == 0, << "area " << area.area);
  if (std::isfinite(smaller)) {
    if (rel == Relation::a_contains_b || rel == Relation::b_contains_a) {
      FUZZ_CHECK(std::abs(area.area - smaller) <= rel_tol * smaller,
                 << "containment: area " << area.area << ", smaller ellipse " << smaller);
    } else {
      FUZZ_CHECK(area.area <= smaller * (1 + rel_tol), << "area " << area.area << " > smaller ellipse " << smaller);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const bool is_float = in.byte() & 1;
  trace() = is_float ? "float: " : "double: ";
  if (is_float) {
    run<float>(in);
  } else {
    run<double>(in);
  }
  return 0;
}
