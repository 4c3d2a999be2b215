// Ellipsoids from the user's geometry: the minimum-volume enclosing ellipse or ellipsoid of
// a set of points, certified.
//
// Math. The minimum-volume ellipsoid containing points p_1..p_m of R^N (Loewner-John) is
// { x : (x - c)^T (N S_u)^-1 (x - c) <= 1 } for the optimal weights u of the dual problem
//     maximize ln det M(u),  M(u) = sum_i u_i q_i q_i^T,  q_i = (p_i, 1),  u >= 0, sum u = 1,
// with c = sum_i u_i p_i and S_u = sum_i u_i (p_i - c)(p_i - c)^T. Any weights bound the
// optimum from below: for every ellipsoid (A, c') containing the points,
//     1 >= sum_i u_i (p_i - c')^T A (p_i - c') >= tr(A S_u) >= N det(A S_u)^(1/N),
// so det A <= det (N S_u)^-1, and its volume is at least that of the ellipsoid above. And
// that ellipsoid grown by rho = max_i (p_i - c)^T (N S_u)^-1 (p_i - c) contains every point,
// with volume rho^(N/2) times the bound: the weights certify their own ellipsoid. They are
// found by Todd and Yildirim's coordinate ascent with Wolfe's away steps (Ahipasaoglu, Sun
// and Todd, 2008), from Kumar and Yildirim's 2N extreme points, on a small working set that
// grows by the points the current ellipsoid leaves out (a core set), in coordinates
// whitened by the current ellipsoid at every pass (the weights are affine-invariant, so the
// conditioning of the cloud costs no accuracy).
//
// Guarantees, of the body as stored (its center, axes and radii in T; float axes taken as
// every query takes them, detail/axes.hpp):
//   containment  every point p satisfies (p - c)^T M (p - c) <= 1, M = axes diag(radii)^-2
//                axes^T, decided in rational arithmetic where a rounding-error bound cannot
//                (the body is grown by a few ulps so that it holds);
//   volume       vol(body) <= (1 + volume_gap) min volume, volume_gap computed in rational
//                arithmetic from the weights and the stored numbers and rounded up: a bound,
//                not an estimate. The weights take an eighth of the requested gap, the
//                body's rounding and growth the rest; where they need more (float bodies,
//                about 1e-6; double bodies thinner than about 1e-3) the status says so
//                (rounding_limited) and volume_gap says by how much.
// Cost: O(m N^2) per pass over the points, a few passes (bench/RESULTS.md); the working set
// is tens of points.
//
// Input: at least N + 1 finite points that span R^N. Empty input, a NaN or infinite
// coordinate (RowInputError: its row and "points"), fewer points, or points within 1e-8 of
// their extent from a line or plane (an ellipsoid that thin is not representable:
// Ellipsoid::max_aspect_ratio) throw InputError("points") saying which.
#pragma once

#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace ellipsect {

namespace detail {
inline constexpr RealRange volume_gap_range{"volume_gap", 1e-12, 1, true, true};
inline constexpr char max_enclosing_iterations_field[] = "max_enclosing_iterations";
}  // namespace detail

struct EnclosingOptions {
  // The volume gap to reach: vol(body) <= (1 + volume_gap) min volume, in [1e-12, 1].
  RealOption<detail::volume_gap_range> volume_gap = 1e-9;
  // The weight updates (ascent and away steps) of all passes together, in [1, 10000000].
  // Reached: EnclosingStatus::did_not_converge, the body still containing every point and
  // its gap still certified.
  IterationCap<detail::max_enclosing_iterations_field, 10'000'000> max_enclosing_iterations = 1'000'000;
};

enum class EnclosingStatus {
  optimal,           // volume_gap <= the requested gap
  rounding_limited,  // the weights meet the requested gap, the body as stored in T does not
                     // (volume_gap says by how much): rounding its axes to T moves the tips
                     // of a thin body by about N (r_max / r_min)^2 ulps of its form
  did_not_converge,  // max_enclosing_iterations reached, or the weights stalled short of the
                     // gap at their rounding's floor (points nearly all on one ellipsoid):
                     // the body contains every point, volume_gap bounds it
};
std::string_view to_string(EnclosingStatus s) noexcept;

template <class T, int N>
struct EnclosingEllipsoid {
  EnclosingStatus status = EnclosingStatus::optimal;
  Ellipsoid<T, N> body;  // contains every point, as stored
  double volume_gap = 0;  // certified: vol(body) <= (1 + volume_gap) min volume
  std::int64_t iterations = 0;  // weight updates
  int passes = 0;               // passes over all the points
  // The points that carry the certificate (indices into the input) and their weights u
  // (summing to 1 up to rounding): the points on the boundary of the optimum.
  std::vector<std::size_t> support;
  std::vector<double> weights;
};

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Vec<T, N>> points, const EnclosingOptions& options = {});

}  // namespace ellipsect
