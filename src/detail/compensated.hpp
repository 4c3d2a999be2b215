// Error-free transformations and double-length values (Knuth's two-sum, Dekker's product
// with Veltkamp's split: exact without a fused multiply-add) for F = double or the wide type (detail/wide.hpp),
// and the compensated dot product of Ogita, Rump and Oishi (SIAM J. Sci. Comput. 2005,
// "Dot2"), whose unevaluated result hi + lo is within gamma_2n^2 sum |x_i y_i| of the exact
// dot product (gamma_k = k eps / (1 - k eps)). The source file including this header must be
// compiled with -ffp-contract=off: a contracted split or product is no longer error-free.
// Valid while no product over- or underflows (the callers keep their lengths in range).
#pragma once

#include "math.hpp"

#include <cmath>
#include <limits>

namespace ellipsect::detail {

template <class F>
struct Double {
  F hi = 0, lo = 0;  // the value hi + lo, |lo| <= ulp(hi) / 2 once normalized
};

template <class F>
Double<F> two_sum(F a, F b) noexcept {
  const F s = a + b;
  const F z = s - a;
  return {s, (a - (s - z)) + (b - z)};
}

template <class F>
Double<F> two_product(F a, F b) noexcept {
  const F split = F((1ull << ((std::numeric_limits<F>::digits + 1) / 2)) + 1);
  const auto halves = [split](F x, F& high, F& low) {
    const F c = split * x;
    high = c - (c - x);
    low = x - high;
  };
  F ah, al, bh, bl;
  halves(a, ah, al);
  halves(b, bh, bl);
  const F p = a * b;
  return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}

// a + b, a * b, a * a of double-length values, to a few eps^2 relative.
template <class F>
Double<F> add(Double<F> a, Double<F> b) noexcept {
  const Double<F> s = two_sum(a.hi, b.hi);
  return two_sum(s.hi, s.lo + a.lo + b.lo);
}

template <class F>
Double<F> times(Double<F> a, F b) noexcept {
  const Double<F> p = two_product(a.hi, b);
  return two_sum(p.hi, p.lo + a.lo * b);
}

template <class F>
Double<F> square(Double<F> a) noexcept {
  const Double<F> p = two_product(a.hi, a.hi);
  return two_sum(p.hi, p.lo + F(2) * a.hi * a.lo);
}

// Double-length arithmetic as operators, for code written once over F and Double<F> (each
// result within a few eps^2 of the exact operation on its operands; products and quotients
// of normalized values). Comparisons compare the values hi + lo.
template <class F>
Double<F> operator+(Double<F> a, Double<F> b) noexcept {
  return add(a, b);
}
template <class F>
Double<F> operator-(Double<F> a) noexcept {
  return {-a.hi, -a.lo};
}
template <class F>
Double<F> operator-(Double<F> a, Double<F> b) noexcept {
  return add(a, -b);
}
template <class F>
Double<F> operator*(Double<F> a, Double<F> b) noexcept {
  const Double<F> p = two_product(a.hi, b.hi);
  return two_sum(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}
template <class F>
Double<F> operator/(Double<F> a, Double<F> b) noexcept {
  const F q = a.hi / b.hi;
  const Double<F> r = a - b * Double<F>{q, 0};
  return two_sum(q, (r.hi + r.lo) / b.hi);
}
template <class F>
bool operator<(Double<F> a, Double<F> b) noexcept {
  return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo);
}
template <class F>
bool operator<=(Double<F> a, Double<F> b) noexcept {
  return !(b < a);
}
template <class F>
bool operator>(Double<F> a, Double<F> b) noexcept {
  return b < a;
}
template <class F>
bool operator>=(Double<F> a, Double<F> b) noexcept {
  return !(a < b);
}
// The built-in types' roots beside Double's below (detail/math.hpp).
using ellipsect::sqrt;

// sqrt(a) for a >= 0: one Newton correction of the working-precision root.
template <class F>
Double<F> sqrt(Double<F> a) noexcept {
  if (!(a.hi > F(0))) return {};
  const F s = sqrt(a.hi);
  const Double<F> r = a - two_product(s, s);
  return two_sum(s, (r.hi + r.lo) / (F(2) * s));
}

// Dot2: add(x, y) for each term, then value().
template <class F>
struct CompensatedDot {
  F sum = 0, error = 0;
  void add(F x, F y) noexcept {
    const Double<F> p = two_product(x, y);
    const Double<F> s = two_sum(sum, p.hi);
    sum = s.hi;
    error += s.lo + p.lo;
  }
  Double<F> value() const noexcept { return two_sum(sum, error); }
};

}  // namespace ellipsect::detail
