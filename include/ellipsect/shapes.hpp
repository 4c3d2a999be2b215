// Shapes: ellipses (N = 2), ellipsoids (N = 3) and hyperellipsoids, as validated values.
//
// An ellipsoid is the closed set { center + axes * diag(radii) * u : |u| <= 1 }, or
// equivalently { x : (x - center)^T M (x - center) <= 1 } with M = axes diag(radii)^-2 axes^T.
// `axes` has orthonormal columns (the principal directions), `radii` are positive.
//
// Every factory validates its input once and throws InputError naming the offending
// field; a constructed Ellipsoid is always valid, so queries on it are noexcept. Validation
// costs a few comparisons and a Gram matrix (axes^T axes, to check orthonormality), with
// no allocation or string work unless the input is rejected: about 5 ns for make_ball, 7 ns
// for an ellipse from axes, 7-10 ns for an ellipsoid from a rotation matrix; a quaternion
// adds its matrix (about 11 ns in all), an angle its sine and cosine (about 15 ns;
// bench/RESULTS.md). The factories over arrays (make_ellipsoids, ...) do the same per row,
// naming the first bad row.
//
// ABI. The public types are laid out the same whatever the compiler flags (-march, -m...)
// and Eigen settings (EIGEN_MAX_STATIC_ALIGN_BYTES, EIGEN_DONT_ALIGN) of the program that
// includes these headers: Vec and Mat are unaligned Eigen matrices (Eigen::DontAlign,
// stored as plain arrays of T), and the static_asserts after each public type pin its size
// and alignment to those of the same members with Vec and Mat as arrays of T, so a layout
// that could differ from the library's is a compile error, never a silent misreading.
// Aligned Eigen vectors and matrices (Eigen::Vector3d, ...) convert implicitly wherever a
// Vec or Mat is taken.
//
// Range: every finite center and every finite positive radius is accepted and supported by
// the queries, from subnormals to the largest double, for bodies whose aspect ratio
// (largest / smallest radius) is at most max_aspect_ratio = 1e8: they rescale each pair by a power of two
// (exactly), and compute pairs whose radii differ by more than 2^160 or whose coordinates
// exceed 2^340 times their largest radius in long double (docs/method.md, section 7).
// float bodies are computed in double, which holds every float length squared or cubed.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace ellipsect {
namespace detail {
struct ShapeAccess;
}

template <class T, int N> using Vec = Eigen::Matrix<T, N, 1, Eigen::DontAlign>;
template <class T, int N> using Mat = Eigen::Matrix<T, N, N, Eigen::DontAlign>;
template <class T> using Quat = Eigen::Quaternion<T, Eigen::DontAlign>;
// A Vec parameter of a query whose T and N are deduced from its other arguments (the
// bodies), so aligned Eigen vectors and Eigen expressions convert to it.
template <class T, int N> using VecArg = std::type_identity_t<Vec<T, N>>;
template <class T> using Vec2 = Vec<T, 2>;
template <class T> using Vec3 = Vec<T, 3>;
template <class T> using Mat2 = Mat<T, 2>;
template <class T> using Mat3 = Mat<T, 3>;

namespace detail {

// Size and alignment of a struct with members of types M..., in order, by the C++ layout
// rules (each member at the next multiple of its alignment, the size rounded up to the
// largest alignment). With Vec and Mat written as arrays of T no compiler flag changes it.
template <class... M>
struct PlainLayout {
  static constexpr std::size_t align = std::max({alignof(M)...});
  static constexpr std::size_t size = [] {
    std::size_t end = 0;
    ((end = (end + alignof(M) - 1) / alignof(M) * alignof(M) + sizeof(M)), ...);
    return (end + align - 1) / align * align;
  }();
};
template <class S, class... M>
inline constexpr bool has_plain_layout =
    sizeof(S) == PlainLayout<M...>::size && alignof(S) == PlainLayout<M...>::align;

}  // namespace detail

static_assert(detail::has_plain_layout<Vec2<float>, float[2]> && detail::has_plain_layout<Vec3<double>, double[3]> &&
              detail::has_plain_layout<Mat2<float>, float[4]> && detail::has_plain_layout<Mat3<double>, double[9]> &&
              detail::has_plain_layout<Quat<double>, double[4]>);

// Thrown for invalid input; field() names the offending field, e.g. "radii[1]".
class InputError : public std::invalid_argument {
public:
  InputError(std::string field, const std::string& what)
      : std::invalid_argument("ellipsect: " + field + ": " + what), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

private:
  std::string field_;
};

// Thrown by the factories over arrays for their first invalid row: row() is its index,
// field() the field as the single-body factory names it ("radii[1]", "quaternion.x"),
// detail() what that factory's message says of it ("must be > 0 (got -1)"); what() is
// "ellipsect: row <row>: <field>: <detail>".
class RowInputError : public InputError {
public:
  RowInputError(std::size_t row, std::string field, std::string detail)
      : InputError(field, detail),
        row_(row),
        detail_(std::move(detail)),
        message_("ellipsect: row " + std::to_string(row) + ": " + this->field() + ": " + detail_) {}
  std::size_t row() const noexcept { return row_; }
  const std::string& detail() const noexcept { return detail_; }
  const char* what() const noexcept override { return message_.c_str(); }

private:
  std::size_t row_;
  std::string detail_, message_;
};

// Trivially copyable and standard-layout: an array of bodies may be copied with memcpy and
// read (not written: that would skip validation) as rows of (2 N + N^2) values of T:
// center, axes (column by column), radii. Filling an array of bodies (a binding's numpy
// columns, a structure of arrays) needs no allocation: default-construct or resize, then
// assign factory results; factories allocate only the message of an InputError they throw,
// and take Eigen::Map views of the caller's rows (they convert to Vec and Mat).
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

  // Largest accepted aspect ratio, largest radius / smallest radius: the range in which the
  // queries are tested against the reference. Far beyond it the stored axes' rounding (eps
  // times the largest radius) exceeds the smallest radius, and a rotated body no longer has
  // the shape its radii describe.
  static constexpr T max_aspect_ratio = T(1e8);

  // The default body: the unit ball at the origin (center 0, axes the identity, radii 1),
  // valid like every other, so containers can be resized and arrays declared; a constant
  // expression, no allocation, no check.
  constexpr Ellipsoid() noexcept : center_{}, axes_{}, radii_{} {
    for (int i = 0; i < N; ++i) {
      axes_[static_cast<std::size_t>(i * (N + 1))] = T(1);
      radii_[static_cast<std::size_t>(i)] = T(1);
    }
  }

  // center: finite; axes: finite, orthonormal columns (within axes_tolerance);
  // radii: finite and > 0 ("radii[i]"), aspect ratio at most max_aspect_ratio ("radii").
  // Throws InputError naming the field otherwise.
  static Ellipsoid from_axes(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& radii);

  // The quadric form (x - center)^T M (x - center) <= 1 (seed equations (1)-(2)); M must
  // be finite, symmetric (relative asymmetry <= 1e-12 for double, 1e-5 for float) and
  // positive definite with condition number below 1 / (64 eps); axes are M's eigenvectors,
  // radii M's eigenvalues^-1/2, accurate to about eps * cond(M) relative.
  static Ellipsoid from_quadric(const Vec<T, N>& center, const Mat<T, N>& M);

  // Read-only views of the fields, valid while the body lives (they convert to Vec / Mat
  // and to aligned Eigen types).
  Eigen::Map<const Vec<T, N>> center() const noexcept { return Eigen::Map<const Vec<T, N>>(center_.data()); }
  Eigen::Map<const Mat<T, N>> axes() const noexcept { return Eigen::Map<const Mat<T, N>>(axes_.data()); }
  Eigen::Map<const Vec<T, N>> radii() const noexcept { return Eigen::Map<const Vec<T, N>>(radii_.data()); }

  // The quadric matrix M = axes diag(radii)^-2 axes^T (to rounding while radii^-2 is a normal
  // number: beyond about 1e154 its entries become subnormal and lose digits).
  Mat<T, N> quadric() const noexcept;
  // The same shape moved by `offset`.
  Ellipsoid translated(const Vec<T, N>& offset) const;

private:
  friend struct detail::ShapeAccess;  // the factories' good path, exact rescaling in the queries
  // Unchecked; the factories validate first.
  Ellipsoid(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& radii) noexcept;

  std::array<T, N> center_;
  std::array<T, N * N> axes_;  // column-major
  std::array<T, N> radii_;
};

template <class T> using Ellipse2 = Ellipsoid<T, 2>;
template <class T> using Ellipsoid3 = Ellipsoid<T, 3>;

static_assert(std::is_trivially_copyable_v<Ellipse2<float>> && std::is_trivially_copyable_v<Ellipsoid3<double>> &&
              std::is_standard_layout_v<Ellipsoid3<double>>);
static_assert(detail::has_plain_layout<Ellipse2<float>, float[2], float[4], float[2]> &&
              detail::has_plain_layout<Ellipsoid3<double>, double[3], double[9], double[3]>);

// An ellipse whose first axis makes `angle` radians with the x axis (counter-clockwise).
template <class T>
Ellipse2<T> make_ellipse(const Vec2<T>& center, T angle, const Vec2<T>& radii);

// An ellipsoid rotated by a unit quaternion (|q|^2 within 2e-9 of 1 for double, 2e-5 for
// float: |q| within 1e-9, 1e-5). The axes are the columns of the rotation matrix of q / |q|,
// to 8 ulps of 1 per entry (formed without a square root or a division; at most 3.3 measured
// over 3 million random quaternions, where q.normalized().toRotationMatrix() has 5.5).
// Errors name the components in Eigen's constructor order Quaternion(w, x, y, z):
// "quaternion.w", "quaternion.x", ... (an aligned Eigen::Quaterniond converts implicitly).
template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Quat<T>& rotation, const Vec3<T>& radii);

// An ellipsoid whose axes are the columns of a rotation (or any orthonormal) matrix.
template <class T>
Ellipsoid3<T> make_ellipsoid(const Vec3<T>& center, const Mat3<T>& rotation, const Vec3<T>& radii);

// A ball (circle, sphere) of the given radius (errors name the field "radius").
template <class T, int N>
Ellipsoid<T, N> make_ball(const Vec<T, N>& center, T radius);

// Orientations stored with fewer digits than the type (float32 arrays, rounded text) made
// exact first: a quaternion whose norm is within normalize_tolerance of 1 divided by its norm;
// a matrix within it of orthonormal (largest |R^T R - I|) replaced by its polar factor, the
// nearest orthonormal matrix (U V^T of its singular value decomposition; a reflection stays
// one). Farther ones, and non-finite ones, are returned as given, for the factories to reject
// with their usual errors.
inline constexpr double normalize_tolerance = 1e-5;
template <class T>
Quat<T> normalized_quaternion(const Quat<T>& q);
template <class T, int N>
Mat<T, N> normalized_rotation(const Mat<T, N>& rotation);

// How the array factories read orientations: as given, or made exact first as above.
enum class Orientations { as_given, normalized };

// Factories over arrays: out[i] from row i of contiguous arrays (structure of arrays, rows
// one after another as numpy's C order stores them): centers and radii hold N values per
// row, and the orientation
//   make_ellipses     angles: one per row (empty: every angle 0);
//   make_ellipsoids   quaternions: (w, x, y, z) per row, Eigen's constructor order (empty:
//                     every body unrotated);
//   make_bodies       rotations: an N x N matrix per row, row by row; the axes are its columns.
// Each row gets the single-body factory's checks and answer bit for bit, with no cost per row
// beyond them. The first invalid row throws RowInputError (its index, the field, the
// reason), and out's rows before it are written; an array whose length is not out.size()
// rows throws InputError naming it ("centers", "angles", ...). `orientations`: quaternions and
// rotations as given, or each normalized first (normalized_quaternion, normalized_rotation).
template <class T>
void make_ellipses(std::span<const T> centers, std::span<const T> angles, std::span<const T> radii,
                   std::span<Ellipse2<T>> out);
template <class T>
void make_ellipsoids(std::span<const T> centers, std::span<const T> quaternions, std::span<const T> radii,
                     std::span<Ellipsoid3<T>> out, Orientations orientations = Orientations::as_given);
template <class T, int N>
void make_bodies(std::span<const T> centers, std::span<const T> rotations, std::span<const T> radii,
                 std::span<Ellipsoid<T, N>> out, Orientations orientations = Orientations::as_given);

}  // namespace ellipsect
