// Derivatives of query results with respect to the bodies' parameters: the types shared by
// the value-and-gradient functions, which live beside the values they differentiate
// (signed_distance_gradient in distance.hpp, perram_wertheim_gradient in
// contact_function.hpp, first_contact_gradient in contact.hpp).
//
// Parameters of a body: its center, its radii (in the stored order of its axes), and its
// orientation as a world-frame rotation vector phi at the current pose: the body turned about
// its center to axes exp([phi]x) * axes (2D: phi a counterclockwise angle), differentiated at
// phi = 0. So d/dphi of a quantity q is the rate of q as the body spins about its center
// with unit angular velocity about each world axis (quaternion_gradient below carries it to
// a quaternion's components).
//
// Method: at an exact solution the derivatives follow in closed form, with no second solve:
// optimal values by the envelope theorem (the derivative of the maximized function at the
// maximizer), solution times by implicit differentiation of the contact condition. Each
// function states where its value is not differentiable and what it returns there.
#pragma once

#include <ellipsect/shapes.hpp>

#include <type_traits>

namespace ellipsect {

// A rotation vector: an angle in 2D, a world-frame axis times angle in 3D.
template <class T, int N>
using RotationVector = std::conditional_t<N == 2, T, Vec<T, 3>>;

// The gradient of a scalar with respect to one body's parameters.
template <class T, int N>
struct BodyGradient {
  Vec<T, N> center;
  RotationVector<T, N> orientation;
  Vec<T, N> radii;
};
static_assert(detail::has_plain_layout<BodyGradient<float, 2>, float[2], float, float[2]> &&
              detail::has_plain_layout<BodyGradient<double, 3>, double[3], double[3], double[3]>);

// The derivatives of a point (a vector quantity) by one body's parameters: column j by
// parameter j, so center(i, j) = d point_i / d center_j.
template <class T, int N>
using TurnJacobian = Eigen::Matrix<T, N, (N == 2 ? 1 : 3), Eigen::DontAlign>;
template <class T, int N>
struct BodyJacobian {
  Mat<T, N> center;
  TurnJacobian<T, N> orientation;
  Mat<T, N> radii;
};
static_assert(detail::has_plain_layout<BodyJacobian<float, 2>, float[4], float[2], float[4]> &&
              detail::has_plain_layout<BodyJacobian<double, 3>, double[9], double[9], double[9]>);

// The gradient by the components of a quaternion q = (w, x, y, z) of a quantity whose gradient
// by the world rotation vector is g, for a body whose axes are those of q / |q| (any nonzero
// norm). A world turn dphi takes q to (1, dphi / 2) q, so a change dq is the turn
// dphi = 2 vec(dq conj(q)) / |q|^2 = 2 (w dv - dw v + v x dv) / |q|^2 (v = (x, y, z); a change
// along q turns nothing), and
//     d/dw = -2 (v . g) / |q|^2,   d/dv = 2 (w g + g x v) / |q|^2.
// Exact up to rounding (a few ulps of |g|).
template <class T>
Vec<T, 4> quaternion_gradient(const Vec<T, 4>& q, const Vec<T, 3>& g) noexcept {
  const T w = q[0];
  const Vec<T, 3> v = q.template tail<3>();
  const T k = T(2) / q.squaredNorm();
  Vec<T, 4> out;
  out[0] = -k * v.dot(g);
  out.template tail<3>() = k * (w * g + g.cross(v));
  return out;
}

}  // namespace ellipsect
