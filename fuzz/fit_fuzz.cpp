// Fuzz target `fit`: fit_ellipsoid (geometry.hpp) on up to 40 points decoded from the input
// (2D or 3D, double or float; an iteration cap of 1 to 60 and the tolerance 1e-8 or 1e-12
// from the input), checked against geometry.hpp:
//   - it throws InputError naming "points", always for fewer than 5 (2D) or 9 (3D) points or a
//     non-finite coordinate; or it answers a body of finite center, positive finite radii;
//   - rms_residual and max_residual are finite, rms <= max (to rounding), and the descent
//     guarantee holds: rms_residual <= algebraic_rms_residual + 1e-14 (float: 1e-6) of the
//     largest of the points' coordinates and the two bodies' radii, whatever the status;
//   - iterations within the cap, rank within [0, P].
#include "fuzz_support.hpp"

#include <ellipsect/geometry.hpp>

#include <algorithm>
#include <vector>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

template <class T, int N>
void run(Bytes& in) {
  const std::size_t count = in.byte() % 41;
  const double tolerance = in.flag() ? 1e-12 : 1e-8;
  const int cap = 1 + in.byte() % 60;
  const std::vector<Vec<T, N>> points = read_points<T, N>(in, count);
  const bool finite = all_finite<T, N>(points);
  double largest = 0;
  for (const auto& p : points)
    if (p.allFinite()) largest = std::max(largest, double(p.cwiseAbs().maxCoeff()));
  constexpr int P = EllipsoidFit<T, N>::parameters;
  EllipsoidFit<T, N> f;
  try {
    f = fit_ellipsoid<T, N>(points, {.fit_tolerance = tolerance, .max_fit_iterations = cap});
  } catch (const InputError& error) {
    FUZZ_CHECK(error.field() == "points", << "field " << error.field() << ": " << error.what());
    return;
  }
  FUZZ_CHECK(finite && count >= std::size_t(N == 2 ? 5 : 9), << "a fit of " << count << " points, finite " << finite);
  FUZZ_CHECK(f.body.center().allFinite() && f.body.radii().allFinite() && f.body.radii().minCoeff() > 0,
             << "body " << describe(f.body));
  FUZZ_CHECK(std::isfinite(f.rms_residual) && std::isfinite(f.max_residual) && f.rms_residual >= 0,
             << "residuals " << f.rms_residual << " " << f.max_residual);
  const double size = std::max({largest, double(f.body.radii().maxCoeff()), double(f.algebraic.radii().maxCoeff())});
  const double rounding = (std::is_same_v<T, float> ? 1e-6 : 1e-14) * size;
  FUZZ_CHECK(f.rms_residual <= f.max_residual * (1 + 1e-12) + rounding, << "rms " << f.rms_residual << " max " << f.max_residual);
  FUZZ_CHECK(f.rms_residual <= f.algebraic_rms_residual + rounding,
             << "rms " << f.rms_residual << " above the algebraic start's " << f.algebraic_rms_residual << " status "
             << to_string(f.status));
  FUZZ_CHECK(f.iterations >= 0 && f.iterations <= cap, << "iterations " << f.iterations << " cap " << cap);
  FUZZ_CHECK(f.rank >= 0 && f.rank <= P, << "rank " << f.rank);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  by_type_and_dimension(in, [&]<class T, int N>() { run<T, N>(in); });
  return 0;
}
