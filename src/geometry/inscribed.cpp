// The maximum-volume ellipsoid inside a polytope of half-spaces (geometry.hpp): phase I on the
// Chebyshev-ball linear program, a barrier method on (B, d) (in double along the path, in
// long double at the centers that certify), the dual point of the last center corrected to
// feasibility, the body shrunk by ulps until the exact classification finds it inside every
// half-space, its volume gap from the dual bound.
#include <ellipsect/classify.hpp>
#include <ellipsect/geometry.hpp>
#include <ellipsect/half_space.hpp>

#include "detail/axes.hpp"
#include "detail/compensated.hpp"
#include "detail/hull.hpp"
#include "detail/instantiate.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <utility>

namespace ellipsect {

std::string_view to_string(InscribedStatus s) noexcept {
  static constexpr std::string_view names[] = {"optimal", "rounding_limited", "did_not_converge", "unbounded",
                                                "empty"};  // in the enum's order
  const auto k = static_cast<std::size_t>(s);
  return k < std::size(names) ? names[k] : "?";
}

namespace {

using L = long double;
template <int N> using LV = Eigen::Matrix<L, N, 1>;
template <int N> using LM = Eigen::Matrix<L, N, N>;

const L eps_l = std::numeric_limits<L>::epsilon();

// The half-spaces as a_i^T y <= beta_i in coordinates y = (x - origin) / scale: a_i the stored
// normal, beta_i = n_i . (p_i - origin) / scale, the differences exact (two-sum in double),
// the products exact (Dekker's in long double) and their sum compensated.
template <class T, int N>
struct Planes {
  std::vector<LV<N>> a;
  std::vector<L> beta;
  Vec<double, N> origin;
  L scale = 1;

  Planes(std::span<const HalfSpace<T, N>> h, const Vec<double, N>& o, L s) : origin(o), scale(s) {
    a.reserve(h.size());
    beta.reserve(h.size());
    for (const auto& hs : h) {
      detail::Double<L> sum{};
      for (int j = 0; j < N; ++j) {
        const detail::Double<double> diff = detail::two_sum<double>(double(hs.point()[j]), -o[j]);
        const L n = L(hs.normal()[j]);
        sum = detail::add(sum, detail::two_product<L>(n, L(diff.hi)));
        sum = detail::add(sum, detail::two_product<L>(n, L(diff.lo)));
      }
      a.push_back(hs.normal().template cast<L>());
      beta.push_back((sum.hi + sum.lo) / s);
    }
  }
  std::size_t size() const { return a.size(); }
};

// A symmetric positive definite solve of the Newton system, Jacobi-scaled, with a ridge of
// 1e-18 for directions the objective leaves flat (normals that do not span).
template <class H, class G>
G newton_direction(const H& h, const G& g) {
  using S = typename G::Scalar;
  const Eigen::Index n = g.size();
  G d(n);
  for (Eigen::Index i = 0; i < n; ++i) d[i] = h(i, i) > 0 ? 1 / std::sqrt(h(i, i)) : 1;
  H s = d.asDiagonal() * h * d.asDiagonal();
  s.diagonal().array() += S(1e-18);
  const G x = Eigen::LDLT<H>(s).solve(-(d.asDiagonal() * g));
  return d.asDiagonal() * x;
}

// ---- Phase I: maximize r subject to a_i^T x + r <= beta_i and |x_j| + r <= box ----

enum class Start { interior, empty, unbounded, capped };

template <class T, int N>
struct Phase1 {
  LV<N> x = LV<N>::Zero();
  L r = 0;
  int steps = 0;
  Start found = Start::capped;
};

constexpr int phase1_steps = 3000;

template <class T, int N>
Phase1<T, N> phase_one(const Planes<T, N>& p) {
  const L box = L(1e12);
  std::vector<LV<N>> a = p.a;
  std::vector<L> beta = p.beta;
  for (int j = 0; j < N; ++j) {
    a.push_back(LV<N>::Unit(j));
    beta.push_back(box);
    a.push_back(-LV<N>::Unit(j));
    beta.push_back(box);
  }
  const std::size_t m = a.size();
  constexpr int n = N + 1;
  using LX = Eigen::Matrix<L, n, 1>;
  using LXX = Eigen::Matrix<L, n, n>;
  Phase1<T, N> out;
  L lowest = *std::min_element(beta.begin(), beta.end());
  out.r = lowest - 1;
  LX v;
  v << out.x, out.r;
  const auto slacks = [&](const LX& at, std::vector<L>& s) {
    s.resize(m);
    for (std::size_t i = 0; i < m; ++i) {
      s[i] = beta[i] - a[i].dot(at.template head<N>()) - at[N];
      if (!(s[i] > 0)) return false;
    }
    return true;
  };
  const auto value = [&](const LX& at, L t, const std::vector<L>& s) {
    L f = -t * at[N];
    for (L si : s) f -= std::log(si);
    return f;
  };
  std::vector<L> s, next;
  slacks(v, s);
  const L gap_floor = L(1e-13);
  for (L t = L(m);; t *= 10) {
    // Center at t.
    for (int inner = 0; inner < 60; ++inner) {
      if (out.steps >= phase1_steps) {
        out.x = v.template head<N>(), out.r = v[N];
        return out;
      }
      ++out.steps;
      LX g = LX::Zero();
      LXX h = LXX::Zero();
      g[N] = -t;
      for (std::size_t i = 0; i < m; ++i) {
        LX c;
        c << a[i], 1;
        const L inverse = 1 / s[i];
        g += inverse * c;
        h.template selfadjointView<Eigen::Lower>().rankUpdate(c, inverse * inverse);
      }
      h = h.template selfadjointView<Eigen::Lower>();
      const LX dv = newton_direction(h, g);
      const L lambda2 = -g.dot(dv);
      if (!(lambda2 > L(1e-10))) break;
      L alpha = 1;
      for (std::size_t i = 0; i < m; ++i) {
        LX c;
        c << a[i], 1;
        const L rate = c.dot(dv);
        if (rate > 0) alpha = std::min(alpha, L(0.99) * s[i] / rate);
      }
      const L f0 = value(v, t, s);
      bool moved = false;
      for (int halving = 0; halving < 60; ++halving, alpha /= 2) {
        const LX trial = v + alpha * dv;
        if (!slacks(trial, next)) continue;
        if (lambda2 < L(1e-3) || value(trial, t, next) <= f0 - L(0.25) * alpha * lambda2) {
          v = trial;
          s.swap(next);
          moved = true;
          break;
        }
      }
      if (!moved) break;
    }
    out.x = v.template head<N>(), out.r = v[N];
    const L gap = 2 * L(m) / t;  // twice the central gap m / t: the center's rounding included
    if (out.r >= L(1e10)) {
      out.found = Start::unbounded;
      return out;
    }
    if (out.r > 0 && gap <= out.r / 4) {
      out.found = Start::interior;
      return out;
    }
    // No ball above 1e-12 of the points' extent; or the gap at its floor.
    if (out.r + gap <= L(1e-12) || gap < gap_floor) {
      out.found = out.r + gap > L(1e-12) && out.r > 0 ? Start::interior : Start::empty;
      return out;
    }
  }
}

// ---- The barrier method on (B, d) ----

// B's coordinates in the symmetric basis E_a = e_k e_l^T + e_l e_k^T (halved where k = l): the
// pairs (k, k), then (k, l) for k < l.
template <int N>
constexpr int sym_size = N * (N + 1) / 2;

template <int N>
constexpr std::array<std::pair<int, int>, sym_size<N>> symmetric_basis = [] {
  std::array<std::pair<int, int>, sym_size<N>> e{};
  std::size_t a = 0;
  for (int k = 0; k < N; ++k) e[a++] = {k, k};
  for (int k = 0; k < N; ++k)
    for (int l = k + 1; l < N; ++l) e[a++] = {k, l};
  return e;
}();

// The half-spaces as the barrier sees them, in the scalar S of its centering: a_i, beta_i, and
// the parts of the Hessian of -log(s_i^2 - |B a_i|^2) that do not change with (B, d):
// U_i^T U_i (U_i's columns E_a a_i, the derivatives of B a_i) and a_i a_i^T.
template <class S, int N>
struct Faces {
  static constexpr int q = sym_size<N>;
  std::vector<Eigen::Matrix<S, N, 1>> a;
  std::vector<S> beta;
  std::vector<Eigen::Matrix<S, N, q>> u;
  std::vector<Eigen::Matrix<S, q, q>> uu;
  std::vector<Eigen::Matrix<S, N, N>> aa;

  template <class T>
  explicit Faces(const Planes<T, N>& p) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Eigen::Matrix<S, N, 1> ai = p.a[i].template cast<S>();
      Eigen::Matrix<S, N, q> ui = Eigen::Matrix<S, N, q>::Zero();  // E_a a_i = e_k a_il + e_l a_ik
      for (int c = 0; c < q; ++c) {
        const auto [k, l] = symmetric_basis<N>[std::size_t(c)];
        ui(k, c) = ai[l];
        ui(l, c) = ai[k];
      }
      a.push_back(ai);
      beta.push_back(S(p.beta[i]));
      u.push_back(ui);
      uu.push_back(ui.transpose() * ui);
      aa.push_back(ai * ai.transpose());
    }
  }
  std::size_t size() const { return a.size(); }
};

template <class S, int N>
struct Iterate {
  Eigen::Matrix<S, N, N> b = Eigen::Matrix<S, N, N>::Identity();
  Eigen::Matrix<S, N, 1> d = Eigen::Matrix<S, N, 1>::Zero();

  template <class R>
  Iterate<R, N> cast() const {
    Iterate<R, N> y;
    y.b = b.template cast<R>();
    y.d = d.template cast<R>();
    return y;
  }
};

// The barrier's value at (B, d), or infinity outside its domain.
template <class S, int N>
S barrier(const Faces<S, N>& p, const Iterate<S, N>& x, S t) {
  const Eigen::LLT<Eigen::Matrix<S, N, N>> llt(x.b);
  if (llt.info() != Eigen::Success) return std::numeric_limits<S>::infinity();
  S logdet = 0;
  for (int k = 0; k < N; ++k) {
    const S dk = llt.matrixL()(k, k);
    if (!(dk > 0)) return std::numeric_limits<S>::infinity();
    logdet += 2 * std::log(dk);
  }
  S f = -t * logdet;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const S s = p.beta[i] - p.a[i].dot(x.d);
    const S w = (x.b * p.a[i]).norm();
    if (!(s > w)) return std::numeric_limits<S>::infinity();
    f -= std::log((s - w) * (s + w));
  }
  return f;
}

// The dual point of the iterate at t, corrected (geometry.hpp): its value D with the
// rounding allowance added, and the weights mu_i s_i / N. ok false where the correction
// leaves a cone or -G is not definite.
struct Dual {
  bool ok = false;
  L value = 0;
  std::vector<double> weights;
};

template <int N>
Dual dual_point(const Faces<L, N>& p, const Iterate<L, N>& x, L t) {
  const std::size_t m = p.size();
  Dual out;
  std::vector<L> mu(m), s(m);
  std::vector<LV<N>> z(m);
  LV<N> r = LV<N>::Zero();
  LM<N> normal = LM<N>::Zero();
  for (std::size_t i = 0; i < m; ++i) {
    s[i] = p.beta[i] - p.a[i].dot(x.d);
    const LV<N> w = x.b * p.a[i];
    const L nw = w.norm();
    const L g = (s[i] - nw) * (s[i] + nw);
    if (!(s[i] > 0 && g > 0)) return out;
    mu[i] = 2 * s[i] / (t * g);
    z[i] = -2 * w / (t * g);
    r += mu[i] * p.a[i];
    normal.noalias() += mu[i] * p.aa[i];
  }
  const Eigen::LDLT<LM<N>> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return out;
  const LV<N> lambda = ldlt.solve(r);
  if (!lambda.allFinite()) return out;
  LV<N> residual = LV<N>::Zero();
  L total_mu = 0, terms = 0, dual = 0;
  LM<N> g = LM<N>::Zero();
  for (std::size_t i = 0; i < m; ++i) {
    const L f = 1 - p.a[i].dot(lambda);
    if (!(f > 0)) return out;
    mu[i] *= f;
    z[i] *= f;
    const L nz = z[i].norm();
    if (nz > mu[i]) z[i] *= mu[i] / nz * (1 - 4 * eps_l);
    residual += mu[i] * p.a[i];
    total_mu += mu[i];
    dual += mu[i] * p.beta[i];
    terms += std::abs(mu[i] * p.beta[i]);
    g.noalias() += (p.a[i] * z[i].transpose() + z[i] * p.a[i].transpose()) / 2;
  }
  const Eigen::LLT<LM<N>> llt(-g);
  if (llt.info() != Eigen::Success) return out;
  L logdet = 0;
  for (int k = 0; k < N; ++k) {
    const L dk = llt.matrixL()(k, k);
    if (!(dk > 0)) return out;
    logdet += 2 * std::log(dk);
  }
  dual -= logdet + N;
  // The residual |sum mu_i a_i| (and its own rounding) times the polytope's extent from the
  // origin, at most |d| + N r_max (John: the polytope lies in the optimum scaled by N about its
  // center), twice for safety; and the long double evaluation's rounding.
  const L r_max = Eigen::SelfAdjointEigenSolver<LM<N>>(x.b, Eigen::EigenvaluesOnly).eigenvalues()[N - 1];
  const L extent = x.d.norm() + 2 * N * r_max;
  const L allowance = (residual.norm() + 4 * eps_l * L(m) * total_mu) * extent +
                      64 * eps_l * L(m + N) * (terms + std::abs(logdet) + N);
  out.value = dual + allowance;
  out.weights.resize(m);
  for (std::size_t i = 0; i < m; ++i) out.weights[i] = double(mu[i] * s[i] / N);
  out.ok = std::isfinite(double(out.value));
  return out;
}

// The Newton step of the barrier at (B, d), t: direction (B part, d part) and decrement^2.
// In the coordinates v = (B's in E_a, d), with s_i = beta_i - a_i . d, w_i = B a_i,
// g_i = s_i^2 - |w_i|^2 and r_i = (U_i^T w_i, s_i a_i): the term -log g_i has gradient
// 2 r_i / g_i and Hessian 4 r_i r_i^T / g_i^2 + (2 / g_i) diag(U_i^T U_i, -a_i a_i^T);
// -t log det B has gradient -t tr(B^-1 E_a) and Hessian t tr(B^-1 E_a B^-1 E_b).
template <class S, int N>
std::pair<Iterate<S, N>, S> newton_step(const Faces<S, N>& p, const Iterate<S, N>& x, S t) {
  constexpr int q = sym_size<N>;
  constexpr int nv = q + N;
  using V = Eigen::Matrix<S, nv, 1>;
  using H = Eigen::Matrix<S, nv, nv>;
  using M = Eigen::Matrix<S, N, N>;
  V g = V::Zero();
  H h = H::Zero();
  const M inverse = x.b.inverse();
  std::array<M, q> ia;  // B^-1 E_a = (B^-1 e_k) e_l^T + (B^-1 e_l) e_k^T (halved where k = l)
  for (int c = 0; c < q; ++c) {
    const auto [k, l] = symmetric_basis<N>[std::size_t(c)];
    ia[std::size_t(c)] = inverse.col(k) * M::Identity().row(l);
    if (k != l) ia[std::size_t(c)] += inverse.col(l) * M::Identity().row(k);
  }
  for (int a = 0; a < q; ++a) {
    g[a] = -t * ia[std::size_t(a)].trace();
    for (int b = 0; b <= a; ++b)  // tr(X Y) = sum of X .* Y^T
      h(a, b) = t * ia[std::size_t(a)].cwiseProduct(ia[std::size_t(b)].transpose()).sum();
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    const S s = p.beta[i] - p.a[i].dot(x.d);
    const Eigen::Matrix<S, N, 1> w = x.b * p.a[i];
    const S nw = w.norm();
    const S gi = (s - nw) * (s + nw);
    V r;
    r.template head<q>() = p.u[i].transpose() * w;
    r.template tail<N>() = s * p.a[i];
    g += (2 / gi) * r;
    h.template selfadjointView<Eigen::Lower>().rankUpdate(r, 4 / (gi * gi));
    h.template topLeftCorner<q, q>() += (2 / gi) * p.uu[i];
    h.template bottomRightCorner<N, N>() -= (2 / gi) * p.aa[i];
  }
  h = h.template selfadjointView<Eigen::Lower>();
  const V dv = newton_direction(h, g);
  Iterate<S, N> step;
  for (int c = 0; c < q; ++c) {
    const auto [k, l] = symmetric_basis<N>[std::size_t(c)];
    step.b(k, l) = step.b(l, k) = dv[c];
  }
  step.d = dv.template tail<N>();
  return {step, -g.dot(dv)};
}

// Newton's method on the barrier at t from x, damped (Armijo on a quarter of the decrement),
// until the decrement reaches its floor, the steps run out (capped) or the body's trace passes
// too_large (unbounded).
enum class Centering { centered, capped, unbounded };

template <class S, int N>
Centering center_at(const Faces<S, N>& p, Iterate<S, N>& x, S t, S too_large, int& left, int& iterations) {
  S previous = std::numeric_limits<S>::infinity();
  for (int inner = 0; inner < 80; ++inner) {
    if (left <= 0) return Centering::capped;
    --left;
    ++iterations;
    const auto [dx, lambda2] = newton_step<S, N>(p, x, t);
    if (!(lambda2 >= 0) || lambda2 < S(1e-22)) break;
    const S f0 = barrier<S, N>(p, x, t);
    S alpha = 1;
    bool moved = false;
    for (int halving = 0; halving < 80; ++halving, alpha /= 2) {
      Iterate<S, N> trial;
      trial.b = x.b + alpha * dx.b;
      trial.d = x.d + alpha * dx.d;
      const S f = barrier<S, N>(p, trial, t);
      if (!std::isfinite(double(f))) continue;
      if (lambda2 < S(1e-3) || f <= f0 - S(0.25) * alpha * lambda2) {
        x = trial;
        moved = true;
        break;
      }
    }
    if (!moved) break;
    if (x.b.trace() > too_large) return Centering::unbounded;
    // Near the center Newton's decrement squares at each step: where it does not fall
    // fourfold it has reached its rounding's floor (which grows with t: the slacks of the
    // touching half-spaces are about 1/t of their distances, so rounded to eps t).
    if (lambda2 < S(1e-6) && lambda2 > previous / 4) break;
    previous = lambda2;
  }
  return Centering::centered;
}

InputError unrepresentable() {
  return InputError("half_spaces", "no ellipsoid stored in the type lies inside them: its aspect ratio would exceed 1e8 "
                                   "(a polytope that thin) or its radii the type's range");
}

template <class T, int N>
L log_det_stored(const Ellipsoid<T, N>& body, L scale) {
  L s = 0;
  for (int k = 0; k < N; ++k) s += std::log(L(body.radii()[k]) / scale);
  const LM<N> axes = detail::work_axes<double>(body).template cast<L>();
  return s + std::log(std::abs(axes.determinant()));
}

// The largest power of two at most v (v > 0).
L power_of_two_below(L v) {
  int e = 0;
  (void)std::frexp(v, &e);
  return std::ldexp(L(1), e - 1);
}

}  // namespace

template <class T, int N>
InscribedEllipsoid<T, N> inscribed_ellipsoid(std::span<const HalfSpace<T, N>> half_spaces, const InscribedOptions& options) {
  const std::size_t m = half_spaces.size();
  if (m < std::size_t(N + 1))
    throw InputError("half_spaces", "must hold at least " + std::to_string(N + 1) + " half-spaces (got " +
                                        std::to_string(m) + "): fewer bound no polytope");
  InscribedEllipsoid<T, N> out;
  const auto give_up = [&](InscribedStatus status) {
    // Bounded exactly where the normals surround the origin (no v with n_i . v <= 0 for all i).
    std::vector<Vec<T, N>> normals;
    for (const auto& h : half_spaces) normals.push_back(h.normal());
    if (status == InscribedStatus::unbounded && detail::surrounds_origin<T, N>(normals))
      throw InputError("half_spaces", "bound a polytope that reaches beyond 1e10 times the extent of their points "
                                      "from them: out of the solver's range");
    out.status = status;
    out.body = Ellipsoid<T, N>();
    out.volume_gap = std::numeric_limits<double>::infinity();
    out.active.clear();
    out.weights.clear();
    return out;
  };

  // Phase I on the planes' points' bounding box, centered and scaled by a power of two.
  Vec<L, N> lo = Vec<L, N>::Constant(std::numeric_limits<L>::infinity()), hi = -lo;
  for (const auto& h : half_spaces) {
    lo = lo.cwiseMin(h.point().template cast<L>());
    hi = hi.cwiseMax(h.point().template cast<L>());
  }
  const Vec<L, N> mid = lo + (hi - lo) / 2;
  L extent = (hi - lo).maxCoeff();
  if (!(extent > 0)) extent = std::max(mid.cwiseAbs().maxCoeff(), L(std::numeric_limits<T>::min()) * L(1e10));
  const L scale1 = power_of_two_below(extent) * 2;
  const Planes<T, N> first(half_spaces, mid.template cast<double>(), scale1);
  const Phase1<T, N> start = phase_one<T, N>(first);
  out.iterations = start.steps;
  if (start.found == Start::empty) return give_up(InscribedStatus::empty);
  if (start.found == Start::unbounded) return give_up(InscribedStatus::unbounded);
  if (!(start.r > 0)) return give_up(InscribedStatus::did_not_converge);

  // The barrier's coordinates: about the Chebyshev center (in double), scaled by a power of
  // two at most its inradius.
  const Vec<double, N> center =
      (first.origin.template cast<L>() + scale1 * start.x).template cast<double>();
  const L inradius = start.r * scale1;
  const L scale = power_of_two_below(inradius);
  const Planes<T, N> p(half_spaces, center, scale);
  const L lowest = *std::min_element(p.beta.begin(), p.beta.end());
  if (!(lowest > 0))
    throw InputError("half_spaces", "their interior lies within the rounding of its position: no body stored in the type "
                                    "lies inside them");
  // Radii beyond 1e12 of the larger of the points' extent and the inradius: unbounded.
  const L too_large = L(1e12) * std::max(scale1, inradius) / scale;

  const Faces<L, N> faces(p);
  const Faces<double, N> faces_double(p);
  Iterate<L, N> x;
  x.b = LM<N>::Identity() * (lowest / 2);
  x.d.setZero();
  const double requested = options.volume_gap;
  const L target = std::log1p(L(requested) / 8);
  int left = options.max_inscribed_iterations;
  bool capped = false, stalled = false, have_dual = false;
  Dual best;
  Iterate<L, N> at_best = x;
  L t_best = 1;
  // The path is followed in double while the touching half-spaces' slacks (about 1/t of their
  // distances) keep 20 bits there and no certificate is due (m / t above the target: the
  // central gap is 2m / t); the centers that certify, in long double, from there on.
  const L t_double = std::ldexp(L(1), -20) / L(std::numeric_limits<double>::epsilon());
  for (L t = L(m);; t *= 8) {
    const bool certifying = L(m) / t <= target;
    Centering c;
    if (t <= t_double && !certifying) {
      Iterate<double, N> y = x.template cast<double>();
      c = center_at<double, N>(faces_double, y, double(t), double(too_large), left, out.iterations);
      x = y.template cast<L>();
    } else {
      c = center_at<L, N>(faces, x, t, too_large, left, out.iterations);
    }
    if (c == Centering::unbounded) return give_up(InscribedStatus::unbounded);
    capped = c == Centering::capped;
    const Dual dual = capped || certifying ? dual_point<N>(faces, x, t) : Dual{};
    if (dual.ok) {
      L logdet = 0;
      const Eigen::LLT<LM<N>> llt(x.b);
      for (int k = 0; k < N; ++k) logdet += 2 * std::log(llt.matrixL()(k, k));
      if (!have_dual || dual.value < best.value) best = dual, at_best = x, t_best = t;
      have_dual = true;
      if (dual.value - logdet <= target) break;
    }
    if (capped) break;
    // The central gap 2m / t a 64th of the target and still no certificate: stalled (at
    // larger t the centers' rounding only grows).
    if (2 * L(m) / t < target / 64) {
      stalled = true;
      break;
    }
  }
  if (!have_dual) at_best = x;

  // The body in T, shrunk by ulps until the exact classification finds it inside every
  // half-space.
  const Eigen::SelfAdjointEigenSolver<LM<N>> eig(at_best.b);
  const Vec<L, N> c = center.template cast<L>() + scale * at_best.d;
  Vec<L, N> radii;
  for (int k = 0; k < N; ++k) radii[k] = scale * std::max(eig.eigenvalues()[k], L(0));
  const Mat<T, N> axes = eig.eigenvectors().template cast<T>();
  Options exact;
  exact.tolerance = Tolerance::exact;
  L factor = 1;
  bool inside = false;
  for (int round = 0; round < 60 && !inside; ++round) {
    const L margin = round == 0 ? L(0) : std::ldexp(L(std::numeric_limits<T>::epsilon()), round);
    try {
      out.body = Ellipsoid<T, N>::from_axes(c.template cast<T>(), axes, (radii * (factor * (1 - margin))).template cast<T>());
    } catch (const InputError&) {
      throw unrepresentable();
    }
    inside = true;
    L worst = 1;
    const Mat<L, N> work = detail::work_axes<double>(out.body).template cast<L>();
    for (const auto& h : half_spaces) {
      if (classify(out.body, h, exact) == Relation::b_contains_a) continue;
      inside = false;
      const Vec<L, N> n = h.normal().template cast<L>();
      const L room = n.dot(h.point().template cast<L>() - out.body.center().template cast<L>());
      const L rho = (out.body.radii().template cast<L>().asDiagonal() * (work.transpose() * n)).norm();
      if (room > 0 && rho > 0) worst = std::min(worst, room / rho);
    }
    if (!inside) factor *= worst;
  }
  if (!inside) throw unrepresentable();

  if (have_dual) {
    const L gap = std::expm1(best.value - log_det_stored<T, N>(out.body, scale));
    out.volume_gap = std::nextafter(double(std::max(gap, L(0)) * (1 + 16 * eps_l)), std::numeric_limits<double>::infinity());
    const double threshold = double(std::sqrt(2 / (t_best * N)));
    for (std::size_t i = 0; i < m; ++i)
      if (best.weights[i] > threshold) {
        out.active.push_back(i);
        out.weights.push_back(best.weights[i]);
      }
  } else {
    out.volume_gap = std::numeric_limits<double>::infinity();
  }
  out.status = out.volume_gap <= requested ? InscribedStatus::optimal
               : capped || stalled          ? InscribedStatus::did_not_converge
                                            : InscribedStatus::rounding_limited;
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                             \
  template InscribedEllipsoid<T, N> inscribed_ellipsoid<T, N>(std::span<const HalfSpace<T, N>>, const InscribedOptions&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
