// Classification in the reduced frame: S is the unit ball at the origin, O the
// axis-aligned ellipsoid (center k, semi-axes e).
//
//   origin outside O:  gap = |closest point of O| - 1 decides separated / touching;
//                      a deeper pair is O-inside-S when O's farthest point has norm <= 1.
//   origin inside O:   S is inside O when O's boundary is at least 1 away from the origin,
//                      O is inside S when its farthest point is within 1; both: equal.
//
// Every comparison with 1 allows the relative band `tol` (Options::tolerance): scaling S
// about its center by (1 + gap) makes it touch O, and the Perram-Wertheim factor mu of
// the pair satisfies |mu - 1| <= |gap|, so the band bounds mu too.
#pragma once

#include "reduce.hpp"
#include "secular.hpp"

#include <Eigen/Cholesky>

#include <limits>

namespace ellipsect::detail {

enum class ReducedRelation { separated, touching, overlapping, s_contains_o, o_contains_s, equal };

template <class R, int N>
R gap_reduced(const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  if (level_at_origin(e, k) <= R(0)) return -std::numeric_limits<R>::infinity();
  return closest_from_outside(e, k).norm - R(1);
}

// `margin` receives the smallest distance of a compared quantity from its threshold: a
// caller whose rounding error may exceed it re-decides in a wider type.
template <class R, int N>
ReducedRelation classify_reduced(const Vec<R, N>& e, const Vec<R, N>& k, R tol, R& margin) noexcept {
  margin = std::numeric_limits<R>::infinity();
  auto le = [&](R x, R threshold) {
    margin = std::min(margin, std::abs(x - threshold));
    return x <= threshold;
  };
  auto ge = [&](R x, R threshold) {
    margin = std::min(margin, std::abs(x - threshold));
    return x >= threshold;
  };
  const R q0 = level_at_origin(e, k);
  margin = std::abs(q0);
  if (q0 > R(0)) {
    const R d = closest_from_outside(e, k).norm;
    if (!le(d, R(1) + tol)) return ReducedRelation::separated;
    if (!le(d, R(1) - tol)) return ReducedRelation::touching;
    return le(farthest(e, k).norm, R(1) + tol) ? ReducedRelation::s_contains_o : ReducedRelation::overlapping;
  }
  const bool s_in_o = ge(closest_from_inside(e, k).norm, R(1) - tol);
  const bool o_in_s = le(farthest(e, k).norm, R(1) + tol);
  if (s_in_o && o_in_s) return ReducedRelation::equal;
  if (s_in_o) return ReducedRelation::o_contains_s;
  if (o_in_s) return ReducedRelation::s_contains_o;
  return ReducedRelation::overlapping;
}

// Rounding of reduced-frame distances: the SVD and the frame change carry about `ulps`
// ulps relative to |k|, O's largest semi-axis and the world positions in S units.
inline constexpr int reduced_frame_ulps = 32;

template <class R, int N, class T>
R reduced_rounding(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, const Vec<R, N>& e, const Vec<R, N>& k) noexcept {
  const R world = R(s.center().norm()) + R(o.center().norm());
  return R(reduced_frame_ulps) * std::numeric_limits<R>::epsilon() *
         (k.norm() + e.maxCoeff() + world / R(s.radii().minCoeff()));
}

// Certain separation from the circumscribed balls: their distance exceeds the sum of the
// radii by more than the band, so mu - 1 and hence the reduced gap exceed it too.
template <class R, int N, class T>
bool bounding_balls_apart(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, R tol) noexcept {
  const R dist = (o.center().template cast<R>() - s.center().template cast<R>()).norm();
  const R reach = R(s.radii().maxCoeff()) + R(o.radii().maxCoeff());
  return dist > reach * (R(1) + R(2) * tol + R(1e-9));
}

// Certain overlap from the inscribed balls (margin 1e-9 for rounding).
template <class R, int N, class T>
bool inscribed_balls_meet(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o) noexcept {
  const R dist = (o.center().template cast<R>() - s.center().template cast<R>()).norm();
  const R reach = R(s.radii().minCoeff()) + R(o.radii().minCoeff());
  return dist < reach * (R(1) - R(1e-9));
}

// A cheap certificate from the Perram-Wertheim function F(l) = l (1 - l) r^T C^-1 r,
// C = (1 - l) Ms^-1 + l Mo^-1, r = c_o - c_s, whose maximum over l is mu^2 (mu: the factor
// that makes the scaled bodies touch). Any single l bounds mu from below, so
// F(l) >= 1.01^2 certifies separation; and the point x(l) = c_s + (1 - l) Ms^-1 C^-1 r
// lies inside both bodies when its two quadrics are <= 0.98, which certifies overlap.
// l is the exact maximizer for two balls, rho_s / (rho_s + rho_o) with rho the support
// radii along r. The margins (1%) dwarf the rounding of F (relative eps * cond(C) <= 1e-8
// for aspect ratios up to 1e4, the range where the filter is used), so a certified answer
// is also the one the exact path would give, far outside the tangency band.
enum class Certificate { unknown, separated, overlapping };

template <class R, int N, class T>
Certificate pw_certificate(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o) noexcept {
  const auto aspect = [](const Ellipsoid<T, N>& e) { return e.radii().maxCoeff() / e.radii().minCoeff(); };
  if (aspect(s) > T(1e4) || aspect(o) > T(1e4)) return Certificate::unknown;
  const Mat<R, N> as = s.axes().template cast<R>(), ao = o.axes().template cast<R>();
  const Vec<R, N> rs = s.radii().template cast<R>(), ro = o.radii().template cast<R>();
  const Vec<R, N> cs = s.center().template cast<R>(), co = o.center().template cast<R>();
  const Vec<R, N> r = co - cs;
  const Mat<R, N> inv_s = as * rs.cwiseAbs2().asDiagonal() * as.transpose();
  const Mat<R, N> inv_o = ao * ro.cwiseAbs2().asDiagonal() * ao.transpose();
  const R rho_s = std::sqrt(r.dot(inv_s * r)), rho_o = std::sqrt(r.dot(inv_o * r));
  if (!(rho_s + rho_o > R(0))) return Certificate::unknown;
  const R l = rho_s / (rho_s + rho_o);
  const Eigen::LLT<Mat<R, N>> llt((R(1) - l) * inv_s + l * inv_o);
  if (llt.info() != Eigen::Success) return Certificate::unknown;
  const Vec<R, N> y = llt.solve(r);
  if (l * (R(1) - l) * r.dot(y) >= R(1.01 * 1.01)) return Certificate::separated;
  const Vec<R, N> x = cs + (R(1) - l) * (inv_s * y);
  const R qs = (as.transpose() * (x - cs)).cwiseQuotient(rs).squaredNorm();
  const R qo = (ao.transpose() * (x - co)).cwiseQuotient(ro).squaredNorm();
  return qs <= R(0.98) && qo <= R(0.98) ? Certificate::overlapping : Certificate::unknown;
}

}  // namespace ellipsect::detail
