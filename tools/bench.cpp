// `ellipsect bench`: times the queries on a scene's pairs and prints queries per second.
#include "broad_phase.hpp"
#include "commands.hpp"
#include "common.hpp"

#include <ellipsect/version.hpp>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

namespace ellipsect::cli {

namespace {

using Clock = std::chrono::steady_clock;

struct Timing {
  std::string query;
  int threads;
  std::uint64_t queries;
  double seconds;
};

template <int N>
int bench(const Input& in, const BenchOptions& opt) {
  const Window w = effective_window(in, opt.common);
  const int max_threads = resolve_threads(opt.common.threads);
  std::vector<std::string> names = opt.queries;
  if (names.empty()) {
    names = {"overlap", "classify"};
    if (in.has_velocity) names.push_back("contact");
  }
  for (const auto& q : names)
    if (q != "overlap" && q != "classify" && q != "contact" && q != "distance")
      throw UsageError("--query: unknown query \"" + q + "\" (available: overlap, classify, contact, distance)");

  const auto t_load = Clock::now();
  PairSet<N> set = load_pair_set<N>(in, opt.common, w, in.has_velocity, opt.limit, 1);
  // Only body pairs are timed: a scene's obstacle pairs are left out.
  std::erase_if(set.pairs, [&](const IndexPair& p) { return p.second >= set.bodies.size(); });
  const double load_s = std::chrono::duration<double>(Clock::now() - t_load).count();
  double broad_s = -1;
  if (set.pairs_from_broad_phase) {
    const auto t0 = Clock::now();
    const auto again = broad_phase<N>(set.bodies, w, in.has_velocity);
    broad_s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (again.size() < set.pairs.size()) throw std::logic_error("broad phase is not deterministic");
  }
  if (set.pairs.empty()) throw BadInput(in.path + ": no pairs to time (the broad phase found none; list pairs)");
  // Bodies at the window start (moved and turned), so the timed loop holds the queries only.
  std::vector<Ellipsoid<double, N>> shapes;
  shapes.reserve(set.bodies.size());
  for (const auto& b : set.bodies) shapes.push_back(shape_at<N>(b, w.t0, in.path));
  const double t_max = w.t1 - w.t0;
  const std::size_t n_pairs = set.pairs.size();

  std::vector<int> thread_counts = {1};
  if (max_threads > 1) thread_counts.push_back(max_threads);
  std::vector<Timing> timings;
  std::atomic<std::uint64_t> sink{0};
  // Each thread makes whole passes over the pairs (starting at its own offset) until the
  // minimum time has passed; throughput is all queries over the wall time.
  for (const auto& q : names) {
    const int kind = q == "overlap" ? 0 : q == "classify" ? 1 : q == "contact" ? 2 : 3;
    auto one_pass = [&](std::size_t offset) {
      std::uint64_t local = 0;
      for (std::size_t i = 0; i < n_pairs; ++i) {
        std::size_t k = i + offset;
        if (k >= n_pairs) k -= n_pairs;
        const auto& a = shapes[set.pairs[k].first];
        const auto& bb = shapes[set.pairs[k].second];
        if (kind == 0) {
          local += overlap(a, bb) ? 1u : 0u;
        } else if (kind == 1) {
          local += static_cast<std::uint64_t>(classify(a, bb));
        } else if (kind == 2) {
          local += static_cast<std::uint64_t>(first_contact(a, set.bodies[set.pairs[k].first].motion, bb,
                                                            set.bodies[set.pairs[k].second].motion, t_max)
                                                  .status);
        } else {
          local += static_cast<std::uint64_t>(signed_distance(a, bb).status);
        }
      }
      return local;
    };
    for (const int threads : thread_counts) {
      sink.fetch_add(one_pass(0), std::memory_order_relaxed);  // warm-up
      std::atomic<std::uint64_t> passes{0};
      const auto start = Clock::now();
      // Exactly `threads` threads, each timing its own passes: a measurement of that thread
      // count, which the shared pool (parallel.hpp: up to its workers, late ones not waited
      // for) does not promise; the program's work runs on the pool.
      std::vector<std::thread> pool;
      for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
          const std::size_t offset = n_pairs * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
          std::uint64_t local = 0, mine = 0;
          do {
            local += one_pass(offset);
            ++mine;
          } while (std::chrono::duration<double>(Clock::now() - start).count() < opt.min_time);
          passes.fetch_add(mine);
          sink.fetch_add(local, std::memory_order_relaxed);
        });
      for (auto& th : pool) th.join();
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      timings.push_back({q, threads, passes.load() * n_pairs, elapsed});
    }
  }

  std::string text;
  if (opt.format == "json") {
    text = "{\n  \"ellipsect\": \"" + std::string(version) + "\",\n  \"scene\": ";
    append_json_string(text, in.path);
    text += ",\n  \"dimension\": " + std::to_string(N) + ",\n  \"bodies\": " + std::to_string(set.bodies.size()) +
            ",\n  \"pairs\": " + std::to_string(n_pairs) + ",\n  \"load_seconds\": ";
    append_number(text, load_s);
    text += ",\n  \"broad_phase_seconds\": ";
    if (broad_s >= 0) append_number(text, broad_s); else text += "null";
    text += ",\n  \"results\": [\n";
    for (std::size_t i = 0; i < timings.size(); ++i) {
      const Timing& t = timings[i];
      text += "    {\"query\": \"" + t.query + "\", \"threads\": " + std::to_string(t.threads) +
              ", \"queries\": " + std::to_string(t.queries) + ", \"seconds\": ";
      append_number(text, t.seconds);
      text += ", \"queries_per_second\": ";
      append_number(text, static_cast<double>(t.queries) / t.seconds);
      text += i + 1 < timings.size() ? "},\n" : "}\n";
    }
    text += "  ]\n}\n";
  } else {
    char line[256];
    std::snprintf(line, sizeof line, "ellipsect bench: %s: %dD, %zu bodies, %zu pairs (%s)\n", in.path.c_str(), N,
                  set.bodies.size(), n_pairs,
                  set.pairs_from_broad_phase ? "broad-phase candidates" : "listed");
    text += line;
    std::snprintf(line, sizeof line, "load %.3f s", load_s);
    text += line;
    if (broad_s >= 0) {
      std::snprintf(line, sizeof line, ", broad phase %.3f ms", broad_s * 1e3);
      text += line;
    }
    text += "\n\n";
    std::snprintf(line, sizeof line, "%-10s %8s %12s %9s %14s %10s\n", "query", "threads", "queries", "seconds",
                  "queries/s", "ns/query");
    text += line;
    for (const Timing& t : timings) {
      const double qps = static_cast<double>(t.queries) / t.seconds;
      std::snprintf(line, sizeof line, "%-10s %8d %12llu %9.3f %14.4g %10.1f\n", t.query.c_str(), t.threads,
                    static_cast<unsigned long long>(t.queries), t.seconds, qps, 1e9 / qps);
      text += line;
    }
  }
  Output out(opt.output);
  out.write(text);
  out.commit();
  return sink.load() == 0xFFFFFFFFFFFFFFFFull ? exit_internal : exit_ok;  // keeps the results alive
}

}  // namespace

int run_bench(const BenchOptions& opt) {
  if (!(opt.min_time >= 0)) throw UsageError("--min-time: must be >= 0");
  if (opt.limit == 0) throw UsageError("--limit: must be > 0");
  Input in = open_input(opt.common.scene);
  in.read_mesh_files = opt.common.read_mesh_files;
  return in.dim == 2 ? bench<2>(in, opt) : bench<3>(in, opt);
}

}  // namespace ellipsect::cli
