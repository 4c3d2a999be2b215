// Fuzz target `factories`: make_ellipse, make_ellipsoid (quaternion and matrix), from_axes,
// from_quadric, make_ball and translated, in double and float, on raw values (any bit
// pattern). Each call either throws InputError naming one of its arguments, or returns a
// valid body (shapes.hpp):
//   - it throws exactly when the header says so for the checks that are stated exactly
//     (a non-finite center, radius or angle, a radius <= 0, a non-unit quaternion);
//   - center and radii round-trip bit for bit (from_axes, make_ellipse, make_ellipsoid,
//     make_ball), the axes are orthonormal to 16 N eps, and equal the given ones where those
//     are orthonormal to 4 N eps (from_axes, matrix make_ellipsoid);
//   - from_quadric: positive finite radii, orthonormal axes, and quadric() within
//     64 eps cond(M) of M (relative, largest entry).
// Then Options from the bytes left (options.hpp): each field throws InputError naming it
// exactly when its value lies outside the stated range, and otherwise holds the value given;
// all three at once throw for the first invalid one, in declaration order.
#include "fuzz_support.hpp"

#include <ellipsect/options.hpp>

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

namespace {

using namespace ellipsect;
using namespace ellipsect::fuzz;

template <class T, int N>
T orthonormality(const Mat<T, N>& A) {
  return (A.transpose() * A - Mat<T, N>::Identity()).cwiseAbs().maxCoeff();
}

// The error names one of the call's arguments.
void check_field(const InputError& e, std::initializer_list<std::string_view> fields) {
  bool ok = false;
  for (const auto f : fields) ok = ok || e.field().rfind(f, 0) == 0;
  FUZZ_CHECK(ok, << "InputError field \"" << e.field() << "\": " << e.what());
}

template <class T, int N>
void check_valid(const Ellipsoid<T, N>& e) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  FUZZ_CHECK(all_finite(e.center()) && all_finite(e.axes()) && all_finite(e.radii()) && (e.radii().array() > 0).all(),
             << describe(e));
  const T off = orthonormality<T, N>(e.axes());
  FUZZ_CHECK(off <= 16 * N * eps, << "axes off by " << off);
}

template <class T, int N>
void check_body(const Ellipsoid<T, N>& e, const Vec<T, N>& center, const Vec<T, N>& radii) {
  check_valid(e);
  FUZZ_CHECK(same_bits(e.center(), center) && same_bits(e.radii(), radii), << describe(e));
}

// Radii the factories accept: finite, positive, aspect ratio within max_aspect_ratio.
template <class T>
bool supported_radii(const auto& radii) {
  return radii.allFinite() && (radii.array() > T(0)).all() && !(radii.maxCoeff() > T(1e8) * radii.minCoeff());
}

template <class T, int N>
void from_axes_and_quadric(Bytes& in) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  Vec<T, N> center, radii;
  Mat<T, N> axes;
  for (int i = 0; i < N; ++i) center[i] = static_cast<T>(in.number());
  for (int i = 0; i < N; ++i) radii[i] = static_cast<T>(in.number());
  for (int i = 0; i < N * N; ++i) axes(i) = static_cast<T>(in.number());
  trace() += "center " + hex(center) + " radii " + hex(radii) + " axes " +
             hex(Eigen::Matrix<T, N * N, 1>(Eigen::Map<Eigen::Matrix<T, N * N, 1>>(axes.data())));
  try {
    const auto e = Ellipsoid<T, N>::from_axes(center, axes, radii);
    check_body(e, center, radii);
    if (orthonormality<T, N>(axes) <= 4 * N * eps) FUZZ_CHECK(same_bits(e.axes(), axes), << describe(e));
  } catch (const InputError& e) {
    check_field(e, {"center", "axes", "radii"});
    FUZZ_CHECK(!(center.allFinite() && supported_radii<T>(radii) && axes.allFinite() &&
                 orthonormality<T, N>(axes) <= Ellipsoid<T, N>::axes_tolerance),
               << "valid input rejected: " << e.what());
  }
  // The same numbers as a quadric matrix (symmetrized half the time, so both paths run).
  Mat<T, N> M = axes;
  if (in.flag()) M = (axes + axes.transpose()) / 2;
  try {
    const auto e = Ellipsoid<T, N>::from_quadric(center, M);
    check_valid(e);
    FUZZ_CHECK(same_bits(e.center(), center), << describe(e));
    const T cond = (e.radii().maxCoeff() / e.radii().minCoeff()) * (e.radii().maxCoeff() / e.radii().minCoeff());
    // Against M's symmetric part: an accepted asymmetry (shapes.hpp) cannot be reproduced.
    const Mat<T, N> symmetric = M / 2 + M.transpose() / 2;
    const T err = (e.quadric() - symmetric).cwiseAbs().maxCoeff() / M.cwiseAbs().maxCoeff();
    // Where M's smallest eigenvalue is subnormal, quadric()'s entries carry fewer digits.
    if (M.cwiseAbs().maxCoeff() / cond >= std::numeric_limits<T>::min() / eps)
      FUZZ_CHECK(
          err <= 64 * eps * cond, << "quadric() off by " << err << " relative, cond " << cond << " " << describe(e));
  } catch (const InputError& e) {
    check_field(e, {"center", "M"});
  }
}

template <class T>
void ellipse(Bytes& in) {
  Vec2<T> center, radii;
  for (int i = 0; i < 2; ++i) center[i] = static_cast<T>(in.number());
  for (int i = 0; i < 2; ++i) radii[i] = static_cast<T>(in.number());
  const T angle = static_cast<T>(in.number());
  trace() += "center " + hex(center) + " radii " + hex(radii) + " angle " + hex(angle);
  const bool valid = center.allFinite() && supported_radii<T>(radii) && std::isfinite(angle);
  try {
    const auto e = make_ellipse<T>(center, angle, radii);
    FUZZ_CHECK(valid, << "invalid input accepted");
    check_body(e, center, radii);
    // The first axis makes `angle` with x: (cos, sin), to a few ulps.
    const T err = std::max(std::abs(e.axes()(0, 0) - std::cos(angle)), std::abs(e.axes()(1, 0) - std::sin(angle)));
    FUZZ_CHECK(err <= 16 * std::numeric_limits<T>::epsilon(), << "first axis off by " << err << " " << describe(e));
  } catch (const InputError& e) {
    check_field(e, {"center", "angle", "radii"});
    FUZZ_CHECK(!valid, << "valid input rejected: " << e.what());
  }
}

template <class T>
void ellipsoid(Bytes& in) {
  Vec3<T> center, radii;
  for (int i = 0; i < 3; ++i) center[i] = static_cast<T>(in.number());
  for (int i = 0; i < 3; ++i) radii[i] = static_cast<T>(in.number());
  Eigen::Quaternion<T> q(static_cast<T>(in.number()), static_cast<T>(in.number()), static_cast<T>(in.number()),
                         static_cast<T>(in.number()));
  if (in.flag() && q.coeffs().allFinite() && q.norm() > 0) q.normalize();
  trace() += "center " + hex(center) + " radii " + hex(radii) + " q (x, y, z, w) " + hex(q.coeffs());
  const T q_tolerance = sizeof(T) >= sizeof(double) ? T(1e-9) : T(1e-5);
  // |q| computed in double: a float |q| can round across the limit.
  const double qn = q.coeffs().template cast<double>().norm();
  const bool valid = center.allFinite() && supported_radii<T>(radii) && q.coeffs().allFinite();
  try {
    const auto e = make_ellipsoid<T>(center, q, radii);
    FUZZ_CHECK(valid && std::abs(qn - 1) <= 2 * q_tolerance, << "invalid input accepted, |q| = " << qn);
    check_body(e, center, radii);
    const T err = (e.axes() - q.normalized().toRotationMatrix()).cwiseAbs().maxCoeff();
    FUZZ_CHECK(err <= 16 * std::numeric_limits<T>::epsilon(), << "axes off q's matrix by " << err);
    // The same rotation as a matrix.
    const auto m = make_ellipsoid<T>(center, Mat3<T>(e.axes()), radii);
    check_body(m, center, radii);
  } catch (const InputError& e) {
    check_field(e, {"center", "quaternion", "radii"});
    FUZZ_CHECK(!valid || std::abs(qn - 1) >= q_tolerance / 2, << "valid input rejected: " << e.what());
  }
}

template <class T, int N>
void ball_and_translated(Bytes& in) {
  Vec<T, N> center, offset;
  for (int i = 0; i < N; ++i) center[i] = static_cast<T>(in.number());
  const T radius = static_cast<T>(in.number());
  for (int i = 0; i < N; ++i) offset[i] = static_cast<T>(in.number());
  trace() += "center " + hex(center) + " radius " + hex(radius) + " offset " + hex(offset);
  const bool valid = center.allFinite() && std::isfinite(radius) && radius > 0;
  try {
    const auto e = make_ball<T, N>(center, radius);
    FUZZ_CHECK(valid, << "invalid input accepted");
    check_body(e, center, Vec<T, N>(Vec<T, N>::Constant(radius)));
    FUZZ_CHECK((same_bits(e.axes(), Mat<T, N>(Mat<T, N>::Identity()))), << describe(e));
    const Vec<T, N> moved = center + offset;
    try {
      const auto t = e.translated(offset);
      FUZZ_CHECK(moved.allFinite(), << "non-finite center accepted");
      FUZZ_CHECK(same_bits(t.center(), moved) && same_bits(t.radii(), e.radii()) && same_bits(t.axes(), e.axes()),
                 << describe(t));
    } catch (const InputError& x) {
      check_field(x, {"center"});
      FUZZ_CHECK(!moved.allFinite(), << "valid offset rejected: " << x.what());
    }
  } catch (const InputError& e) {
    check_field(e, {"center", "radius"});
    FUZZ_CHECK(!valid, << "valid input rejected: " << e.what());
  }
}

// A cap value: any 64-bit pattern shifted right by 0 to 63 bits (small values and
// negatives as often as huge ones).
std::int64_t cap_value(Bytes& in) {
  const auto bits = static_cast<std::int64_t>(in.u64());
  return bits >> (in.byte() % 64);
}

// The field of the InputError that make() throws, or "" when it returns.
template <class Make>
std::string field_of(Make make) {
  try {
    make();
  } catch (const InputError& e) {
    return e.field();
  }
  return "";
}

void options(Bytes& in) {
  const double tolerance = in.number();
  const std::int64_t iterations = cap_value(in), steps = cap_value(in);
  trace() += "options " + hex(tolerance) + " " + std::to_string(iterations) + " " + std::to_string(steps) + "; ";
  const bool tolerance_ok = tolerance == 0 || (tolerance >= 1e-14 && tolerance <= 1e-9);  // NaN: false
  const bool iterations_ok = iterations >= 1 && iterations <= 100000, steps_ok = steps >= 1 && steps <= 1000000;
  double kept_tolerance = 0;
  const std::string t = field_of([&] { kept_tolerance = Options{.tolerance = tolerance}.tolerance.value(); });
  FUZZ_CHECK(t == (tolerance_ok ? "" : "tolerance"), << "tolerance " << hex(tolerance) << ": \"" << t << "\"");
  FUZZ_CHECK(!tolerance_ok || same_bits(kept_tolerance, tolerance), << "tolerance kept as " << hex(kept_tolerance));
  int kept_iterations = 0;
  const std::string i =
      field_of([&] { kept_iterations = Options{.max_contact_iterations = iterations}.max_contact_iterations; });
  FUZZ_CHECK(i == (iterations_ok ? "" : "max_contact_iterations"),
             << "max_contact_iterations " << iterations << ": \"" << i << "\"");
  FUZZ_CHECK(!iterations_ok || kept_iterations == iterations, << "max_contact_iterations kept as " << kept_iterations);
  Options o;
  const std::string s = field_of([&] { o.max_motion_steps = steps; });
  FUZZ_CHECK(s == (steps_ok ? "" : "max_motion_steps"), << "max_motion_steps " << steps << ": \"" << s << "\"");
  FUZZ_CHECK(o.max_motion_steps == (steps_ok ? steps : 10000), << "max_motion_steps after assignment " << o.max_motion_steps);
  const std::string first = !tolerance_ok     ? "tolerance"
                            : !iterations_ok  ? "max_contact_iterations"
                            : !steps_ok       ? "max_motion_steps"
                                              : "";
  const std::string all = field_of([&] {
    (void)Options{.tolerance = tolerance, .max_contact_iterations = iterations, .max_motion_steps = steps};
  });
  FUZZ_CHECK(all == first, << "all three at once: \"" << all << "\", expected \"" << first << "\"");
}

template <class T>
void run(Bytes& in, int which) {
  switch (which) {
    case 0: ellipse<T>(in); break;
    case 1: ellipsoid<T>(in); break;
    case 2: from_axes_and_quadric<T, 2>(in); break;
    case 3: from_axes_and_quadric<T, 3>(in); break;
    case 4: ball_and_translated<T, 2>(in); break;
    default: ball_and_translated<T, 3>(in); break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::uint8_t kind = in.byte();
  const int which = (kind >> 1) % 6;
  trace() = std::string(kind & 1 ? "float" : "double") + " factory " + std::to_string(which) + ": ";
  if (kind & 1) {
    run<float>(in, which);
  } else {
    run<double>(in, which);
  }
  options(in);
  return 0;
}
