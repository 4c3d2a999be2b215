// Shapes: ellipses (N = 2), ellipsoids (N = 3) and hyperellipsoids, as validated values.
//
// An ellipsoid is the closed set { center + axes * diag(radii) * u : |u| <= 1 }, or
// equivalently { x : (x - center)^T M (x - center) <= 1 } with M = axes diag(radii)^-2 axes^T.
// `axes` has orthonormal columns (the principal directions), `radii` are positive.
//
// Every factory validates its input once and throws InputError naming the offending
// field; a constructed Ellipsoid is always valid, so queries on it are noexcept.
//
// Range: every finite positive radius and finite center is accepted and supported by the
// queries, from subnormals to the largest double: they rescale each pair by a power of two
// (exactly), and compute pairs whose radii differ by more than 2^160 or whose coordinates
// exceed 2^340 times their largest radius in long double (docs/method.md, section 7).
// float bodies are computed in double, which holds every float length squared or cubed.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <stdexcept>
#include <string>

namespace ellipsect {
namespace detail {
struct ShapeAccess;
}

template <class T, int N> using Vec = Eigen::Matrix<T, N, 1>;
template <class T, int N> using Mat = Eigen::Matrix<T, N, N>;
template <class T> using Vec2 = Vec<T, 2>;
template <class T> using Vec3 = Vec<T, 3>;
template <class T> using Mat2 = Mat<T, 2>;
template <class T> using Mat3 = Mat<T, 3>;

// Thrown for invalid input; field() names the offending field, e.g. "radii[1]".
class InputError : public std::invalid_argument {
public:
  InputError(std::string field, const std::string& what)
      : std::invalid_argument("ellipsect: " + field + ": " + what), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

private:
  std::string field_;
};

template <class T, int N>
class Ellipsoid {
  static_assert(N >= 2, "ellipsect: dimension must be at least 2");

public:
  using Scalar = T;
  static constexpr int dim = N;

  // Largest accepted deviation max|axes^T axes - I|. Axes farther than 4 N eps from
  // orthonormal are re-orthonormalized (moving the shape by at most this relative amount);
  // closer ones are kept as given.
  static constexpr T axes_tolerance = sizeof(T) >= sizeof(double) ? T(1e-9) : T(1e-5);

  // center: finite; axes: finite, orthonormal columns (within axes_tolerance);
  // radii: finite and > 0. Throws InputError naming the field otherwise.
  static Ellipsoid from_axes(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& radii);

  // The quadric form (x - center)^T M (x - center) <= 1 (seed equations (1)-(2)); M must
  // be finite, symmetric (relative asymmetry <= 1e-12 for double, 1e-5 for float) and
  // positive definite with condition number below 1 / (64 eps); axes are M's eigenvectors,
  // radii M's eigenvalues^-1/2, accurate to about eps * cond(M) relative.
  static Ellipsoid from_quadric(const Vec<T, N>& center, const Mat<T, N>& M);

  const Vec<T, N>& center() const noexcept { return center_; }
  const Mat<T, N>& axes() const noexcept { return axes_; }
  const Vec<T, N>& radii() const noexcept { return radii_; }

  // The quadric matrix M = axes diag(radii)^-2 axes^T.
  Mat<T, N> quadric() const noexcept;
  // The same shape moved by `offset`.
  Ellipsoid translated(const Vec<T, N>& offset) const;

private:
  friend struct detail::ShapeAccess;  // exact power-of-two rescaling inside the queries
  Ellipsoid() = default;
  Vec<T, N> center_;
  Mat<T, N> axes_;
  Vec<T, N> radii_;
};

template <class T> using Ellipse2 = Ellipsoid<T, 2>;
template <class T> using Ellipsoid3 = Ellipsoid<T, 3>;

// An ellipse whose first axis makes `angle` radians with the x axis (counter-clockwise).
template <class T>
Ellipse2<T> make_ellipse(const Vec2<T>& center, T angle, const Vec2<T>& radii);

// An ellipsoid rotated by a unit quaternion (|q| within 1e-9 of 1 for double, 1e-5 for
// float; it is normalized). The axes are the columns of q's rotation matrix.
template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Eigen::Quaternion<T>& rotation,
                             const Vec3<T>& radii);

// An ellipsoid whose axes are the columns of a rotation (or any orthonormal) matrix.
template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Mat3<T>& rotation, const Vec3<T>& radii);

// A ball (circle, sphere) of the given radius.
template <class T, int N>
Ellipsoid<T, N> make_ball(const Vec<T, N>& center, T radius);

}  // namespace ellipsect
