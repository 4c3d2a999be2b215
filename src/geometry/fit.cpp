// The least-squares ellipse or ellipsoid of points (geometry.hpp): an algebraic start
// (Halir-Flusser's direct ellipse fit in 2D, Li-Griffiths' ellipsoid fit in 3D, Taubin's
// general conic or quadric), then Levenberg-Marquardt on the orthogonal distances of
// closest_point with their exact derivatives (envelope theorem).
#include <ellipsect/geometry.hpp>
#include <ellipsect/point.hpp>

#include "detail/enum_names.hpp"
#include "detail/instantiate.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

namespace ellipsect {

std::string_view to_string(FitStatus s) noexcept {
  static constexpr std::string_view names[] = {"converged", "did_not_converge", "not_an_ellipse"};  // in the enum's order
  return detail::name_of(s, names);
}

namespace {

template <int N> using V = Eigen::Matrix<double, N, 1>;
template <int N> using M = Eigen::Matrix<double, N, N>;

// The points as the solver sees them: z = (p - origin) 2^-k, origin their mean (rounded to
// double), 2^k within a factor 2 of their RMS radius: the fit of scaled points is the scaled
// fit, bit for bit.
template <class T, int N>
struct Cloud {
  std::vector<V<N>> z;
  V<N> origin;
  double scale = 1;  // 2^k

  explicit Cloud(std::span<const Vec<T, N>> points) {
    constexpr std::size_t least = N == 2 ? 5 : 9;
    if (points.size() < least)
      throw InputError("points", "must hold at least " + std::to_string(least) + " points (got " +
                                     std::to_string(points.size()) + ")");
    Eigen::Matrix<long double, N, 1> sum = Eigen::Matrix<long double, N, 1>::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const V<N> p = points[i].template cast<double>();
      if (!p.allFinite()) throw RowInputError(i, "points", "must be finite");
      sum += p.template cast<long double>();
    }
    origin = (sum / static_cast<long double>(points.size())).template cast<double>();
    z.reserve(points.size());
    long double squares = 0;
    for (const auto& p : points) {
      z.push_back(p.template cast<double>() - origin);
      squares += static_cast<long double>(z.back().squaredNorm());
    }
    const double rms = double(std::sqrt(squares / static_cast<long double>(points.size())));
    if (!std::isfinite(rms)) throw InputError("points", "must span less than the largest double in each coordinate");
    if (rms == 0) throw InputError("points", "are all equal: no ellipse passes near them in the least-squares sense");
    int k = 0;
    (void)std::frexp(rms, &k);
    scale = std::ldexp(1.0, k);
    for (auto& y : z) y *= std::ldexp(1.0, -k);
    // The cloud's principal spreads: the least within 1e-8 of the largest is a line (plane).
    M<N> cov = M<N>::Zero();
    for (const auto& y : z) cov.noalias() += y * y.transpose();
    const Eigen::SelfAdjointEigenSolver<M<N>> eig(cov);
    const double low = std::max(eig.eigenvalues()[0], 0.0), high = eig.eigenvalues()[N - 1];
    if (!(std::sqrt(low / high) > 1e-8))
      throw InputError("points", std::string("lie within 1e-8 of their spread from a ") + (N == 2 ? "line" : "plane") +
                                     ": no ellipse" + (N == 2 ? "" : "oid") + " is determined by them");
  }
};

// A body in the solver's coordinates: center, orientation (2D an angle, 3D a unit quaternion)
// and radii.
template <int N>
struct Pose {
  V<N> c = V<N>::Zero();
  std::conditional_t<N == 2, double, Eigen::Quaterniond> turn{};
  V<N> r = V<N>::Ones();

  M<N> axes() const {
    if constexpr (N == 2) {
      M<N> R;
      R << std::cos(turn), -std::sin(turn), std::sin(turn), std::cos(turn);
      return R;
    } else {
      return turn.toRotationMatrix();
    }
  }
};

template <int N>
Pose<N> pose_of(const V<N>& c, M<N> R, const V<N>& r) {
  if (R.determinant() < 0) R.col(N - 1) *= -1;
  Pose<N> p;
  p.c = c;
  p.r = r;
  if constexpr (N == 2) p.turn = std::atan2(R(1, 0), R(0, 0));
  else p.turn = Eigen::Quaterniond(R).normalized();
  return p;
}

// The conic (quadric) z^T A z + g . z + f = 0 as coefficients of the monomials
//   2D  (x^2, xy, y^2, x, y, 1)
//   3D  (x^2, y^2, z^2, 2yz, 2xz, 2xy, 2x, 2y, 2z, 1)
template <int N> inline constexpr int terms = N == 2 ? 6 : 10;
template <int N> using Coefficients = Eigen::Matrix<double, terms<N>, 1>;

template <int N>
Coefficients<N> monomials(const V<N>& p) {
  Coefficients<N> m;
  if constexpr (N == 2) {
    m << p[0] * p[0], p[0] * p[1], p[1] * p[1], p[0], p[1], 1;
  } else {
    const double x = p[0], y = p[1], z = p[2];
    m << x * x, y * y, z * z, 2 * y * z, 2 * x * z, 2 * x * y, 2 * x, 2 * y, 2 * z, 1;
  }
  return m;
}

// d monomials / d p: row j the gradient of monomial j.
template <int N>
Eigen::Matrix<double, terms<N>, N> monomial_gradients(const V<N>& p) {
  Eigen::Matrix<double, terms<N>, N> g = Eigen::Matrix<double, terms<N>, N>::Zero();
  if constexpr (N == 2) {
    g(0, 0) = 2 * p[0];
    g(1, 0) = p[1];
    g(1, 1) = p[0];
    g(2, 1) = 2 * p[1];
    g(3, 0) = 1;
    g(4, 1) = 1;
  } else {
    const double x = p[0], y = p[1], z = p[2];
    g(0, 0) = 2 * x;
    g(1, 1) = 2 * y;
    g(2, 2) = 2 * z;
    g(3, 1) = 2 * z, g(3, 2) = 2 * y;
    g(4, 0) = 2 * z, g(4, 2) = 2 * x;
    g(5, 0) = 2 * y, g(5, 1) = 2 * x;
    g(6, 0) = 2;
    g(7, 1) = 2;
    g(8, 2) = 2;
  }
  return g;
}

// The ellipse (ellipsoid) of a conic's coefficients, or none where the conic is a hyperbola,
// parabola, line pair, imaginary or not finite.
template <int N>
std::optional<Pose<N>> ellipsoid_of(const Coefficients<N>& a) {
  if (!a.allFinite()) return std::nullopt;
  M<N> A;
  V<N> g;
  if constexpr (N == 2) {
    A << a[0], a[1] / 2, a[1] / 2, a[2];
    g << a[3], a[4];
  } else {
    A << a[0], a[5], a[4], a[5], a[1], a[3], a[4], a[3], a[2];
    g << 2 * a[6], 2 * a[7], 2 * a[8];
  }
  const double f = a[terms<N> - 1];
  const Eigen::SelfAdjointEigenSolver<M<N>> form(A);
  const V<N> l = form.eigenvalues();
  // Definite, one sign (flipped to positive), well inside the range of aspect ratios.
  const double sign = l[N - 1] > 0 ? 1 : -1;
  const V<N> lp = sign * l;
  if (!(lp.minCoeff() > 1e-16 * lp.maxCoeff())) return std::nullopt;
  const V<N> c = -form.eigenvectors() * (form.eigenvectors().transpose() * g).cwiseQuotient(l) / 2;
  const double k = -sign * (f + g.dot(c) / 2);  // the form's value at the center, negated: (z - c)^T A (z - c) = k
  if (!(k > 0)) return std::nullopt;
  const V<N> r = (k * lp.cwiseInverse()).cwiseSqrt();
  if (!r.allFinite() || !c.allFinite()) return std::nullopt;
  return pose_of<N>(c, form.eigenvectors(), r);
}

// The ellipse-specific direct fit: Halir and Flusser's form of Fitzgibbon, Pilu and Fisher's
// (2D), Li and Griffiths' with k = 4 (3D): minimize a^T S a subject to a^T C a = 1 on the
// quadratic block a1 (the linear block a2 = T a1 eliminated), the eigenvector of C1^-1 M of
// positive a1^T C1 a1 (one exists, of a positive eigenvalue) with the least a1^T M a1 / a1^T C1 a1.
template <int N>
std::optional<Coefficients<N>> direct_fit(const std::vector<V<N>>& z) {
  constexpr int q = N == 2 ? 3 : 6, l = terms<N> - q;
  Eigen::Matrix<double, terms<N>, terms<N>> S = Eigen::Matrix<double, terms<N>, terms<N>>::Zero();
  for (const auto& p : z) {
    const Coefficients<N> m = monomials<N>(p);
    S.template selfadjointView<Eigen::Lower>().rankUpdate(m);
  }
  S = S.template selfadjointView<Eigen::Lower>();
  const Eigen::Matrix<double, q, q> S1 = S.template topLeftCorner<q, q>();
  const Eigen::Matrix<double, q, l> S2 = S.template topRightCorner<q, l>();
  const Eigen::Matrix<double, l, l> S3 = S.template bottomRightCorner<l, l>();
  const Eigen::LDLT<Eigen::Matrix<double, l, l>> s3(S3);
  if (s3.info() != Eigen::Success || !(s3.vectorD().minCoeff() > 0)) return std::nullopt;
  const Eigen::Matrix<double, l, q> T = -s3.solve(S2.transpose());
  Eigen::Matrix<double, q, q> Mr = S1 + S2 * T;
  Mr = (Mr + Mr.transpose()).eval() / 2;
  Eigen::Matrix<double, q, q> C1 = Eigen::Matrix<double, q, q>::Zero(), C1inv = C1;
  if constexpr (N == 2) {
    C1 << 0, 0, 2, 0, -1, 0, 2, 0, 0;
    C1inv << 0, 0, 0.5, 0, -1, 0, 0.5, 0, 0;
  } else {
    C1.template topLeftCorner<3, 3>() << -1, 1, 1, 1, -1, 1, 1, 1, -1;
    C1.template bottomRightCorner<3, 3>() = -4 * M<3>::Identity();
    C1inv.template topLeftCorner<3, 3>() << 0, 0.5, 0.5, 0.5, 0, 0.5, 0.5, 0.5, 0;
    C1inv.template bottomRightCorner<3, 3>() = -0.25 * M<3>::Identity();
  }
  // The real eigenvalues of C1^-1 M from its real Schur form, each one's vector the null
  // vector of C1^-1 M - mu I (its least right singular vector).
  const Eigen::Matrix<double, q, q> Mc = C1inv * Mr;
  const Eigen::RealSchur<Eigen::Matrix<double, q, q>> schur(Mc, false);
  if (schur.info() != Eigen::Success) return std::nullopt;
  const Eigen::Matrix<double, q, q>& U = schur.matrixT();
  std::optional<Eigen::Matrix<double, q, 1>> best;
  double best_value = std::numeric_limits<double>::infinity();
  for (int k = 0; k < q; ++k) {
    if ((k + 1 < q && U(k + 1, k) != 0) || (k > 0 && U(k, k - 1) != 0)) continue;  // a complex pair's block
    const Eigen::Matrix<double, q, q> shifted = Mc - U(k, k) * Eigen::Matrix<double, q, q>::Identity();
    const Eigen::JacobiSVD<Eigen::Matrix<double, q, q>> svd(shifted, Eigen::ComputeFullV);
    const Eigen::Matrix<double, q, 1> v = svd.matrixV().col(q - 1);
    const double constraint = v.dot(C1 * v);
    if (!(constraint > 0)) continue;
    const double value = v.dot(Mr * v) / constraint;
    if (value < best_value) best_value = value, best = v;
  }
  if (!best) return std::nullopt;
  Coefficients<N> a;
  a << *best, T * *best;
  return a;
}

// Taubin's fit of the general conic (quadric): minimize sum (m_i . a)^2 / sum |grad_i . a|^2,
// the constant eliminated; its value is a first-order estimate of the mean squared orthogonal
// distance to that conic.
template <int N>
struct GeneralFit {
  Coefficients<N> a;
  double rms = 0;  // sqrt of the minimized ratio
};

template <int N>
std::optional<GeneralFit<N>> taubin_fit(const std::vector<V<N>>& z) {
  constexpr int t = terms<N>, u = t - 1;
  Eigen::Matrix<double, t, t> S = Eigen::Matrix<double, t, t>::Zero();
  Eigen::Matrix<double, u, u> G = Eigen::Matrix<double, u, u>::Zero();
  for (const auto& p : z) {
    S.template selfadjointView<Eigen::Lower>().rankUpdate(monomials<N>(p));
    const Eigen::Matrix<double, u, N> g = monomial_gradients<N>(p).template topRows<u>();
    G.noalias() += g * g.transpose();
  }
  S = S.template selfadjointView<Eigen::Lower>();
  const double n = S(u, u);
  const Eigen::Matrix<double, u, 1> s = S.template topRightCorner<u, 1>();
  const Eigen::Matrix<double, u, u> R = S.template topLeftCorner<u, u>() - s * s.transpose() / n;
  const Eigen::LLT<Eigen::Matrix<double, u, u>> gl(G);
  if (gl.info() != Eigen::Success) return std::nullopt;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix<double, u, u>> es(R, G);
  if (es.info() != Eigen::Success) return std::nullopt;
  const Eigen::Matrix<double, u, 1> v = es.eigenvectors().col(0);
  GeneralFit<N> out;
  out.a << v, -s.dot(v) / n;
  out.rms = std::sqrt(std::max(v.dot(R * v), 0.0) / std::max(v.dot(G * v), std::numeric_limits<double>::min()));
  if (!out.a.allFinite()) return std::nullopt;
  return out;
}

// The orthogonal residuals of the points to a pose and, where asked, the normal equations of
// their Jacobian in (center, rotation increment, log radii): A = J^T J, g = J^T d.
// The orthogonal residuals of the points to a body and, where asked, the normal equations of
// their Jacobian in K parameters: A = J^T J, g = J^T d.
template <int K>
struct Residuals {
  using VK = Eigen::Matrix<double, K, 1>;
  using MK = Eigen::Matrix<double, K, K>;
  bool valid = false;  // a body from_axes accepts
  double ss = 0;
  double floor = 0;  // a bound on the rounding of ss (closest_point's, point.hpp)
  MK A = MK::Zero();
  VK g = VK::Zero();
};

// One pass of closest_point over the points. `row(x, y, n, d)` gives the Jacobian's row of a
// point x at its closest point y (outward unit normal n, signed distance d).
template <int K, int N, class Row>
Residuals<K> pass(const Pose<N>& pose, const std::vector<V<N>>& z, bool jacobian, Row&& row) {
  Residuals<K> out;
  if (!pose.c.allFinite() || !pose.r.allFinite()) return out;
  const M<N> R = pose.axes();
  Ellipsoid<double, N> body;
  try {
    body = Ellipsoid<double, N>::from_axes(pose.c, R, pose.r);
  } catch (const InputError&) {
    return out;
  }
  out.valid = true;
  const V<N> inv2 = pose.r.cwiseAbs2().cwiseInverse();
  double reach = 0;
  for (const auto& x : z) {
    const ClosestPoint<double, N> cp = closest_point(body, Vec<double, N>(x));
    const double d = cp.signed_distance;
    out.ss += d * d;
    reach = std::max(reach, (x - pose.c).norm());
    if (!jacobian) continue;
    const V<N> y = cp.point;
    const V<N> nl = (R.transpose() * (y - pose.c)).cwiseProduct(inv2);  // the normal in the body's frame
    const double norm = nl.norm();
    if (!(norm > 0)) continue;
    const Eigen::Matrix<double, K, 1> j = row(x, y, V<N>(R * (nl / norm)), d);
    out.A.template selfadjointView<Eigen::Lower>().rankUpdate(j);
    out.g.noalias() += d * j;
  }
  out.A = out.A.template selfadjointView<Eigen::Lower>();
  const double e = 1e-14 * (pose.r.maxCoeff() + reach);
  out.floor = 2 * std::sqrt(double(z.size()) * out.ss) * e + double(z.size()) * (e * e + 1.2e-16 * out.ss);
  return out;
}

// In the pose's parameters (center, rotation increment, log radii), by the envelope theorem.
template <int N>
Residuals<fit_parameter_count<N>> pose_residuals(const Pose<N>& pose, const std::vector<V<N>>& z) {
  constexpr int K = fit_parameter_count<N>;
  const M<N> R = pose.axes();
  return pass<K, N>(pose, z, true, [&](const V<N>&, const V<N>& y, const V<N>& n, double) {
    Eigen::Matrix<double, K, 1> row;
    const V<N> v = y - pose.c;
    row.template head<N>() = -n;
    if constexpr (N == 2) row[N] = -(v[0] * n[1] - v[1] * n[0]);
    else row.template segment<3>(N) = -v.cross(n);
    row.template tail<N>() = -(R.transpose() * n).cwiseProduct(R.transpose() * v);
    return row;
  });
}

// In the conic's coefficients a (Q = a . monomials, negative inside): the boundary moves out by
// -(m(y) . da) / |grad Q(y)|, so dd/da = m(y) / |grad Q(y)|.
template <int N>
Residuals<terms<N>> conic_residuals(const Coefficients<N>& a, const std::vector<V<N>>& z) {
  const std::optional<Pose<N>> pose = ellipsoid_of<N>(a);
  if (!pose) return {};
  return pass<terms<N>, N>(*pose, z, true, [&](const V<N>&, const V<N>& y, const V<N>&, double) {
    const V<N> grad = monomial_gradients<N>(y).transpose() * a;
    return Coefficients<N>(monomials<N>(y) / grad.norm());
  });
}

// The coefficients of a pose's conic, unit norm, negative inside.
template <int N>
Coefficients<N> conic_of(const Pose<N>& p) {
  const M<N> R = p.axes();
  const M<N> A = R * p.r.cwiseAbs2().cwiseInverse().asDiagonal() * R.transpose();
  const V<N> g = -2 * A * p.c;
  const double f = p.c.dot(A * p.c) - 1;
  Coefficients<N> a;
  if constexpr (N == 2) a << A(0, 0), 2 * A(0, 1), A(1, 1), g[0], g[1], f;
  else a << A(0, 0), A(1, 1), A(2, 2), A(1, 2), A(0, 2), A(0, 1), g[0] / 2, g[1] / 2, g[2] / 2, f;
  return a.normalized();
}

template <int N>
Pose<N> moved(const Pose<N>& p, const Eigen::Matrix<double, fit_parameter_count<N>, 1>& delta) {
  Pose<N> out = p;
  out.c += delta.template head<N>();
  if constexpr (N == 2) {
    out.turn += delta[N];
  } else {
    const V<3> w = delta.template segment<3>(N);
    const double angle = w.norm();
    const Eigen::Quaterniond q = angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle))
                                           : Eigen::Quaterniond::Identity();
    out.turn = (q * p.turn).normalized();
  }
  out.r = (p.r.array() * delta.template tail<N>().array().exp()).matrix();
  return out;
}

// J^T J scaled to a unit diagonal (columns of zero norm kept at 1e-300), its eigenvalues and
// vectors: the Gauss-Newton step and the covariance through its pseudo-inverse.
template <int K>
struct Normal {
  using VK = Eigen::Matrix<double, K, 1>;
  using MK = Eigen::Matrix<double, K, K>;
  VK scale;  // 1 / sqrt(A_kk)
  MK scaled;
  Eigen::SelfAdjointEigenSolver<MK> eig;
  int rank = 0;
  explicit Normal(const MK& A) {
    const double top = A.diagonal().maxCoeff();
    for (int k = 0; k < K; ++k) scale[k] = 1 / std::sqrt(std::max(A(k, k), 1e-24 * top + 1e-300));
    scaled = scale.asDiagonal() * A * scale.asDiagonal();
    eig.compute(scaled);
    for (int k = 0; k < K; ++k) rank += kept(k);
  }
  bool kept(int k) const { return eig.eigenvalues()[k] > 1e-12 * std::max(eig.eigenvalues()[K - 1], 0.0); }
  // A^+ b, the eigenvalues below 1e-12 of the largest taken as 0.
  VK pseudo_solve(const VK& b) const {
    VK y = eig.eigenvectors().transpose() * scale.cwiseProduct(b);
    for (int k = 0; k < K; ++k) y[k] = kept(k) ? y[k] / eig.eigenvalues()[k] : 0;
    return scale.cwiseProduct(eig.eigenvectors() * y);
  }
  MK pseudo_inverse() const {
    VK inv;
    for (int k = 0; k < K; ++k) inv[k] = kept(k) ? 1 / eig.eigenvalues()[k] : 0;
    return scale.asDiagonal() * eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose() *
           scale.asDiagonal();
  }
  // (A + lambda diag(A)) step = -g, diag(A) floored as above.
  VK damped_step(const VK& g, double lambda) const {
    MK m = scaled;
    m.diagonal().array() += lambda;
    return -scale.cwiseProduct(Eigen::LDLT<MK>(m).solve(scale.cwiseProduct(g)));
  }
};

enum class Descent { stationary, capped, stalled, runaway };

// Levenberg-Marquardt with Nielsen's update of the damping, from x (its residuals `at`):
// stationary where the Gauss-Newton step is below tol (infinity norm) or the residuals are
// orthogonal to the Jacobian's columns to a cosine of tol, or where no step lowers S beyond its
// rounding; there Gauss-Newton's steps are taken whenever they do not raise S beyond it (a few),
// so that the stationary point is reached to the rounding of the residuals rather than of S.
// `runaway(x)` ends the descent.
template <int K, class X, class Evaluate, class Move, class Runaway>
Descent levenberg_marquardt(X& x, Residuals<K>& at, double tol, int& iterations, int cap, Evaluate&& evaluate,
                            Move&& move, Runaway&& runaway) {
  using VK = Eigen::Matrix<double, K, 1>;
  double lambda = 1e-3, nu = 2;
  int rejected = 0, floor_steps = 0;
  for (;;) {
    if (at.ss == 0) return Descent::stationary;
    const Normal<K> normal(at.A);
    const VK gauss_newton = -normal.pseudo_solve(at.g);
    double cosine = 0;
    for (int k = 0; k < K; ++k)
      if (at.A(k, k) > 0) cosine = std::max(cosine, std::abs(at.g[k]) / std::sqrt(at.A(k, k) * at.ss));
    if (cosine <= tol) return Descent::stationary;
    if (gauss_newton.template lpNorm<Eigen::Infinity>() <= tol) {
      // Within tol of the stationary point: its last step taken where it does not raise S beyond
      // rounding (on points on a body it ends at the rounding's floor, Gauss-Newton converging
      // quadratically there).
      if (iterations < cap) {
        ++iterations;
        const X trial = move(x, gauss_newton);
        Residuals<K> next = evaluate(trial);
        if (next.valid && next.ss <= at.ss + at.floor && !runaway(trial)) {
          x = trial;
          at = std::move(next);
        }
      }
      return Descent::stationary;
    }
    const double gn_decrease = -at.g.dot(gauss_newton);  // predicted, of S
    const bool at_floor = gn_decrease <= at.floor;
    if (rejected >= 12 || floor_steps >= 8) return at_floor ? Descent::stationary : Descent::stalled;
    if (iterations >= cap) return Descent::capped;
    const VK step = at_floor ? gauss_newton : normal.damped_step(at.g, lambda);
    const X trial = move(x, step);
    ++iterations;
    Residuals<K> next = evaluate(trial);
    if (next.valid && (next.ss < at.ss || (at_floor && next.ss <= at.ss + at.floor))) {
      if (at_floor) {
        ++floor_steps;
      } else {
        const VK scaled_step = step.cwiseQuotient(normal.scale);
        const double predicted = lambda * scaled_step.squaredNorm() - step.dot(at.g);
        const double rho = predicted > 0 ? (at.ss - next.ss) / predicted : 1;
        lambda *= std::max(1.0 / 3, 1 - std::pow(2 * rho - 1, 3));
        nu = 2;
      }
      rejected = 0;
      x = trial;
      at = std::move(next);
      if (runaway(x)) return Descent::runaway;
    } else {
      if (at_floor) floor_steps = 8;  // Gauss-Newton raised S: the rounding decides from here
      lambda *= nu;
      nu *= 2;
      ++rejected;
    }
  }
}

template <class T, int N>
Ellipsoid<T, N> world_body(const Cloud<T, N>& cloud, const Pose<N>& p) {
  const Eigen::Matrix<long double, N, 1> c =
      cloud.origin.template cast<long double>() + static_cast<long double>(cloud.scale) * p.c.template cast<long double>();
  try {
    return Ellipsoid<T, N>::from_axes(c.template cast<T>(), p.axes().template cast<T>(),
                                      (cloud.scale * p.r).template cast<T>());
  } catch (const InputError&) {
    throw InputError("points", "the fitted body is not representable in the type (radii beyond its range)");
  }
}

// RMS and largest |d| of the points to the stored body, by closest_point in T.
template <class T, int N>
std::pair<double, double> stored_residuals(const Ellipsoid<T, N>& body, std::span<const Vec<T, N>> points) {
  long double ss = 0;
  double worst = 0;
  for (const auto& p : points) {
    const double d = double(closest_point(body, p).signed_distance);
    ss += static_cast<long double>(d) * d;
    worst = std::max(worst, std::abs(d));
  }
  return {double(std::sqrt(ss / static_cast<long double>(points.size()))), worst};
}

}  // namespace

template <class T, int N>
EllipsoidFit<T, N> fit_ellipsoid(std::span<const Vec<T, N>> points, const FitOptions& options) {
  constexpr int P = fit_parameter_count<N>;
  using VP = Eigen::Matrix<double, P, 1>;
  const Cloud<T, N> cloud(points);
  const auto& z = cloud.z;
  const double n = double(z.size());
  const double tol = options.fit_tolerance;
  EllipsoidFit<T, N> out;

  // The starts: the ellipse-specific direct fit, Taubin's conic where it is an ellipse, and the
  // cloud's RMS ball about its mean; the closest to the points begins the descent.
  const std::optional<Coefficients<N>> direct = direct_fit<N>(z);
  const std::optional<Pose<N>> direct_pose = direct ? ellipsoid_of<N>(*direct) : std::nullopt;
  const std::optional<GeneralFit<N>> general = taubin_fit<N>(z);
  const std::optional<Pose<N>> general_pose = general ? ellipsoid_of<N>(general->a) : std::nullopt;
  Pose<N> pose;
  pose.r = V<N>::Constant(std::sqrt(std::accumulate(z.begin(), z.end(), 0.0,
                                                    [](double s, const V<N>& y) { return s + y.squaredNorm(); }) /
                                    n));
  if constexpr (N == 3) pose.turn = Eigen::Quaterniond::Identity();
  const auto no_row = [](const V<N>&, const V<N>&, const V<N>&, double) { return VP::Zero().eval(); };
  double start_ss = pass<P, N>(pose, z, false, no_row).ss;
  for (const auto* start : {&direct_pose, &general_pose}) {
    if (!*start) continue;
    const double ss = pass<P, N>(**start, z, false, no_row).ss;
    if (ss < start_ss) pose = **start, start_ss = ss;
  }

  // First along the conic's coefficients, in which the valleys of short arcs and near circles
  // are straight (the conics through points a linear family), to 1e-6; then in the pose's
  // parameters to fit_tolerance.
  const int cap = options.max_fit_iterations;
  const auto too_large = [](const Pose<N>& p) { return p.r.maxCoeff() > 1e4; };
  Descent descent = Descent::stationary;
  {
    Coefficients<N> a = conic_of<N>(pose);
    Residuals<terms<N>> at = conic_residuals<N>(a, z);
    if (at.valid) {
      descent = levenberg_marquardt<terms<N>>(
          a, at, std::max(tol, 1e-6), out.iterations, cap, [&](const Coefficients<N>& b) { return conic_residuals<N>(b, z); },
          [](const Coefficients<N>& b, const Coefficients<N>& step) { return Coefficients<N>((b + step).normalized()); },
          [&](const Coefficients<N>& b) {
            const auto p = ellipsoid_of<N>(b);
            return !p || too_large(*p);
          });
      if (const auto p = ellipsoid_of<N>(a)) pose = *p;
    }
  }
  Residuals<P> at = pose_residuals<N>(pose, z);
  if (descent != Descent::runaway)
    descent = levenberg_marquardt<P>(
        pose, at, tol, out.iterations, cap, [&](const Pose<N>& p) { return pose_residuals<N>(p, z); },
        [](const Pose<N>& p, const VP& step) { return moved<N>(p, step); }, too_large);

  // Not an ellipse: the general conic is not one and fits markedly better, or the ellipse ran
  // away towards a parabola or a line.
  const double rms = std::sqrt(at.ss / n);
  const bool conic_better = general && !general_pose && rms > 2 * general->rms + 1e-8;
  out.status = descent == Descent::runaway || conic_better ? FitStatus::not_an_ellipse
               : descent == Descent::stationary            ? FitStatus::converged
                                                           : FitStatus::did_not_converge;

  out.body = world_body<T, N>(cloud, pose);
  std::tie(out.rms_residual, out.max_residual) = stored_residuals<T, N>(out.body, points);
  if (direct_pose) {
    out.algebraic = world_body<T, N>(cloud, *direct_pose);
    out.algebraic_rms_residual = stored_residuals<T, N>(out.algebraic, points).first;
  } else {
    out.algebraic_rms_residual = std::numeric_limits<double>::infinity();
  }

  // The covariance: sigma^2 (J^T J)^+ in the solver's parameters, carried to the world's
  // (center times the scale, radii from log radii: dr = r dlog r).
  const Normal<P> normal(at.A);
  out.rank = normal.rank;
  const double sigma2 = z.size() > std::size_t(P) ? at.ss / (n - P) : std::numeric_limits<double>::quiet_NaN();
  VP d;
  d.template head<N>().setConstant(cloud.scale);
  d.template segment<P - 2 * N>(N).setOnes();
  d.template tail<N>() = cloud.scale * pose.r;
  out.covariance = sigma2 * (d.asDiagonal() * normal.pseudo_inverse() * d.asDiagonal());
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N) \
  template EllipsoidFit<T, N> fit_ellipsoid<T, N>(std::span<const Vec<T, N>>, const FitOptions&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
