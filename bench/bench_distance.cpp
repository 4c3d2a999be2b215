// ns per query and error against the 50-digit reference for distances and penetration
// depths, side by side with FCL 0.7 (fcl::distance on fcl::Ellipsoidd, GJK through its
// libccd solver and its own "indep" solver) and libccd 2.1 (ccdGJKPenetration, i.e. GJK +
// EPA, and ccdMPRPenetration, with an ellipsoid support function), all with their default
// tolerances, on the same seeded cases (scenarios/scenarios.hpp), per case category:
//
//   distance/*          separated pairs:   ellipsect::distance, fcl::distance
//   penetration/*       overlapping pairs: ellipsect::signed_distance, fcl::distance with
//                       enable_signed_distance, ccdGJKPenetration, ccdMPRPenetration
//   intersect2/*, area2/*  ellipsect only (no peer computes them)
//   */from_pose/*       the same, both bodies built inside the timed query from their poses
//                       (bench_support.hpp: center, unit quaternion, radii): make_ellipsoid;
//                       FCL's fcl::Ellipsoidd and Transform3d, then fcl::distance on
//                       geometries and transforms; libccd's rotation matrices
//
// Counters: median_ns, the median over pairs of the time of one query (bench_support.hpp;
// Google Benchmark's time is the mean while cycling through the pairs); max_err and
// med_err, the largest and median |d - d_ref| / scale with scale = largest radius of a + of
// b + |d_ref|; fails, the queries that returned no answer (libccd reporting no
// intersection, a non-finite result), left out of the errors. The last name component is
// the category ("mix": the pairs of every category together).
#include <ellipsect/distance.hpp>
#include <ellipsect/intersect2.hpp>

#include "bench/bench_support.hpp"
#include "bench/peers.hpp"
#include "scenarios/scenarios.hpp"
#include "tests/reference/distance_reference.hpp"

#include <benchmark/benchmark.h>

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/narrowphase/distance.h>
#endif

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace ellipsect;
constexpr int cases_per_category = 128;

template <int N>
struct Pair {
  scenarios::Case<N> c;
  double reference;  // signed distance, 50 digits rounded
  double scale;      // largest radius of a + of b + |reference|
};

enum class Set { separated, overlapping };

// The pairs of one category (-1: all) that are separated or overlapping, with their
// reference distances, computed once.
template <int N>
const std::vector<Pair<N>>& pairs(int category, Set set) {
  static std::map<std::pair<int, Set>, std::vector<Pair<N>>> cache;
  const auto key = std::make_pair(category, set);
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  std::vector<Pair<N>> out;
  for (int k = 0; k < static_cast<int>(scenarios::all_categories.size()); ++k) {
    if (category >= 0 && k != category) continue;
    for (int i = 0; i < cases_per_category; ++i) {
      const auto c = scenarios::make_case<N>(scenarios::all_categories[k], 700000 + i);
      if ((classify(c.a, c.b) == Relation::separated) != (set == Set::separated)) continue;
      const auto r = reference::signed_distance<N>({c.a.center(), c.a.axes(), c.a.radii()},
                                                   {c.b.center(), c.b.axes(), c.b.radii()});
      const double d = reference::to_double(r.distance);
      out.push_back({c, d, c.a.radii().maxCoeff() + c.b.radii().maxCoeff() + std::abs(d)});
    }
  }
  return cache[key] = std::move(out);
}

std::string category_name(int category) {
  return category < 0 ? "mix" : std::string(scenarios::name(scenarios::all_categories[category]));
}

// Runs `query` (returning the signed distance, or NaN for no answer) over the pairs:
// errors once, then the shared timing loop.
template <int N, class Prepared, class Query>
void run(benchmark::State& state, const std::vector<Pair<N>>& ps, const std::vector<Prepared>& prepared, Query query) {
  std::vector<double> errors;
  int fails = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double d = query(prepared[i]);
    if (std::isfinite(d))
      errors.push_back(std::abs(d - ps[i].reference) / ps[i].scale);
    else
      ++fails;
  }
  std::sort(errors.begin(), errors.end());
  bench::time_cases(state, prepared, query);
  state.counters["max_err"] = errors.empty() ? NAN : errors.back();
  state.counters["med_err"] = errors.empty() ? NAN : errors[errors.size() / 2];
  state.counters["fails"] = fails;
}

template <int N>
std::vector<scenarios::Case<N>> cases_of(const std::vector<Pair<N>>& ps) {
  std::vector<scenarios::Case<N>> out;
  for (const auto& p : ps) out.push_back(p.c);
  return out;
}

template <int N>
void ellipsect_distance(benchmark::State& state, int category, Set set) {
  const auto& ps = pairs<N>(category, set);
  run<N>(state, ps, cases_of<N>(ps), [set](const scenarios::Case<N>& c) {
    const auto d = set == Set::separated ? distance(c.a, c.b) : signed_distance(c.a, c.b);
    return d.status == DistanceStatus::did_not_converge ? NAN : d.distance;
  });
}

template <class Query>
void run_from_pose(benchmark::State& state, int category, Set set, Query query) {
  const auto& ps = pairs<3>(category, set);
  std::vector<std::pair<bench::Pose3, bench::Pose3>> poses;
  for (const auto& p : ps) poses.emplace_back(bench::pose_of(p.c.a), bench::pose_of(p.c.b));
  run<3>(state, ps, poses, query);
}

void ellipsect_distance_from_pose(benchmark::State& state, int category, Set set) {
  run_from_pose(state, category, set, [set](const std::pair<bench::Pose3, bench::Pose3>& p) {
    const auto a = bench::body_of(p.first), b = bench::body_of(p.second);
    const auto d = set == Set::separated ? distance(a, b) : signed_distance(a, b);
    return d.status == DistanceStatus::did_not_converge ? NAN : d.distance;
  });
}

void ellipsect_intersect(benchmark::State& state, int category) {
  bench::time_cases(state, cases_of<2>(pairs<2>(category, Set::overlapping)),
                    [](const scenarios::Case<2>& c) { return intersect_boundaries(c.a, c.b); });
}

void ellipsect_area(benchmark::State& state, int category) {
  bench::time_cases(state, cases_of<2>(pairs<2>(category, Set::overlapping)),
                    [](const scenarios::Case<2>& c) { return overlap_area(c.a, c.b); });
}

#ifdef ELLIPSECT_HAVE_FCL
struct FclPair {
  std::shared_ptr<fcl::CollisionObjectd> a, b;
};

using bench::fcl_object;

void fcl_distance(benchmark::State& state, int category, Set set, fcl::GJKSolverType solver) {
  const auto& ps = pairs<3>(category, set);
  std::vector<FclPair> objects;
  for (const auto& p : ps) objects.push_back({fcl_object(p.c.a), fcl_object(p.c.b)});
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  request.enable_signed_distance = set == Set::overlapping;
  request.gjk_solver_type = solver;
  run<3>(state, ps, objects, [&](const FclPair& o) {
    fcl::DistanceResultd result;
    fcl::distance(o.a.get(), o.b.get(), request, result);
    return result.min_distance;
  });
}

void fcl_distance_from_pose(benchmark::State& state, int category, Set set, fcl::GJKSolverType solver) {
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  request.enable_signed_distance = set == Set::overlapping;
  request.gjk_solver_type = solver;
  run_from_pose(state, category, set, [&](const std::pair<bench::Pose3, bench::Pose3>& p) {
    const fcl::Ellipsoidd a = bench::fcl_shape(p.first), b = bench::fcl_shape(p.second);
    fcl::DistanceResultd result;
    fcl::distance(&a, bench::fcl_pose(p.first), &b, bench::fcl_pose(p.second), request, result);
    return result.min_distance;
  });
}
#endif

#ifdef ELLIPSECT_HAVE_CCD
using bench::CcdBody;
using bench::ccd_center;
using bench::ccd_support;

using CcdPenetration = int (*)(const void*, const void*, const ccd_t*, ccd_real_t*, ccd_vec3_t*, ccd_vec3_t*);

ccd_t ccd_setup() {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd_support;
  ccd.support2 = ccd_support;
  ccd.center1 = ccd_center;
  ccd.center2 = ccd_center;
  ccd.max_iterations = 1000;
  return ccd;
}

void ccd_penetration(benchmark::State& state, int category, CcdPenetration method) {
  const auto& ps = pairs<3>(category, Set::overlapping);
  std::vector<std::pair<CcdBody, CcdBody>> bodies;
  for (const auto& p : ps)
    bodies.push_back({{p.c.a.axes(), p.c.a.radii(), p.c.a.center()}, {p.c.b.axes(), p.c.b.radii(), p.c.b.center()}});
  const ccd_t ccd = ccd_setup();
  run<3>(state, ps, bodies, [&](const std::pair<CcdBody, CcdBody>& b) {
    ccd_real_t depth;
    ccd_vec3_t dir, pos;
    return method(&b.first, &b.second, &ccd, &depth, &dir, &pos) == 0 ? -depth : NAN;
  });
}

void ccd_penetration_from_pose(benchmark::State& state, int category, CcdPenetration method) {
  const ccd_t ccd = ccd_setup();
  run_from_pose(state, category, Set::overlapping, [&](const std::pair<bench::Pose3, bench::Pose3>& p) {
    const CcdBody a = bench::ccd_body(p.first), b = bench::ccd_body(p.second);
    ccd_real_t depth;
    ccd_vec3_t dir, pos;
    return method(&a, &b, &ccd, &depth, &dir, &pos) == 0 ? -depth : NAN;
  });
}
#endif

void register_all() {
  const int categories = static_cast<int>(scenarios::all_categories.size());
  for (int category = -1; category < categories; ++category) {
    const std::string cat = "/" + category_name(category);
    // Split by classify alone here; the reference distances are computed on first use.
    bool has[2][2] = {{false, false}, {false, false}};  // [N - 2][set]
    for (int k = 0; k < categories; ++k) {
      if (category >= 0 && k != category) continue;
      for (int i = 0; i < cases_per_category; ++i) {
        const auto c2 = scenarios::make_case<2>(scenarios::all_categories[k], 700000 + i);
        const auto c3 = scenarios::make_case<3>(scenarios::all_categories[k], 700000 + i);
        has[0][classify(c2.a, c2.b) == Relation::separated ? 0 : 1] = true;
        has[1][classify(c3.a, c3.b) == Relation::separated ? 0 : 1] = true;
      }
    }
    if (has[1][0]) {
      benchmark::RegisterBenchmark(("distance/3/ellipsect" + cat).c_str(), ellipsect_distance<3>, category, Set::separated);
#ifdef ELLIPSECT_HAVE_FCL
      benchmark::RegisterBenchmark(("distance/3/fcl_libccd" + cat).c_str(), fcl_distance, category, Set::separated,
                                   fcl::GST_LIBCCD);
      benchmark::RegisterBenchmark(("distance/3/fcl_indep" + cat).c_str(), fcl_distance, category, Set::separated,
                                   fcl::GST_INDEP);
#endif
      benchmark::RegisterBenchmark(("distance/3/from_pose/ellipsect" + cat).c_str(), ellipsect_distance_from_pose,
                                   category, Set::separated);
#ifdef ELLIPSECT_HAVE_FCL
      benchmark::RegisterBenchmark(("distance/3/from_pose/fcl_libccd" + cat).c_str(), fcl_distance_from_pose, category,
                                   Set::separated, fcl::GST_LIBCCD);
#endif
    }
    if (has[1][1]) {
      benchmark::RegisterBenchmark(("penetration/3/ellipsect" + cat).c_str(), ellipsect_distance<3>, category,
                                   Set::overlapping);
#ifdef ELLIPSECT_HAVE_FCL
      benchmark::RegisterBenchmark(("penetration/3/fcl_libccd" + cat).c_str(), fcl_distance, category, Set::overlapping,
                                   fcl::GST_LIBCCD);
#endif
#ifdef ELLIPSECT_HAVE_CCD
      benchmark::RegisterBenchmark(("penetration/3/ccd_gjk_epa" + cat).c_str(), ccd_penetration, category,
                                   &ccdGJKPenetration);
      benchmark::RegisterBenchmark(("penetration/3/ccd_mpr" + cat).c_str(), ccd_penetration, category, &ccdMPRPenetration);
#endif
      benchmark::RegisterBenchmark(("penetration/3/from_pose/ellipsect" + cat).c_str(), ellipsect_distance_from_pose,
                                   category, Set::overlapping);
#ifdef ELLIPSECT_HAVE_FCL
      benchmark::RegisterBenchmark(("penetration/3/from_pose/fcl_libccd" + cat).c_str(), fcl_distance_from_pose,
                                   category, Set::overlapping, fcl::GST_LIBCCD);
#endif
#ifdef ELLIPSECT_HAVE_CCD
      benchmark::RegisterBenchmark(("penetration/3/from_pose/ccd_mpr" + cat).c_str(), ccd_penetration_from_pose,
                                   category, &ccdMPRPenetration);
#endif
    }
    if (has[0][0])
      benchmark::RegisterBenchmark(("distance/2/ellipsect" + cat).c_str(), ellipsect_distance<2>, category, Set::separated);
    if (has[0][1]) {
      benchmark::RegisterBenchmark(("penetration/2/ellipsect" + cat).c_str(), ellipsect_distance<2>, category,
                                   Set::overlapping);
      benchmark::RegisterBenchmark(("intersect2/ellipsect" + cat).c_str(), ellipsect_intersect, category);
      benchmark::RegisterBenchmark(("area2/ellipsect" + cat).c_str(), ellipsect_area, category);
    }
  }
}

}  // namespace

int main(int argc, char** argv) { return ellipsect::bench::run_main(argc, argv, register_all); }
