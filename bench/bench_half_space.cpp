// A body against a half-space: ns per query and wrong answers against the 50-digit reference
// (tests/reference/half_space_reference.hpp), side by side with FCL 0.7 (fcl::collide of an
// fcl::Ellipsoidd and an fcl::Halfspaced, which FCL answers in closed form,
// detail::ellipsoidHalfspaceIntersect; with contacts: its penetration depth and point), on the
// same seeded 3D cases (scenarios/half_space.hpp) per category:
//
//   overlap/*        ellipsect::overlap, fcl::collide (boolean)
//   depth/*          ellipsect::signed_distance, fcl::collide with contacts (penetration depth)
//   first_contact/*  ellipsect::first_contact (FCL's continuousCollide does not take half-spaces)
//
// Counters: median_ns (bench_support.hpp); wrong: answers that differ from the reference's
// (overlap: outside the tangency band 1e-12 rho, the band counted as either answer; depth:
// an error above 1e-9 of scale = largest radius + |depth|, or no depth for an overlapping
// pair); max_err: the largest depth or time error (relative to scale, or to the time).
#include <ellipsect/half_space.hpp>

#include "bench/bench_support.hpp"
#include "scenarios/half_space.hpp"
#include "tests/reference/half_space_reference.hpp"

#include <benchmark/benchmark.h>

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/narrowphase/collision.h>
#endif

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;
using scenarios::Plane;
constexpr int cases_per_category = 256;

struct Item {
  scenarios::PlaneCase<3> c;
  double lower, upper, rho;  // the reference's gaps, rounded
  double time;               // the reference's first contact time (inf: none)
};

const std::vector<Item>& items(int category) {
  static std::vector<std::vector<Item>> cache(scenarios::planes.size() + 1);
  auto& out = cache[static_cast<std::size_t>(category + 1)];
  if (!out.empty()) return out;
  for (int k = 0; k < static_cast<int>(scenarios::planes.size()); ++k) {
    if (category >= 0 && k != category) continue;
    for (int i = 0; i < cases_per_category; ++i) {
      const auto c = scenarios::make_plane_case<3>(scenarios::planes[static_cast<std::size_t>(k)], 900000 + i);
      const reference::Body<3> body{c.a.center(), c.a.axes(), c.a.radii()};
      const auto g = reference::half_space_gaps<3>(body, c.b.point(), c.b.normal());
      const auto t = reference::half_space_contact_time<3>(body, c.b.point(), c.b.normal(), c.va, c.vb, c.t_max);
      out.push_back({c, reference::to_double(g.lower), reference::to_double(g.upper), reference::to_double(g.rho),
                     reference::to_double(t)});
    }
  }
  return out;
}

std::string category_name(int category) {
  return category < 0 ? "mix" : scenarios::name(scenarios::planes[static_cast<std::size_t>(category)]);
}

// Whether an overlap answer is wrong: outside the band, it must be the reference's.
bool wrong_overlap(const Item& it, bool got) {
  const double band = 1e-12 * it.rho;
  if (std::abs(it.lower) <= band) return false;
  return got != (it.lower < 0);
}

void finish(benchmark::State& state, int wrong, double max_err) {
  state.counters["wrong"] = wrong;
  state.counters["max_err"] = max_err;
}

void ellipsect_overlap(benchmark::State& state, int category) {
  const auto& its = items(category);
  int wrong = 0;
  for (const auto& it : its) wrong += wrong_overlap(it, overlap(it.c.a, it.c.b));
  bench::time_cases(state, its, [](const Item& it) { return overlap(it.c.a, it.c.b); });
  finish(state, wrong, 0);
}

void ellipsect_depth(benchmark::State& state, int category) {
  const auto& its = items(category);
  int wrong = 0;
  double max_err = 0;
  for (const auto& it : its) {
    const double err = std::abs(signed_distance(it.c.a, it.c.b).distance - it.lower) /
                       (it.c.a.radii().maxCoeff() + std::abs(it.lower));
    max_err = std::max(max_err, err);
    wrong += err > 1e-9;
  }
  bench::time_cases(state, its, [](const Item& it) { return signed_distance(it.c.a, it.c.b).distance; });
  finish(state, wrong, max_err);
}

void ellipsect_first_contact(benchmark::State& state, int category) {
  const auto& its = items(category);
  int wrong = 0;
  double max_err = 0;
  for (const auto& it : its) {
    const auto c = first_contact(it.c.a, it.c.va, it.c.b, it.c.vb, it.c.t_max);
    if (it.lower <= 0 || std::isinf(it.time)) continue;  // started in contact, or no contact
    if (c.status != ContactStatus::hit) {
      wrong += std::abs(it.time - it.c.t_max) > 1e-12 * it.time && std::abs(it.lower) > 1e-12 * it.rho;
      continue;
    }
    const double err = std::abs(c.time - it.time) / it.time;
    max_err = std::max(max_err, err);
    wrong += err > 1e-9;
  }
  bench::time_cases(state, its,
                    [](const Item& it) { return first_contact(it.c.a, it.c.va, it.c.b, it.c.vb, it.c.t_max).time; });
  finish(state, wrong, max_err);
}

#ifdef ELLIPSECT_HAVE_FCL
// FCL's shapes: the ellipsoid posed by its axes (a reflection's third axis negated: the same
// set), the half-space {x : n . x <= d} with d = n . p.
struct FclItem {
  fcl::Ellipsoidd a;
  fcl::Transform3d pose;
  fcl::Halfspaced b;
};

std::vector<FclItem> fcl_items(const std::vector<Item>& its) {
  std::vector<FclItem> out;
  for (const auto& it : its) {
    fcl::Transform3d pose = fcl::Transform3d::Identity();
    Mat3<double> axes = it.c.a.axes();
    if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
    pose.linear() = axes;
    pose.translation() = it.c.a.center();
    const Vec3<double> n = it.c.b.normal();
    out.push_back({fcl::Ellipsoidd(it.c.a.radii()[0], it.c.a.radii()[1], it.c.a.radii()[2]), pose,
                   fcl::Halfspaced(n, n.dot(it.c.b.point()))});
  }
  return out;
}

fcl::CollisionResultd fcl_collide(const FclItem& f, bool contacts) {
  fcl::CollisionRequestd request;
  request.enable_contact = contacts;
  fcl::CollisionResultd result;
  fcl::collide(&f.a, f.pose, &f.b, fcl::Transform3d::Identity(), request, result);
  return result;
}

void fcl_overlap(benchmark::State& state, int category) {
  const auto& its = items(category);
  const auto fs = fcl_items(its);
  int wrong = 0;
  for (std::size_t i = 0; i < its.size(); ++i) wrong += wrong_overlap(its[i], fcl_collide(fs[i], false).isCollision());
  bench::time_cases(state, fs, [](const FclItem& f) { return fcl_collide(f, false).isCollision(); });
  finish(state, wrong, 0);
}

void fcl_depth(benchmark::State& state, int category) {
  const auto& its = items(category);
  const auto fs = fcl_items(its);
  int wrong = 0;
  double max_err = 0;
  for (std::size_t i = 0; i < its.size(); ++i) {
    if (its[i].lower >= 0) continue;  // FCL reports a depth only for colliding pairs
    const auto r = fcl_collide(fs[i], true);
    if (!r.isCollision() || r.numContacts() == 0) {
      ++wrong;
      continue;
    }
    const double err = std::abs(r.getContact(0).penetration_depth + its[i].lower) /
                       (its[i].c.a.radii().maxCoeff() + std::abs(its[i].lower));
    max_err = std::max(max_err, err);
    wrong += err > 1e-9;
  }
  bench::time_cases(state, fs, [](const FclItem& f) { return fcl_collide(f, true).numContacts(); });
  finish(state, wrong, max_err);
}
#endif

void register_all() {
  for (int category = -1; category < static_cast<int>(scenarios::planes.size()); ++category) {
    const std::string name = category_name(category);
    benchmark::RegisterBenchmark(("overlap/ellipsect/" + name).c_str(), ellipsect_overlap, category);
    benchmark::RegisterBenchmark(("depth/ellipsect/" + name).c_str(), ellipsect_depth, category);
    benchmark::RegisterBenchmark(("first_contact/ellipsect/" + name).c_str(), ellipsect_first_contact, category);
#ifdef ELLIPSECT_HAVE_FCL
    benchmark::RegisterBenchmark(("overlap/fcl/" + name).c_str(), fcl_overlap, category);
    benchmark::RegisterBenchmark(("depth/fcl/" + name).c_str(), fcl_depth, category);
#endif
  }
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
