// Reduction of a pair to "unit ball + axis-aligned ellipsoid" (seed section 3).
//
// With the sphere body S = (K0, R0, radii a) and the other body O = (K1, R1, radii b):
//   Y = diag(1/a) R0^T (X - K0)          maps S to the unit ball,
//   O becomes { K2 + L u : |u| <= 1 }    with L = diag(1/a) R0^T R1 diag(b),
//   L = U Sigma V^T (SVD)                gives O's semi-axes e = Sigma along U's columns,
//   Z = U^T Y                            makes O axis-aligned with center k = U^T K2.
// The seed factors M2 = L^-T L^-1 with a symmetric eigensolver; its eigenvalues can spread
// over (aspect_S * aspect_O)^2 (1e16 for two 1e4 needles), where a symmetric solver loses
// the small ones entirely. The one-sided structure of L lets one-sided Jacobi return every
// semi-axis to high relative accuracy instead (tests/regression/seed_bugs_test.cpp).
//
// Which body becomes the ball does not depend on argument order (the larger body when the
// largest radii differ by more than 2^26, otherwise the rounder, ties broken by the raw
// data), so every query is exactly symmetric under swapping a and b.
#pragma once

#include <ellipsect/shapes.hpp>

#include "axes.hpp"
#include "wide.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace ellipsect::detail {

// Working precision: float inputs are computed in double, results rounded back.
template <class T> using Work = std::conditional_t<(sizeof(T) < sizeof(double)), double, T>;
// The wider type used to re-decide answers that rounding in Work<T> could flip.
template <class R> using Wide = WideFloat;

// Bodies whose largest radii differ by more than this factor: the larger becomes the ball.
inline constexpr double sphere_body_size_ratio = 0x1p26;

template <class T, int N>
bool is_sphere_body(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) noexcept {
  // A small body near a large one's boundary is measured in the large one's frame: in the
  // small one's, the large one's center lies (size ratio) units away and is rounded by eps
  // times that, beyond the tangency band from a ratio of about 2^26 on (in the wide type too)
  // and beyond the small body's own size at 2^52 (two balls of radius ratio 2^154: classify,
  // overlap and first_contact each answered their own rounding).
  const T size_a = a.radii().maxCoeff(), size_b = b.radii().maxCoeff();
  if (size_a > size_b * T(sphere_body_size_ratio)) return true;
  if (size_b > size_a * T(sphere_body_size_ratio)) return false;
  const T ra = a.radii().maxCoeff() / a.radii().minCoeff();
  const T rb = b.radii().maxCoeff() / b.radii().minCoeff();
  if (ra != rb) return ra < rb;
  // Ties: the raw data in a total order (radii, center, axes; -0 before +0), so that two
  // bodies differing in any bit are ordered the same way whichever comes first.
  auto compare = [](const auto& x, const auto& y) {
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const T u = x.data()[i], v = y.data()[i];
      if (u != v) return u < v ? -1 : 1;
      if (signbit(u) != signbit(v)) return signbit(u) ? -1 : 1;
    }
    return 0;
  };
  if (const int c = compare(a.radii(), b.radii())) return c < 0;
  if (const int c = compare(a.center(), b.center())) return c < 0;
  return compare(b.axes(), a.axes()) >= 0;
}

// a * b + c with about one rounding: a hardware fma where the build has one, Dekker's exact
// product otherwise (libm's software fma is ~50x slower). The wide type is only used where
// its 11 extra bits already cover the second rounding.
template <class R>
R mul_add(R a, R b, R c) noexcept {
  if constexpr (std::is_same_v<R, double>) {
#ifdef FP_FAST_FMA
    return fma(a, b, c);
#else
    constexpr double split = 134217729.0;  // 2^27 + 1
    const double p = a * b;
    const double as = a * split, bs = b * split;
    const double ah = as - (as - a), bh = bs - (bs - b);
    const double al = a - ah, bl = b - bh;
    const double err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;  // a * b = p + err exactly
    return (p + c) + err;
#endif
  } else {
    return a * b + c;
  }
}

// Singular values and left singular vectors of L by one-sided (Hestenes) Jacobi: plane
// rotations from the right orthogonalize L's columns, which converge to sigma_i u_i.
// For L = B diag(b) the relative error of every sigma_i is about eps * cond(B) (Demmel and
// Veselic 1992); here B = diag(1/a) R0^T R1, so cond(B) is the sphere body's aspect ratio,
// the smaller of the two by the choice of the sphere body (unless their sizes differ by
// 2^26). Sweeps stop when every column pair is orthogonal to working precision (quadratic
// convergence: 2-4 sweeps in practice); the cap only bounds the loop, as the columns are
// then orthogonal to rounding anyway.
template <class R, int N>
void left_singular(Mat<R, N> w, Vec<R, N>& sigma, Mat<R, N>& u) noexcept {
  const R eps = std::numeric_limits<R>::epsilon();
  Vec<R, N> norm2 = w.colwise().squaredNorm().transpose();  // updated by each rotation
  for (int sweep = 0; sweep < 16; ++sweep) {
    R largest = 0;  // largest relative off-diagonal |gamma| / sqrt(alpha beta) this sweep
    for (int p = 0; p < N - 1; ++p)
      for (int q = p + 1; q < N; ++q) {
        const R gamma = w.col(p).dot(w.col(q));
        // sqrt of each norm: their product overflows for columns beyond 1e77 (radius ratios).
        const R relative = abs(gamma) / (sqrt(norm2[p]) * sqrt(norm2[q]));
        if (!(relative > eps)) continue;
        largest = std::max(largest, relative);
        const R zeta = (norm2[q] - norm2[p]) / (2 * gamma);
        const R t = (zeta >= 0 ? R(1) : R(-1)) / (abs(zeta) + sqrt(R(1) + zeta * zeta));
        const R c = R(1) / sqrt(R(1) + t * t), s = c * t;
        const Vec<R, N> wp = w.col(p);
        w.col(p) = c * wp - s * w.col(q);
        w.col(q) = s * wp + c * w.col(q);
        norm2[p] -= t * gamma;
        norm2[q] += t * gamma;
      }
    // Quadratic convergence: a sweep that started within sqrt(eps) of orthogonality ends
    // at eps, so the confirming sweep is skipped.
    if (!(largest > sqrt(eps))) break;
  }
  for (int i = 0; i < N; ++i) {
    sigma[i] = w.col(i).norm();
    u.col(i) = w.col(i) / sigma[i];
  }
}

// A pair in query order: the sphere body s, the other body o, and whether s is argument a.
template <class T, int N>
struct OrderedPair {
  const Ellipsoid<T, N>& s;
  const Ellipsoid<T, N>& o;
  bool a_is_s;
};

template <class T, int N>
OrderedPair<T, N> order_pair(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) noexcept {
  const bool a_is_s = is_sphere_body(a, b);
  return {a_is_s ? a : b, a_is_s ? b : a, a_is_s};
}

template <class R, int N>
struct Reduced {
  Vec<R, N> e;          // semi-axes of O in the Z frame
  Vec<R, N> k;          // center of O in the Z frame (S is the unit ball at the origin)
  Mat<R, N> to_z;       // Z = to_z (X - K0)      = U^T diag(1/a) R0^T (X - K0)
  Mat<R, N> to_world;   // X = K0 + to_world Z    = K0 + R0 diag(a) U Z
  Mat<R, N> normal_map; // world normal of S at world point K0 + to_world Z: normal_map Z
};

template <class R, int N, class T>
Reduced<R, N> reduce(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o) noexcept {
  const Mat<R, N> R0 = work_axes<R>(s);
  const Vec<R, N> a = s.radii().template cast<R>();
  const Mat<R, N> sT = a.cwiseInverse().asDiagonal() * R0.transpose();  // diag(1/a) R0^T
  const Mat<R, N> L = sT * work_axes<R>(o) * o.radii().template cast<R>().asDiagonal();
  Reduced<R, N> r;
  Mat<R, N> U;
  left_singular(L, r.e, U);
  r.to_z = U.transpose() * sT;
  r.k = r.to_z * (o.center().template cast<R>() - s.center().template cast<R>());
  r.to_world = R0 * a.asDiagonal() * U;
  r.normal_map = R0 * a.cwiseInverse().asDiagonal() * U;
  return r;
}

}  // namespace ellipsect::detail
