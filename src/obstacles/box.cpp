#include <ellipsect/box.hpp>
#include <ellipsect/half_space.hpp>

#include "detail/at_body.hpp"
#include "detail/contact_start.hpp"
#include "detail/gradient.hpp"
#include "detail/instantiate.hpp"
#include "detail/polytope_distance.hpp"
#include "detail/math.hpp"
#include "detail/obstacle_motion.hpp"
#include "detail/validate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>

namespace ellipsect {

template <class T, int N>
Box<T, N> Box<T, N>::from_axes(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& half_extents) {
  try {
    return Box(Ellipsoid<T, N>::from_axes(center, axes, half_extents));
  } catch (const InputError& e) {
    // The body's checks name its radii: here they are the half extents.
    std::string field = e.field();
    if (field.starts_with("radii")) field.replace(0, 5, "half_extents");
    const std::string prefix = "ellipsect: " + e.field() + ": ";
    const std::string what = e.what();
    throw InputError(field, what.starts_with(prefix) ? what.substr(prefix.size()) : what);
  }
}

template <class T, int N>
Vec<T, N> Box<T, N>::corner(int k) const noexcept {
  Vec<T, N> x = center();
  for (int i = 0; i < N; ++i) x += ((k >> i) & 1 ? T(1) : T(-1)) * half_extents()[i] * axes().col(i);
  return x;
}

// The box as a polytope (detail/polytope_distance.hpp): its 2^N corners (corner k at +h_i
// where bit i of k is set), the edges between corners differing in one bit, and (3D) the
// faces, three corners each with bit i fixed.
template <class T, int N>
struct detail::PolytopeTraits<Box<T, N>> {
  static constexpr int count = 1 << N;
  static std::array<Vec<T, N>, count> vertices(const Box<T, N>& b) noexcept {
    std::array<Vec<T, N>, count> out;
    for (int k = 0; k < count; ++k) out[std::size_t(k)] = b.corner(k);
    return out;
  }
  static constexpr auto edges = [] {
    std::array<std::array<int, 2>, N * count / 2> e{};
    std::size_t n = 0;
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < count; ++k)
        if (!((k >> i) & 1)) e[n++] = {k, k | (1 << i)};
    return e;
  }();
  static constexpr auto faces = [] {
    std::array<std::array<int, 3>, N == 3 ? 2 * N : 0> f{};
    if constexpr (N == 3)
      for (int i = 0; i < N; ++i)
        for (int side = 0; side < 2; ++side) {
          const int base = side << i;
          f[std::size_t(2 * i + side)] = {base, base | (1 << ((i + 1) % N)), base | (1 << ((i + 2) % N))};
        }
    return f;
  }();
};

template <class T, int N>
std::array<Triangle<T, N>, N == 2 ? 2 : 12> Box<T, N>::triangles() const noexcept {
  const auto corners = detail::PolytopeTraits<Box<T, N>>::vertices(*this);  // each computed once, shared by its triangles
  const auto tri = [&](int p, int q, int r) { return make_triangle<T, N>(corners[p], corners[q], corners[r]); };
  if constexpr (N == 2) {
    return {tri(0, 1, 3), tri(0, 3, 2)};
  } else {
    // Each face: the corners with bit i fixed, split along a diagonal.
    std::array<Triangle<T, N>, 12> out;
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      for (const int side : {0, 1}) {
        const int base = side << i;
        const int p = base, q = base | (1 << j), r = base | (1 << j) | (1 << k), s = base | (1 << k);
        out[n++] = tri(p, q, r);
        out[n++] = tri(p, r, s);
      }
    }
    return out;
  }
}

namespace {

// The relation from the triangles' (box.hpp, "Math"), and the index of the triangle that
// decides touching or overlapping (-1 when none does: containment or the center inside).
template <class T, int N, class Triangles>
std::pair<Relation, int> relation_of(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Triangles& triangles,
                                     const Options& options) {
  int contained = 0, overlapping = -1, touching = -1;
  for (int k = 0; k < int(triangles.size()); ++k) {
    const Relation r = classify(a, triangles[std::size_t(k)], options);
    contained += r == Relation::a_contains_b;
    if ((r == Relation::overlapping || r == Relation::a_contains_b) && overlapping < 0) overlapping = k;
    if (r == Relation::touching && touching < 0) touching = k;
  }
  if (contained == int(triangles.size())) return {Relation::a_contains_b, -1};
  bool center_inside = true;
  const Vec<T, N> local = b.axes().transpose() * Vec<T, N>(a.center() - b.center());
  for (int i = 0; i < N; ++i) center_inside = center_inside && abs(local[i]) <= b.half_extents()[i];
  if (overlapping < 0 && !center_inside) return {touching < 0 ? Relation::separated : Relation::touching, touching};
  // The body meets the box: inside it when inside each face's half-space.
  for (int i = 0; i < N; ++i)
    for (const T side : {T(-1), T(1)}) {
      const Vec<T, N> normal = side * b.axes().col(i);
      const Vec<T, N> point = b.center() + b.half_extents()[i] * normal;
      if (classify(a, make_half_space<T, N>(point, normal), options) != Relation::b_contains_a)
        return {Relation::overlapping, overlapping};
    }
  return {Relation::b_contains_a, -1};
}

// The features that can hold the box's point nearest the body where the two are apart
// (detail::Near), from two necessary conditions on that point p, in the box's frame (body
// center c, support radii rho_i = |diag(r) A^T u_i| along the box's axes u_i, half extents h):
//   slabs      p lies within D of the body (D the distance), so |p_i - c_i| <= rho_i + D <=
//              rho_i + U for every i, where U >= D is the distance from the box's point q
//              nearest c to where the segment from c to q leaves the body;
//   sides      along an axis where the body's slab c_i +- rho_i lies wholly beyond the box's,
//              every direction from the body to the box, so the normal at the nearest points,
//              has that side's sign: the feature lies on the face on the body's side.
// A feature is a set of corners: along each axis fixed at one side, or spanning both. 1e-9
// of the lengths is left for rounding, and 16 ulps of T of the corners' magnitude for the
// corners as computed in T.
template <class T, int N, std::size_t E, std::size_t F>
detail::Near near_features(const Ellipsoid<T, N>& a, const Box<T, N>& b, const std::array<std::array<int, 2>, E>& edges,
                           const std::array<std::array<int, 3>, F>& faces) noexcept {
  using W = std::conditional_t<(sizeof(T) < sizeof(double)), double, T>;
  const Mat<W, N> box = b.axes().template cast<W>(), body = a.axes().template cast<W>();
  const Vec<W, N> h = b.half_extents().template cast<W>(), r = a.radii().template cast<W>();
  const Vec<W, N> c = box.transpose() * (a.center().template cast<W>() - b.center().template cast<W>());
  const Vec<W, N> to_box = c.cwiseMax(-h).cwiseMin(h) - c;
  const W exit = 1 / r.cwiseInverse().cwiseProduct(body.transpose() * (box * to_box)).norm();
  const W reach = std::max(W(0), (1 - exit) * to_box.norm());
  const W corners = W(16) * W(std::numeric_limits<T>::epsilon()) * (W(detail::max_abs(b.center())) + h.norm());
  // allowed[i]: bit 0 the side -h_i, bit 1 the side +h_i, bit 2 spanning both.
  std::array<unsigned, N> allowed{};
  for (int i = 0; i < N; ++i) {
    const W rho = r.cwiseProduct(body.transpose() * box.col(i)).norm();
    const W margin = W(1e-9) * (abs(c[i]) + rho + reach + h[i]) + corners;
    const W lo = c[i] - rho - reach - margin, hi = c[i] + rho + reach + margin;
    if (!(lo <= hi)) return {};  // not finite: no certificate
    allowed[i] = unsigned(lo <= -h[i] && -h[i] <= hi) | unsigned(lo <= h[i] && h[i] <= hi) << 1 |
                 unsigned(lo <= h[i] && -h[i] <= hi) << 2;
    if (c[i] - rho > h[i] + margin) allowed[i] &= 2u;
    if (c[i] + rho < -h[i] - margin) allowed[i] &= 1u;
  }
  const auto near = [&](std::initializer_list<int> corners) {
    for (int i = 0; i < N; ++i) {
      unsigned bits = 0;
      for (const int k : corners) bits |= 1u << ((k >> i) & 1);
      if (!(allowed[i] & (bits == 3u ? 4u : bits))) return false;
    }
    return true;
  };
  detail::Near out{0, 0, 0};
  for (int k = 0; k < (1 << N); ++k) out.vertices |= std::uint32_t(near({k})) << k;
  for (std::size_t e = 0; e < E; ++e) out.edges |= std::uint32_t(near({edges[e][0], edges[e][1]})) << e;
  for (std::size_t f = 0; f < F; ++f) out.faces |= std::uint32_t(near({faces[f][0], faces[f][1], faces[f][2]})) << f;
  return out;
}

// The body in the box's frame: center c, half extents h, radii r, the body's support radii
// along the box's axes rho_i = |diag(r) A^T u_i|, and the status band (detail::status_band)
// of the pair; W is double for float, else T.
template <class T, int N>
struct InBoxFrame {
  using W = std::conditional_t<(sizeof(T) < sizeof(double)), double, T>;
  Mat<W, N> to_body;  // box frame -> body frame
  Vec<W, N> c, h, r, rho;
  W band;

  InBoxFrame(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
    const Mat<W, N> box = b.axes().template cast<W>();
    to_body = a.axes().template cast<W>().transpose() * box;
    h = b.half_extents().template cast<W>();
    r = a.radii().template cast<W>();
    c = box.transpose() * (a.center().template cast<W>() - b.center().template cast<W>());
    for (int i = 0; i < N; ++i) rho[i] = r.cwiseProduct(to_body.col(i)).norm();
    band = detail::status_band<T>(options, r.maxCoeff(), c.norm() + h.norm(),
                                  W(detail::max_abs(a.center())) + W(detail::max_abs(b.center())) + h.norm());
  }
  bool finite() const noexcept { return band < std::numeric_limits<W>::infinity(); }
};

// What the box's frame alone settles (about 50 ns, no triangles), with q the box's point
// nearest c:
//   separated    a slab of the box along one of its axes, or the plane through q across
//                q - c (it supports the box), keeps the body off by more than the band, so
//                classify says separated;
//   overlapping  c inside the box by more than the band, or q inside the body scaled by
//                1 - band / R about its center;
//   unsettled    otherwise (within the band of tangency, or not finite).
enum class Settled { separated, overlapping, unsettled };

template <class T, int N>
Settled settled_relation(const InBoxFrame<T, N>& f) noexcept {
  using W = typename InBoxFrame<T, N>::W;
  if (!f.finite()) return Settled::unsettled;
  if ((f.h - f.c.cwiseAbs()).minCoeff() > f.band) return Settled::overlapping;
  const Vec<W, N> to_q = f.c.cwiseMax(-f.h).cwiseMin(f.h) - f.c;
  const Vec<W, N> in_body = f.to_body * to_q;
  if (in_body.cwiseQuotient(f.r).norm() < 1 - f.band / f.r.maxCoeff()) return Settled::overlapping;
  for (int i = 0; i < N; ++i)
    if (abs(f.c[i]) - f.h[i] - f.rho[i] > f.band) return Settled::separated;
  const W gap = to_q.norm();  // > 0 here: c is outside the box
  if (gap - f.r.cwiseProduct(in_body).norm() / gap > f.band) return Settled::separated;
  return Settled::unsettled;
}

template <class T, int N>
Settled settled_relation(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
  return settled_relation(InBoxFrame<T, N>(a, b, options));
}

// The pair moved by minus the body's center (detail/at_body.hpp): the box's corners,
// computed in T, are rounded to ulps of the pair's extent (a box 1e6 sizes from the origin had
// corners 1e-10 of its size off, beyond the accuracy stated).
template <class T, int N>
struct BoxAtBody : detail::AtBody<T, N, Box<T, N>> {
  BoxAtBody(const Ellipsoid<T, N>& a_world, const Box<T, N>& b_world) noexcept
      : detail::AtBody<T, N, Box<T, N>>(a_world, b_world, b_world.center()) {}
};

template <class T, int N>
Relation classify_at_body(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
  if (settled_relation(a, b, options) == Settled::separated) return Relation::separated;
  return relation_of(a, b, b.triangles(), options).first;
}

}  // namespace

template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a_world, const Box<T, N>& b_world, const Options& options) noexcept {
  const BoxAtBody<T, N> p(a_world, b_world);
  return classify_at_body(p.a, p.b, options);
}

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a_world, const Box<T, N>& b_world, const Options& options) noexcept {
  const BoxAtBody<T, N> p(a_world, b_world);
  const Settled settled = settled_relation(p.a, p.b, options);
  if (settled != Settled::unsettled) return settled == Settled::overlapping;
  return relation_of(p.a, p.b, p.b.triangles(), options).first != Relation::separated;
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a_world, const VecArg<T, N>& velocity_a, const Box<T, N>& b_world,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  Contact<T, N> out = detail::unanswered_contact<T, N>();
  if (!detail::valid_motion<T, N>(velocity_a, velocity_b, t_max)) return out;
  const BoxAtBody<T, N> p(a_world, b_world);
  const Ellipsoid<T, N>& a = p.a;
  const Box<T, N>& b = p.b;
  const auto in_world = [&](Contact<T, N> c) {
    c.point += p.shift;  // NaN stays NaN
    return c;
  };
  const auto triangles = b.triangles();
  const InBoxFrame<T, N> frame(a, b, options);
  if (settled_relation(frame) != Settled::separated) {
    const auto [relation, triangle] = relation_of(a, b, triangles, options);
    if (relation == Relation::touching)
      return in_world(first_contact(a, velocity_a, triangles[std::size_t(triangle)], velocity_b, t_max, options));
    if (relation != Relation::separated) {
      out.status = ContactStatus::overlapping_at_start;
      out.time = T(0);
      return out;
    }
  }
  // Apart at the start, the body first meets the boundary at a point p where some outward
  // normal m of the box (a nonnegative sum of the normals of the faces through p) has
  // m . v <= 0, v = velocity_a - velocity_b (else the body would overlap the box just
  // before). A face through p whose normal has n . v > 0, or whose plane the body lay wholly
  // inside of at the start (it reached the plane by t, so n . v > 0 too), cannot be the
  // only ones: some other face through p is kept, and its triangles hold p. So in 3D the
  // triangles of such faces (beyond the rounding of the corners' cross product; by more
  // than the band) are skipped: most of the twelve. The argument needs the triangles to
  // bound a box: a box thinner along an axis than 64 ulps of its corners' magnitude has
  // corners, as computed in T, whose faces cross (a float plate 3e-6 thick at 16 from the
  // origin: a big face's triangle met the body before the rim the skipping kept), so all
  // twelve are tested there.
  const Vec<T, N> v = velocity_a - velocity_b;
  using W = typename InBoxFrame<T, N>::W;
  const W corners = W(64) * W(std::numeric_limits<T>::epsilon()) * (W(detail::max_abs(b.center())) + frame.h.norm());
  const bool skip_faces = frame.finite() && frame.h.minCoeff() > corners;
  const auto skipped = [&](std::size_t k) {
    if constexpr (N == 3) {
      if (!skip_faces) return false;
      const Triangle<T, N>& t = triangles[k];
      const int axis = int(k) / 4;  // Box::triangles: face (axis, side) holds triangles 4 axis + 2 side + {0, 1}
      const W side = int(k) / 2 % 2 ? 1 : -1;
      if (side * frame.c[axis] + frame.rho[axis] < frame.h[axis] - frame.band) return true;
      const Vec<T, N> e1 = t.vertex(1) - t.vertex(0), e2 = t.vertex(2) - t.vertex(0);
      Vec<T, N> n = e1.cross(e2);
      if (n.dot(t.vertex(0) - b.center()) < T(0)) n = -n;
      return n.dot(v) > T(64) * std::numeric_limits<T>::epsilon() * e1.norm() * e2.norm() * v.norm();
    } else {
      return false;
    }
  };
  out.status = ContactStatus::no_contact_in_window;
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    if (skipped(k)) continue;
    const Triangle<T, N>& t = triangles[k];
    const Contact<T, N> c = first_contact(a, velocity_a, t, velocity_b, t_max, options);
    if (c.status == ContactStatus::hit && !(c.time >= out.time)) out = c;
  }
  return in_world(out);
}

template <class T, int N>
Distance<T, N> signed_distance(const Ellipsoid<T, N>& a_world, const Box<T, N>& b_world, const Options& options) noexcept {
  const BoxAtBody<T, N> p(a_world, b_world);
  const Ellipsoid<T, N>& a = p.a;
  const Box<T, N>& b = p.b;
  using P = detail::PolytopeTraits<Box<T, N>>;
  Distance<T, N> out = detail::polytope_signed_distance<T, N>(
      a, b, options, [&] { return classify_at_body(a, b, options); }, near_features(a, b, P::edges, P::faces));
  out.point_a += p.shift;
  out.point_b += p.shift;
  return out;
}

template <class T, int N>
Distance<T, N> distance(const Ellipsoid<T, N>& a, const Box<T, N>& b, const Options& options) noexcept {
  return detail::unsigned_distance(signed_distance(a, b, options));
}

template <class T, int N>
DistanceGradient<T, N, BoxGradient<T, N>> signed_distance_gradient(const Ellipsoid<T, N>& a, const Box<T, N>& b,
                                                                   const Options& options) noexcept {
  // The touching point y = p + d n (less a's center) less the box's center, in the box's
  // frame, on the box.
  const auto local = [&](const auto& n, const auto& p, auto d) {
    using R = decltype(d);
    const Vec<R, N> y = p + d * n;
    const Vec<R, N> e = b.half_extents().template cast<R>();
    return Vec<R, N>((b.axes().template cast<R>().transpose() *
                      (y + (a.center().template cast<R>() - b.center().template cast<R>())))
                         .cwiseMax(-e)
                         .cwiseMin(e));
  };
  // The faces the touching point lies on (within 1e-9 of the extent; their inward normals, the
  // directions from the body to the box there), and the edge where it lies
  // inside the box's range along one axis only (`free`), in double length from the box's
  // center, half extents and axes: the first end center - c + sum over the others of
  // +-e_i a_i - e_free a_free, the edge 2 e_free a_free (polish_normal keeps n where the
  // maximum is not inside that edge's stratum).
  const auto stratum = [&](const auto& n, const auto& p, auto d, auto& out) {
    if constexpr (N == 3) {
      using R = decltype(d);
      const Vec<R, 3> u = local(n, p, d);
      int free = -1;
      for (int i = 0; i < 3; ++i) {
        if (abs(u[i]) < R(b.half_extents()[i]) * R(1 - 1e-9)) {
          free = free == -1 ? i : 3;
          continue;
        }
        out.faces[out.face_count++] = (u[i] > 0 ? R(-1) : R(1)) * b.axes().col(i).template cast<R>();
      }
      if (free < 0 || free > 2) return;
      out.edge = true;
      out.sides[0] = out.faces[0];
      out.sides[1] = out.faces[1];
      out.side_count = 2;
      for (int j = 0; j < 3; ++j) {
        detail::Double<R> q = detail::two_sum(R(b.center()[j]), -R(a.center()[j]));
        for (int i = 0; i < 3; ++i) {
          const R side = i == free ? R(-1) : u[i] > 0 ? R(1) : R(-1);
          q = q + detail::two_product(side * R(b.half_extents()[i]), R(b.axes()(j, i)));
        }
        out.q[j] = q;
        out.e[j] = detail::two_product(R(2) * R(b.half_extents()[free]), R(b.axes()(j, free)));
      }
    }
  };
  return detail::shape_distance_gradient<T, N, BoxGradient<T, N>>(
      a, signed_distance(a, b, options), stratum, [&](const auto& n, const auto& p, auto d) {
        using R = decltype(d);
        const Mat<R, N> axes = b.axes().template cast<R>();
        const Vec<R, N> e = b.half_extents().template cast<R>();
        const Vec<R, N> u = local(n, p, d);
        BoxGradient<T, N> out;
        out.center = n.template cast<T>();
        out.orientation = detail::rotation_in<T, R, N>(detail::turn_rate<R, N>(Vec<R, N>(axes * u), n));
        out.half_extents = u.cwiseQuotient(e).cwiseProduct(axes.transpose() * n).template cast<T>();
        return out;
      });
}

// ---- Rigid motion (detail/obstacle_motion.hpp) --------------------------------------------

namespace detail::obstacle {
template <class T, int N>
struct ObstacleTraits<Box<T, N>> : PolytopeObstacle<T, N, Box<T, N>> {
  static std::optional<Vec<R, N>> inner_point(const Box<T, N>& b) noexcept {
    return Vec<R, N>(b.center().template cast<R>());
  }
};
}  // namespace detail::obstacle

ELLIPSECT_RIGID_OBSTACLE_CONTACT(Box)

// ---- The factories -----------------------------------------------------------------------

// The box's frame is a body's, whose translated() names its center: here the argument is the
// offset.
template <class T, int N>
Box<T, N> Box<T, N>::translated(const Vec<T, N>& offset) const {
  return Box(detail::ShapeAccess::unchecked<T, N>(detail::moved<T, N>(center(), offset, "the center"), axes(),
                                                  half_extents()));
}

#define ELLIPSECT_INSTANTIATE(T, N) ELLIPSECT_INSTANTIATE_OBSTACLE(Box, BoxGradient, T, N)
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
