// Independent high-precision REFERENCE for the ellipsect tests (header templates, N = 2 or 3).
//
// Everything here is computed in `Real` (168-bit binary floating point, about 50 decimal
// digits) by routes that are deliberately different from the library's (Eberly: affine map
// of A to the unit ball, SVD of B, Newton on the distance secular equation):
//
//   * relation / contact scale: the Perram-Wertheim (PW) function
//         F(lambda) = lambda (1 - lambda) r^T C(lambda)^-1 r,
//         C(lambda) = (1 - lambda) Ma^-1 + lambda Mb^-1,   r = cb - ca,
//     maximised over lambda in [0, 1] (mu^2 = max F); F, F', F'' are evaluated directly from
//     C (LDL^T of C at every step, no simultaneous diagonalisation), and the maximiser is the
//     root of the strictly decreasing F', found by bracketed, safeguarded Newton.  (F is
//     strictly concave: in the eigenbasis of K = La^-1 Mb^-1 La^-T, La = Ax_a diag(r_a),
//     F = sum z_i^2 lambda (1 - lambda) / D_i, D_i = 1 - lambda + lambda k_i, and
//     F'' = -2 sum z_i^2 k_i / D_i^3 < 0; F'(0) = r^T Ma r > 0, F'(1) = -r^T Mb r < 0.)
//     The PW point x = ca + (1 - lambda) Ma^-1 C^-1 r is the minimiser over x of
//     lambda q_A(x) + (1 - lambda) q_B(x) (check: (lambda Ma + (1 - lambda) Mb)(x - ca) =
//     (1 - lambda) Mb r); at the optimal lambda q_A(x) = q_B(x) = mu^2 (envelope theorem).
//   * containment / boundary extrema: extrema of a quadratic on the unit sphere via a
//     one-dimensional secular (trust-region) equation, after a cyclic Jacobi eigen-
//     decomposition written here (not Eigen's solver).  The optimal value is computed from
//     its dual form, which is stationary in the multiplier, and the "hard case" (gradient
//     orthogonal to the extreme eigenspace, e.g. concentric bodies) is handled exactly.
//   * first contact under constant velocities: mu(t) is the gauge of the (convex, centrally
//     symmetric) Minkowski sum A - B evaluated at r(t) = r0 + t v, hence CONVEX in t.
//     d(mu^2)/dt = 2 lambda (1 - lambda) v . C^-1 r (envelope theorem) and its derivative
//     are available in closed form, so t_min = argmin mu is the root of the increasing
//     d(mu^2)/dt (bracketed Newton, full precision; this replaces the golden-section search
//     suggested in the brief and gives min_mu to full precision), and the contact time is the
//     root of mu^2(t) = 1 on [0, t_min] (bracketed Newton from t = 0; mu^2 is convex and
//     decreasing there, so Newton approaches monotonically).
//
// Input bodies are double; they are converted EXACTLY to Real, and the axes are then
// re-orthonormalised in Real (modified Gram-Schmidt, twice), which defines the exact body
// used by every function (but classify_stored, which takes the axes as given: the body of
// the exact mode, whose quadric is formed from the stored axes).  Results are exact for
// that body to roughly 1e-45 relative (see the notes at each function); more precisely
// about 1e-50 times the condition number of the quadrics involved (e.g. ~1e-39 for axis
// ratios of 1e6 inside one body).
//
// `band` (classify, first_contact) only widens the tests `touching`, `equal` and
// `touching_at_start`; exact tangencies computed here come out as 1 +- ~1e-50, so pass a
// band > 0 (e.g. 1e-30) to recognise them; band = 0 makes the outcome rounding-dependent.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/eigen.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ellipsect::reference {

using Real = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<50>,
                                           boost::multiprecision::et_off>;

template <int N> using RVec = Eigen::Matrix<Real, N, 1>;
template <int N> using RMat = Eigen::Matrix<Real, N, N>;
template <int N> using DVec = Eigen::Matrix<double, N, 1>;
template <int N> using DMat = Eigen::Matrix<double, N, N>;

inline double to_double(const Real& x) { return x.convert_to<double>(); }

template <int N> inline DVec<N> to_double(const RVec<N>& v) {
  DVec<N> out;
  for (int i = 0; i < N; ++i) out(i) = to_double(v(i));
  return out;
}

// Exact conversion (every double is representable in Real).
template <int N> inline RVec<N> to_real(const DVec<N>& v) {
  RVec<N> out;
  for (int i = 0; i < N; ++i) out(i) = Real(v(i));
  return out;
}

// ------------------------------------------------------------------------------------------
// Public types
// ------------------------------------------------------------------------------------------

// { center + axes * diag(radii) * u : |u| <= 1 }; axes orthonormal columns (to ~1e-16; more
// than 1e-6 deviation throws std::invalid_argument), radii finite and > 0.
template <int N> struct Body {
  Eigen::Matrix<double, N, 1> center;
  Eigen::Matrix<double, N, N> axes;
  Eigen::Matrix<double, N, 1> radii;
};

template <int N> struct PwResult {
  Real mu;      // contact scale factor (0 when the centres coincide)
  Real lambda;  // maximiser of F (0.5, meaningless, when the centres coincide)
  Eigen::Matrix<Real, N, 1> point;  // where A and B, both scaled by mu about their centres, touch
};

template <int N> struct Range {
  Real min, max;
};

enum class Relation { separated, touching, overlapping, a_contains_b, b_contains_a, equal };

template <int N> struct Classification {
  Relation relation;
  Real mu;            // PW scale factor
  Real a_in_b;        // max over boundary(A) of sqrt(q_B)   (<= 1 iff A inside B)
  Real b_in_a;        // max over boundary(B) of sqrt(q_A)   (<= 1 iff B inside A)
  Real min_a_over_b;  // min over boundary(B) of sqrt(q_A)
  Real min_b_over_a;  // min over boundary(A) of sqrt(q_B)
  Real margin;        // min |x - 1| over the five numbers above
};

enum class ContactKind { hit, touching_at_start, overlapping_at_start, none };

template <int N> struct Contact {
  ContactKind kind;
  Real time;  // hit: contact time; *_at_start: 0; none: +infinity
  Eigen::Matrix<Real, N, 1> point;   // PW point (world frame) at `time` (none: at argmin mu)
  Eigen::Matrix<Real, N, 1> normal;  // unit Ma (x - ca(t)), A -> B (zero if centres coincide)
  Real min_mu;  // min of mu(t) over the window [0, min(t_max, horizon)], in every case
  Real t_min;   // where that minimum is reached (0 if mu is non-decreasing from the start)
};

inline const char* name(Relation r) {
  switch (r) {
    case Relation::separated: return "separated";
    case Relation::touching: return "touching";
    case Relation::overlapping: return "overlapping";
    case Relation::a_contains_b: return "a_contains_b";
    case Relation::b_contains_a: return "b_contains_a";
    case Relation::equal: return "equal";
  }
  return "?";
}
inline const char* name(ContactKind k) {
  switch (k) {
    case ContactKind::hit: return "hit";
    case ContactKind::touching_at_start: return "touching_at_start";
    case ContactKind::overlapping_at_start: return "overlapping_at_start";
    case ContactKind::none: return "none";
  }
  return "?";
}

namespace detail {

inline const Real& eps() {
  static const Real e = std::numeric_limits<Real>::epsilon();  // 2^-167 ~ 5.3e-51
  return e;
}
inline Real infinity() { return std::numeric_limits<Real>::infinity(); }

template <int N> inline Real dot(const RVec<N>& a, const RVec<N>& b) {
  Real s = a(0) * b(0);
  for (int i = 1; i < N; ++i) s += a(i) * b(i);
  return s;
}
template <int N> inline RVec<N> matvec(const RMat<N>& A, const RVec<N>& x) {
  RVec<N> y;
  for (int i = 0; i < N; ++i) {
    Real s = A(i, 0) * x(0);
    for (int j = 1; j < N; ++j) s += A(i, j) * x(j);
    y(i) = s;
  }
  return y;
}
template <int N> inline bool is_zero(const RVec<N>& v) {
  for (int i = 0; i < N; ++i)
    if (v(i) != 0) return false;
  return true;
}

// A body in Real: exact copy of the double input with re-orthonormalised axes.
template <int N> struct RBody {
  RVec<N> c;      // centre
  RMat<N> axes;   // orthonormal columns
  RVec<N> radii;  // > 0
  RMat<N> M;      // axes diag(radii)^-2 axes^T
  RMat<N> P;      // M^-1 = axes diag(radii)^2 axes^T
  RMat<N> L;      // axes diag(radii)
  Real rmin, rmax;
};

template <int N> void complete_rbody(RBody<N>& r);

template <int N> RBody<N> make_rbody(const Body<N>& b, const char* name = "body") {
  static_assert(N >= 1, "dimension");
  for (int i = 0; i < N; ++i) {
    if (!std::isfinite(b.center(i)))
      throw std::invalid_argument(std::string("reference: ") + name + ".center not finite");
    if (!(std::isfinite(b.radii(i)) && b.radii(i) > 0))
      throw std::invalid_argument(std::string("reference: ") + name + ".radii must be finite > 0");
    for (int j = 0; j < N; ++j)
      if (!std::isfinite(b.axes(i, j)))
        throw std::invalid_argument(std::string("reference: ") + name + ".axes not finite");
  }
  const DMat<N> gram = b.axes.transpose() * b.axes - DMat<N>::Identity();
  if (gram.cwiseAbs().maxCoeff() > 1e-6)
    throw std::invalid_argument(std::string("reference: ") + name + ".axes not orthonormal");

  RBody<N> r;
  r.c = to_real<N>(b.center);
  r.radii = to_real<N>(b.radii);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) r.axes(i, j) = Real(b.axes(i, j));
  // Modified Gram-Schmidt, applied twice ("twice is enough").
  for (int pass = 0; pass < 2; ++pass) {
    for (int j = 0; j < N; ++j) {
      RVec<N> v = r.axes.col(j);
      for (int k = 0; k < j; ++k) {
        const RVec<N> q = r.axes.col(k);
        const Real p = dot<N>(q, v);
        for (int i = 0; i < N; ++i) v(i) -= p * q(i);
      }
      const Real n = sqrt(dot<N>(v, v));
      for (int i = 0; i < N; ++i) r.axes(i, j) = v(i) / n;
    }
  }
  complete_rbody<N>(r);
  return r;
}

// Fills rmin, rmax, L, M and P of a body whose centre, orthonormal axes and radii are set.
template <int N> void complete_rbody(RBody<N>& r) {
  r.rmin = r.radii(0);
  r.rmax = r.radii(0);
  for (int k = 1; k < N; ++k) {
    r.rmin = std::min(r.rmin, r.radii(k));
    r.rmax = std::max(r.rmax, r.radii(k));
  }
  RVec<N> inv2, sq;
  for (int k = 0; k < N; ++k) {
    sq(k) = r.radii(k) * r.radii(k);
    inv2(k) = Real(1) / sq(k);
  }
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < N; ++k) r.L(i, k) = r.axes(i, k) * r.radii(k);
    for (int j = 0; j <= i; ++j) {
      Real m = 0, p = 0;
      for (int k = 0; k < N; ++k) {
        const Real aa = r.axes(i, k) * r.axes(j, k);
        m += aa * inv2(k);
        p += aa * sq(k);
      }
      r.M(i, j) = r.M(j, i) = m;
      r.P(i, j) = r.P(j, i) = p;
    }
  }
}

// LDL^T of a symmetric positive definite matrix (no pivoting needed).
template <int N> struct Ldlt {
  RMat<N> L;     // unit lower triangular (strict part used)
  RVec<N> dinv;  // 1 / D
  void compute(const RMat<N>& A) {
    RVec<N> d;
    for (int j = 0; j < N; ++j) {
      Real s = A(j, j);
      for (int k = 0; k < j; ++k) s -= L(j, k) * L(j, k) * d(k);
      d(j) = s;
      dinv(j) = Real(1) / s;
      for (int i = j + 1; i < N; ++i) {
        Real t = A(i, j);
        for (int k = 0; k < j; ++k) t -= L(i, k) * L(j, k) * d(k);
        L(i, j) = t * dinv(j);
      }
    }
  }
  RVec<N> solve(const RVec<N>& b) const {
    RVec<N> x = b;
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < i; ++k) x(i) -= L(i, k) * x(k);
    for (int i = 0; i < N; ++i) x(i) *= dinv(i);
    for (int i = N - 1; i >= 0; --i)
      for (int k = i + 1; k < N; ++k) x(i) -= L(k, i) * x(k);
    return x;
  }
};

// Root of an INCREASING function on [lo, hi], f(lo) <= 0 <= f(hi) (endpoints are never
// evaluated unless x starts there), by safeguarded Newton (rtsafe): Newton steps that leave
// the bracket or do not shrink fast enough are replaced by bisection.  fdf(x, f, df) sets
// f(x) and f'(x).  `scale` is the absolute size of the interval (roots near 0 are resolved
// to ~1e-52 * scale).  Termination: a step below ~1e-46 relative, or a Newton step below
// 1e-24 relative followed by one more Newton step (quadratic convergence makes that final
// step exact to rounding; waiting for a tiny step instead could loop on rounding noise).
template <class FDF>
Real newton_increasing(FDF&& fdf, Real lo, Real hi, Real x, const Real& scale,
                       int* evaluations = nullptr, int max_iter = 1000) {
  static const Real rel_strict = eps() * Real(1e4), abs_strict = eps() * Real(1e-2);
  static const Real rel_loose("1e-24"), abs_loose("1e-34");
  if (!(x >= lo && x <= hi)) x = lo + (hi - lo) / 2;
  Real dx_old = hi - lo, dx = dx_old;
  Real f, df;
  bool finishing = false;
  int it = 0;
  for (; it < max_iter; ++it) {
    fdf(x, f, df);
    if (f == 0) break;
    if (f < 0) lo = x; else hi = x;
    Real xn;
    bool in_bracket = false, newton = false;
    if (df > 0) {
      xn = x - f / df;
      in_bracket = xn > lo && xn < hi;
      newton = in_bracket && abs(2 * f) <= abs(dx_old * df);
    }
    if (finishing) {
      if (in_bracket) x = xn;
      break;
    }
    if (!newton) xn = lo + (hi - lo) / 2;
    dx_old = dx;
    dx = xn - x;
    x = xn;
    const Real ax = abs(xn);
    if (abs(dx) <= abs_strict * scale + rel_strict * ax ||
        hi - lo <= abs_strict * scale + rel_strict * ax)
      break;
    if (newton && abs(dx) <= abs_loose * scale + rel_loose * ax) finishing = true;
  }
  if (evaluations) *evaluations += it + 1;
  return x;
}

// Cyclic Jacobi eigen-decomposition of a symmetric matrix: A = V diag(h) V^T.
template <int N> void jacobi_eigen(RMat<N> A, RVec<N>& h, RMat<N>& V) {
  V.setIdentity();
  Real fro2 = 0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) fro2 += A(i, j) * A(i, j);
  const Real thresh = fro2 * eps() * eps() * Real(1e-4);
  for (int sweep = 0; sweep < 60; ++sweep) {
    Real off = 0;
    for (int p = 0; p < N; ++p)
      for (int q = p + 1; q < N; ++q) off += A(p, q) * A(p, q);
    if (off <= thresh) break;
    for (int p = 0; p < N; ++p) {
      for (int q = p + 1; q < N; ++q) {
        const Real apq = A(p, q);
        if (apq == 0) continue;
        const Real theta = (A(q, q) - A(p, p)) / (2 * apq);
        Real t = Real(1) / (abs(theta) + sqrt(theta * theta + 1));
        if (theta < 0) t = -t;
        const Real c = Real(1) / sqrt(t * t + 1);
        const Real s = t * c;
        for (int k = 0; k < N; ++k) {  // A <- A J
          const Real akp = A(k, p), akq = A(k, q);
          A(k, p) = c * akp - s * akq;
          A(k, q) = s * akp + c * akq;
        }
        for (int k = 0; k < N; ++k) {  // A <- J^T A
          const Real apk = A(p, k), aqk = A(q, k);
          A(p, k) = c * apk - s * aqk;
          A(q, k) = s * apk + c * aqk;
        }
        A(p, q) = 0;
        A(q, p) = 0;
        for (int k = 0; k < N; ++k) {  // V <- V J
          const Real vkp = V(k, p), vkq = V(k, q);
          V(k, p) = c * vkp - s * vkq;
          V(k, q) = s * vkp + c * vkq;
        }
      }
    }
  }
  for (int i = 0; i < N; ++i) h(i) = A(i, i);
}

// ---------------------------------------------------------------- Perram-Wertheim core

template <int N> struct PwState {
  bool centres_coincide = false;
  Real lambda;  // maximiser
  Real F;       // mu^2
  Real Fpp;     // F''(lambda) < 0
  RVec<N> w;    // C(lambda)^-1 r
  Ldlt<N> chol; // factorisation of C(lambda)
  int iterations = 0;
};

// Evaluates everything at lambda. Returns F'(lambda) in Fp.
template <int N>
void pw_eval(const RMat<N>& Pa, const RMat<N>& Pb, const RMat<N>& Delta, const RVec<N>& r,
             const Real& lam, PwState<N>& s, Real& Fp) {
  const Real oml = 1 - lam;
  RMat<N> C;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j <= i; ++j) C(i, j) = C(j, i) = oml * Pa(i, j) + lam * Pb(i, j);
  s.chol.compute(C);
  s.w = s.chol.solve(r);
  const RVec<N> dw = matvec<N>(Delta, s.w);
  const RVec<N> u = s.chol.solve(dw);
  const Real g = dot<N>(r, s.w);    // r^T C^-1 r
  const Real gp = -dot<N>(s.w, dw); // d/dlambda
  const Real gpp = 2 * dot<N>(dw, u);
  const Real ll = lam * oml, one_m2l = 1 - 2 * lam;
  s.lambda = lam;
  s.F = ll * g;
  Fp = one_m2l * g + ll * gp;
  s.Fpp = -2 * g + 2 * one_m2l * gp + ll * gpp;
}

template <int N>
PwState<N> pw_solve(const RMat<N>& Pa, const RMat<N>& Pb, const RVec<N>& r, Real guess = -1) {
  PwState<N> s;
  if (is_zero<N>(r)) {
    s.centres_coincide = true;
    s.lambda = Real(0.5);
    s.F = 0;
    s.Fpp = 0;
    s.w.setZero();
    RMat<N> C = (Pa + Pb) / 2;
    s.chol.compute(C);
    return s;
  }
  const RMat<N> Delta = Pb - Pa;
  if (!(guess > 0 && guess < 1)) {
    // Support-function guess (exact for two balls): lambda = h_A / (h_A + h_B).
    const Real ha = sqrt(dot<N>(r, matvec<N>(Pa, r)));
    const Real hb = sqrt(dot<N>(r, matvec<N>(Pb, r)));
    guess = ha / (ha + hb);
  }
  int count = 0;
  auto fdf = [&](const Real& lam, Real& f, Real& df) {
    Real Fp;
    pw_eval<N>(Pa, Pb, Delta, r, lam, s, Fp);
    ++count;
    f = -Fp;  // increasing in lambda
    df = -s.Fpp;
  };
  const Real lam = newton_increasing(fdf, Real(0), Real(1), guess, Real(1));
  Real Fp;
  pw_eval<N>(Pa, Pb, Delta, r, lam, s, Fp);
  s.iterations = count + 1;
  return s;
}

template <int N> RVec<N> pw_point(const RBody<N>& a, const PwState<N>& s) {
  // x = ca + (1 - lambda) Ma^-1 C^-1 r  (then x - cb = -lambda Mb^-1 C^-1 r).
  RVec<N> x = matvec<N>(a.P, s.w);
  const Real oml = 1 - s.lambda;
  for (int i = 0; i < N; ++i) x(i) = a.c(i) + oml * x(i);
  return x;
}

// ---------------------------------------------------------------- quadratic on the sphere

// Given b_i and offsets d_i >= 0 of the eigenvalues from the extreme one, returns s >= 0 with
// sum b_i^2 / (s + d_i)^2 = 1, or s = 0 if that sum at s = 0+ is <= 1 (hard case), and
// T = sum b_i^2 / (s + d_i) (terms with b_i = 0 omitted).
template <int N> void secular(const RVec<N>& b, const RVec<N>& d, Real& s, Real& T) {
  Real bn2 = 0, dmax = 0;
  for (int i = 0; i < N; ++i) {
    bn2 += b(i) * b(i);
    dmax = std::max(dmax, d(i));
  }
  auto terms = [&](const Real& x, Real& psi, Real& psi3, Real& t) {
    psi = 0;
    psi3 = 0;
    t = 0;
    for (int i = 0; i < N; ++i) {
      if (b(i) == 0) continue;
      const Real q = Real(1) / (x + d(i));
      const Real b2q = b(i) * b(i) * q;
      t += b2q;
      psi += b2q * q;
      psi3 += b2q * q * q;
    }
  };
  if (bn2 == 0) {
    s = 0;
    T = 0;
    return;
  }
  bool infinite_at_zero = false;
  for (int i = 0; i < N; ++i)
    if (b(i) != 0 && d(i) == 0) infinite_at_zero = true;
  if (!infinite_at_zero) {
    Real psi0, psi30, t0;
    terms(Real(0), psi0, psi30, t0);
    if (psi0 <= 1) {  // hard case: multiplier at the extreme eigenvalue
      s = 0;
      T = t0;
      return;
    }
  }
  const Real bn = sqrt(bn2);
  const Real hi = bn;  // psi(bn) <= bn2 / bn^2 = 1
  Real lo = bn - dmax;  // psi(s) >= bn2 / (s + dmax)^2
  if (lo < 0) lo = 0;
  // Moré-Sorensen form: phi(s) = psi(s)^-1/2 - 1, increasing and nearly linear.
  auto fdf = [&](const Real& x, Real& f, Real& df) {
    Real psi, psi3, t;
    terms(x, psi, psi3, t);
    const Real ip = Real(1) / sqrt(psi);
    f = ip - 1;
    df = ip * ip * ip * psi3;
  };
  const Real scale = bn + dmax;
  s = newton_increasing(fdf, lo, hi, hi, scale);
  Real psi, psi3;
  terms(s, psi, psi3, T);
}

// min and max of q(u) = u^T H u + 2 g^T u + c0 over |u| = 1 (values of q, not sqrt).
template <int N>
void sphere_quadratic_extrema(const RMat<N>& H, const RVec<N>& g, const Real& c0, Real& qmin,
                              Real& qmax) {
  RVec<N> h;
  RMat<N> V;
  jacobi_eigen<N>(H, h, V);
  RVec<N> b;
  for (int i = 0; i < N; ++i) {
    Real s = 0;
    for (int k = 0; k < N; ++k) s += V(k, i) * g(k);
    b(i) = s;
  }
  Real hmax = h(0), hmin = h(0);
  for (int i = 1; i < N; ++i) {
    hmax = std::max(hmax, h(i));
    hmin = std::min(hmin, h(i));
  }
  RVec<N> d;
  Real s, T;
  // max: sigma = hmax + s >= hmax, q = sigma + c0 + g^T (sigma - H)^-1 g (dual form).
  for (int i = 0; i < N; ++i) d(i) = hmax - h(i);
  secular<N>(b, d, s, T);
  qmax = hmax + s + c0 + T;
  // min: sigma = hmin - s <= hmin, q = sigma + c0 - g^T (H - sigma)^-1 g.
  for (int i = 0; i < N; ++i) d(i) = h(i) - hmin;
  secular<N>(b, d, s, T);
  qmin = hmin - s + c0 - T;
  if (qmin < 0) qmin = 0;
}

template <int N> Range<N> metric_range_impl(const RBody<N>& m, const RBody<N>& bd) {
  // x = c_b + L u, q(x) = |diag(1/r_m) Ax_m^T (x - c_m)|^2 = |K u + e|^2.
  RMat<N> K;
  RVec<N> e;
  const RVec<N> dc = bd.c - m.c;
  for (int i = 0; i < N; ++i) {
    const Real ir = Real(1) / m.radii(i);
    Real se = 0;
    for (int k = 0; k < N; ++k) se += m.axes(k, i) * dc(k);
    e(i) = se * ir;
    for (int j = 0; j < N; ++j) {
      Real s = 0;
      for (int k = 0; k < N; ++k) s += m.axes(k, i) * bd.L(k, j);
      K(i, j) = s * ir;
    }
  }
  RMat<N> H;
  RVec<N> g;
  for (int i = 0; i < N; ++i) {
    Real sg = 0;
    for (int k = 0; k < N; ++k) sg += K(k, i) * e(k);
    g(i) = sg;
    for (int j = 0; j <= i; ++j) {
      Real s = 0;
      for (int k = 0; k < N; ++k) s += K(k, i) * K(k, j);
      H(i, j) = H(j, i) = s;
    }
  }
  const Real c0 = dot<N>(e, e);
  Real qmin, qmax;
  sphere_quadratic_extrema<N>(H, g, c0, qmin, qmax);
  return Range<N>{sqrt(qmin), sqrt(qmax)};
}

template <int N> Real abs_minus_one(const Real& x) { return abs(x - 1); }

}  // namespace detail

// ------------------------------------------------------------------------------------------
// 1. Perram-Wertheim scale factor
// ------------------------------------------------------------------------------------------

// mu, the maximising lambda and the PW point x = ca + (1 - lambda) Ma^-1 C^-1 r, where the
// bodies scaled by mu about their own centres touch: q_A(x) = q_B(x) = mu^2 and
// grad q_A(x) is antiparallel to grad q_B(x).  mu: ~1e-48 relative; lambda, point: ~1e-45.
template <int N> PwResult<N> pw(const Body<N>& a, const Body<N>& b) {
  const detail::RBody<N> ra = detail::make_rbody<N>(a, "a"), rb = detail::make_rbody<N>(b, "b");
  const RVec<N> r = rb.c - ra.c;
  const detail::PwState<N> s = detail::pw_solve<N>(ra.P, rb.P, r);
  return PwResult<N>{sqrt(s.F), s.lambda, detail::pw_point<N>(ra, s)};
}

template <int N> Real pw_scale(const Body<N>& a, const Body<N>& b) { return pw<N>(a, b).mu; }

// The same, with the bodies moved by t * velocity (t in Real, centres moved exactly).
template <int N>
PwResult<N> pw_at(const Body<N>& a, const Eigen::Matrix<double, N, 1>& va, const Body<N>& b,
                  const Eigen::Matrix<double, N, 1>& vb, const Real& t) {
  detail::RBody<N> ra = detail::make_rbody<N>(a, "a"), rb = detail::make_rbody<N>(b, "b");
  ra.c += to_real<N>(va) * t;
  rb.c += to_real<N>(vb) * t;
  const detail::PwState<N> s = detail::pw_solve<N>(ra.P, rb.P, RVec<N>(rb.c - ra.c));
  return PwResult<N>{sqrt(s.F), s.lambda, detail::pw_point<N>(ra, s)};
}

// ------------------------------------------------------------------------------------------
// 2. Range of the metric body's gauge over the boundary of another body
// ------------------------------------------------------------------------------------------

// min / max over x on boundary(`boundary`) of sqrt((x - c_m)^T M_m (x - c_m)).
// max <= 1 iff `boundary` lies inside `metric`.  Accuracy ~1e-47 absolute (relative to the
// size of the values).
template <int N> Range<N> metric_range(const Body<N>& metric, const Body<N>& boundary) {
  return detail::metric_range_impl<N>(detail::make_rbody<N>(metric, "metric"),
                                      detail::make_rbody<N>(boundary, "boundary"));
}

// ------------------------------------------------------------------------------------------
// 3. Classification
// ------------------------------------------------------------------------------------------

// equal        if |a_in_b - 1| <= band and |b_in_a - 1| <= band
// a_contains_b if b_in_a <= 1           (exact, includes internal tangency)
// b_contains_a if a_in_b <= 1
// separated    if mu > 1 + band
// touching     if |mu - 1| <= band
// overlapping  otherwise                 (checked in this order)
namespace detail {
template <int N> Classification<N> classify_rbodies(const RBody<N>& ra, const RBody<N>& rb, double band) {
  Classification<N> c;
  const detail::PwState<N> s = detail::pw_solve<N>(ra.P, rb.P, RVec<N>(rb.c - ra.c));
  c.mu = sqrt(s.F);
  const Range<N> over_a = detail::metric_range_impl<N>(rb, ra);  // metric B, boundary A
  const Range<N> over_b = detail::metric_range_impl<N>(ra, rb);  // metric A, boundary B
  c.a_in_b = over_a.max;
  c.min_b_over_a = over_a.min;
  c.b_in_a = over_b.max;
  c.min_a_over_b = over_b.min;
  using detail::abs_minus_one;
  c.margin = std::min({abs_minus_one<N>(c.mu), abs_minus_one<N>(c.a_in_b),
                       abs_minus_one<N>(c.b_in_a), abs_minus_one<N>(c.min_a_over_b),
                       abs_minus_one<N>(c.min_b_over_a)});
  const Real bd(band);
  if (abs_minus_one<N>(c.a_in_b) <= bd && abs_minus_one<N>(c.b_in_a) <= bd)
    c.relation = Relation::equal;
  else if (c.b_in_a <= 1)
    c.relation = Relation::a_contains_b;
  else if (c.a_in_b <= 1)
    c.relation = Relation::b_contains_a;
  else if (c.mu > 1 + bd)
    c.relation = Relation::separated;
  else if (abs_minus_one<N>(c.mu) <= bd)
    c.relation = Relation::touching;
  else
    c.relation = Relation::overlapping;
  return c;
}

// The body exactly as stored: the quadric M = A diag(radii)^-2 A^T of the axes A as given
// (orthonormal only to their rounding), not re-orthonormalised. Its boundary is
// c + L u, |u| = 1, with L = A^-T diag(radii) (L^T M L = I), and P = M^-1 = L L^T; the
// gauge (x - c)^T M (x - c) = |diag(radii)^-1 A^T (x - c)|^2 uses A as given.
template <int N> RBody<N> make_stored_rbody(const Body<N>& b, const char* name = "body") {
  RBody<N> r = make_rbody<N>(b, name);  // validation, centre, radii, rmin, rmax
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) r.axes(i, j) = Real(b.axes(i, j));
  const RMat<N> inv_t = r.axes.inverse().transpose();
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < N; ++k) r.L(i, k) = inv_t(i, k) * r.radii(k);
    for (int j = 0; j <= i; ++j) {
      Real m = 0;
      for (int k = 0; k < N; ++k) m += r.axes(i, k) * r.axes(j, k) / (r.radii(k) * r.radii(k));
      r.M(i, j) = r.M(j, i) = m;
    }
  }
  for (int i = 0; i < N; ++i)
    for (int j = 0; j <= i; ++j) {
      Real p = 0;
      for (int k = 0; k < N; ++k) p += r.L(i, k) * r.L(j, k);
      r.P(i, j) = r.P(j, i) = p;
    }
  return r;
}
}  // namespace detail

template <int N> Classification<N> classify(const Body<N>& a, const Body<N>& b, double band) {
  return detail::classify_rbodies<N>(detail::make_rbody<N>(a, "a"), detail::make_rbody<N>(b, "b"), band);
}

// classify() of the bodies exactly as stored (detail::make_stored_rbody): the referee of the
// exact mode (Options::tolerance = 0), which answers for the stored quadrics. Its margins
// resolve relative gaps down to about 1e-45 (times the quadrics' condition numbers).
template <int N> Classification<N> classify_stored(const Body<N>& a, const Body<N>& b, double band) {
  return detail::classify_rbodies<N>(detail::make_stored_rbody<N>(a, "a"), detail::make_stored_rbody<N>(b, "b"),
                                     band);
}

// ------------------------------------------------------------------------------------------
// 4. First contact under constant velocities
// ------------------------------------------------------------------------------------------

namespace detail {

// A finite horizon after which (for t_max = inf) neither a contact nor the minimum of mu can
// occur: with Ra, Rb the largest and ra, rb the smallest radii, |r|/(Ra+Rb) <= mu <=
// |r|/(ra+rb); take t_s = max(0, closest approach of the centres) and R = 2 max(Ra + Rb,
// kappa |r(t_s)|), kappa = (Ra+Rb)/(ra+rb); after the time T >= t_s where |r(T)| = R,
// mu(t) > 2 max(1, mu(t_s)).
template <int N>
Real horizon(const RBody<N>& a, const RBody<N>& b, const RVec<N>& r0, const RVec<N>& v) {
  const Real vv = dot<N>(v, v);
  Real ts = -dot<N>(r0, v) / vv;
  if (ts < 0) ts = 0;
  const RVec<N> rs = r0 + v * ts;
  const Real big = a.rmax + b.rmax, kappa = big / (a.rmin + b.rmin);
  const Real R = 2 * std::max(big, kappa * sqrt(dot<N>(rs, rs)));
  const Real rv = dot<N>(rs, v);
  const Real disc = rv * rv + vv * (R * R - dot<N>(rs, rs));
  return ts + (sqrt(disc) - rv) / vv;
}

}  // namespace detail

// kind: overlapping_at_start if mu(0) < 1 - band; touching_at_start if |mu(0) - 1| <= band;
// otherwise hit at the first t in [0, t_max] with mu(t) = 1 when min mu <= 1, else none.
// Zero relative velocity (exactly, vb == va) or t_max == 0: none (or a start state).
// min_mu / t_min are the minimum of mu over the window and its location, filled for every
// kind (for the start states too); with t_max = inf the window is [0, horizon], which
// contains the global minimum over [0, inf).
// Precision: time ~1e-45 relative for transversal contacts (a near-double root, grazing
// paths with min_mu within ~1e-20 of 1, only gives ~sqrt of that); min_mu ~1e-48.
template <int N>
Contact<N> first_contact(const Body<N>& a, const Eigen::Matrix<double, N, 1>& va,
                         const Body<N>& b, const Eigen::Matrix<double, N, 1>& vb, double t_max,
                         double band) {
  using namespace detail;
  if (std::isnan(t_max) || t_max < 0)
    throw std::invalid_argument("reference: t_max must be >= 0 (or +inf)");
  const RBody<N> ra = make_rbody<N>(a, "a"), rb = make_rbody<N>(b, "b");
  const RVec<N> va_r = to_real<N>(va);
  const RVec<N> v = to_real<N>(vb) - va_r;
  const RVec<N> r0 = rb.c - ra.c;

  Real lam_guess = -1;
  auto state_at = [&](const Real& t) {
    PwState<N> s = pw_solve<N>(ra.P, rb.P, RVec<N>(r0 + v * t), lam_guess);
    if (!s.centres_coincide) lam_guess = s.lambda;
    return s;
  };
  auto fill = [&](Contact<N>& c, const Real& t, const PwState<N>& s) {
    RBody<N> at = ra;
    at.c = ra.c + va_r * t;
    c.point = pw_point<N>(at, s);
    RVec<N> n = matvec<N>(ra.M, RVec<N>(c.point - at.c));
    const Real nn = sqrt(dot<N>(n, n));
    if (nn > 0) n /= nn;
    c.normal = n;
  };

  Contact<N> c;
  const PwState<N> s0 = state_at(Real(0));
  const Real mu0 = sqrt(s0.F);

  // m(t) = mu(t)^2 is convex; m'(t) = 2 lambda (1 - lambda) v . w,
  // m''(t) = 2 lambda (1 - lambda) v^T C^-1 v - G^2 / F'',
  // G = 2 (1 - 2 lambda) v . w - 2 lambda (1 - lambda) (C^-1 v) . (Delta w).
  const RMat<N> Delta = rb.P - ra.P;
  auto dm = [&](const PwState<N>& s) {
    const Real ll = s.lambda * (1 - s.lambda);
    return 2 * ll * dot<N>(v, s.w);
  };
  auto d2m = [&](const PwState<N>& s) {
    if (s.centres_coincide) {  // m(t) = (t - t0)^2 gauge(v)^2 near the coincidence
      const PwState<N> sv = pw_solve<N>(ra.P, rb.P, v);
      return 2 * sv.F;
    }
    const Real ll = s.lambda * (1 - s.lambda);
    const RVec<N> cv = s.chol.solve(v);
    const Real G = 2 * (1 - 2 * s.lambda) * dot<N>(v, s.w) -
                   2 * ll * dot<N>(cv, matvec<N>(Delta, s.w));
    return 2 * ll * dot<N>(v, cv) - G * G / s.Fpp;
  };

  // Minimum of mu over the window [0, T], T = min(t_max, horizon): root of the increasing m'.
  Real t_min = 0;
  PwState<N> smin = s0;
  if (!is_zero<N>(v) && t_max > 0 && dm(s0) < 0) {
    Real T = horizon<N>(ra, rb, r0, v);
    if (std::isfinite(t_max) && Real(t_max) < T) T = Real(t_max);
    const PwState<N> sT = state_at(T);
    if (dm(sT) <= 0) {
      t_min = T;
      smin = sT;
    } else {
      const Real tc = -dot<N>(r0, v) / dot<N>(v, v);
      auto fdf = [&](const Real& t, Real& f, Real& df) {
        const PwState<N> s = state_at(t);
        f = dm(s);
        df = d2m(s);
      };
      t_min = newton_increasing(fdf, Real(0), T, tc, T);
      smin = state_at(t_min);
    }
  }
  c.min_mu = sqrt(smin.F);
  c.t_min = t_min;

  const Real bd(band);
  if (mu0 < 1 - bd || abs(mu0 - 1) <= bd) {
    c.kind = mu0 < 1 - bd ? ContactKind::overlapping_at_start : ContactKind::touching_at_start;
    c.time = 0;
    fill(c, Real(0), s0);
    return c;
  }
  if (c.min_mu > 1) {
    c.kind = ContactKind::none;
    c.time = infinity();
    fill(c, t_min, smin);
    return c;
  }
  // Contact: root of 1 - m(t) (increasing on [0, t_min]).
  Real t_hit = t_min;
  if (smin.F < 1) {
    auto fdf = [&](const Real& t, Real& f, Real& df) {
      const PwState<N> s = state_at(t);
      f = 1 - s.F;
      df = -dm(s);
    };
    t_hit = newton_increasing(fdf, Real(0), t_min, Real(0), t_min);
  }
  c.kind = ContactKind::hit;
  c.time = t_hit;
  fill(c, t_hit, state_at(t_hit));
  return c;
}

// The functions the tests and benchmarks call, for N = 2 and 3: compiled once, in
// reference.cpp (the library ellipsect_reference), not in every program that includes
// this header.
#define ELLIPSECT_REFERENCE_FUNCTIONS(extern_, N) \
  extern_ template detail::RBody<N> detail::make_rbody<N>(const Body<N>&, const char*); \
  extern_ template PwResult<N> pw<N>(const Body<N>&, const Body<N>&); \
  extern_ template Real pw_scale<N>(const Body<N>&, const Body<N>&); \
  extern_ template PwResult<N> pw_at<N>(const Body<N>&, const DVec<N>&, const Body<N>&, const DVec<N>&, const Real&); \
  extern_ template Range<N> metric_range<N>(const Body<N>&, const Body<N>&); \
  extern_ template Classification<N> classify<N>(const Body<N>&, const Body<N>&, double); \
  extern_ template Contact<N> first_contact<N>(const Body<N>&, const DVec<N>&, const Body<N>&, const DVec<N>&, double, \
                                               double);
ELLIPSECT_REFERENCE_FUNCTIONS(extern, 2)
ELLIPSECT_REFERENCE_FUNCTIONS(extern, 3)

}  // namespace ellipsect::reference
