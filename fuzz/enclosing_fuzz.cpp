// Fuzz target `enclosing`: enclosing_ellipsoid (geometry.hpp) on up to 40 points decoded from
// the input (2D or 3D, double or float, a small iteration cap from the input), checked
// against geometry.hpp:
//   - it either throws InputError naming "points" (or "points" with a row), or answers;
//   - an answer's body holds every point: (p - c)^T A (p - c) <= 1 + 1e-30 evaluated in 50
//     digits from the stored numbers, the axes as every query takes them (detail/axes.hpp:
//     double's as stored, float's their orthonormal polar factor in double);
//   - volume_gap is a number >= 0; optimal means volume_gap <= the requested gap; the
//     support indices are in range and their weights positive;
//   - fewer than N + 1 points, or a non-finite coordinate, always throws.
#include "fuzz_support.hpp"

#include <ellipsect/geometry.hpp>

#include "detail/axes.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <vector>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;
using F = boost::multiprecision::cpp_bin_float_50;

template <class T, int N>
F form(const Ellipsoid<T, N>& b, const Vec<T, N>& p) {
  const Mat<double, N> axes = detail::work_axes<double>(b);
  F q = 0;
  for (int k = 0; k < N; ++k) {
    F y = 0;
    for (int j = 0; j < N; ++j) y += F(axes(j, k)) * (F(double(p[j])) - F(double(b.center()[j])));
    y /= F(double(b.radii()[k]));
    q += y * y;
  }
  return q;
}

template <class T, int N>
void run(Bytes& in) {
  const std::size_t count = in.byte() % 41;
  const double gap = in.flag() ? 1e-9 : 1e-3;
  const int cap = 1 + in.byte() % 200;
  const std::vector<Vec<T, N>> points = read_points<T, N>(in, count);
  const bool finite = all_finite<T, N>(points);
  EnclosingEllipsoid<T, N> e;
  try {
    e = enclosing_ellipsoid<T, N>(points, {.volume_gap = gap, .max_enclosing_iterations = cap});
  } catch (const InputError& error) {
    FUZZ_CHECK(error.field() == "points", << "field " << error.field() << ": " << error.what());
    return;
  }
  FUZZ_CHECK(finite && count >= std::size_t(N + 1), << "answered for " << count << " points, finite " << finite);
  const F margin = F(1e-30);
  for (std::size_t i = 0; i < points.size(); ++i)
    FUZZ_CHECK(form(e.body, points[i]) <= 1 + margin, << "point " << i << " outside: " << double(form(e.body, points[i]) - 1)
                                                      << " body " << describe(e.body));
  FUZZ_CHECK(e.volume_gap >= 0 && !std::isnan(e.volume_gap), << "volume_gap " << e.volume_gap);
  if (e.status == EnclosingStatus::optimal) FUZZ_CHECK(e.volume_gap <= gap, << "optimal with gap " << e.volume_gap);
  FUZZ_CHECK(e.support.size() == e.weights.size() && !e.support.empty(), << "support " << e.support.size());
  for (std::size_t k = 0; k < e.support.size(); ++k)
    FUZZ_CHECK(e.support[k] < points.size() && e.weights[k] > 0, << "support " << e.support[k] << " weight " << e.weights[k]);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  by_type_and_dimension(in, [&]<class T, int N>() { run<T, N>(in); });
  return 0;
}
