// The minimum-volume enclosing ellipsoid of points (geometry.hpp): the weights by a
// coordinate ascent with away steps on a core set, the body from the weights, its
// containment and its volume gap certified in rational arithmetic.
#include <ellipsect/classify.hpp>
#include <ellipsect/geometry.hpp>

#include "detail/axes.hpp"
#include "detail/enum_names.hpp"
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
  return detail::name_of(s, names);
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
// before, the two extreme points along it. Throws InputError(name) for a flat cloud.
template <int N>
std::vector<std::size_t> extreme_points(const std::vector<V<N>>& y, const char* name) {
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
      throw InputError(name, "lie within 1e-9 of their extent from a " + std::string(j == 0 ? "point" : j == 1 ? "line" : "plane") +
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

// Newton's step for ln det M: its quadratic model (gradient omega, Hessian
// -(q_i^T M^-1 q_j)^2, a ridge of 1e-12 for the directions that leave M unchanged) maximized
// over the simplex u >= 0, sum u = 1 by a primal active-set method (Nocedal and Wright, 16.3:
// weights enter and leave the support within the one step, so that a point the model wants in
// does not zigzag against one it wants out), then halved until ln det M grows. False where it
// does not grow.
template <int N>
bool newton_step(std::vector<double>& u, const std::vector<V<N>>& z, const Lifted<N>& at) {
  using Lift = Lifted<N>;
  const Eigen::Index k = Eigen::Index(u.size());
  Eigen::Matrix<L, Lift::n, Eigen::Dynamic> q(Lift::n, k);
  for (Eigen::Index i = 0; i < k; ++i) q.col(i) = Lift::lift(z[std::size_t(i)]);
  const LMatrix g = q.transpose() * at.ldlt.solve(q);
  LMatrix h = g.cwiseProduct(g);
  h.diagonal().array() += L(1e-12) * h.diagonal().maxCoeff();
  LVector x(k);
  for (Eigen::Index i = 0; i < k; ++i) x[i] = u[std::size_t(i)];
  // The model, omega^T (x - u) - (x - u)^T H (x - u) / 2, is -(x^T H x / 2 - c^T x) + const.
  const LVector omega = g.diagonal(), c = omega + h * x;
  std::vector<char> bound(static_cast<std::size_t>(k));
  for (Eigen::Index i = 0; i < k; ++i) bound[std::size_t(i)] = x[i] <= 0;
  for (int round = 0; round < 4 * int(k) + 20; ++round) {
    std::vector<Eigen::Index> free;
    for (Eigen::Index i = 0; i < k; ++i)
      if (!bound[std::size_t(i)]) free.push_back(i);
    const Eigen::Index f = Eigen::Index(free.size());
    LMatrix hf(f, f);
    LVector cf(f);
    for (Eigen::Index a = 0; a < f; ++a) {
      cf[a] = c[free[std::size_t(a)]];
      for (Eigen::Index b = 0; b < f; ++b) hf(a, b) = h(free[std::size_t(a)], free[std::size_t(b)]);
    }
    // The face's optimum: H_FF x_F = c_F - nu 1, sum x_F = 1.
    const Eigen::LDLT<LMatrix> hl(hf);
    const LVector a = hl.solve(cf), b = hl.solve(LVector::Ones(f));
    const L nu = (a.sum() - 1) / b.sum();
    LVector step(f);
    for (Eigen::Index i = 0; i < f; ++i) step[i] = a[i] - nu * b[i] - x[free[std::size_t(i)]];
    if (step.cwiseAbs().maxCoeff() <= L(1e-15)) {
      // At the face's optimum: release the bound weight of the most negative multiplier
      // (H x - c)_i + nu, or stop where none is.
      const LVector grad = h * x - c;
      Eigen::Index release = -1;
      L most = L(-1e-12);
      for (Eigen::Index i = 0; i < k; ++i)
        if (bound[std::size_t(i)] && grad[i] + nu < most) most = grad[i] + nu, release = i;
      if (release < 0) break;
      bound[std::size_t(release)] = 0;
      continue;
    }
    L t = 1;
    Eigen::Index blocking = -1;
    for (Eigen::Index i = 0; i < f; ++i)
      if (step[i] < 0 && -x[free[std::size_t(i)]] / step[i] < t) t = -x[free[std::size_t(i)]] / step[i], blocking = free[std::size_t(i)];
    for (Eigen::Index i = 0; i < f; ++i) x[free[std::size_t(i)]] += t * step[i];
    if (blocking >= 0) x[blocking] = 0, bound[std::size_t(blocking)] = 1;
  }
  LVector du(k);
  for (Eigen::Index i = 0; i < k; ++i) du[i] = x[i] - L(u[std::size_t(i)]);
  // Within about 1e-9 of the model's optimum the full step is taken: there ln det M grows by
  // less than its rounding.
  const bool close = omega.dot(du) < L(1e-9);
  L t = 1;
  for (int halving = 0; halving < 30; ++halving, t /= 2) {
    std::vector<double> next = u;
    for (Eigen::Index i = 0; i < k; ++i) next[std::size_t(i)] = double(std::max(L(0), L(u[std::size_t(i)]) + t * du[i]));
    const double total = std::accumulate(next.begin(), next.end(), 0.0);
    for (double& v : next) v /= total;
    if (close || Lifted<N>(z, next).log_det > at.log_det) {
      if (next == u) return false;
      u = std::move(next);
      return true;
    }
  }
  return false;
}

// The weights of the working set until max omega <= (1 + eps) n (n = N + 1), the budget is
// spent, or the excess stalls: Newton's step over the working set, else Todd and Yildirim's
// step towards the point of largest omega (the exact line search of ln det M), which brings
// it in, or their away step from the weighted point of least omega (Ahipasaoglu, Sun and
// Todd).
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
    if (newton_step<N>(w.u, w.z, at)) continue;
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

InputError unrepresentable(const char* name) {
  return InputError(name, "no ellipsoid stored in the type holds them: its aspect ratio would exceed 1e8 (points close to "
                              "a line or plane) or its radii the type's range");
}

// The body of the weights' ellipsoid grown to hold every point (rho, geometry.hpp), in T:
// its axes the eigenvectors of S_u, its radii sqrt(N rho lambda) 2^k, about the center.
template <class T, int N>
Ellipsoid<T, N> body_of(const Cloud<T, N>& cloud, const Frame<N>& frame, const char* name) {
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
    throw unrepresentable(name);
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

// The stored body's form (p - c)^T M (p - c) = sum_k y_k^2 / r_k^2, y = A^T (p - c) (A the
// axes every query computes with, detail/axes.hpp), in dyadic rationals: excess(p) exactly 0
// where it is <= 1 (the body holds p), else the form rounded up.
template <int N>
struct ExactForm {
  using D = detail::rational::Dyadic;
  std::array<D, N> center;
  std::array<std::array<D, N>, N> axes;  // axes[i][k]: row i of A
  std::array<D, N> r2;                    // r_k^2
  D volume2;                              // prod_k r_k^2

  template <class T>
  explicit ExactForm(const Ellipsoid<T, N>& e) : volume2(1.0) {
    const Mat<double, N> a = detail::work_axes<double>(e);
    for (int i = 0; i < N; ++i) {
      center[std::size_t(i)] = D(double(e.center()[i]));
      for (int k = 0; k < N; ++k) axes[std::size_t(i)][std::size_t(k)] = D(a(i, k));
    }
    for (int k = 0; k < N; ++k) {
      const D r(double(e.radii()[k]));
      r2[std::size_t(k)] = r * r;
      volume2 = volume2 * r2[std::size_t(k)];
    }
  }

  double excess(const Vec<double, N>& p) const {
    std::array<D, N> d;
    for (int i = 0; i < N; ++i) d[std::size_t(i)] = D(p[i]) - center[std::size_t(i)];
    D num;  // sum_k y_k^2 prod_{j != k} r_j^2: the form times prod r^2
    for (int k = 0; k < N; ++k) {
      D y;
      for (int i = 0; i < N; ++i) y += axes[std::size_t(i)][std::size_t(k)] * d[std::size_t(i)];
      D term = y * y;
      for (int j = 0; j < N; ++j)
        if (j != k) term = term * r2[std::size_t(j)];
      num += term;
    }
    if (!(volume2 < num)) return 0;
    return detail::rational::quotient(num, volume2) * (1 + 2 * std::numeric_limits<double>::epsilon());
  }
};

// The body grown by the least factor (up to a few ulps) that makes it hold every point: each
// round grows it by the largest excess and a margin of ulps that doubles, so that a few
// rounds suffice (the margin passes any rounding within 60).
template <class T, int N>
Ellipsoid<T, N> grown_to_hold(Ellipsoid<T, N> body, std::span<const Vec<T, N>> points, const char* name) {
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
      const ExactForm<N> exact(body);
      for (std::size_t i : unsure) worst = std::max(worst, exact.excess(points[i].template cast<double>()));
      if (worst == 0) return body;
    }
    // Grow by sqrt(worst) and a margin of ulps of T that doubles each round.
    const T factor = T(std::sqrt(worst) * (1 + std::ldexp(double(std::numeric_limits<T>::epsilon()), round + 2)));
    try {
      body = Ellipsoid<T, N>::from_axes(body.center(), body.axes(), Vec<T, N>(body.radii() * factor));
    } catch (const InputError&) {
      throw unrepresentable(name);
    }
  }
  throw unrepresentable(name);
}

// det m for N = 2, 3, exact.
template <int N>
detail::rational::Dyadic determinant(const std::array<std::array<detail::rational::Dyadic, N>, N>& m) {
  if constexpr (N == 2) {
    return m[0][0] * m[1][1] - m[0][1] * m[1][0];
  } else {
    static_assert(N == 3);
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
}

// vol(body) / (the weights' lower bound) - 1, exact to the last rounding, rounded up
// (geometry.hpp): ratio^2 = 1 / (det M_body det(N S_u)). With T = sum u_i, P = sum u_i p_i and
// D_i = T p_i - P (so p_i - P / T = D_i / T), N S_u = (N / T^3) sum u_i D_i D_i^T and
// det M_body = det(A)^2 / prod r_k^2: ratio^2 = T^(3N) prod r_k^2 / (N^N det(sum u_i D_i D_i^T)
// det(A)^2), every factor a dyadic rational, one division.
template <class T, int N>
double certified_gap(const Ellipsoid<T, N>& body, std::span<const Vec<T, N>> points, const std::vector<std::size_t>& support,
                     const std::vector<double>& weights) {
  using D = detail::rational::Dyadic;
  using DMat = std::array<std::array<D, N>, N>;
  D total;
  for (double u : weights) total += D(u);
  if (!(sign(total) > 0)) return std::numeric_limits<double>::infinity();
  std::array<D, N> sum;
  for (std::size_t i = 0; i < support.size(); ++i)
    for (int j = 0; j < N; ++j) sum[std::size_t(j)] += D(weights[i]) * D(double(points[support[i]][j]));
  DMat s{};
  for (std::size_t i = 0; i < support.size(); ++i) {
    std::array<D, N> d;
    for (int j = 0; j < N; ++j) d[std::size_t(j)] = total * D(double(points[support[i]][j])) - sum[std::size_t(j)];
    const D u(weights[i]);
    for (int a = 0; a < N; ++a) {
      const D ud = u * d[std::size_t(a)];
      for (int b = a; b < N; ++b) s[std::size_t(a)][std::size_t(b)] += ud * d[std::size_t(b)];
    }
  }
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < a; ++b) s[std::size_t(a)][std::size_t(b)] = s[std::size_t(b)][std::size_t(a)];
  const D det_s = determinant<N>(s);
  if (!(sign(det_s) > 0)) return std::numeric_limits<double>::infinity();
  const ExactForm<N> form(body);
  const D det_a = determinant<N>(form.axes);
  D numerator = form.volume2, denominator = det_s * det_a * det_a;
  for (int k = 0; k < 3 * N; ++k) numerator = numerator * total;
  for (int k = 0; k < N; ++k) denominator = denominator * D(double(N));
  const double r2 = detail::rational::quotient(numerator, denominator);
  const double r = std::sqrt(r2);
  return std::nextafter(r - 1 + 3 * std::numeric_limits<double>::epsilon() * r, std::numeric_limits<double>::infinity());
}

// The enclosing ellipsoid of points, its errors naming `name` (the caller's argument).
template <class T, int N>
EnclosingEllipsoid<T, N> enclose_points(std::span<const Vec<T, N>> points, const EnclosingOptions& options, const char* name) {
  constexpr int n = N + 1;
  if (points.size() < std::size_t(n))
    throw InputError(name, "must hold at least " + std::to_string(n) + " points (got " + std::to_string(points.size()) + ")");
  const Cloud<T, N> cloud(points);
  EnclosingEllipsoid<T, N> out;
  std::int64_t budget = options.max_enclosing_iterations;

  // The weights' target: rho^(N/2) <= 1 + gap/8, rho <= 1 + eps n / N (geometry.hpp); the
  // rest of the gap is left to the body's rounding and growth.
  const double tight = std::expm1(std::log1p(options.volume_gap / 8) * 2 / N) * N / n;
  Working<N> w;
  w.index = extreme_points<N>(cloud.y, name);
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
      out.support_points.push_back(points[w.index[k]]);
      out.weights.push_back(w.u[k]);
    }
  out.body = grown_to_hold<T, N>(body_of<T, N>(cloud, frame, name), points, name);
  out.volume_gap = certified_gap<T, N>(out.body, points, out.support, out.weights);
  out.status = out.volume_gap <= options.volume_gap ? EnclosingStatus::optimal
               : capped || stalled                 ? EnclosingStatus::did_not_converge
                                                   : EnclosingStatus::rounding_limited;
  return out;
}

// ---- Bodies: the enclosing ellipsoid of their union, from points on their boundaries ----

// The point of body b farthest outside e in e's form: max over x in b of (x - c)^T M (x - c).
// In e's unit-ball coordinates b is { m + A v : |v| <= 1 }, and the maximum of |m + A v|^2
// lies where v = (lambda - A^T A)^-1 A^T m, |v| = 1, lambda at least the largest eigenvalue
// `top` of A^T A (a convex quadratic maximized on a ball: the trust-region conditions of
// Moré and Sorensen). lambda by bisection on (top, top + |A^T m|], where |v(lambda)| falls
// through 1; where it stays below 1 (A^T m orthogonal to the top eigenvector, the hard
// case), lambda = top and v is completed along that eigenvector. Returns v in b's unit
// coordinates and the form there.
template <class T, int N>
std::pair<V<N>, double> farthest(const Ellipsoid<T, N>& e, const Ellipsoid<T, N>& b) {
  const M<N> re = detail::work_axes<double>(e), rb = detail::work_axes<double>(b);
  const V<N> inverse = e.radii().template cast<double>().cwiseInverse();
  const M<N> a = inverse.asDiagonal() * re.transpose() * rb * b.radii().template cast<double>().asDiagonal();
  const V<N> m = inverse.asDiagonal() * (re.transpose() * (b.center().template cast<double>() - e.center().template cast<double>()));
  const Eigen::SelfAdjointEigenSolver<M<N>> eig(a.transpose() * a);
  const V<N> s = eig.eigenvalues(), g = eig.eigenvectors().transpose() * (a.transpose() * m);
  const auto y_at = [&](double lambda) {
    V<N> y;
    for (int k = 0; k < N; ++k) y[k] = g[k] == 0 ? 0 : g[k] / (lambda - s[k]);
    return y;
  };
  double lo = s[N - 1], hi = s[N - 1] + g.norm();  // |y(hi)| <= 1
  for (int k = 0; k < 200; ++k) {
    const double mid = lo + (hi - lo) / 2;
    if (mid <= lo || mid >= hi) break;
    (y_at(mid).squaredNorm() > 1 ? lo : hi) = mid;
  }
  V<N> y = y_at(hi);
  const double rest = y.squaredNorm() - y[N - 1] * y[N - 1];
  y[N - 1] = std::copysign(std::sqrt(std::max(0.0, 1 - rest)), g[N - 1]);
  V<N> v = eig.eigenvectors() * y;
  v /= v.norm();
  return {v, (m + a * v).squaredNorm()};
}

// b's boundary point center + axes diag(radii) v (|v| = 1) in T, drawn towards the center by
// the least factor 1 - 2^-k (k from min(T's digits, 43) down by 4: 2^-43 leaves double's
// rounding bound room to decide, and costs the lower bound 1e-13) that puts it inside b as
// stored (decided in rationals where the rounding bound cannot), else b's center: the
// weights' bound holds for points inside the bodies.
template <class T, int N>
Vec<T, N> inside_point(const Ellipsoid<T, N>& b, const V<N>& v) {
  using LV = Eigen::Matrix<long double, N, 1>;
  const Form<T, N> form(b);
  const LV c = b.center().template cast<long double>();
  const LV arm = detail::work_axes<double>(b).template cast<long double>() *
                 (b.radii().template cast<long double>().cwiseProduct(v.template cast<long double>()));
  for (int k = std::min(std::numeric_limits<T>::digits, 43); k >= 1; k -= 4) {
    const Vec<T, N> x = (c + arm * (1 - std::ldexp(1.0L, -k))).template cast<T>();
    const auto [q, err] = form(x);
    if (q + err <= 1 || (q - err <= 1 && ExactForm<N>(b).excess(x.template cast<double>()) == 0))
      return x;
  }
  return b.center();
}

// The enclosing ellipsoid of the union of bodies (geometry.hpp): a cutting-plane loop on
// points of their boundaries, each round adding, for every body that the current ellipsoid
// leaves out by more than the target, its farthest point; then the last ellipsoid grown until
// the exact classification finds every body inside, and its gap certified by the weights of
// the points (which lie in the bodies: a bound for the union too). Support: the bodies that
// carry the certificate.
constexpr int max_body_rounds = 100;

template <class T, int N>
EnclosingEllipsoid<T, N> enclose_bodies(std::span<const Ellipsoid<T, N>> bodies, const EnclosingOptions& options,
                                        const char* name) {
  if (bodies.empty()) throw InputError(name, "must hold at least one body");
  // The points of the round (e is theirs) and the body each lies in.
  std::vector<Vec<T, N>> points, next;
  std::vector<std::size_t> owner, next_owner;
  const auto add = [&](std::size_t j, const V<N>& v) {
    next.push_back(inside_point<T, N>(bodies[j], v));
    next_owner.push_back(j);
  };
  for (std::size_t j = 0; j < bodies.size(); ++j)
    for (int k = 0; k < N; ++k) {
      add(j, V<N>::Unit(k));
      add(j, -V<N>::Unit(k));
    }
  // The points' gap takes half the requested one, the bodies' excess (rho^(N/2) <= 1 + gap/4)
  // a quarter, the growth and rounding the rest.
  EnclosingOptions inner = options;
  inner.volume_gap = std::max(options.volume_gap / 2, detail::volume_gap_range.low);
  const double target = std::expm1(std::log1p(options.volume_gap / 4) * 2 / N);
  EnclosingEllipsoid<T, N> e, out;
  std::int64_t left = options.max_enclosing_iterations;
  bool capped = false, stalled = false;
  double rho = 1, best = std::numeric_limits<double>::infinity();
  int since = 0;
  for (int round = 0;; ++round) {
    points.swap(next);
    owner.swap(next_owner);
    inner.max_enclosing_iterations = left;
    e = enclose_points<T, N>(points, inner, name);
    out.iterations += e.iterations;
    out.passes += e.passes;
    left -= e.iterations;
    // The next round's points: each body's farthest and the weighted ones (the others would
    // crowd the face of the optimum). Where the weights stalled, a weighted point within 1e-3
    // (in the unit ball of e) of a newer one of its body leaves: the same contact, located
    // better (near twins are what stalls the weights).
    stalled = e.status == EnclosingStatus::did_not_converge;
    const Mat<double, N> axes = detail::work_axes<double>(e.body);
    const V<N> inverse = e.body.radii().template cast<double>().cwiseInverse();
    const auto unit = [&](const Vec<T, N>& x) -> V<N> {
      return inverse.asDiagonal() * (axes.transpose() * (x.template cast<double>() - e.body.center().template cast<double>()));
    };
    next.clear();
    next_owner.clear();
    rho = 1;
    for (std::size_t j = 0; j < bodies.size(); ++j) {
      const auto [v, form] = farthest<T, N>(e.body, bodies[j]);
      rho = std::max(rho, form);
      if (form > 1 + target) add(j, v);
    }
    const std::size_t added = next.size();
    std::vector<std::size_t> support = e.support;
    std::sort(support.begin(), support.end());  // the newer first
    bool dropped = false;
    for (std::size_t k : support) {
      bool twin = false;
      for (std::size_t i = 0; i < next.size() && stalled && !twin; ++i)
        twin = next_owner[i] == owner[k] && (unit(next[i]) - unit(points[k])).norm() < 1e-3;
      dropped = dropped || twin;
      if (twin) continue;
      next.push_back(points[k]);
      next_owner.push_back(owner[k]);
    }
    // Five rounds that do not halve the excess: its rounding's floor.
    if (rho - 1 < best / 2) best = rho - 1, since = 0;
    const bool more = added > 0 || dropped;
    capped = left < 1 || (more && round + 1 == max_body_rounds);
    if (!more || capped || ++since > 5) break;
  }
  // Grown by sqrt(rho) and a margin of ulps that doubles, until every body is inside (exact
  // classification, internal tangency included).
  Options exact;
  exact.tolerance = Tolerance::exact;
  double factor = std::sqrt(rho);
  for (int round = 0;; ++round) {
    if (round == 60) throw unrepresentable(name);
    const T grow = T(factor * (1 + std::ldexp(double(std::numeric_limits<T>::epsilon()), round + 2)));
    try {
      out.body = Ellipsoid<T, N>::from_axes(e.body.center(), e.body.axes(), Vec<T, N>(e.body.radii() * grow));
    } catch (const InputError&) {
      throw unrepresentable(name);
    }
    double worst = 0;
    for (const auto& b : bodies) {
      const Relation r = classify(out.body, b, exact);
      if (r != Relation::a_contains_b && r != Relation::equal) worst = std::max(worst, farthest<T, N>(out.body, b).second);
    }
    if (worst == 0) break;
    factor *= std::sqrt(std::max(worst, 1.0));
  }
  for (std::size_t k = 0; k < e.support.size(); ++k) {
    out.support.push_back(owner[e.support[k]]);
    out.support_points.push_back(points[e.support[k]]);
  }
  out.weights = e.weights;
  out.volume_gap = certified_gap<T, N>(out.body, points, e.support, e.weights);
  out.status = out.volume_gap <= options.volume_gap ? EnclosingStatus::optimal
               : capped || stalled                 ? EnclosingStatus::did_not_converge
                                                   : EnclosingStatus::rounding_limited;
  return out;
}

}  // namespace

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Vec<T, N>> points, const EnclosingOptions& options) {
  return enclose_points<T, N>(points, options, "points");
}

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Ellipsoid<T, N>> bodies, const EnclosingOptions& options) {
  return enclose_bodies<T, N>(bodies, options, "bodies");
}

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Capsule<T, N>> capsules, const EnclosingOptions& options) {
  std::vector<Ellipsoid<T, N>> balls;
  for (const auto& c : capsules)
    for (int k = 0; k < 2; ++k) balls.push_back(make_ball<T, N>(c.point(k), c.radius()));
  EnclosingEllipsoid<T, N> out = enclose_bodies<T, N>(balls, options, "capsules");
  for (std::size_t& j : out.support) j /= 2;
  return out;
}

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(std::span<const Box<T, N>> boxes, const EnclosingOptions& options) {
  if (boxes.empty()) throw InputError("boxes", "must hold at least one box");
  std::vector<Vec<T, N>> corners;
  for (const auto& b : boxes)
    for (int k = 0; k < 1 << N; ++k) corners.push_back(b.corner(k));
  EnclosingEllipsoid<T, N> out = enclose_points<T, N>(corners, options, "boxes");
  for (std::size_t& j : out.support) j >>= N;
  return out;
}

template <class T, int N>
EnclosingEllipsoid<T, N> enclosing_ellipsoid(const TriangleMesh<T, N>& mesh, const EnclosingOptions& options) {
  const std::span<const T> v = mesh.vertices();
  std::vector<Vec<T, N>> points(v.size() / N);
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = Eigen::Map<const Vec<T, N>>(v.data() + i * N);
  return enclose_points<T, N>(points, options, "mesh");
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                          \
  template EnclosingEllipsoid<T, N> enclosing_ellipsoid<T, N>(std::span<const Vec<T, N>>, const EnclosingOptions&);          \
  template EnclosingEllipsoid<T, N> enclosing_ellipsoid<T, N>(std::span<const Ellipsoid<T, N>>, const EnclosingOptions&);    \
  template EnclosingEllipsoid<T, N> enclosing_ellipsoid<T, N>(std::span<const Capsule<T, N>>, const EnclosingOptions&);      \
  template EnclosingEllipsoid<T, N> enclosing_ellipsoid<T, N>(std::span<const Box<T, N>>, const EnclosingOptions&);          \
  template EnclosingEllipsoid<T, N> enclosing_ellipsoid<T, N>(const TriangleMesh<T, N>&, const EnclosingOptions&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
