// Ellipsoids from the user's geometry, certified: the minimum-volume enclosing ellipse or
// ellipsoid of points, meshes, boxes, capsules and bodies; the least-squares fit of points
// (Fits, below); the maximum-volume inscribed one of a polytope (Inscribed, below).
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
// coordinate (RowInputError: its row and "points"), fewer points, or points within 1e-9 of
// their extent from a line or plane (an ellipsoid that thin is not representable:
// Ellipsoid::max_aspect_ratio) throw InputError("points") saying which.
//
// Of shapes. A mesh: of its vertices (every vertex given, InputError "mesh"). Boxes: of
// their corners as Box::corner computes them (the polytope every box query takes; "boxes").
// Bodies (ellipsoids; capsules as their two end balls, whose hull they are; "bodies",
// "capsules"): the least ellipsoid holding their union, a convex program over ellipsoids
// (an SDP) solved on points of their boundaries by cutting planes: each round encloses the
// points, then adds for every body the current ellipsoid leaves out its farthest point
// (max over the body of the ellipsoid's form: a trust-region problem, solved exactly up to
// rounding); at most 100 rounds. The points lie inside the bodies as stored (checked in
// rationals), so their weights bound the union's optimum from below: the gap is certified
// as for points. Containment: every body inside the returned body as stored, by the exact
// classification (classify.hpp, Tolerance::exact: a_contains_b or equal), the body grown by
// ulps until it holds. The support then names the body (capsule, box) of each certifying
// point, support_points holds the points.
#pragma once

#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
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
  // The points that carry the certificate, their weights u (summing to 1 up to rounding)
  // and where each comes from (an index into the input: the point, vertex, box, capsule or
  // body): the points on the boundary of the optimum.
  std::vector<std::size_t> support;
  std::vector<Vec<T, N>> support_points;
  std::vector<double> weights;
};

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Vec<T, N>> points, const EnclosingOptions& options = {});
template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(const TriangleMesh<T, N>& mesh, const EnclosingOptions& options = {});
template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Box<T, N>> boxes, const EnclosingOptions& options = {});
template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Capsule<T, N>> capsules, const EnclosingOptions& options = {});
template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Ellipsoid<T, N>> bodies, const EnclosingOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Fits: the least-squares ellipse or ellipsoid of a point cloud (edge pixels, a scan), with its
// residuals and the covariance of its parameters.
//
// Math. The fit minimizes the sum of squared orthogonal distances S = sum_i d_i^2, d_i the
// signed distance of point i to the body's boundary (closest_point, point.hpp), over the
// body's parameters: center, orientation, radii. It starts from an algebraic fit, on the points
// moved by their mean and scaled by a power of two near their RMS radius:
//   2D  Fitzgibbon, Pilu and Fisher's ellipse-specific direct fit (constraint 4ac - b^2 = 1), in
//       Halir and Flusser's stable form (scatter split into its quadratic and linear blocks, a
//       3x3 reduced eigenproblem);
//   3D  Li and Griffiths' ellipsoid-specific fit (constraint 4J - I^2 = 1, k = 4: a generalized
//       eigenproblem on the 6x6 reduced scatter);
// and Taubin's fit of the general conic (quadric) where that is an ellipse (ellipsoid), and the
// cloud's RMS ball: the one of these closest to the points (orthogonal RMS) starts
// Levenberg-Marquardt, first along the conic's coefficients a (the boundary moves by
// -(m(y) . da) / |grad Q(y)|, m the monomials: the conics through points are a linear family, so
// the long valleys of short arcs are straight there), then on (center, rotation increment, log
// radii), its Jacobian exact by the envelope theorem:
//   dd/dcenter = -n,  dd/dphi = -(y - c) x n,  dd/dlog r_k = -(axes^T n)_k (axes^T (y - c))_k,
// y the closest point, n the outward unit normal there (gradient.hpp's world rotation vector
// phi). Each accepted step lowers S (within its rounding near the stationary point), so the
// answer is never farther from the points than the start.
// Taubin's conic also decides whether the points are an ellipse at all: where it is a
// hyperbola, parabola or line pair whose residual (Taubin's first-order RMS distance) is below
// half the best ellipse's (and above 1e-8 of the cloud's RMS radius), or where the ellipse runs
// away towards a parabola (radii beyond 1e4 times the cloud's RMS radius: the points then lie on
// less than about 1e-4 radians of it and determine no ellipse), the status says not_an_ellipse.
//
// Guarantees:
//   residuals     rms_residual = sqrt(S / n) and max_residual = max |d_i| are those of the body
//                 as stored, recomputed by closest_point on it (in T), not estimates;
//   descent       rms_residual <= algebraic_rms_residual whatever the status, up to the
//                 rounding of closest_point in T: 1e-14 (float: 1e-6) of the largest of the
//                 points' coordinates and the two bodies' radii (a body run off towards a
//                 parabola has radii up to 1e4 times the cloud's);
//   converged     a stationary point of S: the Gauss-Newton step fell below fit_tolerance
//                 (center in units of the cloud's RMS radius, radii relative, orientation in
//                 radians; that step then taken), or the residuals are orthogonal to every
//                 column of the Jacobian to a cosine of fit_tolerance, or no step lowers S
//                 beyond its rounding. Tested: at fit_tolerance 1e-10, against a 50-digit
//                 Gauss-Newton by another route (distances by bisection on the secular
//                 equation, derivatives by differences) on noisy clouds, the parameters within
//                 1e-9 of the 50-digit stationary point (of the largest radius; angles in
//                 radians), the gradient's cosine below 1e-8; at the default, points on an
//                 ellipse (ellipsoid) give it back within 1e-9 of its largest radius (aspect
//                 ratios to 1e3, scales 1e-6 and 1e6, 1e6 radii from the origin), near circles
//                 of 10^4 points within the noise's average, and noisy clouds and 30 degree
//                 arcs are stationary to a cosine of 1e-6 by differences of closest_point;
//   covariance    sigma^2 (J^T J)^+ with sigma^2 = S / (n - P), J the Jacobian at the answer
//                 in the parameters (center, orientation, radii): gradient.hpp's order, the
//                 orientation the world rotation vector (2D: the angle) at the answer's axes,
//                 P = 5 in 2D, 9 in 3D; tested against the scatter of 300 fits to fresh noise
//                 (standard deviations within 25%). rank is J's; below P (an exact circle's
//                 angle, a spheroid's turn about its axis) the pseudo-inverse reads 0 along
//                 the undetermined directions. n = P: the points are interpolated and the
//                 covariance is NaN.
// Short arcs determine an ellipse poorly: on a 30 degree arc with noise of 1e-3 of the radius
// the least-squares ellipse's center is off by tens of percent of the radius (the covariance
// says so), or the ellipse runs off towards a parabola (not_an_ellipse).
// Cost: one pass of closest_point over the points per iteration, tens of iterations
// (bench/RESULTS.md).
//
// Input: at least 5 (2D) or 9 (3D) finite points. A NaN or infinite coordinate (RowInputError:
// its row and "points"), fewer points, or points within 1e-8 of their spread from a line or
// plane (or all equal) throw InputError("points") saying which.

namespace detail {
inline constexpr RealRange fit_tolerance_range{"fit_tolerance", 1e-15, 1e-3, true, true};
inline constexpr char max_fit_iterations_field[] = "max_fit_iterations";
}  // namespace detail

struct FitOptions {
  // The stationarity to reach (FitStatus::converged above), in [1e-15, 1e-3].
  RealOption<detail::fit_tolerance_range> fit_tolerance = 1e-8;
  // The Levenberg-Marquardt steps tried, each one pass over the points, in [1, 100000].
  // Reached: FitStatus::did_not_converge, the body the best iterate (never farther than the
  // algebraic fit).
  IterationCap<detail::max_fit_iterations_field, 100000> max_fit_iterations = 200;
};

enum class FitStatus {
  converged,         // a stationary point of the sum of squared orthogonal distances
  did_not_converge,  // max_fit_iterations reached, or the steps stalled short of fit_tolerance:
                     // the body the best iterate
  not_an_ellipse,    // the points are a hyperbola, parabola or line pair (hyperboloid, ...)
                     // rather than an ellipse (ellipsoid): the general conic fits them markedly
                     // better, or the ellipse runs away; the body the best ellipse found, its
                     // residuals saying how far it is
};
std::string_view to_string(FitStatus s) noexcept;

// The number of fitted parameters: center, orientation, radii.
template <int N>
inline constexpr int fit_parameter_count = 2 * N + (N == 2 ? 1 : 3);

template <class T, int N>
struct EllipsoidFit {
  static constexpr int parameters = fit_parameter_count<N>;
  FitStatus status = FitStatus::converged;
  Ellipsoid<T, N> body;          // the least-squares body, world frame
  double rms_residual = 0;       // sqrt(mean d_i^2) of the body as stored, world units
  double max_residual = 0;       // max |d_i|
  // The covariance of (center, orientation, radii) (gradient.hpp's order; the orientation a
  // world rotation vector at body's axes, in 2D the angle), world units.
  Eigen::Matrix<double, parameters, parameters, Eigen::DontAlign> covariance =
      Eigen::Matrix<double, parameters, parameters, Eigen::DontAlign>::Zero();
  int rank = 0;                  // of the Jacobian: parameters where every one is determined
  int iterations = 0;            // Levenberg-Marquardt steps tried
  Ellipsoid<T, N> algebraic;     // the algebraic fit the refinement started from
  double algebraic_rms_residual = 0;  // its RMS orthogonal residual
};

template <class T, int N>
EllipsoidFit<T, N> fit_ellipsoid(std::span<const Vec<T, N>> points, const FitOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Inscribed: the maximum-volume ellipse or ellipsoid inside a bounded convex polytope given by
// half-spaces (the inner step of a free-space decomposition), certified.
//
// Math. Each half-space H_i = { x : n_i . (x - p_i) <= 0 } (half_space.hpp) is a_i^T x <= b_i
// with a_i = n_i as stored and b_i = n_i . p_i. The ellipsoid { B u + d : |u| <= 1 } (B
// symmetric positive definite) lies in H_i exactly when |B a_i| + a_i^T d <= b_i, so the
// maximum-volume inscribed ellipsoid solves
//     maximize ln det B  subject to  |B a_i| <= b_i - a_i^T d  (second-order cones).
// Its dual: over mu_i >= |z_i| (z_i in R^N) with sum_i mu_i a_i = 0 and G = sym(sum_i a_i z_i^T)
// negative definite,
//     minimize D(mu, z) = sum_i mu_i b_i - ln det(-G) - N,
// and every such point bounds the optimum: ln det B <= D for every inscribed (B, d) (the
// Lagrangian ln det B + sum_i (mu_i (b_i - a_i^T d) + z_i^T B a_i) >= ln det B, at most D). A
// dual-feasible point also proves the polytope bounded (a direction v with a_i^T v <= 0 for
// every i would give v^T G v = 0). The solve: a barrier method on the N(N+1)/2 + N numbers
// of (B, d), minimizing -t ln det B - sum_i ln((b_i - a_i^T d)^2 - |B a_i|^2) (self-concordant)
// by Newton's method with backtracking, t growing eightfold, on the problem moved to the
// polytope's Chebyshev center and scaled by a power of two near its inradius;
// the start is that center's ball (phase I: a barrier method on the Chebyshev-ball linear
// program maximize r subject to a_i^T x + r <= b_i, within a box 1e12 times the planes'
// points' extent, in long double). The path is followed in double while the touching
// half-spaces' slacks (about 1/t of their distances) keep 20 bits there (t <= 2^-20 / eps)
// and no certificate is due (m / t above the barrier's share of the gap: the central gap is
// 2m / t); the centers that certify, in long double. From each such central point
// (s_i = b_i - a_i^T d, w_i = B a_i, g_i = s_i^2 - |w_i|^2) the dual point mu_i = 2 s_i / (t g_i), z_i = -2 w_i / (t g_i)
// (|z_i| < mu_i), made to satisfy sum_i mu_i a_i = 0 by the least-squares correction
// mu_i (1 - a_i^T lambda), z_i (1 - a_i^T lambda) (lambda from the weighted normal equations;
// the cones kept), bounds the gap; at the center it is 2m / t (m half-spaces).
//
// Guarantees, of the body as stored (center, axes, radii in T; float axes as every query takes
// them, detail/axes.hpp):
//   containment  the body lies in every half-space by the exact classification
//                (classify(body, half_space, Options{.tolerance = Tolerance::exact}) ==
//                b_contains_a, internal tangency included): the barrier's body shrunk by
//                ulps (a margin that doubles, at most 60 rounds) until it does;
//   volume       the maximum volume is at most (1 + volume_gap) vol(body), with
//                volume_gap = exp(D - ln det B) - 1 for
//                the dual point above and the body as stored (its radii, and the determinant
//                of its axes), rounded up. D and ln det B are evaluated in long double on
//                offsets n_i . (p_i - o) formed in compensated arithmetic (o the Chebyshev
//                center in double); the evaluation's rounding, estimated at 64 (m + N) ulps of
//                long double (5.4e-20) of the terms' magnitudes and the correction's residual
//                |sum_i mu_i a_i| times the polytope's extent (at most N times the body's
//                largest radius), about 1e-17 of the gap, is added: a bound up to that
//                estimate, not an estimate of the gap. The barrier takes an eighth of the
//                requested gap, the body's rounding to T and its shrinking the rest; where
//                they need more (float bodies, about 1e-6; a body whose center's ulp is
//                above 1e-10 of its radii) the status says so (rounding_limited) and
//                volume_gap says by how much.
//   weights      the dual point's mu_i (b_i - a_i^T d) / N at the barrier's last center:
//                dimensionless, unchanged by moving or scaling the polytope, summing to 1 up
//                to the gap and the center's rounding (within 1e-5; the dual bound is second
//                order in it); active names the half-spaces whose weight exceeds
//                sqrt(2 / (t N)) (the geometric mean of an inactive half-space's weight,
//                2 / (t N (1 - |w_i|^2 / s_i^2)), and 1): the faces the optimum touches. In
//                world units the multiplier is mu_i = N weight_i / (n_i . (p_i - c)), c the
//                body's center, and z_i = -mu_i B n_i / |B n_i|.
// Statuses: empty where no point has an inscribed ball of radius above 1e-12 of the extent of
// the half-spaces' points (an empty polytope, or one of empty interior: a segment, a plane);
// unbounded where phase I's ball exceeds 1e10 of that extent, or the barrier's largest radius
// exceeds 1e12 times the larger of that extent and the inradius with no dual-feasible point
// found, and the normals do not surround the origin (it is not strictly inside their convex
// hull, decided exactly as hull_half_spaces below decides: some direction v has n_i . v <= 0
// for every i; a wedge, a slab, a box missing a face). Both: body the default (the unit ball at the
// origin, no certificate), volume_gap infinite, active and weights empty. Where the normals
// do surround the origin the polytope is bounded but reaches beyond that range of its planes'
// points (a needle whose far vertex is no plane's point): InputError("half_spaces") says so.
// Accuracy (tests/unit/inscribed_test.cpp): boxes give their axis-aligned ellipsoid of radii
// the half-extents, regular simplices their inscribed balls, triangles their Steiner inellipses
// (area pi / (3 sqrt 3) of the triangle's, center the centroid), turned, 1e6 sizes from the
// origin, at scales 1e-6 and 1e6, with far redundant half-spaces, aspect ratios to 1e4; the
// dual bound recomputed in 50 digits from active and weights, and every support
// |B n_i| + n_i . (c - p_i) <= 0 from the stored numbers in 50 digits.
// Cost: O(m N^4) per Newton step, 100 to 320 steps (turned needles the most), all but the
// last ten or so in double: 0.2-0.8 ms in 2D, 0.5-2.2 ms in 3D for the hulls of 10 points
// (bench/RESULTS.md, "The inscribed ellipsoid").
//
// Input: at least N + 1 half-spaces; fewer (none included) throw InputError("half_spaces").
// A polytope whose inscribed ellipsoid has an aspect ratio above 1e8 (Ellipsoid::
// max_aspect_ratio) or radii beyond the range of T, or whose interior lies within the
// rounding of its position, throws InputError("half_spaces") saying so.
namespace detail {
inline constexpr char max_inscribed_iterations_field[] = "max_inscribed_iterations";
}  // namespace detail

struct InscribedOptions {
  // The volume gap to reach: max volume <= (1 + volume_gap) vol(body), in [1e-12, 1].
  RealOption<detail::volume_gap_range> volume_gap = 1e-9;
  // The Newton steps of the barrier method after phase I (whose own steps, at most 3000, count
  // in InscribedEllipsoid::iterations too), in [1, 1000000]. Reached:
  // InscribedStatus::did_not_converge, the body still inside every half-space and its gap
  // still a bound (infinite where no dual point was formed yet).
  IterationCap<detail::max_inscribed_iterations_field, 1000000> max_inscribed_iterations = 10000;
};

enum class InscribedStatus {
  optimal,           // volume_gap <= the requested gap
  rounding_limited,  // the barrier met the requested gap, the body as stored in T does not
                     // (volume_gap says by how much)
  did_not_converge,  // max_inscribed_iterations reached, or the certificate stalled short of
                     // the gap: the body inside every half-space, volume_gap a bound (or
                     // phase I found no interior point within its steps: the default body,
                     // volume_gap infinite)
  unbounded,         // the half-spaces leave a direction free: no maximum (above)
  empty,             // no interior point (above)
};
std::string_view to_string(InscribedStatus s) noexcept;

template <class T, int N>
struct InscribedEllipsoid {
  InscribedStatus status = InscribedStatus::optimal;
  Ellipsoid<T, N> body;    // inside every half-space, as stored
  double volume_gap = 0;   // certified: max volume <= (1 + volume_gap) vol(body)
  int iterations = 0;      // Newton steps, phase I's included
  // The half-spaces the body touches (dual weight above the threshold above; indices into
  // the input, increasing) and their weights (summing to 1 within 1e-5).
  std::vector<std::size_t> active;
  std::vector<double> weights;
};

template <class T, int N>
InscribedEllipsoid<T, N> inscribed_ellipsoid(std::span<const HalfSpace<T, N>> half_spaces,
                                             const InscribedOptions& options = {});

// The faces of the convex hull of points as half-spaces, outward (N = 2: its edges,
// counterclockwise; N = 3: its facets, coplanar triangles merged), for inscribed_ellipsoid:
// inscribed_ellipsoid(hull_half_spaces(points)) is the largest ellipsoid in their hull.
// Which points are vertices and which faces there are is exact (the signs of orientation
// determinants, a double evaluation where its error bound decides, rationals otherwise;
// collinear and coplanar points on the boundary are no vertices). Each normal is the face's
// in long double rounded to T (the factory's unit normal), each plane put through the face's
// vertex deepest along the normal as stored, so every vertex of the face lies on or outside
// its plane as stored, exactly: the half-spaces differ from the hull's faces by the rounding
// of their normals alone (about the unit roundoff of T times the hull's extent).
// Input: at least N + 1 finite points (RowInputError "points" for the first non-finite;
// InputError "points" for fewer), not all on a line (N = 2) or a plane (N = 3): InputError
// "points" saying so. Cost: O(n log n) in 2D; 3D Quickhull, O(n h) at worst (h the
// vertices).
template <class T, int N>
std::vector<HalfSpace<T, N>> hull_half_spaces(std::span<const Vec<T, N>> points);

}  // namespace ellipsect
