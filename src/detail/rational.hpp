// Rational arithmetic on stored bodies: the numbers every exact decision computes with
// (the exact relation of two bodies, src/pair/exact_relation.cpp; the certificates of the
// enclosing ellipsoids, src/geometry/enclosing.cpp). Every double is a rational, so a
// decision taken here has no rounding.
#pragma once

#include <ellipsect/shapes.hpp>

#include "axes.hpp"

#if ELLIPSECT_EXACT_GMP
#include <boost/multiprecision/gmp.hpp>
#else
#include <boost/multiprecision/cpp_int.hpp>
#endif

#include <array>
#include <bit>
#include <cmath>
#include <utility>

namespace ellipsect::detail::rational {

// Every name below in an inline namespace of its backend: a file built with GMP and one built
// without (a test, the page's tools) then link without one inline function standing in for
// the other's.
#if ELLIPSECT_EXACT_GMP
inline namespace gmp {
#else
inline namespace boost_int {
#endif

// GMP's rationals where the build has GMP (CMakeLists.txt), Boost's own otherwise (the
// WebAssembly page): the same results, GMP about ten times sooner.
#if ELLIPSECT_EXACT_GMP
using Q = boost::multiprecision::mpq_rational;
#else
using Q = boost::multiprecision::cpp_rational;
#endif

using Z = decltype(numerator(Q()));

// A dyadic rational m 2^e (m an integer): every double is one, and sums, differences and
// products of them stay one, exact without the common divisor a rational reduces by after
// each step. What a decision that needs no division computes with.
struct Dyadic {
  Z m = 0;
  int e = 0;

  Dyadic() = default;
  Dyadic(Z mantissa, int exponent) : m(std::move(mantissa)), e(exponent) {}
  // x exactly (finite), its mantissa stripped of trailing zero bits.
  explicit Dyadic(double x) {
    int ex = 0;
    long long i = static_cast<long long>(std::ldexp(std::frexp(x, &ex), 53));  // x = i 2^(ex - 53)
    if (i == 0) return;
    const int zeros = std::countr_zero(static_cast<unsigned long long>(i));
    i >>= zeros;  // arithmetic: i is a multiple of 2^zeros
    m = Z(i);
    e = ex - 53 + zeros;
  }
};

inline Dyadic operator*(const Dyadic& a, const Dyadic& b) { return {a.m * b.m, a.e + b.e}; }
inline Dyadic operator+(const Dyadic& a, const Dyadic& b) {
  if (a.m == 0) return b;
  if (b.m == 0) return a;
  if (a.e >= b.e) return {(a.m << unsigned(a.e - b.e)) + b.m, b.e};
  return {a.m + (b.m << unsigned(b.e - a.e)), a.e};
}
inline Dyadic operator-(const Dyadic& a) { return {-a.m, a.e}; }
inline Dyadic operator-(const Dyadic& a, const Dyadic& b) { return a + -b; }
inline Dyadic& operator+=(Dyadic& a, const Dyadic& b) { return a = a + b; }
inline int sign(const Dyadic& a) { return a.m > 0 ? 1 : a.m < 0 ? -1 : 0; }
inline bool operator<(const Dyadic& a, const Dyadic& b) { return sign(a - b) < 0; }

// a / b (b nonzero) rounded to the nearest double.
inline double quotient(const Dyadic& a, const Dyadic& b) {
  const int shift = a.e - b.e;
  const Q q = shift >= 0 ? Q(a.m << unsigned(shift), b.m) : Q(a.m, b.m << unsigned(-shift));
  return static_cast<double>(q);
}

template <int N> using QVec = std::array<Q, N>;
template <int N> using QMat = std::array<QVec<N>, N>;

template <int N>
Q dot(const QVec<N>& u, const QVec<N>& v) {
  Q s = 0;
  for (int i = 0; i < N; ++i) s += u[i] * v[i];
  return s;
}

template <int N>
QVec<N> times(const QMat<N>& m, const QVec<N>& v) {
  QVec<N> r;
  for (int i = 0; i < N; ++i) r[i] = dot<N>(m[i], v);
  return r;
}

// det m and, where it is nonzero, det m * u^T m^-1 v, by Gaussian elimination.
template <int N>
std::pair<Q, Q> det_and_form(QMat<N> m, const QVec<N>& u, QVec<N> v) {
  Q det = 1;
  for (int c = 0; c < N; ++c) {
    int p = c;
    while (p < N && m[p][c] == 0) ++p;
    if (p == N) return {Q(0), Q(0)};
    if (p != c) {
      std::swap(m[p], m[c]);
      std::swap(v[p], v[c]);
      det = -det;
    }
    det *= m[c][c];
    for (int r = c + 1; r < N; ++r) {
      if (m[r][c] == 0) continue;
      const Q f = m[r][c] / m[c][c];
      for (int k = c; k < N; ++k) m[r][k] -= f * m[c][k];
      v[r] -= f * v[c];
    }
  }
  QVec<N> x;
  for (int r = N - 1; r >= 0; --r) {
    Q s = v[r];
    for (int k = r + 1; k < N; ++k) s -= m[r][k] * x[k];
    x[r] = s / m[r][r];
  }
  return {det, det * dot<N>(u, x)};
}

template <int N>
struct Body {
  QVec<N> center;
  QMat<N> quadric;  // axes diag(radii)^-2 axes^T
};

// The body every query computes with: double's stored axes as given; float's their
// orthonormal polar factor in double (detail/axes.hpp), exact from there.
template <class T, int N>
Body<N> exact_body(const Ellipsoid<T, N>& e) {
  const Mat<double, N> axes = work_axes<double>(e);
  Body<N> b;
  std::array<Q, N> inv_r2;
  for (int k = 0; k < N; ++k) {
    const Q r = Q(double(e.radii()[k]));
    inv_r2[k] = 1 / (r * r);
  }
  for (int i = 0; i < N; ++i) {
    b.center[i] = Q(double(e.center()[i]));
    for (int j = 0; j < N; ++j) {
      Q s = 0;
      for (int k = 0; k < N; ++k) s += Q(axes(i, k)) * Q(axes(j, k)) * inv_r2[k];
      b.quadric[i][j] = s;
    }
  }
  return b;
}

}  // inline namespace
}  // namespace ellipsect::detail::rational
