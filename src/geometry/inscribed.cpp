// The maximum-volume ellipsoid inside a polytope of half-spaces (geometry.hpp): phase I on the
// Chebyshev-ball linear program, a barrier method on (B, d) in long double, the dual point of
// the last center corrected to feasibility, the body shrunk by ulps until the exact
// classification finds it inside every half-space, its volume gap from the dual bound.
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
#include <cmath>
#include <iterator>
#include <limits>
#include <string>

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
using LX = Eigen::Matrix<L, Eigen::Dynamic, 1>;
using LXX = Eigen::Matrix<L, Eigen::Dynamic, Eigen::Dynamic>;

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
LX newton_direction(const LXX& h, const LX& g) {
  const Eigen::Index n = g.size();
  LX d(n);
  for (Eigen::Index i = 0; i < n; ++i) d[i] = h(i, i) > 0 ? 1 / std::sqrt(h(i, i)) : 1;
  LXX s = d.asDiagonal() * h * d.asDiagonal();
  s.diagonal().array() += L(1e-18);
  const LX x = Eigen::LDLT<LXX>(s).solve(-(d.asDiagonal() * g));
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
  Phase1<T, N> out;
  L lowest = *std::min_element(beta.begin(), beta.end());
  out.r = lowest - 1;
  LX v(n);
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
      LX g = LX::Zero(n);
      LXX h = LXX::Zero(n, n);
      g[N] = -t;
      for (std::size_t i = 0; i < m; ++i) {
        LX c(n);
        c << a[i], 1;
        g += c / s[i];
        h.noalias() += c * c.transpose() / (s[i] * s[i]);
      }
      const LX dv = newton_direction(h, g);
      const L lambda2 = -g.dot(dv);
      if (!(lambda2 > L(1e-10))) break;
      L alpha = 1;
      for (std::size_t i = 0; i < m; ++i) {
        LX c(n);
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

template <int N>
struct Iterate {
  LM<N> b = LM<N>::Identity();
  LV<N> d = LV<N>::Zero();
};

// The symmetric basis E_p: e_k e_k^T, then e_k e_l^T + e_l e_k^T (k < l).
template <int N>
std::vector<LM<N>> symmetric_basis() {
  std::vector<LM<N>> e;
  for (int k = 0; k < N; ++k) e.push_back(LV<N>::Unit(k) * LV<N>::Unit(k).transpose());
  for (int k = 0; k < N; ++k)
    for (int l = k + 1; l < N; ++l)
      e.push_back(LV<N>::Unit(k) * LV<N>::Unit(l).transpose() + LV<N>::Unit(l) * LV<N>::Unit(k).transpose());
  return e;
}

// The barrier's value at (B, d), or infinity outside its domain.
template <class T, int N>
L barrier(const Planes<T, N>& p, const Iterate<N>& x, L t) {
  const Eigen::LLT<LM<N>> llt(x.b);
  if (llt.info() != Eigen::Success) return std::numeric_limits<L>::infinity();
  L logdet = 0;
  for (int k = 0; k < N; ++k) {
    const L dk = llt.matrixL()(k, k);
    if (!(dk > 0)) return std::numeric_limits<L>::infinity();
    logdet += 2 * std::log(dk);
  }
  L f = -t * logdet;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const L s = p.beta[i] - p.a[i].dot(x.d);
    const L w = (x.b * p.a[i]).norm();
    if (!(s > w)) return std::numeric_limits<L>::infinity();
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

template <class T, int N>
Dual dual_point(const Planes<T, N>& p, const Iterate<N>& x, L t) {
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
    normal.noalias() += mu[i] * p.a[i] * p.a[i].transpose();
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
template <class T, int N>
std::pair<Iterate<N>, L> newton_step(const Planes<T, N>& p, const Iterate<N>& x, L t, const std::vector<LM<N>>& basis) {
  constexpr int q = N * (N + 1) / 2;
  constexpr int nv = q + N;
  LX g = LX::Zero(nv);
  LXX h = LXX::Zero(nv, nv);
  const LM<N> inverse = x.b.inverse();
  for (int a = 0; a < q; ++a) {
    const LM<N> ia = inverse * basis[std::size_t(a)];
    g[a] = -t * ia.trace();
    for (int b = 0; b <= a; ++b) {
      const L v = t * (ia * inverse * basis[std::size_t(b)]).trace();
      h(a, b) = v;
      h(b, a) = v;
    }
  }
  Eigen::Matrix<L, N + 1, nv> jac;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const L s = p.beta[i] - p.a[i].dot(x.d);
    const LV<N> w = x.b * p.a[i];
    const L nw = w.norm();
    const L gi = (s - nw) * (s + nw);
    jac.setZero();
    for (int a = 0; a < q; ++a) jac.template block<N, 1>(1, a) = basis[std::size_t(a)] * p.a[i];
    for (int j = 0; j < N; ++j) jac(0, q + j) = -p.a[i][j];
    Eigen::Matrix<L, N + 1, 1> grad, jy;
    grad << -2 * s / gi, 2 * w / gi;
    jy << s, -w;
    Eigen::Matrix<L, N + 1, N + 1> hess = (4 / (gi * gi)) * jy * jy.transpose();
    hess(0, 0) -= 2 / gi;
    for (int k = 1; k <= N; ++k) hess(k, k) += 2 / gi;
    g += jac.transpose() * grad;
    h.noalias() += jac.transpose() * hess * jac;
  }
  const LX dv = newton_direction(h, g);
  Iterate<N> step;
  step.b.setZero();
  for (int a = 0; a < q; ++a) step.b += dv[a] * basis[std::size_t(a)];
  step.d = dv.template tail<N>();
  return {step, -g.dot(dv)};
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

  const auto basis = symmetric_basis<N>();
  Iterate<N> x;
  x.b = LM<N>::Identity() * (lowest / 2);
  x.d.setZero();
  const double requested = options.volume_gap;
  const L target = std::log1p(L(requested) / 8);
  int left = options.max_inscribed_iterations;
  bool capped = false, stalled = false, have_dual = false;
  Dual best;
  Iterate<N> at_best = x;
  L t_best = 1;
  for (L t = L(m);; t *= 8) {
    L previous = std::numeric_limits<L>::infinity();
    for (int inner = 0; inner < 80; ++inner) {
      if (left <= 0) {
        capped = true;
        break;
      }
      --left;
      ++out.iterations;
      const auto [dx, lambda2] = newton_step<T, N>(p, x, t, basis);
      if (!(lambda2 >= 0) || lambda2 < L(1e-22)) break;
      const L f0 = barrier<T, N>(p, x, t);
      L alpha = 1;
      bool moved = false;
      for (int halving = 0; halving < 80; ++halving, alpha /= 2) {
        Iterate<N> trial;
        trial.b = x.b + alpha * dx.b;
        trial.d = x.d + alpha * dx.d;
        const L f = barrier<T, N>(p, trial, t);
        if (!std::isfinite(double(f))) continue;
        if (lambda2 < L(1e-3) || f <= f0 - L(0.25) * alpha * lambda2) {
          x = trial;
          moved = true;
          break;
        }
      }
      if (!moved) break;
      if (x.b.trace() > too_large) return give_up(InscribedStatus::unbounded);
      // Near the center Newton's decrement squares at each step: where it does not fall
      // fourfold it has reached its rounding's floor (which grows with t: the slacks of the
      // touching half-spaces are about 1/t of their distances, so rounded to eps t).
      if (lambda2 < L(1e-6) && lambda2 > previous / 4) break;
      previous = lambda2;
    }
    const Dual dual = dual_point<T, N>(p, x, t);
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
