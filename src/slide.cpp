#include <ellipsect/slide.hpp>

#include "detail/instantiate.hpp"
#include "detail/mesh_walk.hpp"
#include "detail/shape_access.hpp"

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

// The obstacles of a world: near(body, visit) calls visit(k, obstacle) for every obstacle
// that may touch the body, swept(body, r, visit) for every one it may meet moving by t r,
// t in [0, 1]; at(k) is obstacle k.
template <class T, int N>
struct HalfSpaces {
  std::span<const HalfSpace<T, N>> world;
  const HalfSpace<T, N>& at(std::size_t k) const { return world[k]; }
  template <class Visit>
  void near(const Ellipsoid<T, N>&, Visit&& visit) const {
    for (std::size_t k = 0; k < world.size(); ++k) visit(k, world[k]);
  }
  template <class Visit>
  void swept(const Ellipsoid<T, N>&, const Vec<T, N>&, Visit&& visit) const {
    for (std::size_t k = 0; k < world.size(); ++k) visit(k, world[k]);
  }
};

template <class T, int N>
struct Mesh {
  const TriangleMesh<T, N>& mesh;
  double tolerance;
  Triangle<T, N> at(std::size_t k) const { return mesh.triangle(k); }
  template <class Visit>
  void near(const Ellipsoid<T, N>& body, Visit&& visit) const {
    detail::for_each_near<T, N>(mesh, body.center().template cast<detail::Work<T>>(),
                                detail::half_extents(body, tolerance),
                                [&](std::uint32_t k) { visit(k, mesh.triangle(k)); });
  }
  template <class Visit>
  void swept(const Ellipsoid<T, N>& body, const Vec<T, N>& r, Visit&& visit) const {
    using W = detail::Work<T>;
    detail::for_each_swept<T, N>(mesh, body.center().template cast<W>(), r.template cast<W>(),
                                 detail::half_extents(body, tolerance), W(1), [&](std::uint32_t k, W t_end) {
                                   visit(k, mesh.triangle(k));
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
  if (!displacement.allFinite() || !Vec<T, N>(body.center() + displacement).allFinite()) return out;
  if (inside_any(body, world, options)) {
    out.status = SlideStatus::overlapping_at_start;
    return out;
  }
  const Vec<T, N> still = Vec<T, N>::Zero();
  Vec<T, N> r = displacement, center = body.center();
  // The obstacles hit by the previous round's move, with their normals facing the body.
  std::vector<std::pair<std::size_t, Vec<T, N>>> hit_last;
  bool constrained = false;  // a touched obstacle took some of the displacement
  for (int round = 0; round < options.max_iterations; ++round) {
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
      t = k < std::numeric_limits<T>::digits ? first * (T(1) - std::ldexp(T(1), k - std::numeric_limits<T>::digits))
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

}  // namespace

template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              std::span<const std::type_identity_t<HalfSpace<T, N>>> world, const Options& options) {
  return slide_through(body, displacement, HalfSpaces<T, N>{world}, options);
}

template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              const TriangleMesh<T, N>& world, const Options& options) {
  return slide_through(body, displacement, Mesh<T, N>{world, options.tolerance}, options);
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
