#include <ellipsect/slide.hpp>

#include "detail/instantiate.hpp"
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

template <class T, int N>
bool inside_any(const Ellipsoid<T, N>& body, std::span<const HalfSpace<T, N>> world, const Options& options) noexcept {
  for (const auto& h : world) {
    const Relation r = classify(body, h, options);
    if (r == Relation::overlapping || r == Relation::b_contains_a) return true;
  }
  return false;
}

// r without what pushes into the touched half-spaces (unit outward normals): projected onto
// one plane, onto two planes' common line (3D), or to nothing (slide.hpp).
template <class T, int N>
Vec<T, N> project(Vec<T, N> r, const std::vector<Vec<T, N>>& touched) noexcept {
  std::vector<Vec<T, N>> active;
  for (int round = 0; round <= N; ++round) {
    const Vec<T, N>* push = nullptr;
    for (const auto& n : touched)
      if (r.dot(n) < T(0) && std::find(active.begin(), active.end(), n) == active.end()) {
        push = &n;
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

}  // namespace

template <class T, int N>
Slide<T, N> collide_and_slide(const Ellipsoid<T, N>& body, const VecArg<T, N>& displacement,
                              std::span<const std::type_identity_t<HalfSpace<T, N>>> world, const Options& options) {
  Slide<T, N> out;
  out.body = body;
  if (!displacement.allFinite() || !Vec<T, N>(body.center() + displacement).allFinite()) return out;
  if (inside_any(body, world, options)) {
    out.status = SlideStatus::overlapping_at_start;
    return out;
  }
  Vec<T, N> r = displacement, center = body.center();
  std::vector<std::size_t> hit_last;  // the half-spaces hit by the previous round's move
  bool constrained = false;           // a touched half-space took some of the displacement
  for (int round = 0; round < options.max_iterations; ++round) {
    const Ellipsoid<T, N> now = at(body, center);
    // Touched: within the tangency band, or just hit (a move shortened by its rounding can
    // stop short of the band).
    std::vector<Vec<T, N>> touched;
    for (std::size_t k = 0; k < world.size(); ++k)
      if (classify(now, world[k], options) == Relation::touching ||
          std::find(hit_last.begin(), hit_last.end(), k) != hit_last.end())
        touched.push_back(world[k].normal());
    const Vec<T, N> free = project<T, N>(r, touched);
    constrained |= free != r;
    r = free;
    if (r == Vec<T, N>::Zero()) break;
    // The earliest contact along r in [0, 1] (ties: every half-space hit then).
    T first = T(1);
    hit_last.clear();
    for (std::size_t k = 0; k < world.size(); ++k) {
      const Contact<T, N> c = first_contact(now, r, world[k], Vec<T, N>::Zero(), T(1), options);
      if (c.status != ContactStatus::hit || c.time > first) continue;
      if (c.time < first) hit_last.clear();
      first = c.time;
      hit_last.push_back(k);
    }
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
      // touched from here on.
      const Ellipsoid<T, N> end = at(body, Vec<T, N>(center + first * r));
      for (std::size_t k = 0; k < world.size(); ++k) {
        const Relation rel = classify(end, world[k], options);
        if (rel == Relation::overlapping || rel == Relation::b_contains_a) hit_last.push_back(k);
      }
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
      out.last_contact = static_cast<int>(hit_last.front());
    }
  }
  out.body = at(body, center);
  out.status = r != Vec<T, N>::Zero()             ? SlideStatus::blocked
               : out.contacts > 0 || constrained ? SlideStatus::slid
                                                 : SlideStatus::moved;
  return out;
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                       \
  template Slide<T, N> collide_and_slide<T, N>(const Ellipsoid<T, N>&, const VecArg<T, N>&,             \
                                               std::span<const std::type_identity_t<HalfSpace<T, N>>>, \
                                               const Options&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
