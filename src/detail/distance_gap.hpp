// The support gap of two bodies as a function of a unit direction n, and its minimization
// on the sphere of directions (docs/distance.md).
//
// With r = c_2 - c_1 and rho_i(n) = |diag(radii_i) axes_i^T n| (the support radius of body i
// about its center), the function minimized here is
//
//     phi(n) = rho_1(n) + rho_2(n) - n . r,
//
// minus the support gap g of distance.hpp, so that min phi = -(signed distance). Its
// gradient is s_1 + s_2 - r, with s_i = M_i^-1 n / rho_i the support offsets (point_1 =
// c_1 + s_1, point_2 = c_2 - s_2), and its Hessian sum_i (M_i^-1 - s_i s_i^T) / rho_i, the
// radii of curvature at the support points. phi is positively homogeneous of degree 1, so
// n . grad phi = phi and the Riemannian Hessian on the sphere, in an orthonormal basis Q
// of the tangent plane, is
//
//     H = Q^T (sum_i (M_i^-1 - s_i s_i^T) / rho_i) Q - phi I.
//
// When phi < 0 (bodies apart along n) H is positive definite and Newton converges from
// anywhere in {phi < 0}, on which phi has a single minimum; when phi > 0 H can be
// indefinite, and the trust region handles the negative curvature.
#pragma once

#include <ellipsect/shapes.hpp>

#include "axes.hpp"
#include "math.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ellipsect::detail {

template <class R, int N> using Tangent = Eigen::Matrix<R, N - 1, 1>;
template <class R, int N> using TangentMat = Eigen::Matrix<R, N - 1, N - 1>;
template <class R, int N> using TangentBasis = Eigen::Matrix<R, N, N - 1>;

// Body 1 and body 2 in working precision: B_i = diag(radii_i) axes_i^T (so rho_i(n) =
// |B_i n| and M_i^-1 = B_i^T B_i), axes and radii, and r = c_2 - c_1.
template <class R, int N>
struct GapBodies {
  Mat<R, N> b1, b2;
  Mat<R, N> axes1, axes2;
  Vec<R, N> radii1, radii2;
  Vec<R, N> r;
  R r_norm;
};

template <class R, int N, class T>
GapBodies<R, N> gap_bodies(const Ellipsoid<T, N>& first, const Ellipsoid<T, N>& second) noexcept {
  GapBodies<R, N> g;
  g.axes1 = work_axes<R>(first);
  g.axes2 = work_axes<R>(second);
  g.radii1 = first.radii().template cast<R>();
  g.radii2 = second.radii().template cast<R>();
  g.b1 = g.radii1.asDiagonal() * g.axes1.transpose();
  g.b2 = g.radii2.asDiagonal() * g.axes2.transpose();
  g.r = second.center().template cast<R>() - first.center().template cast<R>();
  // Offsets whose squares leave the normal range (a 1e-159 center offset) lose digits in
  // norm(), and r / |r| was 7e-8 off unit length.
  g.r_norm = g.r.squaredNorm() >= std::numeric_limits<R>::min() ? g.r.norm() : g.r.stableNorm();
  return g;
}

// An orthonormal basis of the plane orthogonal to the unit vector n (in 3D the branchless
// construction of Duff et al., "Building an Orthonormal Basis, Revisited", 2017).
template <class R, int N>
TangentBasis<R, N> tangent_basis(const Vec<R, N>& n) noexcept {
  static_assert(N == 2 || N == 3, "ellipsect: distances are implemented for N = 2 and 3");
  TangentBasis<R, N> q;
  if constexpr (N == 2) {
    q << -n[1], n[0];
  } else {
    const R sign = copysign(R(1), n[2]);
    const R a = R(-1) / (sign + n[2]);
    const R b = n[0] * n[1] * a;
    q << R(1) + sign * n[0] * n[0] * a, b, sign * b, sign + n[1] * n[1] * a, -sign * n[0], -n[1];
  }
  return q;
}

template <class R, int N>
struct GapAt {
  Vec<R, N> n;                // unit direction
  R phi;                      // rho_1 + rho_2 - n . r
  Vec<R, N> s1, s2;           // support offsets (point_1 = c_1 + s1, point_2 = c_2 - s2)
  Vec<R, N> w1, w2;           // B_i n
  R inv1, inv2;               // 1 / rho_i
  TangentBasis<R, N> q;       // tangent basis at n
  Tangent<R, N> grad;         // Q^T grad phi
  TangentMat<R, N> hess;      // Riemannian Hessian
  R noise;                    // rounding of phi: a few ulps of |r| + rho_1 + rho_2
};

// One body's term of the Hessian, Q^T (B^T B - s s^T) Q / |B n|, with w = B n and inv = 1 / |w|.
template <class R, int N>
TangentMat<R, N> curvature(const Mat<R, N>& b, const Vec<R, N>& w, R inv, const TangentBasis<R, N>& q) noexcept {
  const TangentBasis<R, N> v = b * q;
  Tangent<R, N> st = v.transpose() * w;  // q^T s
  st *= inv;
  return (v.transpose() * v - st * st.transpose()) * inv;
}

template <class R, int N>
void add_hessian(const GapBodies<R, N>& g, GapAt<R, N>& at) noexcept {
  at.hess = curvature<R, N>(g.b1, at.w1, at.inv1, at.q) + curvature<R, N>(g.b2, at.w2, at.inv2, at.q) -
            at.phi * TangentMat<R, N>::Identity();
}

// phi, the support offsets and the gradient at the unit direction n, and the Hessian
// unless `hessian` is false.
template <class R, int N>
GapAt<R, N> gap_at(const GapBodies<R, N>& g, const Vec<R, N>& n, bool hessian = true) noexcept {
  GapAt<R, N> at;
  at.n = n;
  at.q = tangent_basis<R, N>(n);
  at.w1 = g.b1 * n;
  at.w2 = g.b2 * n;
  const R rho1 = at.w1.norm(), rho2 = at.w2.norm();
  at.inv1 = R(1) / rho1;
  at.inv2 = R(1) / rho2;
  at.s1 = g.b1.transpose() * at.w1 * at.inv1;
  at.s2 = g.b2.transpose() * at.w2 * at.inv2;
  at.phi = rho1 + rho2 - n.dot(g.r);
  at.grad = at.q.transpose() * (at.s1 + at.s2 - g.r);
  at.noise = R(8) * std::numeric_limits<R>::epsilon() * (g.r_norm + rho1 + rho2);
  if (hessian) add_hessian<R, N>(g, at);
  return at;
}

// A Hessian h at a nearby direction with tangent basis q_h, written in the basis q: M^T h M
// with M = q_h^T q (the two tangent planes agree to the angle between the directions).
template <class R, int N>
TangentMat<R, N> carried(const TangentMat<R, N>& h, const TangentBasis<R, N>& q_h, const TangentBasis<R, N>& q) noexcept {
  const TangentMat<R, N> m = q_h.transpose() * q;
  return m.transpose() * h * m;
}

// phi alone, for ranking candidate directions.
template <class R, int N>
R gap_value(const GapBodies<R, N>& g, const Vec<R, N>& n) noexcept {
  return (g.b1 * n).norm() + (g.b2 * n).norm() - n.dot(g.r);
}

// The Perram-Wertheim direction y = C^-1 r, C = (1 - l) M_1^-1 + l M_2^-1, at the
// two-ball weight l = rho_1(r) / (rho_1(r) + rho_2(r)) of detail/certificates-inl.hpp, and
// F(l) = l (1 - l) r . y, a lower bound on the square of the Perram-Wertheim factor.
// Whenever F > 1 the bodies are apart along y: with a = rho_1(y), b = rho_2(y) and
// u = y . C y = (1 - l) a^2 + l b^2, Cauchy-Schwarz gives a + b <= sqrt(u / (l (1 - l)))
// = u / sqrt(F), so g(y) = u - a - b >= u (1 - 1 / sqrt(F)) > 0.
template <class R, int N>
struct PwDirection {
  Vec<R, N> n;  // y / |y|
  R f;          // F(l)
};

template <class R, int N>
PwDirection<R, N> pw_direction(const GapBodies<R, N>& g) noexcept {
  const Mat<R, N> p1 = g.b1.transpose() * g.b1, p2 = g.b2.transpose() * g.b2;
  const R rho1 = (g.b1 * g.r).norm(), rho2 = (g.b2 * g.r).norm();
  const R l = rho1 / (rho1 + rho2);
  const Vec<R, N> y = Mat<R, N>((R(1) - l) * p1 + l * p2).inverse() * g.r;  // closed form for N <= 3
  return {unit_vector<R, N>(y), l * (R(1) - l) * g.r.dot(y)};
}

// Smallest eigenvalue of a 1x1 or 2x2 symmetric matrix.
template <class R, int M>
R lowest_eigenvalue(const Eigen::Matrix<R, M, M>& h) noexcept {
  if constexpr (M == 1) {
    return h(0, 0);
  } else {
    const R half_diff = (h(0, 0) - h(1, 1)) / 2;
    return (h(0, 0) + h(1, 1)) / 2 - sqrt(half_diff * half_diff + h(0, 1) * h(0, 1));
  }
}

// A unit eigenvector of a 1x1 or 2x2 symmetric matrix for its eigenvalue lambda.
template <class R, int M>
Eigen::Matrix<R, M, 1> eigenvector(const Eigen::Matrix<R, M, M>& h, R lambda) noexcept {
  if constexpr (M == 1) {
    return Eigen::Matrix<R, 1, 1>(R(1));
  } else {
    // (h - lambda I) v = 0: the larger of the two equivalent row solutions.
    const Eigen::Matrix<R, 2, 1> v1(h(0, 1), lambda - h(0, 0)), v2(lambda - h(1, 1), h(0, 1));
    const Eigen::Matrix<R, 2, 1> best = v1.squaredNorm() >= v2.squaredNorm() ? v1 : v2;
    const R len = best.norm();
    return len > R(0) ? Eigen::Matrix<R, 2, 1>(best / len) : Eigen::Matrix<R, 2, 1>(1, 0);
  }
}

// Solution of h t = -g for a positive definite 1x1 or 2x2 h.
template <class R, int M>
Eigen::Matrix<R, M, 1> newton_solve(const Eigen::Matrix<R, M, M>& h, const Eigen::Matrix<R, M, 1>& g) noexcept {
  if constexpr (M == 1) {
    return Eigen::Matrix<R, 1, 1>(-g[0] / h(0, 0));
  } else {
    const R inv_det = R(1) / (h(0, 0) * h(1, 1) - h(0, 1) * h(1, 0));
    return Eigen::Matrix<R, 2, 1>((h(0, 1) * g[1] - h(1, 1) * g[0]) * inv_det, (h(1, 0) * g[0] - h(0, 0) * g[1]) * inv_det);
  }
}

// Trust-region step for the model phi + grad . t + t^T hess t / 2, |t| <= radius.
// `newton` tells whether it is the full Newton step of a positive definite model (or the
// null step of a model that is flat to rounding, as for concentric balls).
template <class R, int N>
Tangent<R, N> trust_step(const GapAt<R, N>& at, R radius, bool& newton) noexcept {
  using Tan = Tangent<R, N>;
  using TMat = TangentMat<R, N>;
  newton = true;
  // Positive definite: every leading minor positive (no eigenvalue needed).
  const bool definite = at.hess(0, 0) > R(0) && (N == 2 || at.hess.determinant() > R(0));
  if (definite) {
    const Tan t = newton_solve<R, N - 1>(at.hess, at.grad);
    if (t.squaredNorm() <= radius * radius) return t;
  } else if (at.grad.squaredNorm() <= at.noise * at.noise && at.hess.cwiseAbs().maxCoeff() <= at.noise) {
    return Tan::Zero();
  }
  const R lambda = lowest_eigenvalue<R, N - 1>(at.hess);
  newton = false;
  // Levenberg-Marquardt shift: |t| <= |grad| / (lambda + sigma) = radius.
  Tan t = Tan::Zero();
  const R gnorm = at.grad.norm();
  if (gnorm > R(0)) {
    const R sigma = std::max(R(0), -lambda) + gnorm / radius;
    t = newton_solve<R, N - 1>(TMat(at.hess + sigma * TMat::Identity()), at.grad);
  }
  if (lambda <= R(0) && t.norm() < radius / 2) {
    // Negative curvature with a small gradient (near a maximum or saddle): move along the
    // lowest eigenvector, downhill, to the trust radius.
    const Tan v = eigenvector<R, N - 1>(at.hess, lambda);
    const R along = sqrt(radius * radius - t.squaredNorm());
    t += (at.grad.dot(v) > R(0) ? -along : along) * v;
  }
  return t;
}

template <class R, int N>
struct Descent {
  GapAt<R, N> at;
  int iterations = 0;
  bool converged = false;
};

// Where the step n -> n + Q t crosses a kink of phi: the smallest fraction tau in (0, 1) at
// which some body's |B (n + tau Q t)| (a hyperbola in tau) has its minimum, below half its
// value at n; 1 if none. A thin body's support radius is |B n| ~ r_max |n . u| away from
// the plane n . u = 0, a kink smoothed over an angle r_min / r_max: a step across it
// overshoots by the whole step, and shrinking the trust region towards that width takes
// many rejected steps and leaves the radius too small to follow the valley afterwards.
template <class R, int N>
R kink_fraction(const GapBodies<R, N>& g, const Vec<R, N>& n, const Vec<R, N>& step) noexcept {
  R tau = R(1);
  for (const Mat<R, N>* b : {&g.b1, &g.b2}) {
    const Vec<R, N> w0 = *b * n, w1 = *b * step;
    const R at = -w0.dot(w1) / w1.squaredNorm();
    if (at > R(0) && at < tau && (w0 + at * w1).squaredNorm() < R(0.25) * w0.squaredNorm()) tau = at;
  }
  return tau;
}

// Minimizes phi on the sphere from the unit direction n0, at most `max_iterations`
// evaluations of phi after the first. Converged when the Newton step is below the
// resolution of a unit vector, when the model predicts a decrease far below rounding, or
// when Newton stops contracting quadratically while already at the rounding level of phi
// (the gradient is then rounding noise and the direction is as accurate as the data
// allow). Within rounding, Newton steps are taken without the decrease test, which the
// noise would make meaningless. A rejected step that crosses a kink (kink_fraction) is cut
// at the kink, into the valley, where the model holds again. Only trial directions with a
// finite phi are accepted, so the result holds a finite iterate whenever n0 is finite.
template <class R, int N>
Descent<R, N> descend(const GapBodies<R, N>& g, const Vec<R, N>& n0, int max_iterations) noexcept {
  const R eps = std::numeric_limits<R>::epsilon();
  Descent<R, N> d;
  d.at = gap_at<R, N>(g, n0);
  R radius = R(0.5);
  R last_pred = std::numeric_limits<R>::infinity();
  auto trial_at = [&](const Vec<R, N>& m, bool hessian = true) {
    ++d.iterations;
    return gap_at<R, N>(g, Vec<R, N>(m * (R(1) / m.norm())), hessian);
  };
  // After a step at rounding level the new iterate is nearly always the last: it takes the
  // Hessian of the one before, carried into its tangent basis, for the convergence test (a
  // relative change of the order of the step, far below what the thresholds resolve), and
  // computes its own only if the descent goes on.
  bool carried_hessian = false;
  while (d.iterations < max_iterations) {
    bool newton;
    const Tangent<R, N> t = trust_step<R, N>(d.at, radius, newton);
    const R len = t.norm();
    const R pred = -(d.at.grad.dot(t) + t.dot(d.at.hess * t) / 2);
    const bool rounding_level = newton && pred <= d.at.noise;
    if (newton && (len <= 2 * eps || pred <= eps * d.at.noise || (rounding_level && pred > last_pred / 4))) {
      d.converged = true;
      return d;
    }
    if (carried_hessian) {
      add_hessian<R, N>(g, d.at);
      carried_hessian = false;
      continue;
    }
    const Vec<R, N> step = d.at.q * t;
    GapAt<R, N> trial = trial_at(d.at.n + step, !rounding_level);
    if (rounding_level && isfinite(trial.phi)) {
      trial.hess = carried<R, N>(d.at.hess, d.at.q, trial.q);
      carried_hessian = true;
      last_pred = pred;
      d.at = trial;
      continue;
    }
    if (rounding_level) add_hessian<R, N>(g, trial);  // phi not finite: every iterate has its Hessian
    const R actual = d.at.phi - trial.phi;  // compared with the predicted decrease; NaN rejects
    if (!(actual >= R(0.25) * pred)) {
      const R tau = kink_fraction<R, N>(g, d.at.n, step);
      if (tau < R(1) && d.iterations < max_iterations) {
        const GapAt<R, N> kink = trial_at(d.at.n + tau * step);
        if (kink.phi < d.at.phi) {
          d.at = kink;
          radius = std::max(radius / 4, tau * len);
          continue;
        }
      }
      radius = len / 4;
    } else if (actual > R(0.75) * pred && len > radius / 2) {
      radius = std::min(R(1), 2 * radius);
    }
    if (actual > R(0)) {
      if (newton) last_pred = pred;
      d.at = trial;
    }
  }
  return d;
}

// Directions to start the penetration search from: the Gauss maps of both bodies at a
// fixed symmetric set of parameter points u (the normal of body i at c_i + axes_i
// diag(radii_i) u is along axes_i diag(radii_i)^-1 u). The samples crowd where a body is
// flat, which is where its support radius changes fastest with the direction, so narrow
// valleys of phi are seen. Each valley shows as a sample that is no worse than its
// neighbours in the parameter set; the best of these discrete minima are the starts.
template <int N>
struct GaussSamples {
  static constexpr int count = N == 2 ? 16 : 26;
  std::array<Vec<double, N>, count> u;
  std::array<std::array<int, count>, count> neighbours;  // indices, -1 terminated
  GaussSamples() noexcept {
    if constexpr (N == 2) {
      for (int i = 0; i < count; ++i) u[i] = Vec<double, 2>(cos(i * M_PI / 8), sin(i * M_PI / 8));
    } else {
      int m = 0;  // the directions of the cube's faces, edges and corners
      for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
          for (int z = -1; z <= 1; ++z)
            if (x != 0 || y != 0 || z != 0) u[m++] = Vec<double, 3>(x, y, z).normalized();
    }
    // Neighbours: the adjacent angles in 2D (22.5 degrees), the directions within 60
    // degrees in 3D (face-edge 45, face-corner 54.7, edge-corner 35.3, edge-edge 60).
    const double min_cos = N == 2 ? 0.9 : 0.49;
    for (int i = 0; i < count; ++i) {
      int k = 0;
      for (int j = 0; j < count; ++j)
        if (j != i && u[i].dot(u[j]) >= min_cos) neighbours[i][k++] = j;
      neighbours[i][k] = -1;
    }
  }
};

// Up to Count sampled directions at discrete minima of phi, the smallest phi first.
template <class R, int N, int Count>
int sampled_starts(const GapBodies<R, N>& g, std::array<Vec<R, N>, Count>& best) noexcept {
  static const GaussSamples<N> samples;
  constexpr int count = GaussSamples<N>::count;
  std::array<R, Count> value;
  int found = 0;
  auto offer = [&](R v, const Vec<R, N>& n) {
    if (found == Count && !(v < value[Count - 1])) return;
    int i = found < Count ? found++ : Count - 1;
    for (; i > 0 && v < value[i - 1]; --i) {
      value[i] = value[i - 1];
      best[i] = best[i - 1];
    }
    value[i] = v;
    best[i] = n;
  };
  for (int body = 0; body < 2; ++body) {
    const Mat<R, N>& axes = body == 0 ? g.axes1 : g.axes2;
    const Vec<R, N>& radii = body == 0 ? g.radii1 : g.radii2;
    std::array<Vec<R, N>, count> n;
    std::array<R, count> v;
    for (int i = 0; i < count; ++i) {
      n[i] = Vec<R, N>(axes * samples.u[i].template cast<R>().cwiseQuotient(radii)).normalized();
      v[i] = gap_value<R, N>(g, n[i]);
    }
    for (int i = 0; i < count; ++i) {
      bool minimum = true;
      for (int k = 0; samples.neighbours[i][k] >= 0 && minimum; ++k) minimum = v[i] <= v[samples.neighbours[i][k]];
      if (minimum) offer(v[i], n[i]);
    }
  }
  return found;
}

}  // namespace ellipsect::detail
