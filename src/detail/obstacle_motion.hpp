// First contact of a body in rigid motion with an obstacle (a half-space, triangle, box or
// capsule) moving at a constant velocity (contact.hpp, "Rigid motion against shapes"):
// conservative advancement (rigid_motion.hpp) in the obstacle's frame, where it is at rest
// and the body moves at v_a - v_b and turns. Each step's slab gap along the distance's normal
// n takes the obstacle's least n . x (its vertices, its plane, or its segment less the
// radius): a lower bound on the distance whatever the accuracy of n.
//
// The obstacle's part is ObstacleTraits<Shape>, specialized in the obstacle's own file
// (obstacles/<shape>.cpp; a polytope's derives lowest and coordinate from its
// PolytopeTraits through PolytopeObstacle), which defines its public first_contact with the macro at the end
// and instantiates it with its other queries (instantiate.hpp, ELLIPSECT_INSTANTIATE_OBSTACLE):
//   static Lowest lowest(const Vec<R, N>& n, const Shape&)   least n . x and its terms' size
//                                                            (-inf where unbounded along -n)
//   static std::optional<Vec<R, N>> inner_point(const Shape&)  a point inside (or none)
//   static T coordinate(const Shape&)                        its largest coordinate
// and the shape's distance, signed_distance, linear first_contact and translated().
#pragma once

#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>

#include "contact_start.hpp"
#include "polytope_distance.hpp"
#include "reduce.hpp"
#include "rigid_motion.hpp"
#include "scale.hpp"
#include "shape_access.hpp"
#include "math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace ellipsect::detail::obstacle {

using namespace rigid;

template <class Shape>
struct ObstacleTraits;

// The least n . x over the shape and the size of the terms it comes from (for its rounding);
// -infinity where the shape is unbounded along -n.
struct Lowest {
  R low, magnitude;
};

template <class T, int N, std::size_t K>
Lowest lowest_of(const Vec<R, N>& n, const std::array<Vec<T, N>, K>& points, R grow) noexcept {
  Lowest out{std::numeric_limits<R>::infinity(), 0};
  for (const auto& p : points) {
    const R x = n.dot(p.template cast<R>());
    out.low = std::min(out.low, x);
    out.magnitude = std::max(out.magnitude, abs(x));
  }
  return {out.low - grow, out.magnitude + grow};
}

// The largest coordinate of the points.
template <class T, int N, std::size_t K>
T largest(const std::array<Vec<T, N>, K>& points) noexcept {
  T out = 0;
  for (const auto& p : points) out = std::max(out, detail::max_abs(p));
  return out;
}

// The lowest point and largest coordinate of a convex polytope (a triangle, a box), from its
// vertices (PolytopeTraits, polytope_distance.hpp): its ObstacleTraits derive from this and add
// inner_point.
template <class T, int N, class Shape>
struct PolytopeObstacle {
  static Lowest lowest(const Vec<R, N>& n, const Shape& shape) noexcept {
    return lowest_of(n, PolytopeTraits<Shape>::vertices(shape), R(0));
  }
  static T coordinate(const Shape& shape) noexcept { return largest(PolytopeTraits<Shape>::vertices(shape)); }
};

// A convex shape at rest as the second party of the advancement.
template <class T, int N, class Shape>
struct ShapeParty {
  const Shape& shape;
  const Options& options;
  Vec<R, N> velocity;  // the body's, relative to the shape
  R growing;           // the rate g R_0 at which its largest radius grows

  bool at(R) const noexcept { return true; }
  // The direction u from the body's center to a point inside the shape serves instead of
  // the distance's normal where the slab along it is open by an eighth of the body's largest
  // radius plus 64 ulps of T of its terms (far above the tangency band and the slab's
  // rounding): the step then costs the shape's vertices along u and one support point.
  // (The shapes' distances take no hint.)
  Distance<T, N> near(const Ellipsoid<T, N>& body, bool touched, const Vec<T, N>&) const noexcept {
    const R ulp = R(std::numeric_limits<T>::epsilon());
    const std::optional<Vec<R, N>> inside = ObstacleTraits<Shape>::inner_point(shape);
    if (!touched && inside) {
      const Vec<R, N> center = body.center().template cast<R>(), between = *inside - center;
      const R apart = stable_norm<R, N>(between), big = R(body.radii().maxCoeff());
      if (apart > R(0) && R(body.radii().minCoeff()) > ldexp(R(1), -960)) {
        const Vec<R, N> u = between / apart;
        Vec<R, N> offset;
        const Lowest l = ObstacleTraits<Shape>::lowest(u, shape);
        const R along = u.dot(center), rho = support(body, u, offset);
        if (l.low - along - rho > big / 8 + 64 * ulp * (l.magnitude + abs(along) + rho)) return slab_step<T, N>(u);
      }
    }
    return distance(body, shape, options);
  }
  Distance<T, N> exact(const Ellipsoid<T, N>& body) const noexcept { return signed_distance(body, shape, options); }
  Party side(const Vec<R, N>& n, const Ellipsoid<T, N>&) const noexcept {
    const Lowest l = ObstacleTraits<Shape>::lowest(n, shape);
    return {l.low, 0, 0, 0, 0, l.magnitude, 0, 0};
  }
  // The body's bounding ball (radius R about its center, whatever its turn) lies below the
  // shape's slab and its top does not move towards it (the center's approach and the
  // radius's growth): they never meet.
  bool never(const Vec<R, N>& n, const Ellipsoid<T, N>& body, R margin) const noexcept {
    const R ulp = R(std::numeric_limits<T>::epsilon());
    const R big = R(body.radii().maxCoeff());
    return (growing == R(0) ? n.dot(velocity) <= R(0) : n.dot(velocity) + growing * (1 + 64 * ulp) <= R(0)) &&
           ObstacleTraits<Shape>::lowest(n, shape).low - n.dot(body.center().template cast<R>()) - big * (1 + 64 * ulp) - margin > R(0);
  }
};

template <class T, int N>
bool valid_rigid(const RigidMotion<T, N>& motion, const VecArg<T, N>& velocity_b, T t_max) noexcept {
  return detail::valid_motion<T, N>(motion.velocity, velocity_b, t_max) && all_finite<N>(motion.angular_velocity) &&
         valid_growth(motion.growth);
}

// The body's motion relative to the shape.
template <class T, int N>
RigidMotion<T, N> relative(const RigidMotion<T, N>& motion, const VecArg<T, N>& velocity_b) noexcept {
  return {Vec<T, N>(motion.velocity - velocity_b), motion.angular_velocity, motion.growth};
}

// The advancement against a convex shape at rest, the contact point in the shape's frame.
// Pairs beyond the native range (shapes.hpp, "Range": radii or coordinates beyond 2^+-64
// of each other or of 1) get their start state only, then did_not_converge at 0.
template <class T, int N, class Shape>
Contact<T, N> advance_at_rest(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion, const Shape& b, T coordinate,
                              T t_max, const Options& options) noexcept {
  const detail::Scale scale = detail::scale_of<T>(a.radii().maxCoeff(), a.radii().minCoeff(),
                                                  std::max(detail::max_abs(a.center()), coordinate));
  const bool out_of_range = !isfinite(magnitude<N>(motion.angular_velocity)) || !scale.as_given();
  return advance<T, N>(a, motion, t_max, options, out_of_range,
                       ShapeParty<T, N, Shape>{b, options, motion.velocity.template cast<R>(),
                                               R(motion.growth) * R(a.radii().maxCoeff())});
}

// A hit whose world point lies beyond the range of T (both moving at 1e305: the shape has
// left the range by the contact time) is did_not_converge: its time a certified lower bound,
// point and normal NaN (contact.hpp).
template <class T, int N>
Contact<T, N> beyond_range(Contact<T, N> c) noexcept {
  if (c.status == ContactStatus::hit && !c.point.allFinite()) {
    c.status = ContactStatus::did_not_converge;
    c.point.setConstant(std::numeric_limits<T>::quiet_NaN());
    c.normal.setConstant(std::numeric_limits<T>::quiet_NaN());
  }
  return c;
}

// The answer in world coordinates: the contact point moved with the shape to the contact time.
template <class T, int N>
Contact<T, N> in_world(Contact<T, N> c, const VecArg<T, N>& velocity_b) noexcept {
  if (c.status == ContactStatus::hit) c.point += c.time * velocity_b;
  return beyond_range<T, N>(c);
}

// In the body's frame at time 0 (the shape moved by minus the body's center, the body at the
// origin), as the pair query forms its bodies in a's: the bodies formed at each step and the
// margins for their rounding are relative to the pair, not to the distance from the origin
// (1e6 sizes out, world coordinates moved the times by up to 4.7e-9 of size / speed). The
// point comes back with the body's center and the shape's motion to the contact time. A
// shape whose moved coordinates overflow is taken as given, and so is every float shape,
// whose moved vertices would round by float's last bit, moving the start state off the
// stored pair's (double's rounding lies far inside the tangency band).
template <class T, int N, class Shape>
Contact<T, N> rigid_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion, const Shape& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  if (!valid_rigid<T, N>(motion, velocity_b, t_max)) return detail::unanswered_contact<T, N>();
  if (magnitude<N>(motion.angular_velocity) == R(0) && motion.growth == T(0))
    return first_contact(a, motion.velocity, b, velocity_b, t_max, options);
  const RigidMotion<T, N> moving = relative<T, N>(motion, velocity_b);
  if constexpr (sizeof(T) >= sizeof(double)) {
    std::optional<Shape> moved;
    try {
      moved = b.translated(Vec<T, N>(-a.center()));
    } catch (const InputError&) {  // moved beyond the range of T
    }
    const T coordinate = moved ? ObstacleTraits<Shape>::coordinate(*moved) : std::numeric_limits<T>::infinity();
    if (isfinite(coordinate)) {
      const Ellipsoid<T, N> body = detail::ShapeAccess::unchecked<T, N>(Vec<T, N>::Zero(), a.axes(), a.radii());
      Contact<T, N> c = advance_at_rest<T, N>(body, moving, *moved, coordinate, t_max, options);
      if (c.status == ContactStatus::hit)
        for (int i = 0; i < N; ++i)
          c.point[i] = T(detail::mul_add(R(c.time), R(velocity_b[i]), R(a.center()[i])) + R(c.point[i]));
      return beyond_range<T, N>(c);
    }
  }
  return in_world<T, N>(advance_at_rest<T, N>(a, moving, b, ObstacleTraits<Shape>::coordinate(b), t_max, options),
                        velocity_b);
}

}  // namespace ellipsect::detail::obstacle

// The public first_contact under rigid motion against the obstacle Shape (declared in its
// header), through rigid_contact; in namespace ellipsect, after Shape's ObstacleTraits.
#define ELLIPSECT_RIGID_OBSTACLE_CONTACT(Shape)                                                                   \
  template <class T, int N>                                                                                       \
  Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Shape<T, N>& b,   \
                              const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {         \
    return detail::obstacle::rigid_contact<T, N>(a, motion_a, b, velocity_b, t_max, options);                     \
  }
// (Instantiated with the obstacle's other queries: instantiate.hpp, ELLIPSECT_INSTANTIATE_OBSTACLE.)
