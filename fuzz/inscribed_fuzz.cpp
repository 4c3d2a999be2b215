// Fuzz target `inscribed`: hull_half_spaces and inscribed_ellipsoid (geometry.hpp) on up to 24
// points decoded from the input (2D or 3D, double or float; a small iteration cap from the
// input), checked against geometry.hpp:
//   - hull_half_spaces throws InputError naming "points", always for fewer than N + 1 points
//     or a non-finite coordinate; or it answers N + 1 or more half-spaces, each through an
//     input point, with every point on or inside each (50 digits, up to 64 ulps of T of the
//     points' extent: the normals' rounding);
//   - inscribed_ellipsoid of them throws InputError naming "half_spaces" or answers; where
//     the status is optimal, rounding_limited or did_not_converge with a finite gap, the body
//     as stored lies in every half-space: sqrt(n^T M^-1 n) + n . (c - p) <= 0 in 50 digits
//     (M the body's quadric from its axes as every query takes them, detail/axes.hpp);
//     volume_gap >= 0, at most the requested gap
//     where optimal; active indices in range, increasing.
#include "fuzz_support.hpp"

#include <ellipsect/geometry.hpp>
#include <ellipsect/half_space.hpp>

#include "detail/axes.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <Eigen/LU>

#include <vector>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;
using F = boost::multiprecision::cpp_bin_float_50;

// sqrt(n^T M^-1 n) + n . (c - p) for the stored body {x : (x - c)^T M (x - c) <= 1},
// M = A diag(r)^-2 A^T (A its axes as the queries take them, orthonormal only to rounding:
// M^-1 n = A^-T diag(r)^2 A^-1 n), and the half-space, in 50 digits.
template <class T, int N>
F support_excess(const Ellipsoid<T, N>& b, const HalfSpace<T, N>& h) {
  const Mat<double, N> axes = detail::work_axes<double>(b);
  Eigen::Matrix<F, N, N> a;
  Eigen::Matrix<F, N, 1> n;
  F s = 0, rho = 0;
  for (int k = 0; k < N; ++k) {
    for (int j = 0; j < N; ++j) a(j, k) = F(axes(j, k));
    n[k] = F(double(h.normal()[k]));
    s += n[k] * (F(double(b.center()[k])) - F(double(h.point()[k])));
  }
  const Eigen::Matrix<F, N, 1> y = a.partialPivLu().solve(n);  // A^-1 n
  for (int k = 0; k < N; ++k) rho += y[k] * y[k] * F(double(b.radii()[k])) * F(double(b.radii()[k]));
  return sqrt(rho) + s;
}

template <class T, int N>
void run(Bytes& in) {
  const std::size_t count = in.byte() % 25;
  const double gap = in.flag() ? 1e-9 : 1e-3;
  const int cap = 1 + in.byte() % 300;
  const std::vector<Vec<T, N>> points = read_points<T, N>(in, count);
  const bool finite = all_finite<T, N>(points);
  std::vector<HalfSpace<T, N>> faces;
  try {
    faces = hull_half_spaces<T, N>(points);
  } catch (const InputError& error) {
    FUZZ_CHECK(error.field() == "points", << "field " << error.field() << ": " << error.what());
    return;
  }
  FUZZ_CHECK(finite && count >= std::size_t(N + 1), << "a hull of " << count << " points, finite " << finite);
  FUZZ_CHECK(faces.size() >= std::size_t(N + 1), << faces.size() << " faces");
  F extent = 0;
  for (const auto& a : points)
    for (const auto& b : points)
      for (int k = 0; k < N; ++k) extent = std::max<F>(extent, abs(F(double(a[k])) - F(double(b[k]))));
  const F slack = N * 64 * F(double(std::numeric_limits<T>::epsilon())) * extent;
  for (std::size_t h = 0; h < faces.size(); ++h) {
    bool through = false;
    for (const auto& p : points) {
      F s = 0;
      for (int k = 0; k < N; ++k) s += F(double(faces[h].normal()[k])) * (F(double(p[k])) - F(double(faces[h].point()[k])));
      FUZZ_CHECK(s <= slack, << "a point outside face " << h << " by " << double(s) << " of extent " << double(extent));
      through = through || p == Vec<T, N>(faces[h].point());
    }
    FUZZ_CHECK(through, << "face " << h << " through no input point");
  }
  InscribedEllipsoid<T, N> e;
  try {
    e = inscribed_ellipsoid<T, N>(faces, {.volume_gap = gap, .max_inscribed_iterations = cap});
  } catch (const InputError& error) {
    FUZZ_CHECK(error.field() == "half_spaces", << "field " << error.field() << ": " << error.what());
    return;
  }
  FUZZ_CHECK(e.status != InscribedStatus::unbounded, << "a hull said unbounded");
  FUZZ_CHECK(e.volume_gap >= 0 && !std::isnan(e.volume_gap), << "volume_gap " << e.volume_gap);
  if (e.status == InscribedStatus::optimal) FUZZ_CHECK(e.volume_gap <= gap, << "optimal with gap " << e.volume_gap);
  if (e.status == InscribedStatus::empty || !std::isfinite(e.volume_gap)) return;
  for (std::size_t h = 0; h < faces.size(); ++h)
    FUZZ_CHECK(support_excess(e.body, faces[h]) <= 0, << "body outside face " << h << " by "
                                                       << double(support_excess(e.body, faces[h])) << " body "
                                                       << describe(e.body));
  FUZZ_CHECK(e.active.size() == e.weights.size(), << "active " << e.active.size() << " weights " << e.weights.size());
  for (std::size_t k = 0; k < e.active.size(); ++k)
    FUZZ_CHECK(e.active[k] < faces.size() && (k == 0 || e.active[k] > e.active[k - 1]), << "active " << e.active[k]);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  by_type_and_dimension(in, [&]<class T, int N>() { run<T, N>(in); });
  return 0;
}
