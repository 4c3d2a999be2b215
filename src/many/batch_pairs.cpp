// Every other pair query over spans of bodies (batch.hpp, "Every other pair query"): the
// scalar function on every pair, on the worker pool.
#include <ellipsect/batch.hpp>
#include <ellipsect/parallel.hpp>

#include "detail/instantiate.hpp"

#include <algorithm>
#include <initializer_list>
#include <stdexcept>
#include <string>

namespace ellipsect {
namespace {

constexpr std::size_t pairs_per_task = 64;

// out[i] = answer(i) for every pair, `threads` as BatchOptions::threads; `sizes` are the
// other spans', which must equal out's.
template <class R, class Answer>
void each_pair(std::span<R> out, std::initializer_list<std::size_t> sizes, int threads, const Answer& answer) {
  const std::size_t n = out.size();
  if (std::any_of(sizes.begin(), sizes.end(), [n](std::size_t s) { return s != n; }))
    throw std::invalid_argument("ellipsect: the inputs and out must have equal sizes");
  parallel_for((n + pairs_per_task - 1) / pairs_per_task, threads, [&](std::size_t task) {
    for (std::size_t i = task * pairs_per_task; i < std::min(n, (task + 1) * pairs_per_task); ++i) out[i] = answer(i);
  });
}

}  // namespace

// The queries of two bodies alone: pair i's answer QUERY(a[i], b[i], options.query); the
// result type is the rest of the arguments (it holds commas). Bodies, then ellipses.
#define ELLIPSECT_PAIRWISE_BODY(QUERY)                                                                            \
  {                                                                                                               \
    each_pair(out, {a.size(), b.size()}, options.threads,                                                         \
              [&](std::size_t i) { return QUERY(a[i], b[i], options.query); });                                   \
  }
#define ELLIPSECT_PAIRWISE(QUERY, ...)                                                                            \
  template <class T, int N>                                                                                       \
  void QUERY(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b, std::span<__VA_ARGS__> out,  \
             const BatchOptions& options) ELLIPSECT_PAIRWISE_BODY(QUERY)
#define ELLIPSECT_PAIRWISE_ELLIPSES(QUERY, ...)                                                                   \
  template <class T>                                                                                              \
  void QUERY(std::span<const Ellipse2<T>> a, std::span<const Ellipse2<T>> b, std::span<__VA_ARGS__> out,          \
             const BatchOptions& options) ELLIPSECT_PAIRWISE_BODY(QUERY)
ELLIPSECT_PAIRWISE(distance, Distance<T, N>)
ELLIPSECT_PAIRWISE(signed_distance, Distance<T, N>)
ELLIPSECT_PAIRWISE(signed_distance_gradient, DistanceGradient<T, N>)
ELLIPSECT_PAIRWISE(perram_wertheim, ContactFunction<T>)
ELLIPSECT_PAIRWISE(perram_wertheim_gradient, ContactFunctionGradient<T, N>)
ELLIPSECT_PAIRWISE_ELLIPSES(overlap_area, OverlapArea<T>)
ELLIPSECT_PAIRWISE_ELLIPSES(intersection_over_union, T)
ELLIPSECT_PAIRWISE_ELLIPSES(overlap_area_gradient, OverlapAreaGradient<T>)
ELLIPSECT_PAIRWISE_ELLIPSES(intersection_over_union_gradient, IouGradient<T>)
#undef ELLIPSECT_PAIRWISE_ELLIPSES
#undef ELLIPSECT_PAIRWISE
#undef ELLIPSECT_PAIRWISE_BODY

template <class T, int N>
void closest_approach_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const Ellipsoid<T, N>> b,
                               std::span<const Vec<T, N>> direction, std::span<ClosestApproachGradient<T, N>> out,
                               const BatchOptions& options) {
  for (std::size_t i = 0; i < direction.size(); ++i)  // closest_approach's own check, named by row
    if (!direction[i].allFinite() || direction[i].isZero(0))
      throw InputError("direction[" + std::to_string(i) + "]", "must be finite and nonzero");
  each_pair(out, {a.size(), b.size(), direction.size()}, options.threads,
            [&](std::size_t i) { return closest_approach_gradient(a[i], b[i], direction[i], options.query); });
}

template <class T, int N>
void first_contact_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const Vec<T, N>> velocity_a,
                            std::span<const Ellipsoid<T, N>> b, std::span<const Vec<T, N>> velocity_b,
                            std::span<const T> t_max, std::span<ContactGradient<T, N>> out,
                            const BatchOptions& options) {
  each_pair(out, {a.size(), velocity_a.size(), b.size(), velocity_b.size(), t_max.size()}, options.threads,
            [&](std::size_t i) {
              return first_contact_gradient<T, N>(a[i], velocity_a[i], b[i], velocity_b[i], t_max[i], options.query);
            });
}

template <class T, int N>
void first_contact_gradient(std::span<const Ellipsoid<T, N>> a, std::span<const RigidMotion<T, N>> motion_a,
                            std::span<const Ellipsoid<T, N>> b, std::span<const RigidMotion<T, N>> motion_b,
                            std::span<const T> t_max, std::span<ContactGradient<T, N>> out,
                            const BatchOptions& options) {
  each_pair(out, {a.size(), motion_a.size(), b.size(), motion_b.size(), t_max.size()}, options.threads,
            [&](std::size_t i) {
              return first_contact_gradient<T, N>(a[i], motion_a[i], b[i], motion_b[i], t_max[i], options.query);
            });
}

#define ELLIPSECT_PAIR_SPANS(T, N) std::span<const Ellipsoid<T, N>>, std::span<const Ellipsoid<T, N>>
#define ELLIPSECT_INSTANTIATE(T, N)                                                                               \
  template void distance<T, N>(ELLIPSECT_PAIR_SPANS(T, N), std::span<Distance<T, N>>, const BatchOptions&);       \
  template void signed_distance<T, N>(ELLIPSECT_PAIR_SPANS(T, N), std::span<Distance<T, N>>, const BatchOptions&); \
  template void signed_distance_gradient<T, N>(ELLIPSECT_PAIR_SPANS(T, N), std::span<DistanceGradient<T, N>>,     \
                                               const BatchOptions&);                                              \
  template void perram_wertheim<T, N>(ELLIPSECT_PAIR_SPANS(T, N), std::span<ContactFunction<T>>,                  \
                                      const BatchOptions&);                                                       \
  template void perram_wertheim_gradient<T, N>(ELLIPSECT_PAIR_SPANS(T, N), std::span<ContactFunctionGradient<T, N>>, \
                                               const BatchOptions&);                                              \
  template void closest_approach_gradient<T, N>(ELLIPSECT_PAIR_SPANS(T, N), std::span<const Vec<T, N>>,           \
                                                std::span<ClosestApproachGradient<T, N>>, const BatchOptions&);   \
  template void first_contact_gradient<T, N>(std::span<const Ellipsoid<T, N>>, std::span<const Vec<T, N>>,        \
                                             std::span<const Ellipsoid<T, N>>, std::span<const Vec<T, N>>,        \
                                             std::span<const T>, std::span<ContactGradient<T, N>>,                \
                                             const BatchOptions&);                                                \
  template void first_contact_gradient<T, N>(std::span<const Ellipsoid<T, N>>, std::span<const RigidMotion<T, N>>, \
                                             std::span<const Ellipsoid<T, N>>, std::span<const RigidMotion<T, N>>, \
                                             std::span<const T>, std::span<ContactGradient<T, N>>,                \
                                             const BatchOptions&);
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE
#undef ELLIPSECT_PAIR_SPANS
#define ELLIPSECT_INSTANTIATE(T)                                                                                  \
  template void overlap_area<T>(std::span<const Ellipse2<T>>, std::span<const Ellipse2<T>>,                       \
                                std::span<OverlapArea<T>>, const BatchOptions&);                                  \
  template void intersection_over_union<T>(std::span<const Ellipse2<T>>, std::span<const Ellipse2<T>>,            \
                                           std::span<T>, const BatchOptions&);                                    \
  template void overlap_area_gradient<T>(std::span<const Ellipse2<T>>, std::span<const Ellipse2<T>>,              \
                                         std::span<OverlapAreaGradient<T>>, const BatchOptions&);                 \
  template void intersection_over_union_gradient<T>(std::span<const Ellipse2<T>>, std::span<const Ellipse2<T>>,   \
                                                    std::span<IouGradient<T>>, const BatchOptions&);
ELLIPSECT_FOR_EACH_TYPE(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
