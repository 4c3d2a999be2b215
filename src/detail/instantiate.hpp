// The scalar types and dimensions every public query is compiled for.
#pragma once

// Expand INSTANTIATE(T) for float and double, and INSTANTIATE(T, N) for float and double in 2
// and 3 dimensions. A build that answers in double alone (the demo page's, which defines
// ELLIPSECT_DOUBLE_ONLY) compiles the double ones only.
#ifdef ELLIPSECT_DOUBLE_ONLY
#define ELLIPSECT_FOR_EACH_TYPE(INSTANTIATE) INSTANTIATE(double)
#define ELLIPSECT_FOR_EACH_TYPE_AND_DIM(INSTANTIATE) \
  INSTANTIATE(double, 2)                             \
  INSTANTIATE(double, 3)
#else
#define ELLIPSECT_FOR_EACH_TYPE(INSTANTIATE) \
  INSTANTIATE(float)                         \
  INSTANTIATE(double)
#define ELLIPSECT_FOR_EACH_TYPE_AND_DIM(INSTANTIATE) \
  INSTANTIATE(float, 2)                              \
  INSTANTIATE(float, 3)                              \
  INSTANTIATE(double, 2)                             \
  INSTANTIATE(double, 3)
#endif

// What every convex obstacle (obstacles.hpp: half-space, triangle, box, capsule) answers, its
// header's declarations, for T in N dimensions: the type, classify, overlap, distance,
// signed_distance and its gradient (by the obstacle's Gradient type), first_contact under
// linear and under rigid motion (obstacle_motion.hpp's ELLIPSECT_RIGID_OBSTACLE_CONTACT).
#define ELLIPSECT_INSTANTIATE_OBSTACLE(Shape, Gradient, T, N)                                                       \
  template class Shape<T, N>;                                                                                     \
  template Relation classify<T, N>(const Ellipsoid<T, N>&, const Shape<T, N>&, const Options&) noexcept;          \
  template bool overlap<T, N>(const Ellipsoid<T, N>&, const Shape<T, N>&, const Options&) noexcept;               \
  template Distance<T, N> distance<T, N>(const Ellipsoid<T, N>&, const Shape<T, N>&, const Options&) noexcept;    \
  template Distance<T, N> signed_distance<T, N>(const Ellipsoid<T, N>&, const Shape<T, N>&, const Options&) noexcept; \
  template DistanceGradient<T, N, Gradient<T, N>> signed_distance_gradient<T, N>(const Ellipsoid<T, N>&,           \
                                                                                 const Shape<T, N>&,               \
                                                                                 const Options&) noexcept;         \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const VecArg<T, N>&, const Shape<T, N>&,      \
                                             const VecArg<T, N>&, T, const Options&) noexcept;                    \
  template Contact<T, N> first_contact<T, N>(const Ellipsoid<T, N>&, const RigidMotion<T, N>&, const Shape<T, N>&, \
                                             const VecArg<T, N>&, T, const Options&) noexcept;
