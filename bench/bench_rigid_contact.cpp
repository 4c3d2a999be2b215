// First contact under rigid motion (contact.hpp) side by side with FCL 0.7's
// fcl::continuousCollide on the same seeded pairs, with the answers that disagree with the
// 50-digit reference (tests/reference/rigid_contact_reference.hpp) counted.
//
// Cases: scenarios::make_moving<3>(kind, 900000 + i), i < 128, for the kinds random (spin
// about the pair's own time scale), slow_spin, fast_spin (3 to 10 turns before the bodies
// can meet), needles_pancakes (aspect 1e3, tumbling) and brief (a spinning needle's tip
// sweeping past a small ball crossing its reach) and grazing (paths that touch within
// 1e-9 of the size or miss by as little); scenarios/rigid.hpp. An infinite window
// is replaced by 4 (distance + size) / speed so that FCL, which needs the end pose, gets a
// window that does not depend on the answer.
//
// BM_rigid_contact3/<method>/<kind>
//   ellipsect         first_contact(a, motion_a, b, motion_b, t_max)
//   ellipsect_linear  first_contact(a, v_a, b, v_b, t_max): the same pairs without their
//                     spin, the linear query's cost on them (not judged: another motion)
//   fcl_screw         fcl::continuousCollide from the poses at t = 0 to those at t = t_max
//   fcl_linear        (body_at), default ContinuousCollisionRequestd (CCDC_NAIVE: fcl::collide
//                     at 10 evenly spaced times, toc_err 1e-4), motion CCDM_SCREW or
//                     CCDM_LINEAR (FCL's "interpolated" motion: the rotation interpolated
//                     between the two poses). Neither can represent more than half a turn:
//                     the end pose holds the orientation modulo a full turn. Answer: no contact
//                     if !is_collide, at the start if time_of_contact = 0, else a hit at
//                     time_of_contact * t_max.
//
// Counters: median_ns (median over pairs of one query), n (pairs the reference decides:
// all but those within 2e-12 of touching at the start and those it leaves unresolved),
// wrong (answers that differ from the reference in hit / at the start / no contact, or a
// hit's time off by more than 1e-6 max(t, size / speed) where the approach is not grazing,
// sine >= 1e-3); of those, missed (a contact in the window answered no contact) and late
// (a hit later than the reference's by more than that tolerance).
//
// Run:
//   cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release && cmake --build build/release
//   build/release/bench/bench_rigid_contact --benchmark_min_time=0.2
#include <ellipsect/contact.hpp>

#include "bench/bench_support.hpp"
#include "bench/peers.hpp"
#include "scenarios/rigid.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/reference/rigid_contact_reference.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <vector>

namespace {

using namespace ellipsect;
namespace ref = ellipsect::reference;
using scenarios::Moving;
using scenarios::Spin;

constexpr int cases_per_kind = 128;
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr std::array kinds = {Spin::random, Spin::slow, Spin::fast, Spin::needles, Spin::brief, Spin::grazing};

using bench::Answer;
using bench::Outcome;
using bench::answer;
struct Truth {
  Answer expected;
  double tolerance;  // on a hit's time (inf: grazing, not judged)
};

const std::vector<Moving<3>>& cases(Spin kind) {
  static std::map<Spin, std::vector<Moving<3>>> cache;
  if (const auto it = cache.find(kind); it != cache.end()) return it->second;
  std::vector<Moving<3>> out;
  for (int i = 0; i < cases_per_kind; ++i) {
    Moving<3> m = scenarios::make_moving<3>(kind, 900000 + static_cast<std::uint64_t>(i));
    if (std::isinf(m.t_max)) m.t_max = 4 * ((m.b.center() - m.a.center()).norm() + m.size) / m.speed;
    out.push_back(m);
  }
  return cache[kind] = out;
}

const std::vector<std::optional<Truth>>& truth(Spin kind) {
  static std::map<Spin, std::vector<std::optional<Truth>>> cache;
  if (const auto it = cache.find(kind); it != cache.end()) return it->second;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::optional<Truth>> out;
  for (const Moving<3>& m : cases(kind)) {
    const auto r = ref::rigid_first_contact<3>(ref::to_ref<3>(m.a), {m.ma.velocity, m.ma.angular_velocity},
                                               ref::to_ref<3>(m.b), {m.mb.velocity, m.mb.angular_velocity}, m.t_max,
                                               2 * Options{}.tolerance);
    if (!r.resolved || r.kind == ref::ContactKind::touching_at_start) {
      out.emplace_back();
    } else if (r.kind == ref::ContactKind::overlapping_at_start) {
      out.push_back(Truth{{Outcome::at_start, 0}, inf});
    } else if (r.kind == ref::ContactKind::none) {
      out.push_back(Truth{{Outcome::none, inf}, inf});
    } else {
      const double t = ref::to_double(r.time);
      const double tol = r.approach_sine < ref::Real(1e-3) ? inf : 1e-6 * std::max(t, m.size / m.speed);
      out.push_back(Truth{{Outcome::hit, t}, tol});
    }
  }
  std::fprintf(stderr, "reference for %s: %.1f s\n", scenarios::name(kind),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return cache[kind] = out;
}

template <class Query>
void run(benchmark::State& state, Spin kind, Query query) {
  const auto& items = cases(kind);
  const auto& want = truth(kind);
  int n = 0, wrong = 0, missed = 0, late = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!want[i]) continue;
    ++n;
    const Answer got = query(items[i]);
    const Answer& w = want[i]->expected;
    const bool time_off = got.outcome == Outcome::hit && w.outcome == Outcome::hit &&
                          !(std::abs(got.time - w.time) <= want[i]->tolerance);
    wrong += got.outcome != w.outcome || time_off;
    missed += w.outcome == Outcome::hit && (got.outcome == Outcome::none || got.outcome == Outcome::failed);
    late += w.outcome == Outcome::hit && got.outcome == Outcome::hit && got.time > w.time + want[i]->tolerance;
  }
  state.counters["n"] = n;
  state.counters["wrong"] = wrong;
  state.counters["missed"] = missed;
  state.counters["late"] = late;
  bench::time_cases(state, items, query);
}


void ellipsect_contact(benchmark::State& state, Spin kind) {
  run(state, kind, [](const Moving<3>& m) { return answer(first_contact(m.a, m.ma, m.b, m.mb, m.t_max)); });
}

void ellipsect_linear(benchmark::State& state, Spin kind) {
  bench::time_cases(state, cases(kind), [](const Moving<3>& m) {
    return answer(first_contact(m.a, m.ma.velocity, m.b, m.mb.velocity, m.t_max));
  });
}

#ifdef ELLIPSECT_HAVE_FCL
void fcl_contact(benchmark::State& state, Spin kind, fcl::CCDMotionType motion) {
  std::map<const Moving<3>*, bench::FclMotion> items;
  for (const Moving<3>& m : cases(kind))
    items[&m] = {bench::fcl_shape(m.a), bench::fcl_shape(m.b),
                 bench::fcl_pose(m.a),  bench::fcl_pose(body_at(m.a, m.ma, m.t_max)),
                 bench::fcl_pose(m.b),  bench::fcl_pose(body_at(m.b, m.mb, m.t_max)),
                 m.t_max};
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = motion;
  run(state, kind, [&](const Moving<3>& m) {
    return bench::answer_from_time(bench::fcl_contact_time(items.at(&m), request));
  });
}
#endif

const int registered = [] {
  for (Spin kind : kinds) {
    const std::string k = scenarios::name(kind);
    benchmark::RegisterBenchmark(("BM_rigid_contact3/ellipsect/" + k).c_str(), ellipsect_contact, kind);
    benchmark::RegisterBenchmark(("BM_rigid_contact3/ellipsect_linear/" + k).c_str(), ellipsect_linear, kind);
#ifdef ELLIPSECT_HAVE_FCL
    benchmark::RegisterBenchmark(("BM_rigid_contact3/fcl_screw/" + k).c_str(), fcl_contact, kind, fcl::CCDM_SCREW);
    benchmark::RegisterBenchmark(("BM_rigid_contact3/fcl_linear/" + k).c_str(), fcl_contact, kind, fcl::CCDM_LINEAR);
#endif
  }
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
