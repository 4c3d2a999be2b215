#include <ellipsect/shapes.hpp>

#include "detail/instantiate.hpp"
#include "detail/show.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace ellipsect {
namespace {

using detail::show;

template <class Derived>
void require_finite(const Eigen::MatrixBase<Derived>& m, const std::string& field) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j))) {
        std::ostringstream name;
        name << field;
        if (m.cols() == 1)
          name << '[' << i << ']';
        else
          name << '(' << i << ',' << j << ')';
        throw InputError(name.str(), "must be finite (got " + show(m(i, j)) + ")");
      }
}

template <class T>
void require_positive(T value, const std::string& field) {
  if (!std::isfinite(value)) throw InputError(field, "must be finite (got " + show(value) + ")");
  if (!(value > T(0))) throw InputError(field, "must be > 0 (got " + show(value) + ")");
}

template <class T, int N>
void require_radii(const Vec<T, N>& radii) {
  for (int i = 0; i < N; ++i) require_positive(radii[i], "radii[" + std::to_string(i) + "]");
  if (radii.maxCoeff() > Ellipsoid<T, N>::max_aspect_ratio * radii.minCoeff())
    throw InputError("radii", "aspect ratio " + show(radii.maxCoeff() / radii.minCoeff()) + " exceeds the largest supported, " +
                                  show(Ellipsoid<T, N>::max_aspect_ratio));
}

// Orthonormalize by Householder QR (the Q factor, column signs kept as given).
template <class T, int N>
Mat<T, N> orthonormalized(const Mat<T, N>& m) {
  using W = double;
  const Mat<W, N> mw = m.template cast<W>();
  const Eigen::HouseholderQR<Mat<W, N>> qr(mw);
  Mat<W, N> q = qr.householderQ();
  const Mat<W, N> r = qr.matrixQR().template triangularView<Eigen::Upper>();
  for (int j = 0; j < N; ++j)
    if (r(j, j) < W(0)) q.col(j) = -q.col(j);
  return q.template cast<T>();
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
  require_finite(center, "center");
  require_finite(axes, "axes");
  require_radii(radii);
  const Mat<T, N> gram = axes.transpose() * axes - Mat<T, N>::Identity();
  const T dev = gram.cwiseAbs().maxCoeff();
  if (!(dev <= axes_tolerance))
    throw InputError("axes", "columns must be orthonormal (max |axes^T axes - I| = " + show(dev) + " > " +
                                 show(axes_tolerance) + ")");
  // Axes orthonormal to working precision are kept bit for bit (so rebuilding a body from
  // its own fields reproduces it exactly); others are orthonormalized.
  if (dev <= T(4 * N) * std::numeric_limits<T>::epsilon()) return Ellipsoid(center, axes, radii);
  return Ellipsoid(center, orthonormalized<T, N>(axes), radii);
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
  if (!std::isfinite(angle)) throw InputError("angle", "must be finite (got " + show(angle) + ")");
  const T c = std::cos(angle), s = std::sin(angle);
  Mat2<T> axes;
  axes << c, -s, s, c;
  return Ellipse2<T>::from_axes(center, axes, radii);
}

template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Quat<T>& rotation, const Vec3<T>& radii) {
  // Named in the order of Eigen's constructor Quaternion(w, x, y, z), not of its storage.
  const std::array<std::pair<T, const char*>, 4> parts = {
      {{rotation.w(), "quaternion.w"}, {rotation.x(), "quaternion.x"}, {rotation.y(), "quaternion.y"},
       {rotation.z(), "quaternion.z"}}};
  for (const auto& [value, field] : parts)
    if (!std::isfinite(value)) throw InputError(field, "must be finite (got " + show(value) + ")");
  const T tol = sizeof(T) >= sizeof(double) ? T(1e-9) : T(1e-5);
  const T n = rotation.norm();
  if (!(std::abs(n - T(1)) <= tol))
    throw InputError("quaternion", "must have unit norm (got |q| = " + show(n) + ")");
  return Ellipsoid3<T>::from_axes(center, rotation.normalized().toRotationMatrix(), radii);
}

template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Mat3<T>& rotation, const Vec3<T>& radii) {
  return Ellipsoid3<T>::from_axes(center, rotation, radii);
}

template <class T, int N>
Ellipsoid<T, N> make_ball(const Vec<T, N>& center, T radius) {
  require_positive(radius, "radius");
  return Ellipsoid<T, N>::from_axes(center, Mat<T, N>::Identity(), Vec<T, N>::Constant(radius));
}

#define ELLIPSECT_INSTANTIATE(T, N) \
  template class Ellipsoid<T, N>;   \
  template Ellipsoid<T, N> make_ball<T, N>(const Vec<T, N>&, T);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE
template Ellipse2<float> make_ellipse<float>(const Vec2<float>&, float, const Vec2<float>&);
template Ellipse2<double> make_ellipse<double>(const Vec2<double>&, double, const Vec2<double>&);
template Ellipsoid3<float> make_ellipsoid<float>(const Vec3<float>&, const Quat<float>&, const Vec3<float>&);
template Ellipsoid3<double> make_ellipsoid<double>(const Vec3<double>&, const Quat<double>&, const Vec3<double>&);
template Ellipsoid3<float> make_ellipsoid<float>(const Vec3<float>&, const Mat3<float>&, const Vec3<float>&);
template Ellipsoid3<double> make_ellipsoid<double>(const Vec3<double>&, const Mat3<double>&, const Vec3<double>&);

}  // namespace ellipsect
