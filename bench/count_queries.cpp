// A fixed workload for instruction counts (valgrind --tool=callgrind), which stay stable
// on a loaded machine where timings do not: each query family runs once over the same
// seeded scenario mix as bench_queries (every category, 64 cases each), in its own
// non-inlined function, so callgrind_annotate --inclusive=yes reports it apart from the
// case generation; the rigid first contact over bench_rigid_contact's pairs of each kind
// (64 each), and over the same bodies against a box and a capsule made from the other
// body. Usage in bench/RESULTS.md ("Instruction counts").
#include <ellipsect/ellipsect.hpp>

#include "scenarios/rigid.hpp"
#include "scenarios/scenarios.hpp"

#include <cstdio>
#include <limits>
#include <vector>

namespace {

using namespace ellipsect;
constexpr int cases_per_category = 64;

template <int N>
std::vector<scenarios::Case<N>> mix() {
  std::vector<scenarios::Case<N>> cases;
  for (const auto c : scenarios::all_categories)
    for (int i = 0; i < cases_per_category; ++i) cases.push_back(scenarios::make_case<N>(c, 900000 + i));
  return cases;
}

// Each returns a checksum so the calls cannot be optimized away.
template <int N>
[[gnu::noinline]] double count_overlap(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) sum += overlap(c.a, c.b);
  return sum;
}

template <int N>
[[gnu::noinline]] double count_classify(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) sum += static_cast<int>(classify(c.a, c.b));
  return sum;
}

template <int N>
[[gnu::noinline]] double count_first_contact(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) sum += first_contact(c.a, c.va, c.b, c.vb, c.t_max).iterations;
  return sum;
}

template <int N>
[[gnu::noinline]] double count_distance(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) sum += signed_distance(c.a, c.b).iterations;
  return sum;
}

template <int N>
[[gnu::noinline]] double count_perram_wertheim(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) sum += perram_wertheim(c.a, c.b).iterations;
  return sum;
}

// a's closest point to b's center.
template <int N>
[[gnu::noinline]] double count_closest_point(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) sum += closest_point(c.a, c.b.center()).signed_distance;
  return sum;
}

// The shapes at rest against a: the half-space through b's center facing a, the triangle
// of b's center and its first two semi-axes' tips.
template <int N>
HalfSpace<double, N> half_space_of(const scenarios::Case<N>& c) {
  const Vec<double, N> d = c.b.center() - c.a.center();
  return make_half_space<double, N>(c.b.center(), d.norm() > 0 ? Vec<double, N>(-d.normalized())
                                                               : Vec<double, N>(Vec<double, N>::UnitX()));
}

template <int N>
Triangle<double, N> triangle_of(const scenarios::Case<N>& c) {
  const Vec<double, N> p = c.b.center();
  return make_triangle<double, N>(p, Vec<double, N>(p + c.b.radii()[0] * c.b.axes().col(0)),
                                  Vec<double, N>(p + c.b.radii()[1] * c.b.axes().col(1)));
}

template <int N>
[[gnu::noinline]] double count_half_space(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) {
    const HalfSpace<double, N> h = half_space_of(c);
    sum += signed_distance(c.a, h).distance + static_cast<int>(first_contact(c.a, c.va, h, c.vb, c.t_max).status);
  }
  return sum;
}

template <int N>
[[gnu::noinline]] double count_triangle_contact(const std::vector<scenarios::Case<N>>& cases) {
  double sum = 0;
  for (const auto& c : cases) sum += static_cast<int>(first_contact(c.a, c.va, triangle_of(c), c.vb, c.t_max).status);
  return sum;
}

// bench_rigid_contact's pairs of one kind, an infinite window made finite as there.
template <scenarios::Spin Kind>
std::vector<scenarios::Moving<3>> moving() {
  std::vector<scenarios::Moving<3>> out;
  for (int i = 0; i < cases_per_category; ++i) {
    scenarios::Moving<3> m = scenarios::make_moving<3>(Kind, 900000 + i);
    if (!(m.t_max < std::numeric_limits<double>::infinity()))
      m.t_max = 4 * ((m.b.center() - m.a.center()).norm() + m.size) / m.speed;
    out.push_back(m);
  }
  return out;
}

template <scenarios::Spin Kind>
[[gnu::noinline]] double count_rigid(const std::vector<scenarios::Moving<3>>& cases) {
  double sum = static_cast<int>(Kind);  // (each kind's function its own: no identical-code folding)
  for (const auto& m : cases) sum += first_contact(m.a, m.ma, m.b, m.mb, m.t_max).iterations;
  return sum;
}

// a turning against the box b.center + b.axes diag(b.radii) [-1, 1]^3, and against the
// capsule along b's first axis with b's second radius, each moving at b's velocity.
template <scenarios::Spin Kind>
[[gnu::noinline]] double count_rigid_box(const std::vector<scenarios::Moving<3>>& cases) {
  double sum = static_cast<int>(Kind);
  for (const auto& m : cases)
    sum += first_contact(m.a, m.ma, make_box<double, 3>(m.b.center(), m.b.axes(), m.b.radii()), m.mb.velocity, m.t_max)
               .iterations;
  return sum;
}

template <scenarios::Spin Kind>
[[gnu::noinline]] double count_rigid_capsule(const std::vector<scenarios::Moving<3>>& cases) {
  double sum = static_cast<int>(Kind);
  for (const auto& m : cases) {
    const Vec<double, 3> half = m.b.radii()[0] * m.b.axes().col(0);
    sum += first_contact(m.a, m.ma, make_capsule<double, 3>(m.b.center() - half, m.b.center() + half, m.b.radii()[1]),
                         m.mb.velocity, m.t_max)
               .iterations;
  }
  return sum;
}

template <scenarios::Spin Kind>
double run_rigid() {
  const auto cases = moving<Kind>();
  return count_rigid<Kind>(cases) + count_rigid_box<Kind>(cases) + count_rigid_capsule<Kind>(cases);
}

template <int N>
double run() {
  const auto cases = mix<N>();
  return count_overlap<N>(cases) + count_classify<N>(cases) + count_first_contact<N>(cases) +
         count_distance<N>(cases) + count_perram_wertheim<N>(cases) + count_closest_point<N>(cases) +
         count_half_space<N>(cases) + count_triangle_contact<N>(cases);
}

}  // namespace

int main() {
  using scenarios::Spin;
  const double rigid = run_rigid<Spin::random>() + run_rigid<Spin::slow>() + run_rigid<Spin::fast>() +
                       run_rigid<Spin::needles>() + run_rigid<Spin::brief>() + run_rigid<Spin::grazing>();
  std::printf("checksum %.17g %.17g %.17g\n", run<2>(), run<3>(), rigid);
  return 0;
}
