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

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ellipsect::detail {

template <class R, int N> using Tangent = Eigen::Matrix<R, N - 1, 1>;
template <class R, int N> using TangentMat = Eigen::Matrix<R, N - 1, N - 1>;
template <class R, int N> using TangentBasis = Eigen::Matrix<R, N, N - 1>;

// Body 1 and body 2 in working precision; r = c_2 - c_1.
template <class R, int N>
struct GapBodies {
  Mat<R, N> axes1, axes2;
  Vec<R, N> radii1, radii2;
  Vec<R, N> r;
};

template <class R, int N, class T>
GapBodies<R, N> gap_bodies(const Ellipsoid<T, N>& first, const Ellipsoid<T, N>& second) noexcept {
  return {first.axes().template cast<R>(), second.axes().template cast<R>(), first.radii().template cast<R>(),
          second.radii().template cast<R>(),
          second.center().template cast<R>() - first.center().template cast<R>()};
}

// An orthonormal basis of the plane orthogonal to the unit vector n.
template <class R, int N>
TangentBasis<R, N> tangent_basis(const Vec<R, N>& n) noexcept {
  static_assert(N == 2 || N == 3, "ellipsect: distances are implemented for N = 2 and 3");
  TangentBasis<R, N> q;
  if constexpr (N == 2) {
    q << -n[1], n[0];
  } else {
    int i = 0;  // the coordinate axis least aligned with n
    for (int j = 1; j < 3; ++j)
      if (std::abs(n[j]) < std::abs(n[i])) i = j;
    Vec<R, 3> t = -n[i] * n;
    t[i] += R(1);
    q.col(0) = t.normalized();
    q.col(1) = n.cross(Vec<R, 3>(q.col(0)));
  }
  return q;
}

template <class R, int N>
struct GapAt {
  Vec<R, N> n;                // unit direction
  R phi;                      // rho_1 + rho_2 - n . r
  Vec<R, N> s1, s2;           // support offsets (point_1 = c_1 + s1, point_2 = c_2 - s2)
  TangentBasis<R, N> q;       // tangent basis at n
  Tangent<R, N> grad;         // Q^T grad phi
  TangentMat<R, N> hess;      // Riemannian Hessian
  R noise;                    // rounding of phi: a few ulps of |r| + rho_1 + rho_2
};

// Support radius of one body along n; adds its term to the Hessian.
template <class R, int N>
R support(const Mat<R, N>& axes, const Vec<R, N>& radii, const Vec<R, N>& n, const TangentBasis<R, N>& q,
          Vec<R, N>& s, TangentMat<R, N>& hess) noexcept {
  const Vec<R, N> w = radii.cwiseProduct(axes.transpose() * n);
  const R rho = w.norm();
  s = axes * (radii.cwiseProduct(w) / rho);
  const TangentBasis<R, N> v = radii.asDiagonal() * (axes.transpose() * q);
  const Tangent<R, N> st = q.transpose() * s;
  hess += (v.transpose() * v - st * st.transpose()) / rho;
  return rho;
}

template <class R, int N>
GapAt<R, N> gap_at(const GapBodies<R, N>& g, const Vec<R, N>& n) noexcept {
  GapAt<R, N> at;
  at.n = n;
  at.q = tangent_basis<R, N>(n);
  at.hess.setZero();
  const R rho1 = support<R, N>(g.axes1, g.radii1, n, at.q, at.s1, at.hess);
  const R rho2 = support<R, N>(g.axes2, g.radii2, n, at.q, at.s2, at.hess);
  at.phi = rho1 + rho2 - n.dot(g.r);
  at.grad = at.q.transpose() * (at.s1 + at.s2 - g.r);
  at.hess -= at.phi * TangentMat<R, N>::Identity();
  at.noise = R(8) * std::numeric_limits<R>::epsilon() * (g.r.norm() + rho1 + rho2);
  return at;
}

// phi alone, for ranking candidate directions.
template <class R, int N>
R gap_value(const GapBodies<R, N>& g, const Vec<R, N>& n) noexcept {
  return g.radii1.cwiseProduct(g.axes1.transpose() * n).norm() + g.radii2.cwiseProduct(g.axes2.transpose() * n).norm() -
         n.dot(g.r);
}

// Smallest eigenvalue of a 1x1 or 2x2 symmetric matrix and a unit eigenvector.
template <class R, int M>
R lowest_eigen(const Eigen::Matrix<R, M, M>& h, Eigen::Matrix<R, M, 1>& v) noexcept {
  if constexpr (M == 1) {
    v[0] = R(1);
    return h(0, 0);
  } else {
    const R half_diff = (h(0, 0) - h(1, 1)) / 2;
    const R rad = std::hypot(half_diff, h(0, 1));
    const R lambda = (h(0, 0) + h(1, 1)) / 2 - rad;
    // (h - lambda I) v = 0: take the larger of the two equivalent row solutions.
    const Eigen::Matrix<R, 2, 1> v1(h(0, 1), lambda - h(0, 0)), v2(lambda - h(1, 1), h(0, 1));
    const Eigen::Matrix<R, 2, 1> best = v1.squaredNorm() >= v2.squaredNorm() ? v1 : v2;
    const R len = best.norm();
    v = len > R(0) ? Eigen::Matrix<R, 2, 1>(best / len) : Eigen::Matrix<R, 2, 1>(1, 0);
    return lambda;
  }
}

// Trust-region step for the model phi + grad . t + t^T hess t / 2, |t| <= radius.
// `newton` tells whether it is the full Newton step of a positive definite model (or the
// null step of a model that is flat to rounding, as for concentric balls).
template <class R, int N>
Tangent<R, N> trust_step(const GapAt<R, N>& at, R radius, bool& newton) noexcept {
  using Tan = Tangent<R, N>;
  using TMat = TangentMat<R, N>;
  Tan v;
  const R lambda = lowest_eigen<R, N - 1>(at.hess, v);
  const R gnorm = at.grad.norm();
  newton = true;
  if (std::abs(lambda) <= at.noise && gnorm <= at.noise && at.hess.cwiseAbs().maxCoeff() <= at.noise) return Tan::Zero();
  if (lambda > R(0)) {
    const Tan t = at.hess.llt().solve(-at.grad);
    if (t.norm() <= radius) return t;
  }
  newton = false;
  // Levenberg-Marquardt shift: |t| <= |grad| / (lambda + sigma) = radius.
  Tan t = Tan::Zero();
  if (gnorm > R(0)) {
    const R sigma = std::max(R(0), -lambda) + gnorm / radius;
    t = (at.hess + sigma * TMat::Identity()).llt().solve(-at.grad);
  }
  if (lambda <= R(0) && t.norm() < radius / 2) {
    // Negative curvature with a small gradient (near a maximum or saddle): move along the
    // lowest eigenvector, downhill, to the trust radius.
    const R along = std::sqrt(radius * radius - t.squaredNorm());
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

// Minimizes phi on the sphere from the unit direction n0, at most `max_iterations` steps.
// Converged when the Newton model predicts a decrease far below rounding, or when it
// stops contracting quadratically while already at the rounding level of phi (the
// gradient is then rounding noise and the direction is as accurate as the data allow).
template <class R, int N>
Descent<R, N> descend(const GapBodies<R, N>& g, const Vec<R, N>& n0, int max_iterations) noexcept {
  constexpr R eps = std::numeric_limits<R>::epsilon();
  Descent<R, N> d;
  d.at = gap_at<R, N>(g, n0);
  R radius = R(0.5);
  R last_pred = std::numeric_limits<R>::infinity();
  while (d.iterations < max_iterations) {
    bool newton;
    const Tangent<R, N> t = trust_step<R, N>(d.at, radius, newton);
    const R pred = -(d.at.grad.dot(t) + t.dot(d.at.hess * t) / 2);
    const bool rounding_level = newton && pred <= d.at.noise;
    if (newton && (pred <= eps * d.at.noise || (rounding_level && pred > last_pred / 4))) {
      d.converged = true;
      return d;
    }
    ++d.iterations;
    const GapAt<R, N> trial = gap_at<R, N>(g, Vec<R, N>((d.at.n + d.at.q * t).normalized()));
    const R ratio = (d.at.phi - trial.phi) / pred;
    const R len = t.norm();
    if (ratio < R(0.25)) radius = len / 4;
    else if (ratio > R(0.75) && len > R(0.99) * radius) radius = std::min(R(1), 2 * radius);
    // Within rounding the model is trusted over the noisy decrease.
    if (ratio > R(0) || rounding_level) {
      if (newton) last_pred = pred;
      d.at = trial;
    }
  }
  return d;
}

// Directions to start the penetration search from: the Gauss maps of both bodies at a
// fixed symmetric set of parameter points u (normal of body i at c_i + axes_i diag(radii_i) u
// is axes_i diag(radii_i)^-1 u). The samples crowd where a body is flat, which is where its
// support radius changes fastest with the direction, so narrow valleys of phi are seen.
template <int N>
constexpr int gauss_samples = N == 2 ? 16 : 26;

template <class R, int N>
std::array<Vec<R, N>, gauss_samples<N>> gauss_parameters() noexcept {
  std::array<Vec<R, N>, gauss_samples<N>> u;
  if constexpr (N == 2) {
    for (int i = 0; i < 16; ++i) {
      const R angle = R(i) * R(M_PI / 8);
      u[i] = Vec<R, 2>(std::cos(angle), std::sin(angle));
    }
  } else {
    int m = 0;  // the 26 directions of the cube's faces, edges and corners
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z)
          if (x != 0 || y != 0 || z != 0) u[m++] = Vec<R, 3>(R(x), R(y), R(z)).normalized();
  }
  return u;
}

// The `count` sampled directions with the smallest phi, best first.
template <class R, int N, int Count>
std::array<Vec<R, N>, Count> best_samples(const GapBodies<R, N>& g) noexcept {
  static const auto params = gauss_parameters<R, N>();
  std::array<Vec<R, N>, Count> best;
  std::array<R, Count> value;
  value.fill(std::numeric_limits<R>::infinity());
  auto offer = [&](const Vec<R, N>& n) {
    const R v = gap_value<R, N>(g, n);
    if (!(v < value[Count - 1])) return;
    int i = Count - 1;
    for (; i > 0 && v < value[i - 1]; --i) {
      value[i] = value[i - 1];
      best[i] = best[i - 1];
    }
    value[i] = v;
    best[i] = n;
  };
  for (const auto& u : params) {
    offer(Vec<R, N>(g.axes1 * u.cwiseQuotient(g.radii1)).normalized());
    offer(Vec<R, N>(g.axes2 * u.cwiseQuotient(g.radii2)).normalized());
  }
  return best;
}

}  // namespace ellipsect::detail
