// The exact relation of two stored bodies (detail/exact_relation.hpp).
//
// With A, B the quadric matrices of a and b and d = center_a - center_b, all rational:
//
// Separation (Perram-Wertheim). G(l) = l A + (1 - l) B, positive definite for l in [0, 1];
// F(l) = l (1 - l) (A d)^T G^-1 (B d) is the minimum over x of l q_a(x) + (1 - l) q_b(x),
// and the closed bodies meet iff max F <= 1, their interiors iff max F < 1. So with the
// polynomial p(l) = det G (F - 1), of degree <= N + 1, p(0) = -det B < 0, p(1) = -det A < 0:
//   separated  p > 0 somewhere in (0, 1): p has a root of odd multiplicity there;
//   touching   p has roots in (0, 1), each of even multiplicity (max F = 1);
//   else the interiors meet.
//
// Containment. b lies in a iff max over b of q_a <= 1. This is a trust-region problem, so
// the S-lemma gives strong duality: the maximum is the infimum over mu > mu* of
// g(mu) = mu + mu (A d)^T (mu B - A)^-1 (B d), mu* the largest root of D(mu) = det(mu B - A)
// (the largest eigenvalue of the pencil, > 0), where mu B - A is positive definite. With
// h = D (g - 1) = (mu - 1) D + mu D (A d)^T (mu B - A)^-1 (B d), a polynomial of degree
// N + 1 with positive leading coefficient: b in a iff h has a root above mu* (g <= 1 there),
// or else (h > 0 above mu*, so g > 1 there) g tends to 1 at mu*, which is when mu* is a
// root of h of higher multiplicity than of D (the hard case of the trust-region problem:
// concentric and aligned pairs, internal tangency).
//
// Polynomials are found by exact interpolation of values from Gaussian elimination, roots
// are counted with Sturm sequences, and mu* is isolated by bisection between rationals
// (it terminates: distinct roots of rational polynomials are a positive distance apart).
#include "detail/exact_relation.hpp"

#include "detail/instantiate.hpp"
#include "detail/rational.hpp"

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace ellipsect::detail {

namespace {

using namespace rational;

// Coefficients from the constant term up, no zero leading coefficient (0 is empty).
using Poly = std::vector<Q>;

void trim(Poly& p) {
  while (!p.empty() && p.back() == 0) p.pop_back();
}

// p times the positive rational that makes its coefficients coprime integers: the same
// signs everywhere, the shortest numbers (every polynomial kept below is so reduced).
Poly primitive(Poly p) {
  Z den = 1, num = 0;
  for (const Q& c : p) den = lcm(den, denominator(c));
  for (const Q& c : p) num = gcd(num, Z(numerator(c) * (den / denominator(c))));
  if (num == 0) return p;
  const Q f = Q(den) / Q(num);
  for (Q& c : p) c *= f;
  return p;
}

Poly derivative(const Poly& p) {
  Poly d;
  for (std::size_t i = 1; i < p.size(); ++i) d.push_back(p[i] * static_cast<int>(i));
  return d;
}

Poly minus(Poly a, const Poly& b) {
  if (a.size() < b.size()) a.resize(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) a[i] -= b[i];
  trim(a);
  return a;
}

// a = q b + r with deg r < deg b (b nonzero).
std::pair<Poly, Poly> divide(Poly a, const Poly& b) {
  Poly q(a.size() >= b.size() ? a.size() - b.size() + 1 : 0);
  while (a.size() >= b.size()) {
    const std::size_t shift = a.size() - b.size();
    const Q f = a.back() / b.back();
    q[shift] = f;
    for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] -= f * b[i];
    trim(a);  // the leading coefficient is now exactly 0
  }
  return {std::move(q), std::move(a)};
}

Poly quotient(const Poly& a, const Poly& b) { return divide(a, b).first; }

// Greatest common divisor, primitive (a constant when coprime).
Poly gcd(Poly a, Poly b) {
  while (!b.empty()) a = std::exchange(b, primitive(divide(std::move(a), b).second));
  return primitive(std::move(a));
}

Poly squarefree(const Poly& p) { return primitive(quotient(p, gcd(p, derivative(p)))); }

// The product of the squarefree factors of odd power in p = prod a_i^i (Yun's algorithm):
// its roots are p's roots of odd multiplicity.
Poly odd_part(const Poly& p) {
  const Poly a0 = gcd(p, derivative(p));
  Poly b = quotient(p, a0);
  Poly d = minus(quotient(derivative(p), a0), derivative(b));
  Poly odd{Q(1)};
  for (int i = 1; b.size() > 1; ++i) {
    const Poly a = gcd(b, d);
    if (i % 2 == 1) {
      Poly prod(odd.size() + a.size() - 1);
      for (std::size_t j = 0; j < odd.size(); ++j)
        for (std::size_t k = 0; k < a.size(); ++k) prod[j + k] += odd[j] * a[k];
      odd = std::move(prod);
    }
    b = quotient(b, a);
    d = minus(quotient(d, a), derivative(b));
  }
  return primitive(std::move(odd));
}

// Sturm sequence of a squarefree polynomial: distinct real roots in (lo, hi] are
// changes(lo) - changes(hi) at any lo < hi (a root of p itself included).
class Sturm {
public:
  explicit Sturm(const Poly& p) {
    seq_.push_back(p);
    if (p.size() > 1) seq_.push_back(primitive(derivative(p)));
    while (seq_.size() > 1 && seq_.back().size() > 1) {
      Poly r = primitive(divide(seq_[seq_.size() - 2], seq_.back()).second);
      if (r.empty()) break;
      for (Q& c : r) c = -c;
      seq_.push_back(std::move(r));
    }
  }
  int roots(const Q& lo, const Q& hi) const { return changes(lo) - changes(hi); }
  // Distinct roots above lo.
  int roots_above(const Q& lo) const {
    int n = 0, last = 0;
    for (const Poly& s : seq_) count(s.empty() ? 0 : (s.back() > 0 ? 1 : -1), last, n);
    return changes(lo) - n;
  }

private:
  static void count(int sign, int& last, int& n) {
    if (sign == 0) return;
    if (last != 0 && sign != last) ++n;
    last = sign;
  }
  // The members have integer coefficients (primitive): the sign of s(u / v), v > 0, is
  // that of the integer sum of c_i u^i v^(n - i), formed without any rational reduction.
  int changes(const Q& x) const {
    const Z u = numerator(x), v = denominator(x);
    int n = 0, last = 0;
    for (const Poly& s : seq_) {
      if (s.empty()) continue;
      Z sum = numerator(s.back()), power = 1;
      for (std::size_t i = s.size() - 1; i-- > 0;) {
        power *= v;
        sum = sum * u + numerator(s[i]) * power;
      }
      count(sum > 0 ? 1 : sum < 0 ? -1 : 0, last, n);
    }
    return n;
  }
  std::vector<Poly> seq_;
};

int roots_in(const Poly& p, const Q& lo, const Q& hi) { return p.size() > 1 ? Sturm(squarefree(p)).roots(lo, hi) : 0; }

// The polynomial of degree < points.size() through (points[i], values[i]): Newton's divided
// differences, expanded.
Poly interpolate(const std::vector<Q>& x, std::vector<Q> y) {
  const std::size_t n = x.size();
  for (std::size_t j = 1; j < n; ++j)
    for (std::size_t i = n - 1; i >= j; --i) y[i] = (y[i] - y[i - 1]) / (x[i] - x[i - j]);
  Poly p{y[n - 1]};
  for (std::size_t i = n - 1; i-- > 0;) {  // p = p (t - x[i]) + y[i]
    Poly next(p.size() + 1);
    for (std::size_t k = 0; k < p.size(); ++k) {
      next[k + 1] += p[k];
      next[k] -= p[k] * x[i];
    }
    next[0] += y[i];
    p = std::move(next);
  }
  trim(p);
  return primitive(std::move(p));
}

template <int N>
QMat<N> combination(const Q& s, const QMat<N>& a, const Q& t, const QMat<N>& b) {
  QMat<N> m;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) m[i][j] = s * a[i][j] + t * b[i][j];
  return m;
}

// Whether the closed bodies are apart (-1), touch (0) or their interiors meet (+1).
template <int N>
int external(const QMat<N>& A, const QMat<N>& B, const QVec<N>& ad, const QVec<N>& bd) {
  std::vector<Q> x, y;
  for (int k = 0; k <= N + 1; ++k) {
    const Q l = Q(k) / (N + 1);
    const auto [det, form] = det_and_form<N>(combination<N>(l, A, 1 - l, B), ad, bd);
    x.push_back(l);
    y.push_back(l * (1 - l) * form - det);
  }
  const Poly p = interpolate(x, std::move(y));
  if (roots_in(p, Q(0), Q(1)) == 0) return 1;
  return roots_in(odd_part(p), Q(0), Q(1)) > 0 ? -1 : 0;
}

// Whether body b (quadric B) lies in body a (quadric A), boundaries touching or not.
template <int N>
bool contains(const QMat<N>& A, const QMat<N>& B, const QVec<N>& ad, const QVec<N>& bd) {
  std::vector<Q> xd, yd, xh, yh;
  for (int k = 0; xh.size() < N + 2; ++k) {
    const Q mu = k;
    const auto [det, form] = det_and_form<N>(combination<N>(mu, B, Q(-1), A), ad, bd);
    if (xd.size() < N + 1) {
      xd.push_back(mu);
      yd.push_back(det);
    }
    if (det == 0) continue;  // h needs (mu B - A)^-1; at most N such mu
    xh.push_back(mu);
    yh.push_back((mu - 1) * det + mu * form);
  }
  const Poly D = interpolate(xd, std::move(yd));
  const Poly h = interpolate(xh, std::move(yh));
  // mu* in (lo, hi], the only root of D there; all of D's roots are positive.
  const Sturm sd(squarefree(D));
  // Cauchy's bound rounded up to a power of two, so that the midpoints stay dyadic (short).
  Q bound = 1;
  for (const Q& c : D) bound += abs(c / D.back());
  Q lo = 0, hi = 1;
  while (hi < bound) hi *= 2;
  auto halve = [&] {
    const Q mid = (lo + hi) / 2;
    (sd.roots(mid, hi) > 0 ? lo : hi) = mid;
  };
  while (sd.roots(lo, hi) > 1) halve();
  auto root_at_star = [&](const Poly& p) {
    const Poly g = gcd(p, D);
    return g.size() > 1 && roots_in(g, lo, hi) > 0;
  };
  auto multiplicity = [&](Poly p) {
    int m = 0;
    for (; root_at_star(p); ++m) p = derivative(p);
    return m;
  };
  const int at_star = root_at_star(h) ? 1 : 0;
  const Sturm sh(squarefree(h));
  while (sh.roots(lo, hi) > at_star) halve();
  return sh.roots_above(hi) > 0 || multiplicity(h) > multiplicity(D);
}

}  // namespace

template <class T, int N>
Relation exact_relation(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b) {
  const Body<N> ea = exact_body(a), eb = exact_body(b);
  QVec<N> d;
  for (int i = 0; i < N; ++i) d[i] = ea.center[i] - eb.center[i];
  if (d == QVec<N>{} && ea.quadric == eb.quadric) return Relation::equal;
  const QVec<N> ad = times<N>(ea.quadric, d), bd = times<N>(eb.quadric, d);
  const int meet = external<N>(ea.quadric, eb.quadric, ad, bd);
  if (meet < 0) return Relation::separated;
  if (meet == 0) return Relation::touching;
  // A body inside another has its center there and no larger volume (det of its quadric
  // no smaller): two quick refusals before the search.
  const Q da = det_and_form<N>(ea.quadric, d, d).first, db = det_and_form<N>(eb.quadric, d, d).first;
  if (dot<N>(d, ad) <= 1 && db >= da && contains<N>(ea.quadric, eb.quadric, ad, bd)) return Relation::a_contains_b;
  if (dot<N>(d, bd) <= 1 && da >= db && contains<N>(eb.quadric, ea.quadric, bd, ad)) return Relation::b_contains_a;
  return Relation::overlapping;
}

#define ELLIPSECT_INSTANTIATE(T, N) template Relation exact_relation<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect::detail
