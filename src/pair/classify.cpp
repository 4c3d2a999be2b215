#include <ellipsect/classify.hpp>

#include "detail/certificates-inl.hpp"
#include "detail/classify_impl.hpp"
#include "detail/exact_relation.hpp"
#include "detail/instantiate.hpp"
#include "detail/scale.hpp"

namespace ellipsect {

std::string_view to_string(Relation r) noexcept {
  switch (r) {
    case Relation::separated: return "separated";
    case Relation::touching: return "touching";
    case Relation::overlapping: return "overlapping";
    case Relation::a_contains_b: return "a_contains_b";
    case Relation::b_contains_a: return "b_contains_a";
    case Relation::equal: return "equal";
  }
  return "unknown";
}

namespace {

// The reduced-frame decision in working precision R, repeated in the wider type when
// rounding (plus `slack` relative to the frame's lengths) could have flipped one of its
// comparisons; `sure` is false when it could there too.
template <class R, class T, int N>
detail::ReducedRelation decide(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, R tol, R slack, bool& sure) noexcept {
  const auto red = detail::reduce_settled<R>(s, o);
  R margin;
  const auto rel = detail::classify_reduced<R, N>(red.e, red.k, tol, margin);
  sure = true;
  if (margin > detail::reduced_rounding<R>(s, o, red.e, red.k) + slack * (red.k.norm() + red.e.maxCoeff() + 1))
    return rel;
  using W = detail::Wide<R>;
  const auto wide = detail::reduce_settled<W>(s, o);
  W wide_margin;
  const auto wide_rel = detail::classify_reduced<W, N>(wide.e, wide.k, W(tol), wide_margin);
  sure = wide_margin > detail::reduced_rounding<W>(s, o, wide.e, wide.k) + W(slack) * (wide.k.norm() + wide.e.maxCoeff() + 1);
  return wide_rel;
}

template <class R, class T, int N>
detail::ReducedRelation decide(const Ellipsoid<T, N>& s, const Ellipsoid<T, N>& o, R tol) noexcept {
  bool sure;
  return decide<R>(s, o, tol, R(0), sure);
}

// The classification in W: the working type, where the certificates filter first, or the
// wide type.
template <class W, class T, int N>
[[gnu::always_inline]] inline Relation classify_in(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                                 const Options& options) noexcept {
  using R = detail::Work<T>;
  if constexpr (std::is_same_v<W, R>) {
    namespace hw = detail::HWY_NAMESPACE;
    const double code = hw::certificate_code<true>(a, b, options.tolerance);
    if (code != 0) return detail::certified_relation(code);
  }
  const auto [s, o, a_is_s] = detail::order_pair(a, b);
  // Exact: every comparison against 1 itself, and one within its rounding plus the
  // narrowest band (relative to the reduced frame's lengths: the rounding model is an
  // estimate, which this covers 3000 times over in the wide type) of a threshold is settled
  // in rational arithmetic.
  const bool exact = options.tolerance.is_exact();
  const R tol = exact ? R(0) : R(double(options.tolerance)), slack = exact ? R(Tolerance::min) : R(0);
  bool sure;
  const auto rel = decide<W>(s, o, W(tol), W(slack), sure);
  if (exact && !sure) return detail::exact_relation(a, b);
  switch (rel) {
    case detail::ReducedRelation::s_contains_o: return a_is_s ? Relation::a_contains_b : Relation::b_contains_a;
    case detail::ReducedRelation::o_contains_s: return a_is_s ? Relation::b_contains_a : Relation::a_contains_b;
    case detail::ReducedRelation::separated: return Relation::separated;
    case detail::ReducedRelation::touching: return Relation::touching;
    case detail::ReducedRelation::overlapping: return Relation::overlapping;
    case detail::ReducedRelation::equal: return Relation::equal;
  }
  return Relation::overlapping;
}

// overlap in the working type: the certificates, the gap against 0 where rounding allows,
// then the decision.
template <class T, int N>
[[gnu::always_inline]] inline bool overlap_in(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                             const Options& options) noexcept {
  using R = detail::Work<T>;
  namespace hw = detail::HWY_NAMESPACE;
  const double code = hw::certificate_code<false>(a, b, options.tolerance);
  if (code != 0) return code > 0;
  const auto [s, o, a_is_s] = detail::order_pair(a, b);
  const bool exact = options.tolerance.is_exact();
  const R tol = R(double(options.tolerance));
  const auto red = detail::reduce_settled<R>(s, o);
  // Exact: the gap decides against 0 where rounding allows, classify otherwise.
  if (const int sure = detail::overlap_reduced<R, N>(red.e, red.k, exact ? R(0) : tol,
                                                     detail::reduced_rounding<R>(s, o, red.e, red.k)))
    return sure > 0;
  if (exact) return classify(a, b, options) != Relation::separated;
  return decide<R>(s, o, tol) != detail::ReducedRelation::separated;
}

// overlap run in W at a scale (detail::at_scale). The inputs come as arguments, not
// captures, so that the native path (a few dozen instructions) builds no closure.
struct OverlapAt {
  template <class W, class Units, class T, int N>
  [[gnu::always_inline]] bool operator()(Units units, const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b,
                                         const Options& options) const noexcept {
    constexpr bool wide = !std::is_same_v<W, detail::Work<T>>;
    const bool exact = options.tolerance.is_exact();
    if (exact && (wide || units.loses(a, b))) return classify(a, b, options) != Relation::separated;
    if constexpr (wide) {
      const auto pair = detail::order_pair(a, b);
      return decide<W>(pair.s, pair.o, W(double(options.tolerance))) != detail::ReducedRelation::separated;
    } else {
      return overlap_in(units.body(a), units.body(b), options);
    }
  }
};

}  // namespace

// At the pair's scale (detail/scale.hpp). Exact: a pair whose rescaling would lose a
// subnormal difference gets its exact relation.
template <class T, int N>
Relation classify(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options) noexcept {
  if (detail::identical(a, b)) return Relation::equal;
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), [&]<class W>(auto units) {
    if (options.tolerance.is_exact() && units.loses(a, b)) return detail::exact_relation(a, b);
    decltype(auto) sa = units.body(a);
    decltype(auto) sb = units.body(b);
    if (units.rescaled && detail::identical(sa, sb)) return Relation::equal;
    return classify_in<W>(sa, sb, options);
  });
}

template <class T, int N>
bool overlap(const Ellipsoid<T, N>& a, const Ellipsoid<T, N>& b, const Options& options) noexcept {
  return detail::at_scale<detail::Work<T>>(detail::scale_of(a, b), OverlapAt{}, a, b, options);
}

#define ELLIPSECT_INSTANTIATE(T, N)                                                                          \
  template Relation classify<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, const Options&) noexcept; \
  template bool overlap<T, N>(const Ellipsoid<T, N>&, const Ellipsoid<T, N>&, const Options&) noexcept;
ELLIPSECT_FOR_EACH_TYPE_AND_DIM(ELLIPSECT_INSTANTIATE)
#undef ELLIPSECT_INSTANTIATE

}  // namespace ellipsect
