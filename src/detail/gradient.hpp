// Derivatives of a body's support radius and quadric with respect to its parameters
// (gradient.hpp's conventions), shared by the value-and-gradient functions.
#pragma once

#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/gradient.hpp>

#include "detail/axes.hpp"
#include "detail/compensated.hpp"
#include "detail/secular.hpp"
#include "math.hpp"


#include <array>
#include <cmath>
#include <limits>


namespace ellipsect::detail {

// p x n: the rate of p . n as p turns about the origin with unit angular velocity about
// each world axis (2D: the counterclockwise rate).
template <class R, int N>
RotationVector<R, N> turn_rate(const Vec<R, N>& p, const Vec<R, N>& n) noexcept {
  if constexpr (N == 2) {
    return p[0] * n[1] - p[1] * n[0];
  } else {
    return p.cross(n);
  }
}

// The gradient of rho(n) = |diag(r) A^T n|, the body's support radius along the unit n:
//   d rho / d r_i = r_i (A^T n)_i^2 / rho,   d rho / d phi = p x n,   d rho / d center = 0,
// with p = A diag(r^2) A^T n / rho the body's support point less its center (also stored in
// *support where given). Formed from diag(r) A^T n / rho (entries at most 1), so no length is
// squared.
template <class R, class T, int N>
BodyGradient<R, N> support_radius_gradient(const Ellipsoid<T, N>& body, const Vec<R, N>& n,
                                           Vec<R, N>* support = nullptr) noexcept {
  const Mat<R, N> axes = work_axes<R>(body);
  const Vec<R, N> r = body.radii().template cast<R>();
  const Vec<R, N> q = axes.transpose() * n;
  Vec<R, N> w = r.cwiseProduct(q);
  w /= stable_norm<R, N>(w);
  const Vec<R, N> p = axes * r.cwiseProduct(w);
  if (support != nullptr) *support = p;
  BodyGradient<R, N> out;
  out.center.setZero();
  out.radii = w.cwiseProduct(q);
  out.orientation = turn_rate<R, N>(p, n);
  return out;
}

template <class R, int N>
RotationVector<R, N> times(const RotationVector<R, N>& v, R factor) noexcept {
  if constexpr (N == 2) {
    return v * factor;
  } else {
    return Vec<R, 3>(v * factor);
  }
}

// v rounded to T.
template <class T, class R, int N>
RotationVector<T, N> rotation_in(const RotationVector<R, N>& v) noexcept {
  if constexpr (N == 2) {
    return T(v);
  } else {
    return v.template cast<T>();
  }
}

// factor * g, rounded to T.
template <class T, class R, int N>
BodyGradient<T, N> gradient_in(const BodyGradient<R, N>& g, R factor) noexcept {
  BodyGradient<T, N> out;
  out.center = (g.center * factor).template cast<T>();
  out.radii = (g.radii * factor).template cast<T>();
  out.orientation = rotation_in<T, R, N>(times<R, N>(g.orientation, factor));
  return out;
}

// Every component x: 0 where the value does not depend on the parameters, NaN where no
// derivative is computed.
template <class T, int N>
BodyGradient<T, N> constant_gradient(T x) noexcept {
  BodyGradient<T, N> out;
  out.center.setConstant(x);
  out.radii.setConstant(x);
  if constexpr (N == 2) {
    out.orientation = x;
  } else {
    out.orientation.setConstant(x);
  }
  return out;
}

// A body at the hit for the point's derivatives: its support offset p along n, the
// derivative H = (M - p p^T) / rho of p by n (formed as B (I - w w^T) B^T / rho with
// B = A diag(r), w = B^T n / rho, so no length is squared and cancelled), and
// C = dp / du at fixed n for a world turn u: u x p - H (u x n), columns by u's components.
template <class R, int N>
struct HitSide {
  Vec<R, N> p;
  Mat<R, N> h;
  TurnJacobian<R, N> turn;
  Mat<R, N> axes;
  Vec<R, N> w, q;
  R rho;

  template <class T>
  HitSide(const Ellipsoid<T, N>& body, const Vec<R, N>& n) {
    axes = work_axes<R>(body);
    const Vec<R, N> r = body.radii().template cast<R>();
    q = axes.transpose() * n;
    w = r.cwiseProduct(q);
    rho = stable_norm<R, N>(w);
    w /= rho;
    const Mat<R, N> b = axes * r.asDiagonal();
    p = b * w;
    h = b * (Mat<R, N>::Identity() - w * w.transpose()) * b.transpose() / rho;
    if constexpr (N == 2) {
      const Vec<R, 2> pp(-p[1], p[0]), np(-n[1], n[0]);
      turn = pp - h * np;
    } else {
      Mat<R, 3> cn, cp;  // [n]x, [p]x
      cn << 0, -n[2], n[1], n[2], 0, -n[0], -n[1], n[0], 0;
      cp << 0, -p[2], p[1], p[2], 0, -p[0], -p[1], p[0], 0;
      turn = h * cn - cp;
    }
  }
  // dp / d r_i at fixed n: 2 w_i a_i - (w_i q_i / rho) p.
  Vec<R, N> by_radius(int i) const { return R(2) * w[i] * axes.col(i) - (w[i] * q[i] / rho) * p; }
};

// Where a shape's signed distance to a body may have its maximum (3D): an edge (`edge`) in
// double length, q its first end less the body's center, e its second end less its first, its
// stratum's directions n those orthogonal to e with n . s > 0 for each of the `sides` given (a
// triangle's third vertex less the edge, a box's adjacent faces' inward normals); and the unit
// normals, pointing from the body to the shape, of the faces at the touching point (`faces`).
template <class R>
struct EdgeOffsets {
  bool edge = false;
  std::array<Double<R>, 3> q, e;
  std::array<Vec<R, 3>, 3> sides, faces;
  int side_count = 0, face_count = 0;
};

// The edge q0 q1 (world points) less the body's center, split exactly.
template <class R, class T>
void set_edge(EdgeOffsets<R>& out, const Ellipsoid<T, 3>& a, const Vec<T, 3>& q0, const Vec<T, 3>& q1) noexcept {
  out.edge = true;
  for (int i = 0; i < 3; ++i) {
    out.q[i] = two_sum(R(q0[i]), -R(a.center()[i]));
    out.e[i] = two_sum(R(q1[i]), -R(q0[i]));
  }
}

// The normal of a signed distance whose maximum lies inside the stratum of an edge (3D): the
// directions n orthogonal to the edge's e, where the gap is n . q - rho(n), q the edge line's
// point nearest the body's center, less that center. q is formed in double length from the
// edge's offsets: an edge 1e10 radii long puts the rounding of its end less the center at 1e-6
// radii otherwise. Newton on that circle from n: the step along t = u x n (u = e / |e|) is
// t . (q - p(n)) / (g + t^T H t), with p(n) and H as HitSide's and g = n . q - rho(n). The
// polished n replaces n only where it is that stratum's maximum: every denominator positive,
// the steps together below 1e-4 rad, the sides' conditions held, and the body's support point
// p(n) + g n on the edge strictly between its ends (else the maximum lies on a neighbouring
// stratum, a face or a vertex, where n stays as given).
template <class R, class T>
bool polish_on_edge(const Ellipsoid<T, 3>& a, const EdgeOffsets<R>& edge, Vec<R, 3>& normal) noexcept {
  using D = Double<R>;
  const std::array<D, 3>&q = edge.q, &e = edge.e;
  D eq{}, ee{};
  for (int i = 0; i < 3; ++i) {
    eq = eq + e[i] * q[i];
    ee = ee + e[i] * e[i];
  }
  if (!(ee.hi > R(0))) return false;
  const D f = eq / ee;
  Vec<R, 3> qp, u;
  for (int i = 0; i < 3; ++i) {
    qp[i] = (q[i] - e[i] * f).hi;
    u[i] = e[i].hi;
  }
  const R length = u.norm();
  u /= length;
  Vec<R, 3> n = normal - u * u.dot(normal);
  n /= n.norm();
  R turned = abs(asin(std::min(R(1), abs(u.dot(normal)))));
  for (int step = 0; step < 3; ++step) {
    const HitSide<R, 3> side(a, n);
    const Vec<R, 3> t = u.cross(n);
    const R den = n.dot(qp) - side.rho + t.dot(side.h * t);
    if (!(den > R(0))) return false;
    const R theta = t.dot(qp - side.p) / den;
    n += theta * t;
    n /= n.norm();
    turned += abs(theta);
    if (!(abs(theta) > R(4) * std::numeric_limits<R>::epsilon())) break;
  }
  if (!(turned < R(1e-4))) return false;
  for (int k = 0; k < edge.side_count; ++k)
    if (!(n.dot(edge.sides[k]) > R(0))) return false;
  // The support point's place along the edge from its first end, in units of |e|: it lies at
  // q + s e with p . u = (q + s e) . u (n is orthogonal to u).
  Vec<R, 3> p;
  support_radius_gradient<R>(a, n, &p);
  const R s = p.dot(u) / length - f.hi;
  if (!(s > R(0) && s < R(1))) return false;
  normal = n;
  return true;
}

// The stratum's normal for a signed distance whose maximum lies on an edge (polish_on_edge)
// or, failing that, at a face's normal within 1e-6 rad of n: the face's exact normal (the
// maximum at a face, or at a face's rim, is the face's normal; the solve's own carries its
// rounding, 1e-10 on a box of aspect ratio 1e4).
template <class R, class T>
void polish_normal(const Ellipsoid<T, 3>& a, const EdgeOffsets<R>& stratum, Vec<R, 3>& n) noexcept {
  if (stratum.edge && polish_on_edge<R>(a, stratum, n)) return;
  for (int k = 0; k < stratum.face_count; ++k)
    if ((stratum.faces[k] - n).norm() < R(1e-6)) {
      n = stratum.faces[k];
      return;
    }
}

// signed_distance_gradient of the body a and a shape (shapes' headers), from the signed
// distance d = max over unit n of (min over the shape of n . y) - n . center(a) - rho_a(n)
// (value, its normal n the maximizer). a's part as against a body (envelope theorem);
// the shape's from shape(n, p, d) (in R): the point of the shape where it touches a moved by
// -d n is p + d n less a's center, p a's support point along n less its center (a material
// point of the shape moved at velocity u changes d at the rate n . u). In 3D, n is first
// polished on its stratum (polish_normal), whose edge and faces stratum_of(n, p, d, stratum)
// sets from that point (an EdgeOffsets). A value with no normal
// (did_not_converge) gets NaN for a's part and shape(NaN, NaN, d) for the shape's.
template <class T, int N, class G, class Stratum, class Shape>
DistanceGradient<T, N, G> shape_distance_gradient(const Ellipsoid<T, N>& a, const Distance<T, N>& value,
                                                  Stratum&& stratum_of, Shape&& shape) noexcept {
  using R = std::conditional_t<(sizeof(T) < sizeof(double)), double, T>;
  const bool known = value.status != DistanceStatus::did_not_converge && value.normal.allFinite();
  Vec<R, N> n = known ? Vec<R, N>(value.normal.template cast<R>()) : Vec<R, N>::Constant(std::numeric_limits<R>::quiet_NaN());
  Vec<R, N> p;
  BodyGradient<R, N> ga = support_radius_gradient<R>(a, n, &p);
  if constexpr (N == 3) {
    EdgeOffsets<R> stratum;
    if (known) {
      stratum_of(n, p, R(value.distance), stratum);
      polish_normal<R>(a, stratum, n);
      ga = support_radius_gradient<R>(a, n, &p);
    }
  }
  ga.center = n;
  return {value, gradient_in<T>(ga, R(-1)), shape(n, p, R(value.distance))};
}

// first_contact_gradient's answer before the derivatives of a hit: 0 where the bodies overlap
// at the start (the time is 0 nearby), NaN otherwise.
template <class T, int N>
ContactGradient<T, N> unanswered_gradient(const Contact<T, N>& value) noexcept {
  const T x = value.status == ContactStatus::overlapping_at_start ? T(0) : std::numeric_limits<T>::quiet_NaN();
  const BodyGradient<T, N> g = constant_gradient<T, N>(x);
  ContactPointJacobian<T, N> point;
  for (BodyJacobian<T, N>* j : {&point.a, &point.b}) {
    j->center.setConstant(x);
    j->orientation.setConstant(x);
    j->radii.setConstant(x);
  }
  point.velocity_a.setConstant(x);
  point.velocity_b.setConstant(x);
  point.angular_velocity_a.setConstant(x);
  point.angular_velocity_b.setConstant(x);
  return {value, g, g, Vec<T, N>::Constant(x), Vec<T, N>::Constant(x), g.orientation, g.orientation, point};
}

// exp(-theta [u]x) v for the rotation vector theta = theta u: v turned back by theta.
template <class R, int N>
RotationVector<R, N> turned_back(const RotationVector<R, N>& theta, const RotationVector<R, N>& v) noexcept {
  if constexpr (N == 2) {
    return v;
  } else {
    const R angle = theta.norm();
    if (!(angle > R(0))) return v;
    const Vec<R, 3> u = theta / angle;
    return Vec<R, 3>(v * cos(angle) - sin(angle) * u.cross(v) + (R(1) - cos(angle)) * u.dot(v) * u);
  }
}

// J(theta)^T v, J the left Jacobian of the rotation group: exp([theta + d]x) =
// exp([J(theta) d]x) exp([theta]x) to first order in d, and
// J^T = I - (1 - cos|theta|) / |theta|^2 [theta]x + (|theta| - sin|theta|) / |theta|^3 [theta]x^2
// (series below |theta| = 1e-4, where the closed forms cancel).
template <class R, int N>
RotationVector<R, N> jacobian_transposed(const RotationVector<R, N>& theta, const RotationVector<R, N>& v) noexcept {
  if constexpr (N == 2) {
    return v;
  } else {
    const R angle = theta.norm(), a2 = angle * angle;
    R c1, c2;  // (1 - cos) / angle^2, (angle - sin) / angle^3
    if (angle < R(1e-4)) {
      c1 = R(0.5) - a2 / R(24);
      c2 = R(1) / R(6) - a2 / R(120);
    } else {
      c1 = (R(1) - cos(angle)) / a2;
      c2 = (angle - sin(angle)) / (a2 * angle);
    }
    const Vec<R, 3> tv = theta.cross(v);
    return Vec<R, 3>(v - c1 * tv + c2 * theta.cross(tv));
  }
}

// exp([theta]x) and the left Jacobian J(theta) of the rotation group as matrices (2D: 1).
template <class R, int N>
TurnJacobian<R, N> turn_columns(const RotationVector<R, N>& theta, bool jacobian) {
  if constexpr (N == 2) {
    return TurnJacobian<R, 2>::Zero();  // unused: a 2D turn is its own angle
  } else {
    Mat<R, 3> m;  // row j of the matrix is its transpose applied to e_j
    for (int j = 0; j < 3; ++j) {
      const Vec<R, 3> e = Vec<R, 3>::Unit(j);
      m.row(j) = (jacobian ? jacobian_transposed<R, 3>(theta, e) : turned_back<R, 3>(theta, e)).transpose();
    }
    return m;
  }
}

// S = L L^T for a symmetric positive definite S (N <= 3; backward stable without pivoting),
// and S^-1 b by substitution (b one column or several). A matrix that is not positive
// definite in rounding gives NaN.
template <class R, int N>
struct Cholesky {
  Eigen::Matrix<R, N, N> l = Eigen::Matrix<R, N, N>::Zero();
  explicit Cholesky(const Eigen::Matrix<R, N, N>& s) noexcept {
    for (int j = 0; j < N; ++j) {
      R d = s(j, j);
      for (int k = 0; k < j; ++k) d -= l(j, k) * l(j, k);
      l(j, j) = sqrt(d);
      for (int i = j + 1; i < N; ++i) {
        R x = s(i, j);
        for (int k = 0; k < j; ++k) x -= l(i, k) * l(j, k);
        l(i, j) = x / l(j, j);
      }
    }
  }
  // Every column of b (N rows) at once.
  template <class B>
  B solve(B b) const noexcept {
    for (int i = 0; i < N; ++i) {
      for (int k = 0; k < i; ++k) b.row(i) -= l(i, k) * b.row(k);
      b.row(i) /= l(i, i);
    }
    for (int i = N - 1; i >= 0; --i) {
      for (int k = i + 1; k < N; ++k) b.row(i) -= l(k, i) * b.row(k);
      b.row(i) /= l(i, i);
    }
    return b;
  }
};

// The derivatives of a hit's time t and point x (contact.hpp's first_contact_gradient) from
// the bodies' shapes at t (a_t, b_t; their centers are not read), the offset c_b - c_a at
// time 0, the normal there and the motions; NaN where the closing speed is not > 0.
template <class T, int N, class R>
void contact_time_gradient(ContactGradient<T, N>& out, const Ellipsoid<T, N>& a_t, const Ellipsoid<T, N>& b_t,
                           const Vec<R, N>& offset, const Vec<R, N>& velocity_a, const Vec<R, N>& velocity_b,
                           const RotationVector<R, N>& omega_a, const RotationVector<R, N>& omega_b) noexcept {
  constexpr int K = N == 2 ? 1 : 3;
  using Turn = Eigen::Matrix<R, K, 1>;
  const R t = R(out.value.time);
  // The normal polished by one Newton step on the support gap's maximum at t, whose gradient
  // on the sphere is the tangential part of r - p_a - p_b and whose Hessian there is
  // -(H_a + H_b) (the gap is 0): the point's derivatives see its rounding times H.
  const Vec<R, N> r = offset + t * (velocity_b - velocity_a);
  Vec<R, N> n = out.value.normal.template cast<R>();
  {
    const HitSide<R, N> sa(a_t, n), sb(b_t, n);
    Vec<R, N> residual = r - sa.p - sb.p;
    residual -= n * n.dot(residual);
    n += Cholesky<R, N>(sa.h + sb.h + (sa.rho + sb.rho) * n * n.transpose()).solve(residual);
    n /= stable_norm<R, N>(n);
  }
  const HitSide<R, N> sa(a_t, n), sb(b_t, n);
  auto column_of = [](const RotationVector<R, N>& w) {
    if constexpr (N == 2) {
      return Turn::Constant(w);
    } else {
      return Turn(w);
    }
  };
  const Turn wa = column_of(omega_a), wb = column_of(omega_b);
  // g = n . (c_b - c_a) - rho_a - rho_b; d rho_X = n . dp_X at fixed n (a turn u changes
  // rho_X by (p_X x n) . u = n . (C_X u)). The offsets' rates at fixed n as the bodies turn:
  // C_X omega_X.
  const Vec<R, N> rate_a = sa.turn * wa, rate_b = sb.turn * wb;
  const R closing = n.dot(velocity_a - velocity_b) + n.dot(rate_a) + n.dot(rate_b);
  if (!(closing > R(0))) return;
  // The world turn at t of a turn of the orientation at time 0 (exp(t [omega]x)), and of the
  // angular velocity (t J(t omega)).
  auto turns = [&](const Turn& w, bool jacobian) -> Eigen::Matrix<R, K, K> {
    if constexpr (N == 2) {
      return Eigen::Matrix<R, 1, 1>::Constant(jacobian ? t : R(1));
    } else {
      if (w.isZero(0)) return Mat<R, 3>::Identity() * (jacobian ? t : R(1));
      const TurnJacobian<R, 3> m = turn_columns<R, 3>(Vec<R, 3>(w * t), jacobian);
      return jacobian ? Mat<R, 3>(m * t) : Mat<R, 3>(m);
    }
  };
  // (H_a + H_b) on the tangent plane.
  const Cholesky<R, N> solve(sa.h + sb.h + (sa.rho + sb.rho) * n * n.transpose());
  // The parameters solved for, P per body: its center, its radii and the K world turns of its
  // orientation at t. Each column holds a parameter's explicit change of c_b - c_a - p_a - p_b
  // (e) and of the point c_a + p_a (own); then dt = n . e / closing (d g = 0 along the
  // motion), dn = (H_a + H_b)^-1 P_n (e + (dv - rate_a - rate_b) dt) on the tangent plane and
  // dx = own + (v_a + rate_a) dt + H_a dn, all columns at once. The other parameters follow
  // linearly: a velocity's derivatives are t times its center's (its change of c_X at t is t
  // times theirs), the orientation's and the angular velocity's are the turns' combined by
  // the turns they make at t.
  constexpr int P = 2 * N + K, M = 2 * P;
  Eigen::Matrix<R, N, M> e, own = Eigen::Matrix<R, N, M>::Zero();
  for (int body = 0; body < 2; ++body) {
    const HitSide<R, N>& side = body == 0 ? sa : sb;
    const int at = body * P;
    for (int j = 0; j < N; ++j) {
      e.col(at + j) = Vec<R, N>::Unit(j) * (body == 0 ? R(-1) : R(1));
      e.col(at + N + j) = -side.by_radius(j);
    }
    for (int i = 0; i < K; ++i) e.col(at + 2 * N + i) = -side.turn.col(i);
  }
  own.template leftCols<N>().setIdentity();
  own.template middleCols<N + K>(N) = -e.template middleCols<N + K>(N);
  const Eigen::Matrix<R, 1, M> dt = (n.transpose() * e) / closing;
  Eigen::Matrix<R, N, M> rhs = e + (velocity_b - velocity_a - rate_a - rate_b) * dt;
  rhs -= n * (n.transpose() * rhs);
  const Eigen::Matrix<R, N, M> dx = own + (velocity_a + rate_a) * dt + sa.h * solve.solve(rhs);
  auto body = [&](int at, const Turn& w, BodyGradient<T, N>& g, Vec<T, N>& velocity,
                  RotationVector<T, N>& angular_velocity, BodyJacobian<T, N>& jg, Mat<T, N>& jv,
                  TurnJacobian<T, N>& jw) {
    for (int j = 0; j < N; ++j) {
      g.center[j] = T(dt[at + j]);
      velocity[j] = T(t * dt[at + j]);
      g.radii[j] = T(dt[at + N + j]);
    }
    jg.center = dx.template middleCols<N>(at).template cast<T>();
    jv = (t * dx.template middleCols<N>(at)).template cast<T>();
    jg.radii = dx.template middleCols<N>(at + N).template cast<T>();
    const Eigen::Matrix<R, K, K> orient = turns(w, false), spin = turns(w, true);
    const Eigen::Matrix<R, 1, K> dt_turn = dt.template middleCols<K>(at + 2 * N);
    const Eigen::Matrix<R, N, K> dx_turn = dx.template middleCols<K>(at + 2 * N);
    const Turn go = (dt_turn * orient).transpose(), gw = (dt_turn * spin).transpose();
    jg.orientation = (dx_turn * orient).template cast<T>();
    jw = (dx_turn * spin).template cast<T>();
    if constexpr (N == 2) {
      g.orientation = T(go[0]);
      angular_velocity = T(gw[0]);
    } else {
      g.orientation = go.template cast<T>();
      angular_velocity = gw.template cast<T>();
    }
  };
  body(0, wa, out.a, out.velocity_a, out.angular_velocity_a, out.point.a, out.point.velocity_a,
       out.point.angular_velocity_a);
  body(P, wb, out.b, out.velocity_b, out.angular_velocity_b, out.point.b, out.point.velocity_b,
       out.point.angular_velocity_b);
}

}  // namespace ellipsect::detail
