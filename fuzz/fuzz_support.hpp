// Shared pieces of the libFuzzer targets (docs/fuzzing.md): reading numbers and bodies from
// the fuzzer's bytes, exact (bit for bit) comparisons, and the check that stops the run
// with the violated property and the input's values.
#pragma once

#include <ellipsect/contact.hpp>
#include <ellipsect/shapes.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace ellipsect::fuzz {

// What the current input decoded to, printed when a check fails (hexadecimal floats: the
// values are exact, so the line is a repro).
inline std::string& trace() {
  static std::string t;
  return t;
}

[[noreturn]] inline void fail(const char* check, const char* file, int line, const std::string& detail) {
  std::fprintf(stderr, "\n==== ellipsect fuzz: check failed at %s:%d\n  %s\n  %s\n  input: %s\n", file, line, check,
               detail.c_str(), trace().c_str());
  std::abort();
}

}  // namespace ellipsect::fuzz

// Stops the run when `cond` is false; the remaining arguments are streamed into the message.
#define FUZZ_CHECK(cond, ...)                                                 \
  do {                                                                        \
    if (!(cond)) {                                                            \
      std::ostringstream fuzz_detail_;                                        \
      fuzz_detail_.precision(17);                                             \
      fuzz_detail_ << "" __VA_ARGS__;                                         \
      ::ellipsect::fuzz::fail(#cond, __FILE__, __LINE__, fuzz_detail_.str()); \
    }                                                                         \
  } while (0)

namespace ellipsect::fuzz {

// Reads the fuzzer's bytes front to back; past the end every read gives zeros.
class Bytes {
public:
  Bytes(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}

  std::uint8_t byte() { return p_ < end_ ? *p_++ : 0; }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = v << 8 | byte();
    return v;
  }
  bool flag() { return byte() & 1; }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }

  // A double from a tag byte and its payload, spread over what breaks numerical code: small
  // integers, values near 1, any bit pattern (NaN, infinities, subnormals), powers of ten
  // up to 1e+-308, and the previous value (equal radii, equal bodies).
  double number() {
    const std::uint8_t tag = byte();
    double x = 0;
    switch (tag % 8) {
      case 0: x = static_cast<int>(byte() % 17) - 8; break;
      case 1: {
        const std::uint64_t bits = u64();
        std::memcpy(&x, &bits, sizeof x);
        break;
      }
      case 2: x = 1.0 + static_cast<double>(static_cast<std::int8_t>(byte())) * 0x1p-52; break;
      case 3: x = unit() * std::ldexp(1.0, static_cast<int>(byte() % 121) - 60); break;
      case 4: {
        const int hi = byte();
        x = unit() * std::pow(10.0, (hi << 8 | byte()) % 617 - 308);
        break;
      }
      case 5: x = last_; break;
      default: x = 8 * unit(); break;
    }
    last_ = x;
    return x;
  }

private:
  double unit() {  // in [-1, 1), 2^-31 steps
    const auto v = static_cast<std::uint32_t>(u64());
    return static_cast<double>(static_cast<std::int32_t>(v)) * 0x1p-31;
  }
  const std::uint8_t* p_;
  const std::uint8_t* end_;
  double last_ = 1.0;
};

// Equal bit patterns (NaN equals NaN of the same payload; 0 and -0 differ).
template <class T>
requires std::is_floating_point_v<T>
bool same_bits(T x, T y) { return std::memcmp(&x, &y, sizeof(T)) == 0; }
template <class X, class Y>
bool same_bits(const Eigen::MatrixBase<X>& x, const Eigen::MatrixBase<Y>& y) {
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!same_bits(x(i), y(i))) return false;
  return true;
}

// Equal bits, or both NaN (a NaN field negated flips only its sign bit).
template <class X, class Y>
bool same_bits_or_nan(const Eigen::MatrixBase<X>& x, const Eigen::MatrixBase<Y>& y) {
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (!same_bits(x(i), y(i)) && !(std::isnan(x(i)) && std::isnan(y(i)))) return false;
  return true;
}

template <class Derived>
bool all_finite(const Eigen::MatrixBase<Derived>& x) {
  return x.allFinite();
}

template <class T>
requires std::is_floating_point_v<T> std::string hex(T x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", static_cast<double>(x));
  return buf;
}
template <class Derived>
std::string hex(const Eigen::MatrixBase<Derived>& v) {
  std::string s = "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += (i ? ", " : "") + hex(v(i));
  return s + ")";
}

// A body's exact fields: center, radii, axes (column-major).
template <class T, int N>
std::string describe(const Ellipsoid<T, N>& e) {
  return "{center " + hex(e.center()) + " radii " + hex(e.radii()) + " axes " +
         hex(Eigen::Matrix<T, N * N, 1>(Eigen::Map<const Eigen::Matrix<T, N * N, 1>>(e.axes().data()))) + "}";
}

// A body decoded from the input: center, radii, orientation (an angle in 2D, a quaternion
// normalized here in 3D), so that most inputs give a valid body; nothing when the factory
// rejects the values.
template <class T, int N>
std::optional<Ellipsoid<T, N>> read_body(Bytes& in) {
  Vec<T, N> center, radii;
  for (int i = 0; i < N; ++i) center[i] = static_cast<T>(in.number());
  for (int i = 0; i < N; ++i) radii[i] = static_cast<T>(std::abs(in.number()));
  try {
    if constexpr (N == 2) {
      return make_ellipse<T>(center, static_cast<T>(in.number()), radii);
    } else {
      Eigen::Quaternion<double> q(in.number(), in.number(), in.number(), in.number());
      if (!(q.norm() > 0) || !std::isfinite(q.norm())) q = Eigen::Quaternion<double>::Identity();
      q.normalize();
      return make_ellipsoid<T>(center, q.template cast<T>(), radii);
    }
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// A second body related to `a` as the input chooses: independent, a's copy, a translated
// copy, or a scaled copy about a's center (equal, tangent and nested pairs).
template <class T, int N>
std::optional<Ellipsoid<T, N>> read_partner(Bytes& in, const Ellipsoid<T, N>& a) {
  const std::uint8_t mode = in.byte() % 4;
  try {
    if (mode == 1) return a;
    if (mode == 2) {
      Vec<T, N> d;
      for (int i = 0; i < N; ++i) d[i] = static_cast<T>(in.number());
      return a.translated(d);
    }
    if (mode == 3) {
      const T s = static_cast<T>(std::abs(in.number()));
      return Ellipsoid<T, N>::from_axes(a.center(), a.axes(), Vec<T, N>(a.radii() * s));
    }
  } catch (const InputError&) {
    return std::nullopt;
  }
  return read_body<T, N>(in);
}

// A rigid motion decoded from the input: a velocity, and for about half the bodies a spin.
template <class T, int N>
RigidMotion<T, N> read_motion(Bytes& in) {
  RigidMotion<T, N> m;
  for (int i = 0; i < N; ++i) m.velocity[i] = static_cast<T>(in.number());
  if (in.flag()) {  // about half the bodies turn
    if constexpr (N == 2) {
      m.angular_velocity = static_cast<T>(in.number());
    } else {
      for (int i = 0; i < 3; ++i) m.angular_velocity[i] = static_cast<T>(in.number());
    }
  }
  return m;
}

template <class T, int N>
bool finite_spin(const RigidMotion<T, N>& m) {
  if constexpr (N == 2) return std::isfinite(m.angular_velocity);
  else return m.angular_velocity.allFinite();
}

template <class T, int N>
bool zero_spin(const RigidMotion<T, N>& m) {
  if constexpr (N == 2) return m.angular_velocity == T(0);
  else return (m.angular_velocity.array() == T(0)).all();
}

// Reads the input's first byte and calls run.template operator()<T, N>() for the scalar
// type (double or float) and dimension (2 or 3) it picks, named at the start of the trace.
template <class Run>
void for_type_and_dim(Bytes& in, Run&& run) {
  trace().clear();
  const std::uint8_t kind = in.byte();
  trace() = std::string(kind & 1 ? "float" : "double") + (kind & 2 ? " 3D; " : " 2D; ");
  switch (kind % 4) {
    case 0: run.template operator()<double, 2>(); break;
    case 1: run.template operator()<float, 2>(); break;
    case 2: run.template operator()<double, 3>(); break;
    default: run.template operator()<float, 3>(); break;
  }
}

// `count` points of number()s, each added to trace().
template <class T, int N>
std::vector<Vec<T, N>> read_points(Bytes& in, std::size_t count) {
  std::vector<Vec<T, N>> points;
  for (std::size_t i = 0; i < count; ++i) {
    Vec<T, N> p;
    for (int k = 0; k < N; ++k) p[k] = static_cast<T>(in.number());
    points.push_back(p);
    trace() += hex(p) + " ";
  }
  return points;
}

template <class T, int N>
bool all_finite(const std::vector<Vec<T, N>>& points) {
  for (const auto& p : points)
    if (!p.allFinite()) return false;
  return true;
}

// The input's first byte picks the scalar type (bit 0: float, else double) and the dimension
// (bit 1: 3D, else 2D), named in trace(); then run.template operator()<T, N>().
template <class Run>
void by_type_and_dimension(Bytes& in, Run&& run) {
  const std::uint8_t kind = in.byte();
  trace() = std::string(kind & 1 ? "float " : "double ") + (kind & 2 ? "3D: " : "2D: ");
  if (kind & 1) {
    if (kind & 2) run.template operator()<float, 3>(); else run.template operator()<float, 2>();
  } else {
    if (kind & 2) run.template operator()<double, 3>(); else run.template operator()<double, 2>();
  }
}

}  // namespace ellipsect::fuzz
