#include <ellipsect/slide.hpp>

#include "detail/instantiate.hpp"
#include "detail/mesh_walk.hpp"
#include "detail/scale.hpp"
#include "detail/shape_access.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace ellipsect {

std::string_view to_string(SlideStatus s) noexcept {
  switch (s) {
    case SlideStatus::moved: return "moved";
    case SlideStatus::slid: return "slid";
    case SlideStatus::blocked: return "blocked";
    case SlideStatus::overlapping_at_start: return "overlapping_at_start";
    case SlideStatus::invalid_input: return "invalid_input";
  }
  return "unknown";
}

namespace {

template <class T, int N>
Ellipsoid<T, N> at(const Ellipsoid<T, N>& body, const Vec<T, N>& center) noexcept {
  return detail::ShapeAccess::unchecked<T, N>(center, body.axes(), body.radii());
}

// The obstacles of a world in the frame whose origin is `origin` (the obstacles moved by
// -origin): near(body, visit) calls visit(k, obstacle) for every obstacle that may touch the
// body, swept(body, r, visit) for every one it may meet moving by t r, t in [0, 1]; at(k) is
// obstacle k.
template <class T, int N>
struct HalfSpaces {
  std::vector<HalfSpace<T, N>> world;
  const HalfSpace<T, N>& at(std::size_t k) const { return world[k]; }
  template <class Visit>
  void near(const Ellipsoid<T, N>&, Visit&& visit) const {
    for (std::size_t k = 0; k < world.size(); ++k) visit(k, world[k]);
  }
  template <class Visit>
  void swept(const Ellipsoid<T, N>&, const Vec<T, N>&, Visit&& visit) const {
    for (std::size_t k = 0; k < world.size(); ++k) visit(k, world[k]);
  }
  HalfSpaces(std::span<const HalfSpace<T, N>> given, const Vec<T, N>& origin) {
    world.reserve(given.size());
    for (const auto& h : given) world.push_back(origin.isZero() ? h : h.translated(Vec<T, N>(-origin)));
  }
};

template <class T, int N>
struct Mesh {
  using W = detail::Work<T>;
  const TriangleMesh<T, N>& mesh;
  double tolerance;
  Vec<T, N> origin;
  Triangle<T, N> at(std::size_t k) const {
    return origin.isZero() ? mesh.triangle(k) : mesh.triangle(k).translated(Vec<T, N>(-origin));
  }
  // The hierarchy is in world coordinates: the body's center there, and its half-extents
  // grown by that center's rounding.
  Vec<W, N> center(const Ellipsoid<T, N>& body) const {
    return body.center().template cast<W>() + origin.template cast<W>();
  }
  Vec<W, N> extents(const Ellipsoid<T, N>& body, const Vec<W, N>& c) const {
    return detail::half_extents(body, tolerance).array() + W(2) * std::numeric_limits<W>::epsilon() * c.cwiseAbs().maxCoeff();
  }
  template <class Visit>
  void near(const Ellipsoid<T, N>& body, Visit&& visit) const {
    const Vec<W, N> c = center(body);
    detail::for_each_near<T, N>(mesh, c, extents(body, c), [&](std::uint32_t k) { visit(k, at(k)); });
  }
  template <class Visit>
  void swept(const Ellipsoid<T, N>& body, const Vec<T, N>& r, Visit&& visit) const {
    const Vec<W, N> c = center(body);
    detail::for_each_swept<T, N>(mesh, c, r.template cast<W>(), extents(body, c), W(1), [&](std::uint32_t k, W t_end) {
      visit(k, at(k));
      return t_end;
    });
  }
};

// Overlapping an obstacle, or containing or contained in it.
bool inside(Relation r) noexcept {
  return r != Relation::separated && r != Relation::touching;
}

template <class T, int N, class World>
bool inside_any(const Ellipsoid<T, N>& body, const World& world, const Options& options) {
  bool found = false;
  world.near(body, [&](std::size_t, const auto& obstacle) { found = found || inside(classify(body, obstacle, options)); });
  return found;
}

// The obstacle's side facing the body at their contact: minus the body's outward normal
// there (for a half-space, its outward normal).
template <class T, int N>
Vec<T, N> facing(const Contact<T, N>& c) noexcept {
  return -c.normal;
}

// Whether moving by t r, t in [0, 1], takes the body into the obstacle deeper than half the
// tangency band: whether the body shrunk about its center by that much meets it (or
// already does). A touch that does not (a vertex or an edge flush with the floor the body
// slides on, whose tangent plane the band tilts by up to the square root of the band over
// the curvature) is a graze: it neither stops nor turns the move, which stays touching.
template <class T, int N, class Obstacle>
bool enters(const Ellipsoid<T, N>& body, const Vec<T, N>& r, const Obstacle& obstacle, const Options& options) {
  const Ellipsoid<T, N> core = detail::ShapeAccess::unchecked<T, N>(
      body.center(), body.axes(), Vec<T, N>(body.radii() * T(1 - options.tolerance / 2)));
  return first_contact(core, r, obstacle, Vec<T, N>::Zero(), T(1), options).status !=
         ContactStatus::no_contact_in_window;
}

// An obstacle touched, with its normal facing the body.
template <class T, int N>
struct Touch {
  std::size_t obstacle;
  Vec<T, N> normal;
};

// r without what pushes into the touched obstacles (unit normals facing the body; a push
// that does not enter the obstacle, above, is none): projected onto one plane, onto two
// planes' common line (3D), or to nothing (slide.hpp). Normals within 1e-12 of each other
// are one plane (several triangles touched at one point).
template <class T, int N, class Enters>
Vec<T, N> project(Vec<T, N> r, const std::vector<Touch<T, N>>& touched, Enters&& enters) {
  std::vector<Vec<T, N>> active;
  const auto same = [](const Vec<T, N>& x, const Vec<T, N>& y) { return (x - y).norm() <= T(1e-12); };
  for (int round = 0; round <= N; ++round) {
    const Vec<T, N>* push = nullptr;
    for (const auto& touch : touched)
      if (r.dot(touch.normal) < T(0) &&
          std::none_of(active.begin(), active.end(), [&](const Vec<T, N>& m) { return same(m, touch.normal); }) &&
          enters(touch.obstacle, r)) {
        push = &touch.normal;
        break;
      }
    if (push == nullptr) return r;
    active.push_back(*push);
    if (active.size() == 1) {
      r -= r.dot(*push) * *push;
    } else if constexpr (N == 3) {
      if (active.size() > 2) return Vec<T, N>::Zero();
      const Vec<T, 3> line = active[0].cross(active[1]);
      const T length = line.norm();
      if (!(length > T(0))) return Vec<T, N>::Zero();
      r = r.dot(line / length) * (line / length);
    } else {
      return Vec<T, N>::Zero();
    }
  }
  return Vec<T, N>::Zero();
}

template <class T, int N, class World>
Slide<T, N> slide_through(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement, const World& world,
                          const Options& options) {
  Slide<T, N> out;
  out.body = body;
  if (inside_any(body, world, options)) {
    out.status = SlideStatus::overlapping_at_start;
    return out;
  }
  const Vec<T, N> still = Vec<T, N>::Zero();
  Vec<T, N> r = displacement, center = body.center();
  // The obstacles hit by the previous round's move, with their normals facing the body.
  std::vector<std::pair<std::size_t, Vec<T, N>>> hit_last;
  bool constrained = false;  // a touched obstacle took some of the displacement
  for (int round = 0; round < options.max_slide_rounds; ++round) {
    const Ellipsoid<T, N> now = at(body, center);
    // Touched: within the tangency band, or just hit (a move shortened by its rounding can
    // stop short of the band).
    std::vector<Touch<T, N>> touched;
    for (const auto& hit : hit_last) touched.push_back({hit.first, hit.second});
    world.near(now, [&](std::size_t k, const auto& obstacle) {
      const Contact<T, N> c = first_contact(now, still, obstacle, still, T(0), options);
      if (c.status == ContactStatus::touching_at_start) touched.push_back({k, facing(c)});
    });
    const Vec<T, N> free = project<T, N>(
        r, touched, [&](std::size_t k, const Vec<T, N>& along) { return enters(now, along, world.at(k), options); });
    constrained |= free != r;
    r = free;
    if (r == Vec<T, N>::Zero()) break;
    // The earliest contact along r in [0, 1] (ties: every obstacle hit then).
    T first = T(1);
    hit_last.clear();
    // A graze (r within 1e-9 of the contact's tangent plane, or a touch that does not enter
    // the obstacle: a seam between coplanar triangles slid across) does not stop the move;
    // were it to end inside, the check below shortens it.
    const T grazing = T(1e-9) * r.norm();
    world.swept(now, r, [&](std::size_t k, const auto& obstacle) {
      const Contact<T, N> c = first_contact(now, r, obstacle, still, T(1), options);
      if (c.status != ContactStatus::hit || c.time > first || !(r.dot(facing(c)) < -grazing) ||
          !enters(now, r, obstacle, options))
        return;
      if (c.time < first) hit_last.clear();
      first = c.time;
      hit_last.emplace_back(k, facing(c));
    });
    std::sort(hit_last.begin(), hit_last.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    // The move, shortened by 2^-52, 2^-51, ... of itself where its rounding ends inside.
    T t = first;
    Vec<T, N> next = center + t * r;
    for (int k = 0; inside_any(at(body, next), world, options); ++k) {
      t = k < std::numeric_limits<T>::digits ? first * (T(1) - ldexp(T(1), k - std::numeric_limits<T>::digits))
                                             : T(0);
      next = center + t * r;
      if (t == T(0)) break;
    }
    const bool shortened = t < first;
    if (hit_last.empty() && shortened) {
      // Nothing hit, but the rounded end of the move was inside: what it was inside of is
      // touched from here on, with the normal it is met with along r.
      const Ellipsoid<T, N> end = at(body, Vec<T, N>(center + first * r)), from = at(body, next);
      world.near(end, [&](std::size_t k, const auto& obstacle) {
        if (!inside(classify(end, obstacle, options))) return;
        const Contact<T, N> c =
            first_contact(from, r, obstacle, still, std::numeric_limits<T>::infinity(), options);
        if (c.status == ContactStatus::hit || c.status == ContactStatus::touching_at_start)
          hit_last.emplace_back(k, facing(c));
      });
    }
    out.moved += t * r;
    center = next;
    r *= T(1) - t;
    if (hit_last.empty()) {  // the whole remaining displacement, nothing hit
      r.setZero();
      break;
    }
    if (!shortened || first < T(1)) {
      ++out.contacts;
      out.last_contact = static_cast<int>(hit_last.front().first);
    }
  }
  out.body = at(body, center);
  out.status = r != Vec<T, N>::Zero()             ? SlideStatus::blocked
               : out.contacts > 0 || constrained ? SlideStatus::slid
                                                 : SlideStatus::moved;
  return out;
}

// The world as given (`given`, origin 0) and moved by minus the start body's center
// (`moved`): the slide runs in the body's frame, as the pair queries do, where its rounding is
// relative to the body's size and the tangency band is met; in world coordinates 1e6 sizes
// out, where each center rounds by 1e-10 of the size, beyond the band, the moves shortened for
// that rounding left the path up to 1.6e-7 of the displacement off, or blocked a body sliding
// along a floor and a wall. Only the end comes back: the body's center plus the slide's, and
// where that rounded end overlaps an obstacle (the exact end touches it within the band), it
// is moved off along the obstacles' normals (from the slide's frame, facing the body) by 1,
// 2, 4, ... units of the end's last bit; where no such step clears it (at most 64), the body is
// left at the start, blocked. float worlds stay as given: their moved vertices would round by
// float's last bit.
template <class T, int N, class World, class MakeWorld>
Slide<T, N> slide_in_body_frame(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement, const World& given,
                                MakeWorld&& make_world, bool movable, const Options& options) {
  Slide<T, N> out;
  out.body = body;
  if (!displacement.allFinite() || !Vec<T, N>(body.center() + displacement).allFinite()) return out;
  if (inside_any(body, given, options)) {
    out.status = SlideStatus::overlapping_at_start;
    return out;
  }
  if (sizeof(T) < sizeof(double) || !movable || body.center().isZero()) return slide_through(body, displacement, given, options);
  const Vec<T, N> origin = body.center();
  const World moved = make_world(origin);
  const Slide<T, N> s = slide_through(at<T, N>(body, Vec<T, N>::Zero()), displacement, moved, options);
  if (s.status == SlideStatus::overlapping_at_start || s.status == SlideStatus::invalid_input) return {s.status, body};
  out = s;
  const Vec<T, N> end = origin + s.body.center();
  out.body = at(body, end);
  if (!inside_any(out.body, given, options)) return out;
  // The obstacles within the end's rounding (and the band) of the slide's end.
  const T unit = std::numeric_limits<T>::epsilon() * detail::max_abs(end);
  const T reach = T(4 * N) * unit + T(double(options.tolerance)) * s.body.radii().maxCoeff();
  Vec<T, N> away = Vec<T, N>::Zero();
  moved.near(s.body, [&](std::size_t, const auto& obstacle) {
    const Distance<T, N> d = signed_distance(s.body, obstacle, options);
    if (d.normal.allFinite() && d.distance <= reach) away -= d.normal;
  });
  const T length = away.norm();
  if (length > T(0)) {
    away /= length;
    for (int k = 0; k < 64; ++k) {
      const Vec<T, N> step = away * ldexp(unit, k), nudged = end + step;
      if (!nudged.allFinite()) break;
      if (!inside_any(at(body, nudged), given, options)) {
        out.body = at(body, nudged);
        out.moved += step;
        return out;
      }
    }
  }
  return {SlideStatus::blocked, body, Vec<T, N>::Zero(), s.contacts, s.last_contact};
}

}  // namespace

template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              std::span<const std::type_identity_t<HalfSpace<T, N>>> world, const Options& options) {
  bool movable = true;
  for (const auto& h : world) movable = movable && Vec<T, N>(h.point() - body.center()).allFinite();
  return slide_in_body_frame(
      body, displacement, HalfSpaces<T, N>(world, Vec<T, N>::Zero()),
      [&](const Vec<T, N>& origin) { return HalfSpaces<T, N>(world, origin); }, movable, options);
}

template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              const TriangleMesh<T, N>& world, const Options& options) {
  // Every vertex lies in the root box: where its corners move within range, every vertex does.
  bool movable = true;
  if (!world.nodes().empty())
    for (int i = 0; i < N; ++i)
      movable = movable && isfinite(world.nodes()[0].lo[i] - body.center()[i]) &&
                isfinite(world.nodes()[0].hi[i] - body.center()[i]);
  return slide_in_body_frame(
      body, displacement, Mesh<T, N>{world, options.tolerance, Vec<T, N>::Zero()},
      [&](const Vec<T, N>& origin) { return Mesh<T, N>{world, options.tolerance, origin}; }, movable, options);
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                        \
  template Slide<T, N> collide_and_slide<T, N>(const Ellipsoid<T, N>&, const VecArg<T, N>&,              \
                                               std::span<const std::type_identity_t<HalfSpace<T, N>>>, \
                                               const Options&);                                          \
  template Slide<T, N> collide_and_slide<T, N>(const Ellipsoid<T, N>&, const VecArg<T, N>&,              \
                                               const TriangleMesh<T, N>&, const Options&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
