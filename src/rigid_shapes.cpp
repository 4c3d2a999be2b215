// First contact of a body in rigid motion with a half-space, triangle, box, capsule or mesh
// moving at a constant velocity (contact.hpp, "Rigid motion against shapes"): conservative
// advancement (detail/rigid_motion.hpp) in the shape's frame, where the shape is at rest and
// the body moves at v_a - v_b and turns. Each step's slab gap along the distance's normal n
// takes the shape's least n . x over its vertices (or its plane, or its segment less the
// radius): a lower bound on the distance whatever the accuracy of n.
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
#include <ellipsect/triangle.hpp>

#include "detail/contact_start.hpp"
#include "detail/instantiate.hpp"
#include "detail/mesh_walk.hpp"
#include "detail/reduce.hpp"
#include "detail/rigid_motion.hpp"
#include "detail/scale.hpp"
#include "detail/shape_access.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace ellipsect {

using namespace detail::rigid;

namespace {

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

template <class T, int N>
Lowest lowest_of(const Vec<R, N>& n, const HalfSpace<T, N>& h) noexcept {
  // The distance's normal is exactly -normal (half_space.hpp); along any other direction the
  // half-space reaches -infinity.
  const Vec<R, N> outward = h.normal().template cast<R>();
  if (n != -outward) return {-std::numeric_limits<R>::infinity(), 0};
  const R x = n.dot(h.point().template cast<R>());
  return {x, abs(x)};
}
template <class T, int N>
Lowest lowest_of(const Vec<R, N>& n, const Triangle<T, N>& t) noexcept {
  return lowest_of<T, N, 3>(n, {t.vertex(0), t.vertex(1), t.vertex(2)}, 0);
}
template <class T, int N>
Lowest lowest_of(const Vec<R, N>& n, const Box<T, N>& b) noexcept {
  std::array<Vec<T, N>, 1 << N> corners;
  for (int k = 0; k < (1 << N); ++k) corners[std::size_t(k)] = b.corner(k);
  return lowest_of<T, N, (1 << N)>(n, corners, 0);
}
template <class T, int N>
Lowest lowest_of(const Vec<R, N>& n, const Capsule<T, N>& c) noexcept {
  return lowest_of<T, N, 2>(n, {c.point(0), c.point(1)}, R(c.radius()));
}

// A point inside the shape (none for a half-space, whose distance costs no solve).
template <class T, int N>
std::optional<Vec<R, N>> inner_point(const HalfSpace<T, N>&) noexcept {
  return std::nullopt;
}
template <class T, int N>
std::optional<Vec<R, N>> inner_point(const Triangle<T, N>& t) noexcept {
  return (t.vertex(0).template cast<R>() + t.vertex(1).template cast<R>() + t.vertex(2).template cast<R>()) / 3;
}
template <class T, int N>
std::optional<Vec<R, N>> inner_point(const Box<T, N>& b) noexcept {
  return Vec<R, N>(b.center().template cast<R>());
}
template <class T, int N>
std::optional<Vec<R, N>> inner_point(const Capsule<T, N>& c) noexcept {
  return (c.point(0).template cast<R>() + c.point(1).template cast<R>()) / 2;
}

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
  Distance<T, N> near(const Ellipsoid<T, N>& body, bool touched) const noexcept {
    const R ulp = R(std::numeric_limits<T>::epsilon());
    const std::optional<Vec<R, N>> inside = inner_point<T, N>(shape);
    if (!touched && inside) {
      const Vec<R, N> center = body.center().template cast<R>(), between = *inside - center;
      const R apart = between.stableNorm(), big = R(body.radii().maxCoeff());
      if (apart > R(0) && R(body.radii().minCoeff()) > ldexp(R(1), -960)) {
        const Vec<R, N> u = between / apart;
        Vec<R, N> offset;
        const Lowest l = lowest_of<T, N>(u, shape);
        const R along = u.dot(center), rho = support(body, u, offset);
        if (l.low - along - rho > big / 8 + 64 * ulp * (l.magnitude + abs(along) + rho)) return slab_step<T, N>(u);
      }
    }
    return distance(body, shape, options);
  }
  Distance<T, N> exact(const Ellipsoid<T, N>& body) const noexcept { return signed_distance(body, shape, options); }
  Party side(const Vec<R, N>& n, const Ellipsoid<T, N>&) const noexcept {
    const Lowest l = lowest_of<T, N>(n, shape);
    return {l.low, 0, 0, 0, 0, l.magnitude, 0, 0};
  }
  // The body's bounding ball (radius R about its center, whatever its turn) lies below the
  // shape's slab and its top does not move towards it (the center's approach and the
  // radius's growth): they never meet.
  bool never(const Vec<R, N>& n, const Ellipsoid<T, N>& body, R margin) const noexcept {
    const R ulp = R(std::numeric_limits<T>::epsilon());
    const R big = R(body.radii().maxCoeff());
    return (growing == R(0) ? n.dot(velocity) <= R(0) : n.dot(velocity) + growing * (1 + 64 * ulp) <= R(0)) &&
           lowest_of<T, N>(n, shape).low - n.dot(body.center().template cast<R>()) - big * (1 + 64 * ulp) - margin > R(0);
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

template <class T, int N, std::size_t K>
T largest(const std::array<Vec<T, N>, K>& points) noexcept {
  T out = 0;
  for (const auto& p : points) out = std::max(out, detail::max_abs(p));
  return out;
}

// The shape's largest coordinate (for the range of the pair).
template <class T, int N>
T coordinate_of(const HalfSpace<T, N>& h) noexcept {
  return detail::max_abs(h.point());
}
template <class T, int N>
T coordinate_of(const Triangle<T, N>& t) noexcept {
  return largest<T, N, 3>({t.vertex(0), t.vertex(1), t.vertex(2)});
}
template <class T, int N>
T coordinate_of(const Box<T, N>& b) noexcept {
  std::array<Vec<T, N>, 1 << N> corners;
  for (int k = 0; k < (1 << N); ++k) corners[std::size_t(k)] = b.corner(k);
  return largest<T, N, (1 << N)>(corners);
}
template <class T, int N>
T coordinate_of(const Capsule<T, N>& c) noexcept {
  return largest<T, N, 2>({c.point(0), c.point(1)}) + c.radius();
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
    const T coordinate = moved ? coordinate_of<T, N>(*moved) : std::numeric_limits<T>::infinity();
    if (isfinite(coordinate)) {
      const Ellipsoid<T, N> body = detail::ShapeAccess::unchecked<T, N>(Vec<T, N>::Zero(), a.axes(), a.radii());
      Contact<T, N> c = advance_at_rest<T, N>(body, moving, *moved, coordinate, t_max, options);
      if (c.status == ContactStatus::hit)
        for (int i = 0; i < N; ++i)
          c.point[i] = T(detail::mul_add(R(c.time), R(velocity_b[i]), R(a.center()[i])) + R(c.point[i]));
      return beyond_range<T, N>(c);
    }
  }
  return in_world<T, N>(advance_at_rest<T, N>(a, moving, b, coordinate_of<T, N>(b), t_max, options), velocity_b);
}

}  // namespace

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const HalfSpace<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  return rigid_contact<T, N>(a, motion_a, b, velocity_b, t_max, options);
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Triangle<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  return rigid_contact<T, N>(a, motion_a, b, velocity_b, t_max, options);
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Box<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  return rigid_contact<T, N>(a, motion_a, b, velocity_b, t_max, options);
}

template <class T, int N>
Contact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a, const Capsule<T, N>& b,
                            const VecArg<T, N>& velocity_b, T t_max, const Options& options) noexcept {
  return rigid_contact<T, N>(a, motion_a, b, velocity_b, t_max, options);
}

template <class T, int N>
MeshContact<T, N> first_contact(const Ellipsoid<T, N>& a, const RigidMotion<T, N>& motion_a,
                                const TriangleMesh<T, N>& b, const VecArg<T, N>& velocity_b, T t_max,
                                const Options& options) noexcept {
  if (!valid_rigid<T, N>(motion_a, velocity_b, t_max)) return {detail::unanswered_contact<T, N>(), -1};
  if (magnitude<N>(motion_a.angular_velocity) == R(0) && motion_a.growth == T(0))
    return first_contact(a, motion_a.velocity, b, velocity_b, t_max, options);
  // The candidates: triangles whose boxes the body's bounding ball (radius R at the window's
  // end, grown by the tangency band and 1e-9) meets along its center's path relative to the
  // mesh; each by its own advancement.
  using W = detail::Work<T>;
  const W grown = motion_a.growth == T(0) ? W(1) : 1 + W(motion_a.growth) * W(t_max);
  const W reach = W(a.radii().maxCoeff()) * grown * (1 + 2 * W(double(options.tolerance)) + W(1e-9)) *
                  (sizeof(T) < sizeof(double) ? W(1 + 1e-6) : W(1));
  return detail::mesh_contact<T, N>(a, b, options, (motion_a.velocity - velocity_b).template cast<W>(),
                                    Vec<W, N>::Constant(reach), t_max, false, [&](std::uint32_t k, T t_end) {
    return first_contact(a, motion_a, b.triangle(k), velocity_b, t_end, options);
  });
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                                    \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const HalfSpace<T, N>&, \
                                             const VecArg<T, N>&, T, const Options&) noexcept;                         \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const Triangle<T, N>&,  \
                                             const VecArg<T, N>&, T, const Options&) noexcept;                         \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const Box<T, N>&,       \
                                             const VecArg<T, N>&, T, const Options&) noexcept;                         \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const Capsule<T, N>&,   \
                                             const VecArg<T, N>&, T, const Options&) noexcept;                         \
  template MeshContact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&,                     \
                                                 const TriangleMesh<T, N>&, const VecArg<T, N>&, T, const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
