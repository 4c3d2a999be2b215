// The mechanics of a uniform solid ellipse or ellipsoid, for HardBodies and jam_packing:
// its volume, its principal moments of inertia, and the spin's algebra in 2D (a scalar
// angular velocity) and 3D (a vector).
#pragma once

#include <ellipsect/contact.hpp>
#include <ellipsect/shapes.hpp>

#include <cmath>
#include <numbers>

namespace ellipsect::packing {

template <int N>
using Spin = decltype(RigidMotion<double, N>::angular_velocity);

template <int N>
double volume(const Vec<double, N>& radii) {
  return (N == 2 ? std::numbers::pi : 4.0 / 3.0 * std::numbers::pi) * radii.prod();
}

// Principal moments of a body of mass m along its axes (2D: about the normal).
template <int N>
Vec<double, N == 2 ? 1 : 3> inertia(const Ellipsoid<double, N>& s, double m) {
  const Vec<double, N> r2 = s.radii().cwiseProduct(s.radii());
  if constexpr (N == 2) {
    return Vec<double, 1>(m * (r2[0] + r2[1]) / 4);
  } else {
    return m / 5 * Vec<double, 3>(r2[1] + r2[2], r2[0] + r2[2], r2[0] + r2[1]);
  }
}

// I^-1 applied to a torque (2D: a scalar), in the world frame of shape s.
template <int N>
Spin<N> inverse_inertia(const Ellipsoid<double, N>& s, double m, const Spin<N>& torque) {
  if constexpr (N == 2)
    return torque / inertia<2>(s, m)[0];
  else
    return s.axes() * (s.axes().transpose() * torque).cwiseQuotient(inertia<3>(s, m));
}

// omega . I omega.
template <int N>
double spin_energy(const Ellipsoid<double, N>& s, double m, const Spin<N>& w) {
  if constexpr (N == 2) {
    return inertia<2>(s, m)[0] * w * w;
  } else {
    const Vec<double, 3> body = s.axes().transpose() * w;
    return body.dot(inertia<3>(s, m).cwiseProduct(body));
  }
}

// r x n (2D: its normal component).
template <int N>
Spin<N> cross(const Vec<double, N>& r, const Vec<double, N>& n) {
  if constexpr (N == 2)
    return r.x() * n.y() - r.y() * n.x();
  else
    return r.cross(n);
}

template <int N>
double dot_spin(const Spin<N>& x, const Spin<N>& y) {
  if constexpr (N == 2)
    return x * y;
  else
    return x.dot(y);
}

template <int N>
bool finite_spin(const Spin<N>& w) {
  if constexpr (N == 2)
    return std::isfinite(w);
  else
    return w.allFinite();
}

// Velocity of the material point at r from the center: v + omega x r.
template <int N>
Vec<double, N> point_velocity(const RigidMotion<double, N>& m, const Vec<double, N>& r) {
  if constexpr (N == 2)
    return m.velocity + Vec<double, 2>(-m.angular_velocity * r[1], m.angular_velocity * r[0]);
  else
    return m.velocity + m.angular_velocity.cross(r);
}

}  // namespace ellipsect::packing
