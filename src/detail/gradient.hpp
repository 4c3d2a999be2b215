// Derivatives of a body's support radius and quadric with respect to its parameters
// (gradient.hpp's conventions), shared by the value-and-gradient functions.
#pragma once

#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/gradient.hpp>

#include "detail/axes.hpp"
#include "detail/secular.hpp"

#include <cmath>
#include <limits>


namespace ellipsect::detail {

// p x n: the rate of p . n as p turns about the origin with unit angular velocity about
// each world axis (2D: the counterclockwise rate).
template <class R, int N>
RotationVector<R, N> turn_rate(const Vec<R, N>& p, const Vec<R, N>& n) noexcept {
  if constexpr (N == 2) {
    return p[0] * n[1] - p[1] * n[0];
  } else {
    return p.cross(n);
  }
}

// The gradient of rho(n) = |diag(r) A^T n|, the body's support radius along the unit n:
//   d rho / d r_i = r_i (A^T n)_i^2 / rho,   d rho / d phi = p x n,   d rho / d center = 0,
// with p = A diag(r^2) A^T n / rho the body's support point less its center (also stored in
// *support where given). Formed from diag(r) A^T n / rho (entries at most 1), so no length is
// squared.
template <class R, class T, int N>
BodyGradient<R, N> support_radius_gradient(const Ellipsoid<T, N>& body, const Vec<R, N>& n,
                                           Vec<R, N>* support = nullptr) noexcept {
  const Mat<R, N> axes = work_axes<R>(body);
  const Vec<R, N> r = body.radii().template cast<R>();
  const Vec<R, N> q = axes.transpose() * n;
  Vec<R, N> w = r.cwiseProduct(q);
  w /= stable_norm<R, N>(w);
  const Vec<R, N> p = axes * r.cwiseProduct(w);
  if (support != nullptr) *support = p;
  BodyGradient<R, N> out;
  out.center.setZero();
  out.radii = w.cwiseProduct(q);
  out.orientation = turn_rate<R, N>(p, n);
  return out;
}

template <class R, int N>
RotationVector<R, N> times(const RotationVector<R, N>& v, R factor) noexcept {
  if constexpr (N == 2) {
    return v * factor;
  } else {
    return Vec<R, 3>(v * factor);
  }
}

// v rounded to T.
template <class T, class R, int N>
RotationVector<T, N> rotation_in(const RotationVector<R, N>& v) noexcept {
  if constexpr (N == 2) {
    return T(v);
  } else {
    return v.template cast<T>();
  }
}

// factor * g, rounded to T.
template <class T, class R, int N>
BodyGradient<T, N> gradient_in(const BodyGradient<R, N>& g, R factor) noexcept {
  BodyGradient<T, N> out;
  out.center = (g.center * factor).template cast<T>();
  out.radii = (g.radii * factor).template cast<T>();
  out.orientation = rotation_in<T, R, N>(times<R, N>(g.orientation, factor));
  return out;
}

// Every component x: 0 where the value does not depend on the parameters, NaN where no
// derivative is computed.
template <class T, int N>
BodyGradient<T, N> constant_gradient(T x) noexcept {
  BodyGradient<T, N> out;
  out.center.setConstant(x);
  out.radii.setConstant(x);
  if constexpr (N == 2) {
    out.orientation = x;
  } else {
    out.orientation.setConstant(x);
  }
  return out;
}

// signed_distance_gradient of the body a and a shape (shapes' headers), from the signed
// distance d = max over unit n of (min over the shape of n . y) - n . center(a) - rho_a(n)
// (value, its normal n the maximizer). a's part as against a body (envelope theorem);
// the shape's from shape(n, p, d) (in R): the point of the shape where it touches a moved by
// -d n is p + d n less a's center, p a's support point along n less its center (a material
// point of the shape moved at velocity u changes d at the rate n . u). A value with no normal
// (did_not_converge) gets NaN for a's part and shape(NaN, NaN, d) for the shape's.
template <class T, int N, class G, class Shape>
DistanceGradient<T, N, G> shape_distance_gradient(const Ellipsoid<T, N>& a, const Distance<T, N>& value,
                                                  Shape&& shape) noexcept {
  using R = std::conditional_t<(sizeof(T) < sizeof(double)), double, T>;
  const bool known = value.status != DistanceStatus::did_not_converge && value.normal.allFinite();
  const Vec<R, N> n = known ? Vec<R, N>(value.normal.template cast<R>()) : Vec<R, N>::Constant(std::numeric_limits<R>::quiet_NaN());
  Vec<R, N> p;
  BodyGradient<R, N> ga = support_radius_gradient<R>(a, n, &p);
  ga.center = n;
  return {value, gradient_in<T>(ga, R(-1)), shape(n, p, R(value.distance))};
}

// first_contact_gradient's answer before the derivatives of a hit: 0 where the bodies overlap
// at the start (the time is 0 nearby), NaN otherwise.
template <class T, int N>
ContactGradient<T, N> unanswered_gradient(const Contact<T, N>& value) noexcept {
  const T x = value.status == ContactStatus::overlapping_at_start ? T(0) : std::numeric_limits<T>::quiet_NaN();
  const BodyGradient<T, N> g = constant_gradient<T, N>(x);
  return {value, g, g, Vec<T, N>::Constant(x), Vec<T, N>::Constant(x), g.orientation, g.orientation};
}

// exp(-theta [u]x) v for the rotation vector theta = theta u: v turned back by theta.
template <class R, int N>
RotationVector<R, N> turned_back(const RotationVector<R, N>& theta, const RotationVector<R, N>& v) noexcept {
  if constexpr (N == 2) {
    return v;
  } else {
    const R angle = theta.norm();
    if (!(angle > R(0))) return v;
    const Vec<R, 3> u = theta / angle;
    return Vec<R, 3>(v * std::cos(angle) - std::sin(angle) * u.cross(v) + (R(1) - std::cos(angle)) * u.dot(v) * u);
  }
}

// J(theta)^T v, J the left Jacobian of the rotation group: exp([theta + d]x) =
// exp([J(theta) d]x) exp([theta]x) to first order in d, and
// J^T = I - (1 - cos|theta|) / |theta|^2 [theta]x + (|theta| - sin|theta|) / |theta|^3 [theta]x^2
// (series below |theta| = 1e-4, where the closed forms cancel).
template <class R, int N>
RotationVector<R, N> jacobian_transposed(const RotationVector<R, N>& theta, const RotationVector<R, N>& v) noexcept {
  if constexpr (N == 2) {
    return v;
  } else {
    const R angle = theta.norm(), a2 = angle * angle;
    R c1, c2;  // (1 - cos) / angle^2, (angle - sin) / angle^3
    if (angle < R(1e-4)) {
      c1 = R(0.5) - a2 / R(24);
      c2 = R(1) / R(6) - a2 / R(120);
    } else {
      c1 = (R(1) - std::cos(angle)) / a2;
      c2 = (angle - std::sin(angle)) / (a2 * angle);
    }
    const Vec<R, 3> tv = theta.cross(v);
    return Vec<R, 3>(v - c1 * tv + c2 * theta.cross(tv));
  }
}

// The derivatives of a hit's time t (contact.hpp's first_contact_gradient) from the bodies at
// t (a_t, b_t), the normal n there and the motions; NaN where the closing speed is not > 0.
template <class T, int N, class R>
void contact_time_gradient(ContactGradient<T, N>& out, const Ellipsoid<T, N>& a_t, const Ellipsoid<T, N>& b_t,
                           const Vec<R, N>& velocity_a, const Vec<R, N>& velocity_b,
                           const RotationVector<R, N>& omega_a, const RotationVector<R, N>& omega_b) noexcept {
  const Vec<R, N> n = out.value.normal.template cast<R>();
  const R t = R(out.value.time);
  // dg/dtheta of the support radii at t: g = n . (c_b - c_a) - rho_a - rho_b.
  const BodyGradient<R, N> ra = support_radius_gradient<R>(a_t, n), rb = support_radius_gradient<R>(b_t, n);
  auto dot = [](const RotationVector<R, N>& x, const RotationVector<R, N>& y) {
    if constexpr (N == 2) {
      return x * y;
    } else {
      return x.dot(y);
    }
  };
  const R closing = n.dot(velocity_a - velocity_b) + dot(ra.orientation, omega_a) + dot(rb.orientation, omega_b);
  if (!(closing > R(0))) return;
  const R k = R(-1) / closing;
  // dt/dtheta = (dg/dtheta) / closing.
  auto body = [&](const BodyGradient<R, N>& rho, const Vec<R, N>& center, const RotationVector<R, N>& omega,
                  BodyGradient<T, N>& g, Vec<T, N>& velocity, RotationVector<T, N>& angular_velocity) {
    BodyGradient<R, N> d = rho;  // times -1 / closing below
    d.center = center;
    d.orientation = turned_back<R, N>(RotationVector<R, N>(times<R, N>(omega, t)), rho.orientation);
    g = gradient_in<T>(d, k);
    velocity = (center * (t * k)).template cast<T>();
    angular_velocity = rotation_in<T, R, N>(times<R, N>(
        jacobian_transposed<R, N>(RotationVector<R, N>(times<R, N>(omega, t)), rho.orientation), t * k));
  };
  body(ra, n, omega_a, out.a, out.velocity_a, out.angular_velocity_a);
  body(rb, Vec<R, N>(-n), omega_b, out.b, out.velocity_b, out.angular_velocity_b);
}

}  // namespace ellipsect::detail
