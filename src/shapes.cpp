// The bodies' factories (shapes.hpp); the obstacles' are in their own files (obstacles/).
#include <ellipsect/shapes.hpp>

#include "detail/axes.hpp"
#include "detail/instantiate.hpp"
#include "detail/shape_access.hpp"
#include "detail/show.hpp"
#include "detail/math.hpp"
#include "detail/validate.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace ellipsect {
namespace {

using detail::show;
using detail::element_name;
using detail::require_finite;
using detail::require_positive;
using detail::moved;
using detail::throw_not_finite;

template <class T>
constexpr T quaternion_tolerance = sizeof(T) >= sizeof(double) ? T(1e-9) : T(1e-5);

// A quaternion farther than quaternion_tolerance from unit norm: its first non-finite
// component, named in the order of Eigen's constructor Quaternion(w, x, y, z) (not of its
// storage), or its norm.
template <class T>
[[noreturn, gnu::cold, gnu::noinline]] void throw_bad_quaternion(const Quat<T>& q) {
  for (const auto& [value, field] : {std::pair{q.w(), "quaternion.w"}, std::pair{q.x(), "quaternion.x"},
                                     std::pair{q.y(), "quaternion.y"}, std::pair{q.z(), "quaternion.z"}})
    if (!isfinite(value)) throw_not_finite(field, value);
  throw InputError("quaternion", "must have unit norm (got |q| = " + show(q.norm()) + ")");
}

template <class T, int N>
[[noreturn, gnu::cold, gnu::noinline]] void throw_aspect_ratio(const Vec<T, N>& radii) {
  throw InputError("radii", "aspect ratio " + show(radii.maxCoeff() / radii.minCoeff()) +
                                " exceeds the largest supported, " + show(Ellipsoid<T, N>::max_aspect_ratio));
}

template <class T, int N>
void require_radii(const Vec<T, N>& radii) {
  for (int i = 0; i < N; ++i) require_positive(radii[i], "radii", i);
  if (radii.maxCoeff() > Ellipsoid<T, N>::max_aspect_ratio * radii.minCoeff()) throw_aspect_ratio<T, N>(radii);
}

template <class T>
[[noreturn, gnu::cold, gnu::noinline]] void throw_not_orthonormal(T dev, T tolerance) {
  throw InputError("axes",
                   "columns must be orthonormal (max |axes^T axes - I| = " + show(dev) + " > " + show(tolerance) + ")");
}

// max |axes^T axes - I|.
template <class T, int N>
T orthonormality_deviation(const Mat<T, N>& axes) {
  return (axes.transpose() * axes - Mat<T, N>::Identity()).cwiseAbs().maxCoeff();
}

// Whether from_axes accepts (center, axes, radii) and stores them as given: every value
// finite, radii > 0 within max_aspect_ratio, and |axes^T axes - I| <= 4 N eps entrywise.
// The factories' good path: comparisons combined without a branch per value, NaN and inf
// failing each (c - c is 0 only for a finite c; a non-finite axis makes a Gram entry NaN or
// inf), no string, no exception. The Gram matrix is summed row by row (its upper triangle:
// it is symmetric to the bit), reading each entry of axes alone: loads of adjacent entries
// in pairs straddled the stores that had just written the axes, and stalled.
template <class T, int N>
[[gnu::always_inline]] inline bool kept_as_given(const Vec<T, N>& center, const Mat<T, N>& axes,
                                                 const Vec<T, N>& radii) {
  bool ok = true;
  for (int i = 0; i < N; ++i) {
    ok &= center[i] - center[i] == T(0);
    ok &= radii[i] > T(0);
    ok &= radii[i] <= std::numeric_limits<T>::max();
  }
  ok &= radii.maxCoeff() <= Ellipsoid<T, N>::max_aspect_ratio * radii.minCoeff();
  T gram[N][N] = {};
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i <= j; ++i) gram[i][j] += axes(k, i) * axes(k, j);
  const T close = T(4 * N) * std::numeric_limits<T>::epsilon();
  for (int j = 0; j < N; ++j)
    for (int i = 0; i <= j; ++i) ok &= abs(gram[i][j] - T(i == j)) <= close;
  return ok;
}

// Orthonormalize by Householder QR (the Q factor, column signs kept as given); rarely needed.
template <class T, int N>
[[gnu::noinline]] Mat<T, N> orthonormalized(const Mat<T, N>& m) {
  using W = double;
  const Mat<W, N> mw = m.template cast<W>();
  const Eigen::HouseholderQR<Mat<W, N>> qr(mw);
  Mat<W, N> q = qr.householderQ();
  const Mat<W, N> r = qr.matrixQR().template triangularView<Eigen::Upper>();
  for (int j = 0; j < N; ++j)
    if (r(j, j) < W(0)) q.col(j) = -q.col(j);
  return q.template cast<T>();
}

// The checks of from_axes in order, each throwing InputError naming its field, and the
// axes to store: as given when orthonormal to working precision (so rebuilding a body from
// its own fields reproduces it exactly), else orthonormalized. Only for input that
// kept_as_given rejects.
template <class T, int N>
[[gnu::cold, gnu::noinline]] Mat<T, N> checked_axes(const Vec<T, N>& center, const Mat<T, N>& axes,
                                                    const Vec<T, N>& radii) {
  require_finite(center, "center");
  require_finite(axes, "axes");
  require_radii(radii);
  const T dev = orthonormality_deviation<T, N>(axes);
  if (!(dev <= Ellipsoid<T, N>::axes_tolerance)) throw_not_orthonormal<T>(dev, Ellipsoid<T, N>::axes_tolerance);
  if (dev <= T(4 * N) * std::numeric_limits<T>::epsilon()) return axes;
  return orthonormalized<T, N>(axes);
}

// The body (center, axes(), radii) from from_axes' checks.
template <class T, int N, class Axes>
[[gnu::cold, gnu::noinline]] Ellipsoid<T, N> checked_body(const Vec<T, N>& center, const Axes& axes,
                                                         const Vec<T, N>& radii) {
  const Mat<T, N> a = axes();
  return detail::ShapeAccess::unchecked<T, N>(center, checked_axes<T, N>(center, a, radii), radii);
}

// Every factory ends here: the body (center, axes, radii) as given when kept_as_given accepts
// it, else checked_body(center, recompute, radii), recompute() returning axes again. Inlined
// into each factory, and the rare path recomputes the axes rather than taking their address,
// so that axes a factory computes (from a quaternion, an angle) stay in registers: stored to
// the stack and read back by columns they stalled on store forwarding, about 10 ns per body.
template <class T, int N, class Axes>
[[gnu::always_inline]] inline Ellipsoid<T, N> body(const Vec<T, N>& center, const Mat<T, N>& axes,
                                                   const Vec<T, N>& radii, const Axes& recompute) {
  if (kept_as_given<T, N>(center, axes, radii)) [[likely]]
    return detail::ShapeAccess::unchecked<T, N>(center, axes, radii);
  return checked_body<T, N>(center, recompute, radii);
}

}  // namespace

template <class T, int N>
Ellipsoid<T, N>::Ellipsoid(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& radii) noexcept {
  Eigen::Map<Vec<T, N>>(center_.data()) = center;
  Eigen::Map<Mat<T, N>>(axes_.data()) = axes;
  Eigen::Map<Vec<T, N>>(radii_.data()) = radii;
}

template <class T, int N>
Ellipsoid<T, N> Ellipsoid<T, N>::from_axes(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& radii) {
  return body<T, N>(center, axes, radii, [&] { return axes; });
}

template <class T, int N>
Ellipsoid<T, N> Ellipsoid<T, N>::from_quadric(const Vec<T, N>& center, const Mat<T, N>& M) {
  require_finite(center, "center");
  require_finite(M, "M");
  const T scale = M.cwiseAbs().maxCoeff();
  const T sym_tol = sizeof(T) >= sizeof(double) ? T(1e-12) : T(1e-5);
  if (!(scale > T(0))) throw InputError("M", "must be positive definite (got the zero matrix)");
  const T asym = (M - M.transpose()).cwiseAbs().maxCoeff();
  if (asym > sym_tol * scale)
    throw InputError("M", "must be symmetric (max |M - M^T| = " + show(asym) + ")");
  using W = double;
  // Eigen's tridiagonalization does not take unaligned (DontAlign) matrices.
  using Aligned = Eigen::Matrix<W, N, N>;
  const Aligned Mw = (M.template cast<W>() + M.template cast<W>().transpose()) / W(2);
  const Eigen::SelfAdjointEigenSolver<Aligned> eig(Mw);
  const Vec<W, N> lambda = eig.eigenvalues();  // ascending
  const W floor = W(64) * std::numeric_limits<T>::epsilon() * lambda[N - 1];
  if (!(lambda[0] > floor))
    throw InputError("M", "must be positive definite (smallest eigenvalue " + show(lambda[0]) +
                              ", largest " + show(lambda[N - 1]) + ")");
  return Ellipsoid(center, orthonormalized<T, N>(eig.eigenvectors().template cast<T>()),
                   lambda.cwiseSqrt().cwiseInverse().template cast<T>());
}

template <class T, int N>
Mat<T, N> Ellipsoid<T, N>::quadric() const noexcept {
  return axes() * radii().cwiseAbs2().cwiseInverse().asDiagonal() * axes().transpose();
}

template <class T, int N>
Ellipsoid<T, N> Ellipsoid<T, N>::translated(const Vec<T, N>& offset) const {
  const Vec<T, N> center = this->center() + offset;
  require_finite(center, "center");
  return Ellipsoid(center, axes(), radii());
}

template <class T>
Ellipse2<T> make_ellipse(const Vec2<T>& center, T angle, const Vec2<T>& radii) {
  if (!isfinite(angle)) throw_not_finite("angle", angle);
  const auto axes = [angle] {
    const T c = cos(angle), s = sin(angle);
    Mat2<T> m;
    m << c, -s, s, c;
    return m;
  };
  return body<T, 2>(center, axes(), radii, axes);
}

namespace {

// The rotation matrix of q / |q| for |q|^2 = n2 within 2 tol of 1: R = I + c P, P the
// products of Eigen's toRotationMatrix (2 x y - 2 w z, ...; its c = 1 assumes |q| = 1) and
// c = 2 - n2 in place of 1 / n2 = 1 - d + d^2 - ... (d = n2 - 1): they differ by d^2 <=
// 4 tol^2 (4e-18 in double, 4e-10 in float), below a rounding of c. No square root and no
// division, and P is formed while n2 is: each entry is within a few ulps of the rotation
// matrix of q / |q| (tests/unit/shapes_test.cpp), and body()'s Gram matrix checks
// orthonormality as for any axes.
template <class T>
[[gnu::always_inline]] inline Mat3<T> unit_rotation(const Quat<T>& q, T n2) {
  const T c = T(2) - n2;
  const T w = q.w(), x = q.x(), y = q.y(), z = q.z(), tx = T(2) * x, ty = T(2) * y, tz = T(2) * z;
  const T wx = tx * w, wy = ty * w, wz = tz * w, xx = tx * x, xy = ty * x, xz = tz * x;
  const T yy = ty * y, yz = tz * y, zz = tz * z;
  Mat3<T> m;
  m << T(1) - c * (yy + zz), c * (xy - wz), c * (xz + wy),  //
      c * (xy + wz), T(1) - c * (xx + zz), c * (yz - wx),   //
      c * (xz - wy), c * (yz + wx), T(1) - c * (xx + yy);
  return m;
}

}  // namespace

template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Quat<T>& rotation, const Vec3<T>& radii) {
  // |q|^2 within 2 tol of 1 (|q| within tol, to tol^2); NaN or inf unless every component
  // is finite.
  const T n2 = rotation.squaredNorm();
  if (!(abs(n2 - T(1)) <= T(2) * quaternion_tolerance<T>)) [[unlikely]]
    throw_bad_quaternion(rotation);
  const auto axes = [&] { return unit_rotation<T>(rotation, n2); };
  return body<T, 3>(center, axes(), radii, axes);
}

template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Mat3<T>& rotation, const Vec3<T>& radii) {
  return body<T, 3>(center, rotation, radii, [&] { return rotation; });
}

template <class T, int N>
Ellipsoid<T, N> make_ball(const Vec<T, N>& center, T radius) {
  require_positive(radius, "radius");
  const auto identity = [] { return Mat<T, N>(Mat<T, N>::Identity()); };
  return body<T, N>(center, identity(), Vec<T, N>::Constant(radius), identity);
}

namespace {

// An array of n rows of `per_row` values, or InputError naming it.
void require_rows(std::size_t size, std::size_t n, std::size_t per_row, const char* name) {
  if (size != n * per_row)
    throw InputError(name, "expected " + std::to_string(n * per_row) + " values (" + std::to_string(n) + " rows of " +
                               std::to_string(per_row) + "), got " + std::to_string(size));
}

// make(i) for every row i < n; the first InputError rethrown as RowInputError naming row i.
template <class Make>
void for_each_row(std::size_t n, const Make& make) {
  std::size_t i = 0;
  try {
    for (; i < n; ++i) make(i);
  } catch (const InputError& e) {
    const std::string what = e.what();  // "ellipsect: <field>: <detail>", as InputError builds it
    throw RowInputError(i, e.field(), what.substr(std::string("ellipsect: ").size() + e.field().size() + 2));
  }
}

template <class T, int N>
Vec<T, N> row(std::span<const T> values, std::size_t i) {
  return Eigen::Map<const Vec<T, N>>(values.data() + N * i);
}

}  // namespace

template <class T>
void make_ellipses(std::span<const T> centers, std::span<const T> angles, std::span<const T> radii,
                   std::span<Ellipse2<T>> out) {
  require_rows(centers.size(), out.size(), 2, "centers");
  if (!angles.empty()) require_rows(angles.size(), out.size(), 1, "angles");
  require_rows(radii.size(), out.size(), 2, "radii");
  for_each_row(out.size(), [&](std::size_t i) {
    out[i] = make_ellipse<T>(row<T, 2>(centers, i), angles.empty() ? T(0) : angles[i], row<T, 2>(radii, i));
  });
}

template <class T>
Quat<T> normalized_quaternion(const Quat<T>& q) {
  const T norm = q.coeffs().norm();
  return abs(norm - T(1)) <= T(normalize_tolerance) ? Quat<T>(q.coeffs() / norm) : q;
}

template <class T, int N>
Mat<T, N> normalized_rotation(const Mat<T, N>& rotation) {
  if (!((rotation.transpose() * rotation - Mat<T, N>::Identity()).cwiseAbs().maxCoeff() <= T(normalize_tolerance)))
    return rotation;
  const Eigen::JacobiSVD<Mat<T, N>> svd(rotation, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

template <class T>
void make_ellipsoids(std::span<const T> centers, std::span<const T> quaternions, std::span<const T> radii,
                     std::span<Ellipsoid3<T>> out, Orientations orientations) {
  require_rows(centers.size(), out.size(), 3, "centers");
  if (!quaternions.empty()) require_rows(quaternions.size(), out.size(), 4, "quaternions");
  require_rows(radii.size(), out.size(), 3, "radii");
  for_each_row(out.size(), [&](std::size_t i) {
    const T* q = quaternions.empty() ? nullptr : quaternions.data() + 4 * i;
    const Quat<T> given = q ? Quat<T>(q[0], q[1], q[2], q[3]) : Quat<T>(1, 0, 0, 0);
    const Quat<T> rotation = orientations == Orientations::normalized ? normalized_quaternion<T>(given) : given;
    out[i] = make_ellipsoid<T>(row<T, 3>(centers, i), rotation, row<T, 3>(radii, i));
  });
}

template <class T, int N>
void make_bodies(std::span<const T> centers, std::span<const T> rotations, std::span<const T> radii,
                 std::span<Ellipsoid<T, N>> out, Orientations orientations) {
  require_rows(centers.size(), out.size(), N, "centers");
  require_rows(rotations.size(), out.size(), N * N, "rotations");
  require_rows(radii.size(), out.size(), N, "radii");
  for_each_row(out.size(), [&](std::size_t i) {
    const Mat<T, N> given = Eigen::Map<const Eigen::Matrix<T, N, N, Eigen::RowMajor>>(rotations.data() + N * N * i);
    const Mat<T, N> axes = orientations == Orientations::normalized ? normalized_rotation<T, N>(given) : given;
    out[i] = Ellipsoid<T, N>::from_axes(row<T, N>(centers, i), axes, row<T, N>(radii, i));
  });
}

#define ELLIPSECT_INSTANTIATE(T, N) \
  template class Ellipsoid<T, N>;   \
  template Ellipsoid<T, N> make_ball<T, N>(const Vec<T, N>&, T); \
  template void make_bodies<T, N>(std::span<const T>, std::span<const T>, std::span<const T>, std::span<Ellipsoid<T, N>>, \
                                  Orientations);                                                                     \
  template Mat<T, N> normalized_rotation<T, N>(const Mat<T, N>&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE
#define ELLIPSECT_INSTANTIATE(T)                                                                               \
  template Ellipse2<T> make_ellipse<T>(const Vec2<T>&, T, const Vec2<T>&);                                       \
  template Ellipsoid3<T> make_ellipsoid<T>(const Vec3<T>&, const Quat<T>&, const Vec3<T>&);                      \
  template Ellipsoid3<T> make_ellipsoid<T>(const Vec3<T>&, const Mat3<T>&, const Vec3<T>&);                      \
  template void make_ellipses<T>(std::span<const T>, std::span<const T>, std::span<const T>, std::span<Ellipse2<T>>); \
  template void make_ellipsoids<T>(std::span<const T>, std::span<const T>, std::span<const T>,                   \
                                   std::span<Ellipsoid3<T>>, Orientations);                                        \
  template Quat<T> normalized_quaternion<T>(const Quat<T>&);
ELLIPSECT_FOR_EACH_TYPE(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
