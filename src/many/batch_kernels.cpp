// SIMD build of the certificate filter: Highway compiles this file once per instruction
// set (foreach_target) and dispatches to the widest one the CPU supports. Built with
// -ffp-contract=off so that every lane rounds exactly as the scalar code does.
// (This file, through the library's include path src/.)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "many/batch_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "detail/batch_kernels.hpp"
#include "detail/certificates-inl.hpp"
#include "detail/certificates_float-inl.hpp"

#include <algorithm>
#include <type_traits>
#include <vector>

HWY_BEFORE_NAMESPACE();
namespace ellipsect::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <int N>
struct Layout {
  static constexpr BodyLayout body{N};
  static constexpr int columns = 2 * body.size() + 2 * N + 1;  // a, b, velocity_a, velocity_b, t_max
};

// Column k at row i as lanes of D: loaded as they are, or float columns widened to
// double (exactly) for the double filter.
template <class D, class C>
hn::Vec<D> load_lanes(D d, const C* column) {
  if constexpr (std::is_same_v<hn::TFromD<D>, C>) {
    return hn::LoadU(d, column);
  } else {
    return hn::PromoteTo(d, hn::LoadU(hn::Rebind<C, D>(), column));
  }
}

// `quadric`: also load M (classify).
template <int N, class D, class C>
BodyLanes<hn::Vec<D>, N> load_body(D d, const C* const* src, std::size_t i, int first, bool quadric) {
  constexpr BodyLayout layout = Layout<N>::body;
  auto load = [&](int k) { return load_lanes(d, src[first + k] + i); };
  BodyLanes<hn::Vec<D>, N> b;
  for (int r = 0; r < N; ++r) {
    b.c[r] = load(layout.center(r));
    for (int c = r; c < N; ++c) {
      b.s[r][c] = b.s[c][r] = load(layout.s(r, c));
      if (quadric) b.m[r][c] = b.m[c][r] = load(layout.m(r, c));
    }
  }
  b.rmax = load(layout.rmax());
  b.rmin = load(layout.rmin());
  return b;
}

// The filter's inputs besides the columns: the tolerance (double lanes) and the float
// filter's thresholds made from it (certificates_float-inl.hpp).
struct Band {
  double tol;
  FloatBand in_float;
};

// Lanes of float run the float certificates (overlap and classify of float columns);
// lanes of double the scalar code's, on double columns or on float ones widened.
template <int N, int rounds, class D, class C>
hn::Vec<D> certify_lanes(D d, BatchQuery query, const C* const* src, std::size_t i, const Band& band) {
  using V = hn::Vec<D>;
  constexpr int body = Layout<N>::body.size();
  const bool quadric = query == BatchQuery::classify;
  const auto a = load_body<N>(d, src, i, 0, quadric), b = load_body<N>(d, src, i, body, quadric);
  if constexpr (std::is_same_v<hn::TFromD<D>, float>) {
    if (query == BatchQuery::overlap) return float_code<V, N, false, rounds>(a, b, band.in_float);
    return float_code<V, N, true, rounds>(a, b, band.in_float);
  } else {
    const V vtol = hn::Set(d, band.tol);
    if (query == BatchQuery::overlap) return overlap_code<V, N, rounds>(a, b, vtol);
    if (query == BatchQuery::classify) return classify_code<V, N, rounds>(a, b, vtol);
    V va[N], vb[N];
    for (int k = 0; k < N; ++k) {
      va[k] = load_lanes(d, src[2 * body + k] + i);
      vb[k] = load_lanes(d, src[2 * body + N + k] + i);
    }
    return swept_code<V, N>(a, va, b, vb, load_lanes(d, src[2 * body + 2 * N] + i), vtol);
  }
}

// Two passes: every pair without Newton rounds, then the pairs left open, gathered into
// full vectors, with them. The rounds then run on open lanes only instead of on every
// vector that has one (about a third of them on random pairs); the codes are the same.
template <int N, class D, class C>
void filter(D d, BatchQuery query, const C* const* columns, std::size_t begin, std::size_t end, const Band& band,
             signed char* codes) {
  using Lane = hn::TFromD<D>;
  constexpr int n_columns = Layout<N>::columns;
  const std::size_t lanes = hn::Lanes(d);
  HWY_ALIGN Lane out[HWY_LANES(Lane)];
  C gathered[n_columns][HWY_LANES(Lane)];
  const C* src[n_columns] = {};
  // Rows `rows[0..count)` as one vector, padded by repeating the last; only the columns
  // the query reads (M for classify, velocities and t_max for contact).
  constexpr BodyLayout body = Layout<N>::body;
  auto used = [&](int k) {
    if (k >= 2 * body.size()) return query == BatchQuery::contact;
    const int within = k % body.size();
    return query == BatchQuery::classify || within < body.m(0, 0) || within >= body.rmax();
  };
  auto gather = [&](const std::size_t* rows, std::size_t count) {
    for (int k = 0; k < n_columns; ++k) {
      if (!used(k)) continue;
      for (std::size_t j = 0; j < lanes; ++j) gathered[k][j] = columns[k][rows[std::min(j, count - 1)]];
      src[k] = gathered[k];
    }
  };
  const bool rounds = query != BatchQuery::contact;
  std::vector<std::size_t> open;
  auto first_pass = [&](std::size_t at, std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) {
      codes[at - begin + k] = static_cast<signed char>(out[k]);
      if (rounds && out[k] == 0) open.push_back(at + k);
    }
  };
  std::size_t i = begin;
  for (; i + lanes <= end; i += lanes) {
    hn::Store(certify_lanes<N, 0>(d, query, columns, i, band), d, out);
    first_pass(i, lanes);
  }
  if (i < end) {
    std::size_t rows[HWY_LANES(Lane)];
    for (std::size_t j = 0; j < end - i; ++j) rows[j] = i + j;
    gather(rows, end - i);
    hn::Store(certify_lanes<N, 0>(d, query, src, 0, band), d, out);
    first_pass(i, end - i);
  }
  for (std::size_t g = 0; g < open.size(); g += lanes) {
    const std::size_t count = std::min(lanes, open.size() - g);
    gather(open.data() + g, count);
    hn::Store(certify_lanes<N, newton_steps>(d, query, src, 0, band), d, out);
    for (std::size_t k = 0; k < count; ++k) codes[open[g + k] - begin] = static_cast<signed char>(out[k]);
  }
}

// Float columns: overlap and classify in float lanes, first_contact's swept balls (which
// read only the exact float centers, radii, velocities and t_max) in double lanes.
template <int N, class C>
void certify(BatchQuery query, const C* const* columns, std::size_t begin, std::size_t end, double tol,
             signed char* codes) {
  const Band band{tol, float_band(tol)};
  if constexpr (std::is_same_v<C, float>) {
    if (query != BatchQuery::contact)
      return filter<N>(hn::ScalableTag<float>(), query, columns, begin, end, band, codes);
  }
  filter<N>(hn::ScalableTag<double>(), query, columns, begin, end, band, codes);
}

void CertifyDouble(int dim, BatchQuery query, const double* const* columns, std::size_t begin, std::size_t end,
                   double tol, signed char* codes) {
  (dim == 2 ? certify<2, double> : certify<3, double>)(query, columns, begin, end, tol, codes);
}

void CertifyFloat(int dim, BatchQuery query, const float* const* columns, std::size_t begin, std::size_t end,
                  double tol, signed char* codes) {
  (dim == 2 ? certify<2, float> : certify<3, float>)(query, columns, begin, end, tol, codes);
}

const char* TargetInUse() { return hwy::TargetName(HWY_TARGET); }

}  // namespace ellipsect::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <ellipsect/batch.hpp>

namespace ellipsect {
namespace detail {

HWY_EXPORT(CertifyDouble);
HWY_EXPORT(CertifyFloat);
HWY_EXPORT(TargetInUse);

void certify_pairs(int dim, BatchQuery query, const double* const* columns, std::size_t begin, std::size_t end,
                   double tol, signed char* codes) {
  HWY_DYNAMIC_DISPATCH(CertifyDouble)(dim, query, columns, begin, end, tol, codes);
}

void certify_pairs(int dim, BatchQuery query, const float* const* columns, std::size_t begin, std::size_t end,
                   double tol, signed char* codes) {
  HWY_DYNAMIC_DISPATCH(CertifyFloat)(dim, query, columns, begin, end, tol, codes);
}

std::string target_in_use() { return HWY_DYNAMIC_DISPATCH(TargetInUse)(); }

namespace {

// The CPU's targets, recorded before any pinning narrows what Highway reports.
const std::vector<std::int64_t>& available_targets() {
  static const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  return targets;
}

}  // namespace
}  // namespace detail

std::vector<std::string> simd_targets() {
  std::vector<std::string> names;
  for (const auto t : detail::available_targets()) names.emplace_back(hwy::TargetName(t));
  return names;
}

std::string simd_target() { return detail::target_in_use(); }

void set_simd_target(const std::string& name) {
  if (name.empty()) {
    hwy::SetSupportedTargetsForTest(0);
    return;
  }
  std::string offered;
  for (const auto t : detail::available_targets()) {
    if (name == hwy::TargetName(t)) {
      hwy::SetSupportedTargetsForTest(t);
      return;
    }
    offered += offered.empty() ? "" : ", ";
    offered += hwy::TargetName(t);
  }
  throw InputError("simd_target", "'" + name + "' is not available on this CPU (available: " + offered + ")");
}

}  // namespace ellipsect
#endif  // HWY_ONCE
