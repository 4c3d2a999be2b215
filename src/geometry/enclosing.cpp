// The minimum-volume enclosing ellipsoid of points (geometry.hpp): the weights by a
// coordinate ascent with away steps on a core set, the body from the weights, its
// containment and its volume gap certified in rational arithmetic.
#include <ellipsect/geometry.hpp>

#include "detail/axes.hpp"
#include "detail/instantiate.hpp"
#include "detail/rational.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <string>

namespace ellipsect {

std::string_view to_string(EnclosingStatus s) noexcept {
  static constexpr std::string_view names[] = {"optimal", "rounding_limited", "did_not_converge"};  // in the enum's order
  const auto k = static_cast<std::size_t>(s);
  return k < std::size(names) ? names[k] : "?";
}

namespace {

template <int N> using V = Eigen::Matrix<double, N, 1>;
template <int N> using M = Eigen::Matrix<double, N, N>;

// The points as the solver sees them: y = (p - origin) 2^-k, the cloud's bounding box
// centered and of size about 1 (a scale-free, translation-free problem: the weights of
// the optimum do not change under affine maps).
template <class T, int N>
struct Cloud {
  std::vector<V<N>> y;
  Vec<long double, N> origin;
  int exponent = 0;  // k

  explicit Cloud(std::span<const Vec<T, N>> points) {
    V<N> lo = V<N>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const V<N> p = points[i].template cast<double>();
      if (!p.allFinite()) throw RowInputError(i, "points", "must be finite");
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    if (!(hi - lo).allFinite()) throw InputError("points", "must span less than the largest double in each coordinate");
    const V<N> mid = lo + (hi - lo) / 2;
    (void)std::frexp((hi - lo).maxCoeff(), &exponent);
    origin = mid.template cast<long double>();
    y.reserve(points.size());
    for (const auto& p : points) y.push_back(((p.template cast<double>() - mid).array() * std::ldexp(1.0, -exponent)).matrix());
  }
};

// An ellipsoid estimate in the solver's coordinates: center c and the Cholesky factor L of
// the weights' scatter S_u = L L^T, with L^-1 to whiten.
template <int N>
struct Frame {
  V<N> c = V<N>::Zero();
  M<N> L = M<N>::Identity();
  M<N> inverse = M<N>::Identity();
  // omega = q^T M(u)^-1 q = 1 + |L^-1 (y - c)|^2 (geometry.hpp).
  double omega(const V<N>& y) const { return 1 + (inverse * (y - c)).squaredNorm(); }
  V<N> whiten(const V<N>& y) const { return inverse * (y - c); }
};

// The working set: indices of points and their weights, the points whitened by `frame`.
template <int N>
struct Working {
  std::vector<std::size_t> index;
  std::vector<double> u;
  std::vector<V<N>> z;
};

// Kumar and Yildirim's start: for N directions, each orthogonal to the differences chosen
// before, the two extreme points along it. Throws InputError("points") for a flat cloud.
template <int N>
std::vector<std::size_t> extreme_points(const std::vector<V<N>>& y) {
  std::vector<std::size_t> chosen;
  std::vector<V<N>> basis;  // orthonormal, spanning the chosen differences
  for (int j = 0; j < N; ++j) {
    V<N> d = V<N>::Zero();
    for (int i = 0; i < N; ++i) {  // the coordinate axis farthest from the span so far
      V<N> r = V<N>::Unit(i);
      for (const auto& b : basis) r -= b.dot(r) * b;
      if (r.squaredNorm() > d.squaredNorm()) d = r;
    }
    d.normalize();
    std::size_t hi = 0, lo = 0;
    for (std::size_t i = 1; i < y.size(); ++i) {
      if (d.dot(y[i]) > d.dot(y[hi])) hi = i;
      if (d.dot(y[i]) < d.dot(y[lo])) lo = i;
    }
    // The cloud fits in a box of size in [1, 2): a width below 1e-9 leaves an ellipsoid
    // beyond Ellipsoid::max_aspect_ratio.
    if (!(d.dot(y[hi] - y[lo]) > 1e-9))
      throw InputError("points", "lie within 1e-9 of their extent from a " + std::string(j == 0 ? "point" : j == 1 ? "line" : "plane") +
                                     ": no ellipsoid of positive volume and aspect ratio below 1e8 encloses them");
    chosen.push_back(hi);
    chosen.push_back(lo);
    V<N> e = y[hi] - y[lo];
    for (const auto& b : basis) e -= b.dot(e) * b;
    basis.push_back(e.normalized());
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  return chosen;
}

// ln det M(u), M(u) = sum_i u_i q_i q_i^T with q_i = (z_i, 1), and its factorization, in long
// double: the weights' excess max omega / n - 1 is resolved to about 1e-13 where double's
// rounding leaves it at 1e-10 (for points nearly all on the optimum's boundary).
using L = long double;
using LVector = Eigen::Matrix<L, Eigen::Dynamic, 1>;
using LMatrix = Eigen::Matrix<L, Eigen::Dynamic, Eigen::Dynamic>;

template <int N>
struct Lifted {
  static constexpr int n = N + 1;
  using Q = Eigen::Matrix<L, n, 1>;
  Eigen::LDLT<Eigen::Matrix<L, n, n>> ldlt;
  L log_det = 0;
  Lifted(const std::vector<V<N>>& z, const std::vector<double>& u) {
    Eigen::Matrix<L, n, n> m = Eigen::Matrix<L, n, n>::Zero();
    for (std::size_t i = 0; i < z.size(); ++i) m.noalias() += L(u[i]) * lift(z[i]) * lift(z[i]).transpose();
    ldlt.compute(m);
    log_det = ldlt.vectorD().array().log().sum();
  }
  static Q lift(const V<N>& z) {
    Q q;
    q << z.template cast<L>(), L(1);
    return q;
  }
  L omega(const V<N>& z) const {
    const Q q = lift(z);
    return q.dot(ldlt.solve(q));
  }
};

// Newton's step for ln det M on the face of the simplex of the weighted points: gradient
// omega, Hessian -(q_i^T M^-1 q_j)^2, the step tangent to sum u = 1 (a ridge of 1e-12 for the
// directions that leave M unchanged), cut where a weight reaches 0 (that weight leaves the
// support) and halved until ln det M grows. False where it does not grow.
template <int N>
bool newton_step(std::vector<double>& u, const std::vector<V<N>>& z, const Lifted<N>& at) {
  using Lift = Lifted<N>;
  std::vector<std::size_t> s;
  for (std::size_t i = 0; i < u.size(); ++i)
    if (u[i] > 0) s.push_back(i);
  const Eigen::Index k = Eigen::Index(s.size());
  Eigen::Matrix<L, Lift::n, Eigen::Dynamic> q(Lift::n, k);
  for (Eigen::Index i = 0; i < k; ++i) q.col(i) = Lift::lift(z[s[std::size_t(i)]]);
  const LMatrix g = q.transpose() * at.ldlt.solve(q);
  LMatrix h = g.cwiseProduct(g);
  h.diagonal().array() += L(1e-12) * h.diagonal().maxCoeff();
  const Eigen::LDLT<LMatrix> hl(h);
  const LVector a = hl.solve(LVector(g.diagonal())), b = hl.solve(LVector::Ones(k));
  const L lambda = a.sum() / b.sum();
  const LVector du = a - lambda * b;  // sum du = 0
  L t = 1;
  std::size_t blocking = s.size();
  for (Eigen::Index i = 0; i < k; ++i)
    if (du[i] < 0 && -L(u[s[std::size_t(i)]]) / du[i] < t) {
      t = -L(u[s[std::size_t(i)]]) / du[i];
      blocking = std::size_t(i);
    }
  // Within about 1e-9 of the face's optimum (Newton's decrement) the full step is taken:
  // there ln det M grows by less than its rounding.
  const bool close = LVector(g.diagonal()).dot(du) < L(1e-9);
  for (int halving = 0; halving < 30; ++halving, t /= 2, blocking = s.size()) {
    std::vector<double> next = u;
    for (Eigen::Index i = 0; i < k; ++i) next[s[std::size_t(i)]] = double(std::max(L(0), L(u[s[std::size_t(i)]]) + t * du[i]));
    if (blocking < s.size()) next[s[blocking]] = 0;
    const double total = std::accumulate(next.begin(), next.end(), 0.0);
    for (double& v : next) v /= total;
    if (close || Lifted<N>(z, next).log_det > at.log_det) {
      u = std::move(next);
      return true;
    }
  }
  return false;
}

// The weights of the working set until max omega <= (1 + eps) n (n = N + 1), the budget is
// spent, or the excess stalls: Newton's step on the support where the point of largest omega is in it,
// else Todd and Yildirim's step towards that point (the exact line search of ln det M),
// which brings it in; their away step from the weighted point of least omega where Newton's
// does not help (Ahipasaoglu, Sun and Todd).
enum class Ascent { reached, stalled, capped };

template <int N>
Ascent ascend(Working<N>& w, double eps, std::int64_t& budget, std::int64_t& iterations) {
  constexpr int n = N + 1;
  std::vector<L> omega(w.z.size());
  double best = std::numeric_limits<double>::infinity();
  for (int since = 0;; ++since) {
    const Lifted<N> at(w.z, w.u);
    std::size_t up = 0, down = w.z.size();
    for (std::size_t i = 0; i < w.z.size(); ++i) {
      omega[i] = at.omega(w.z[i]);
      if (omega[i] > omega[up]) up = i;
      if (w.u[i] > 0 && (down == w.z.size() || omega[i] < omega[down])) down = i;
    }
    const double plus = double(omega[up] / n - 1), minus = double(1 - omega[down] / n);
    if (plus <= eps) return Ascent::reached;
    if (budget <= 0) return Ascent::capped;
    // No halving of the excess in 100 steps: the weights are at their rounding's floor
    // (points nearly all on one ellipsoid, the optimum's face degenerate).
    if (plus < best / 2) best = plus, since = 0;
    if (since > 100) return Ascent::stalled;
    --budget;
    ++iterations;
    if (w.u[up] > 0 && newton_step<N>(w.u, w.z, at)) continue;
    if (plus >= minus || w.u[down] >= 1) {
      const double beta = double((omega[up] - n) / (n * (omega[up] - 1)));
      for (double& u : w.u) u *= 1 - beta;
      w.u[up] += beta;
    } else {
      const double most = w.u[down] / (1 - w.u[down]);
      const double beta = omega[down] > 1 ? std::min(double((n - omega[down]) / (n * (omega[down] - 1))), most) : most;
      for (double& u : w.u) u *= 1 + beta;
      w.u[down] = beta == most ? 0 : w.u[down] - beta;
    }
  }
}

// The frame of the weights' ellipsoid, in the coordinates y, from the working set whitened
// by `frame`.
template <int N>
Frame<N> frame_of(const Working<N>& w, const Frame<N>& frame) {
  V<N> cz = V<N>::Zero();
  for (std::size_t i = 0; i < w.z.size(); ++i) cz += w.u[i] * w.z[i];
  M<N> s = M<N>::Zero();
  for (std::size_t i = 0; i < w.z.size(); ++i) s.noalias() += w.u[i] * (w.z[i] - cz) * (w.z[i] - cz).transpose();
  Frame<N> out;
  out.c = frame.c + frame.L * cz;
  out.L = frame.L * Eigen::LLT<M<N>>(s).matrixL().toDenseMatrix();
  out.inverse = out.L.template triangularView<Eigen::Lower>().solve(M<N>::Identity());
  return out;
}

InputError unrepresentable() {
  return InputError("points", "no ellipsoid stored in the type holds them: its aspect ratio would exceed 1e8 (points close to "
                              "a line or plane) or its radii the type's range");
}

// The body of the weights' ellipsoid grown to hold every point (rho, geometry.hpp), in T:
// its axes the eigenvectors of S_u, its radii sqrt(N rho lambda) 2^k, about the center.
template <class T, int N>
Ellipsoid<T, N> body_of(const Cloud<T, N>& cloud, const Frame<N>& frame) {
  double rho = 0;
  for (const auto& y : cloud.y) rho = std::max(rho, (frame.omega(y) - 1) / N);
  using LM = Eigen::Matrix<long double, N, N>;
  const LM l = frame.L.template cast<long double>();
  const Eigen::SelfAdjointEigenSolver<LM> eig(l * l.transpose());
  const long double scale = std::ldexp(1.0L, cloud.exponent);
  const Vec<long double, N> center = cloud.origin + scale * frame.c.template cast<long double>();
  Vec<T, N> radii;
  for (int k = 0; k < N; ++k) radii[k] = T(scale * std::sqrt(N * rho * std::max(eig.eigenvalues()[k], 0.0L)));
  try {
    return Ellipsoid<T, N>::from_axes(center.template cast<T>(), eig.eigenvectors().template cast<T>(), radii);
  } catch (const InputError&) {
    throw unrepresentable();
  }
}

// (p - c)^T M (p - c) of the stored body in double and a bound on its rounding error.
template <class T, int N>
struct Form {
  Mat<double, N> axes;
  Vec<double, N> center, radii;
  explicit Form(const Ellipsoid<T, N>& b)
      : axes(detail::work_axes<double>(b)), center(b.center().template cast<double>()), radii(b.radii().template cast<double>()) {}
  std::pair<double, double> operator()(const Vec<T, N>& p) const {
    const Vec<double, N> d = p.template cast<double>() - center;
    double q = 0, a2 = 0;
    for (int k = 0; k < N; ++k) {
      const double y = axes.col(k).dot(d) / radii[k];
      const double a = axes.col(k).cwiseAbs().dot(d.cwiseAbs()) / radii[k];
      q += y * y;
      a2 += a * a;
    }
    return {q, 8 * (N + 2) * std::numeric_limits<double>::epsilon() * (a2 + q)};
  }
};

// (p - c)^T M (p - c) of the stored body, in rationals: exactly 0 where it is <= 1 (the
// body holds p), else the value rounded up.
template <int N>
double excess_form(const detail::rational::Body<N>& b, const Vec<double, N>& p) {
  using namespace detail::rational;
  QVec<N> d;
  for (int i = 0; i < N; ++i) d[i] = Q(p[i]) - b.center[i];
  const Q q = dot<N>(d, times<N>(b.quadric, d));
  return q <= 1 ? 0 : static_cast<double>(q) * (1 + 2 * std::numeric_limits<double>::epsilon());
}

// The body grown by the least factor (up to a few ulps) that makes it hold every point: each
// round grows it by the largest excess and a margin of ulps that doubles, so that a few
// rounds suffice (the margin passes any rounding within 60).
template <class T, int N>
Ellipsoid<T, N> grown_to_hold(Ellipsoid<T, N> body, std::span<const Vec<T, N>> points) {
  for (int round = 0; round < 60; ++round) {
    const Form<T, N> form(body);
    double worst = 0;
    std::vector<std::size_t> unsure;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto [q, err] = form(points[i]);
      if (q - err > 1) worst = std::max(worst, q + err);
      else if (q + err > 1) unsure.push_back(i);
    }
    if (worst == 0) {
      const auto exact = detail::rational::exact_body(body);
      for (std::size_t i : unsure)
        worst = std::max(worst, excess_form<N>(exact, points[i].template cast<double>()));
      if (worst == 0) return body;
    }
    // Grow by sqrt(worst) and a margin of ulps of T that doubles each round.
    const T factor = T(std::sqrt(worst) * (1 + std::ldexp(double(std::numeric_limits<T>::epsilon()), round + 2)));
    try {
      body = Ellipsoid<T, N>::from_axes(body.center(), body.axes(), Vec<T, N>(body.radii() * factor));
    } catch (const InputError&) {
      throw unrepresentable();
    }
  }
  throw unrepresentable();
}

// vol(body) / (the weights' lower bound) - 1, in rationals, rounded up (geometry.hpp):
// ratio^2 = 1 / (det M_body det(N S_u)) with the weights normalized exactly.
template <class T, int N>
double certified_gap(const Ellipsoid<T, N>& body, std::span<const Vec<T, N>> points, const std::vector<std::size_t>& support,
                     const std::vector<double>& weights) {
  using namespace detail::rational;
  Q total = 0;
  for (double u : weights) total += Q(u);
  QVec<N> c{};
  for (std::size_t i = 0; i < support.size(); ++i)
    for (int j = 0; j < N; ++j) c[j] += Q(weights[i]) * Q(double(points[support[i]][j]));
  for (int j = 0; j < N; ++j) c[j] /= total;
  QMat<N> s{};
  for (std::size_t i = 0; i < support.size(); ++i) {
    QVec<N> d;
    for (int j = 0; j < N; ++j) d[j] = Q(double(points[support[i]][j])) - c[j];
    const Q w = Q(weights[i]) * N / total;
    for (int a = 0; a < N; ++a)
      for (int b = 0; b < N; ++b) s[a][b] += w * d[a] * d[b];
  }
  const QVec<N> zero{};
  const Q det_s = det_and_form<N>(s, zero, zero).first;
  const Q det_body = det_and_form<N>(exact_body(body).quadric, zero, zero).first;
  if (!(det_s > 0)) return std::numeric_limits<double>::infinity();
  const double r2 = static_cast<double>(Q(1) / (det_s * det_body));
  const double r = std::sqrt(r2);
  return std::nextafter(r - 1 + 3 * std::numeric_limits<double>::epsilon() * r, std::numeric_limits<double>::infinity());
}

}  // namespace

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Vec<T, N>> points, const EnclosingOptions& options) {
  constexpr int n = N + 1;
  if (points.size() < std::size_t(n))
    throw InputError("points", "must hold at least " + std::to_string(n) + " points (got " + std::to_string(points.size()) + ")");
  const Cloud<T, N> cloud(points);
  EnclosingEllipsoid<T, N> out;
  std::int64_t budget = options.max_enclosing_iterations;

  // The weights' target: rho^(N/2) <= 1 + gap/8, rho <= 1 + eps n / N (geometry.hpp); the
  // rest of the gap is left to the body's rounding and growth.
  const double tight = std::expm1(std::log1p(options.volume_gap / 8) * 2 / N) * N / n;
  Working<N> w;
  w.index = extreme_points<N>(cloud.y);
  w.u.assign(w.index.size(), 1.0 / double(w.index.size()));
  std::vector<char> in_set(cloud.y.size(), 0);
  for (std::size_t i : w.index) in_set[i] = 1;
  Frame<N> frame;
  bool capped = false, stalled = false;
  for (const double eps : {std::max(tight, 1e-4), tight}) {
    for (;;) {
      ++out.passes;
      w.z.clear();
      for (std::size_t i : w.index) w.z.push_back(frame.whiten(cloud.y[i]));
      const Ascent ascent = ascend<N>(w, eps, budget, out.iterations);
      frame = frame_of<N>(w, frame);
      capped = ascent == Ascent::capped;
      stalled = stalled || ascent == Ascent::stalled;
      // Capped, or at the rounding's floor: the weights are as good as they get (the body
      // is grown to hold every point all the same, and its gap certified).
      if (ascent != Ascent::reached) break;
      // The points the weights' ellipsoid leaves out by more than eps: the worst 32 join.
      std::vector<std::pair<double, std::size_t>> out_of;
      for (std::size_t i = 0; i < cloud.y.size(); ++i) {
        if (in_set[i]) continue;
        const double omega = frame.omega(cloud.y[i]);
        if (omega > (1 + eps) * n) out_of.emplace_back(omega, i);
      }
      if (out_of.empty()) break;
      const std::size_t join = std::min<std::size_t>(out_of.size(), 32);
      std::partial_sort(out_of.begin(), out_of.begin() + std::ptrdiff_t(join), out_of.end(), std::greater<>());
      // Unweighted points well inside leave the set (a core set of tens of points).
      Working<N> kept;
      for (std::size_t k = 0; k < w.index.size(); ++k) {
        if (w.u[k] == 0 && frame.omega(cloud.y[w.index[k]]) < n) {
          in_set[w.index[k]] = 0;
          continue;
        }
        kept.index.push_back(w.index[k]);
        kept.u.push_back(w.u[k]);
      }
      for (std::size_t k = 0; k < join; ++k) {
        kept.index.push_back(out_of[k].second);
        kept.u.push_back(0);
        in_set[out_of[k].second] = 1;
      }
      w = std::move(kept);
    }
    if (capped) break;
  }

  for (std::size_t k = 0; k < w.index.size(); ++k)
    if (w.u[k] > 0) {
      out.support.push_back(w.index[k]);
      out.weights.push_back(w.u[k]);
    }
  out.body = grown_to_hold<T, N>(body_of<T, N>(cloud, frame), points);
  out.volume_gap = certified_gap<T, N>(out.body, points, out.support, out.weights);
  out.status = out.volume_gap <= options.volume_gap ? EnclosingStatus::optimal
               : capped || stalled                 ? EnclosingStatus::did_not_converge
                                                   : EnclosingStatus::rounding_limited;
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N) \
  template EnclosingEllipsoid<T, N> enclosing_ellipsoid<T, N>(std::span<const Vec<T, N>>, const EnclosingOptions&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
