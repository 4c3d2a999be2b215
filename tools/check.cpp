// `ellipsect check`: the relation (and first contact, signed distance) of every pair,
// streamed in input order, computed on all cores.
#include "broad_phase.hpp"
#include "commands.hpp"
#include "common.hpp"

#include <ellipsect/version.hpp>

#include <array>
#include <chrono>
#include <cstdio>
#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <type_traits>
#include <unordered_map>
#include <variant>

namespace ellipsect::cli {

namespace {

constexpr std::size_t chunk_size = 16384;  // pairs read, evaluated and written together
constexpr std::size_t block_size = 256;    // pairs per unit of parallel work
constexpr std::size_t report_all_limit = 1000;  // bodies: up to this many, --report auto lists every pair

constexpr int n_relations = 6;
constexpr int n_statuses = 6;
constexpr int n_distance_statuses = 4;

struct Counters {
  std::uint64_t pairs = 0;
  std::array<std::uint64_t, n_relations> relation{};
  std::array<std::uint64_t, n_statuses> contact{};
  std::array<std::uint64_t, n_distance_statuses> distance{};
  void add(const Counters& o) {
    pairs += o.pairs;
    for (int i = 0; i < n_relations; ++i) relation[static_cast<std::size_t>(i)] += o.relation[static_cast<std::size_t>(i)];
    for (int i = 0; i < n_statuses; ++i) contact[static_cast<std::size_t>(i)] += o.contact[static_cast<std::size_t>(i)];
    for (int i = 0; i < n_distance_statuses; ++i)
      distance[static_cast<std::size_t>(i)] += o.distance[static_cast<std::size_t>(i)];
  }
};

struct BlockOut {
  std::string text;
  Counters counts;
  std::string error;
};

enum class Format { json, csv };

void append_vec(std::string& out, const double* v, int n) {
  out += '[';
  for (int i = 0; i < n; ++i) {
    if (i) out += ", ";
    append_number(out, v[i]);
  }
  out += ']';
}

// `, "key": ` and a number or a vector of n values, or null where it is not defined.
void append_field(std::string& out, const char* key, bool defined, const double* v, int n) {
  out += ", \"";
  out += key;
  out += "\": ";
  if (!defined) {
    out += "null";
  } else if (n == 1) {
    append_number(out, *v);
  } else {
    append_vec(out, v, n);
  }
}

// `"name": {"status": "...", ` as the start of a query's JSON object.
void open_object(std::string& out, const char* name, std::string_view status) {
  out += ", \"";
  out += name;
  out += "\": {\"status\": \"";
  out += status;
  out += '"';
}

// A normal as written: zero components without their sign (0, not -0).
template <int N>
Vec<double, N> unsigned_zeros(const Vec<double, N>& v) {
  return v.unaryExpr([](double x) { return x == 0.0 ? 0.0 : x; });
}

template <int N>
void append_record(std::string& out, Format format, std::uint64_t index, std::uint64_t line, const std::string* a,
                   const std::string* b, const PairResult<N>& r, const Queries& q) {
  const Contact<double, N>& c = r.contact;
  const Distance<double, N>& d = r.distance;
  const Vec<double, N> contact_normal = unsigned_zeros<N>(c.normal), distance_normal = unsigned_zeros<N>(d.normal);
  // Only read when the contact / distance was computed (the fields are set then).
  const bool has_point = q.contact && std::isfinite(c.point[0]);
  const bool has_time = q.contact && std::isfinite(c.time);
  const bool has_distance = q.distance && std::isfinite(d.distance);
  const bool has_witness = q.distance && std::isfinite(d.point_a[0]);
  if (format == Format::json) {
    out += "    {\"index\": ";
    out += std::to_string(index);
    if (line != 0) {
      out += ", \"line\": ";
      out += std::to_string(line);
    }
    out += ", \"a\": ";
    if (a != nullptr) append_json_string(out, *a); else out += "null";
    out += ", \"b\": ";
    if (b != nullptr) append_json_string(out, *b); else out += "null";
    if (q.relation) {
      out += ", \"relation\": \"";
      out += to_string(r.relation);
      out += '"';
      if (r.mesh) {
        out += ", \"relation_triangle\": ";
        out += r.relation_triangle >= 0 ? std::to_string(r.relation_triangle) : "null";
      }
    }
    if (q.contact) {
      open_object(out, "contact", to_string(c.status));
      append_field(out, "time", has_time, &c.time, 1);
      append_field(out, "point", has_point, c.point.data(), N);
      append_field(out, "normal", has_point, contact_normal.data(), N);
      out += ", \"iterations\": ";
      out += std::to_string(c.iterations);
      if (r.mesh) {
        out += ", \"triangle\": ";
        out += r.contact_triangle >= 0 ? std::to_string(r.contact_triangle) : "null";
      }
      out += '}';
    }
    if (q.distance) {
      open_object(out, "distance", to_string(d.status));
      append_field(out, "distance", has_distance, &d.distance, 1);
      append_field(out, "point_a", has_witness, d.point_a.data(), N);
      append_field(out, "point_b", has_witness, d.point_b.data(), N);
      append_field(out, "normal", has_witness, distance_normal.data(), N);
      out += ", \"iterations\": ";
      out += std::to_string(d.iterations);
      if (r.mesh) {
        out += ", \"triangle\": ";
        out += r.distance_triangle >= 0 ? std::to_string(r.distance_triangle) : "null";
      }
      out += '}';
    }
    out += '}';
    return;
  }
  out += std::to_string(index);
  if (line != 0) {
    out += ',';
    out += std::to_string(line);
  }
  out += ',';
  if (a != nullptr) append_csv_field(out, *a);
  out += ',';
  if (b != nullptr) append_csv_field(out, *b);
  if (q.relation) {
    out += ',';
    out += to_string(r.relation);
  }
  if (q.contact) {
    out += ',';
    out += to_string(c.status);
    out += ',';
    if (has_time) append_number(out, c.time);
    for (int i = 0; i < N; ++i) {
      out += ',';
      if (has_point) append_number(out, c.point[i]);
    }
    for (int i = 0; i < N; ++i) {
      out += ',';
      if (has_point) append_number(out, contact_normal[i]);
    }
    out += ',';
    out += std::to_string(c.iterations);
  }
  if (q.distance) {
    out += ',';
    out += to_string(d.status);
    out += ',';
    if (has_distance) append_number(out, d.distance);
    for (const Vec<double, N>* v : {&d.point_a, &d.point_b, &distance_normal})
      for (int i = 0; i < N; ++i) {
        out += ',';
        if (has_witness) append_number(out, (*v)[i]);
      }
    out += ',';
    out += std::to_string(d.iterations);
  }
  if (q.triangles) {
    // relation_triangle, contact_triangle, distance_triangle: empty unless b is a mesh and a
    // triangle decides.
    for (const auto& [on, k] : {std::pair{q.relation, r.relation_triangle}, std::pair{q.contact, r.contact_triangle},
                                std::pair{q.distance, r.distance_triangle}}) {
      if (!on) continue;
      out += ',';
      if (k >= 0) out += std::to_string(k);
    }
  }
  out += '\n';
}

std::string csv_header(int dim, bool line_column, const Queries& q) {
  static const char* axes[3] = {"x", "y", "z"};
  std::string h = "index";
  if (line_column) h += ",line";
  h += ",a,b";
  if (q.relation) h += ",relation";
  if (q.contact) {
    h += ",contact_status,contact_time";
    for (int i = 0; i < dim; ++i) h += std::string(",contact_") + axes[i];
    for (int i = 0; i < dim; ++i) h += std::string(",normal_") + axes[i];
    h += ",contact_iterations";
  }
  if (q.distance) {
    // normal_x, ... are the contact's normal: the distance's is distance_normal_x, ...
    h += ",distance_status,distance";
    for (const char* v : {"point_a_", "point_b_", "distance_normal_"})
      for (int i = 0; i < dim; ++i) h += std::string(",") + v + axes[i];
    h += ",distance_iterations";
  }
  if (q.triangles && q.relation) h += ",relation_triangle";
  if (q.triangles && q.contact) h += ",contact_triangle";
  if (q.triangles && q.distance) h += ",distance_triangle";
  h += '\n';
  return h;
}

void append_window(std::string& out, const Window& w) {
  out += '[';
  append_number(out, w.t0);
  out += ", ";
  if (std::isfinite(w.t1)) append_number(out, w.t1); else out += "null";
  out += ']';
}

std::string json_header(const Input& in, const Window& w, const Queries& q, const std::string& extra) {
  std::string h = "{\n  \"ellipsect\": \"";
  h += version;
  h += "\",\n  \"scene\": ";
  append_json_string(h, in.path);
  h += ",\n  \"dimension\": " + std::to_string(in.dim) + ",\n";
  h += extra;
  h += "  \"time_window\": ";
  append_window(h, w);
  h += ",\n  \"queries\": [";
  bool first = true;
  for (const auto& [on, name] :
       {std::pair{q.relation, "relation"}, std::pair{q.contact, "contact"}, std::pair{q.distance, "distance"}}) {
    if (!on) continue;
    if (!first) h += ", ";
    h += std::string("\"") + name + "\"";
    first = false;
  }
  h += "],\n  \"results\": [\n";
  return h;
}

std::string json_footer(bool any, std::uint64_t pairs, std::uint64_t listed, const Counters& c, const Queries& q) {
  std::string f = any ? "\n  ],\n" : "  ],\n";
  f += "  \"summary\": {\"pairs\": " + std::to_string(pairs) + ", \"listed\": " + std::to_string(listed);
  // ", "name": {"value": count, ...}" for one enum's counters.
  auto counts = [&f](const char* name, int n, auto value, const auto& counter) {
    f += std::string(", \"") + name + "\": {";
    for (int i = 0; i < n; ++i) {
      if (i) f += ", ";
      f += "\"";
      f += to_string(value(i));
      f += "\": " + std::to_string(counter[static_cast<std::size_t>(i)]);
    }
    f += '}';
  };
  if (q.relation) counts("relation", n_relations, [](int i) { return static_cast<Relation>(i); }, c.relation);
  if (q.contact) counts("contact", n_statuses, [](int i) { return static_cast<ContactStatus>(i); }, c.contact);
  if (q.distance)
    counts("distance", n_distance_statuses, [](int i) { return static_cast<DistanceStatus>(i); }, c.distance);
  f += "}\n}\n";
  return f;
}

template <int N>
void count(Counters& c, const PairResult<N>& r, const Queries& q) {
  ++c.pairs;
  if (q.relation) ++c.relation[static_cast<std::size_t>(r.relation)];
  if (q.contact) ++c.contact[static_cast<std::size_t>(r.contact.status)];
  if (q.distance) ++c.distance[static_cast<std::size_t>(r.distance.status)];
}

Queries resolve_queries(const std::vector<std::string>& names, bool has_velocity) {
  Queries q;
  if (names.empty()) {
    q.relation = true;
    q.contact = has_velocity;
    return q;
  }
  q.relation = false;
  for (const auto& n : names) {
    if (n == "relation") {
      q.relation = true;
    } else if (n == "contact") {
      q.contact = true;
    } else if (n == "distance") {
      q.distance = true;
    } else {
      throw UsageError("--query: unknown query \"" + n + "\" (available: relation, contact, distance)");
    }
  }
  return q;
}

// One pair's record and counts added to its block.
template <int N>
void add_record(BlockOut& o, Format format, std::uint64_t index, std::uint64_t line, const std::string* a,
                const std::string* b, const PairResult<N>& r, const Queries& q) {
  if (format == Format::json && !o.text.empty()) o.text += ",\n";
  append_record<N>(o.text, format, index, line, a, b, r, q);
  count<N>(o.counts, r, q);
}

// Runs item(k, block, scratch) for k in [0, n) in blocks of block_size on up to `threads`
// threads; each block's text and counts start empty, and the first BadInput of a block
// stops it and is kept as the block's error. Returns the number of blocks.
template <class Item>
std::size_t process_blocks(std::size_t n, int threads, std::vector<BlockOut>& blocks, const Item& item) {
  const std::size_t n_blocks = (n + block_size - 1) / block_size;
  if (blocks.size() < n_blocks) blocks.resize(n_blocks);
  parallel_for(n_blocks, threads, [&](std::size_t blk) {
    BlockOut& o = blocks[blk];
    o.text.clear();
    o.error.clear();
    o.counts = Counters{};
    RowScratch scratch;
    const std::size_t end = std::min(n, (blk + 1) * block_size);
    try {
      for (std::size_t k = blk * block_size; k < end; ++k) item(k, o, scratch);
    } catch (const BadInput& e) {
      o.error = e.what();
    }
  });
  return n_blocks;
}

// Writes records in input order as chunks complete; shared by both kinds of input.
class RecordWriter {
public:
  RecordWriter(Output& out, Format format, std::string header)
      : out_(out), format_(format), header_(std::move(header)) {}

  void write_blocks(const std::vector<BlockOut>& blocks, std::size_t n_blocks) {
    for (std::size_t b = 0; b < n_blocks; ++b)
      if (!blocks[b].error.empty()) throw BadInput(blocks[b].error);
    start();
    for (std::size_t b = 0; b < n_blocks; ++b) {
      const BlockOut& blk = blocks[b];
      if (blk.text.empty()) continue;
      if (format_ == Format::json && any_) out_.write(",\n");
      out_.write(blk.text);
      any_ = true;
      counts.add(blk.counts);
    }
  }
  void start() {
    if (started_) return;
    out_.write(header_);
    started_ = true;
  }
  bool any() const { return any_; }
  Counters counts;

private:
  Output& out_;
  Format format_;
  std::string header_;
  bool started_ = false;
  bool any_ = false;
};

struct Job {
  std::uint32_t i, j;
  bool deduced;  // left out by the broad phase: separated, no contact
};

// Three stages run concurrently: reading chunk k + 1 (one thread), evaluating chunk k (all
// threads) and writing chunk k - 1 (one thread). Chunks and blocks are double-buffered;
// each stage waits for the one that last used its buffer, so output stays in input order.
// Chunk needs: std::uint64_t first, n; double fraction.
template <class Chunk, class Read, class Process>
std::uint64_t run_pipeline(Read&& read, Process&& process, RecordWriter& writer, Progress& progress) {
  Chunk chunks[2];
  std::vector<BlockOut> blocks[2];
  std::size_t n_blocks[2] = {0, 0};
  std::uint64_t total = 0;
  std::future<bool> reading = std::async(std::launch::async, [&] { return read(chunks[0]); });
  std::future<void> writing;
  for (std::size_t k = 0;; ++k) {
    const std::size_t c = k % 2;
    if (!reading.get()) break;
    reading = std::async(std::launch::async, [&, k] { return read(chunks[(k + 1) % 2]); });
    n_blocks[c] = process(chunks[c], blocks[c]);
    total = chunks[c].first + chunks[c].n;
    if (writing.valid()) writing.get();
    const double fraction = chunks[c].fraction;
    writing = std::async(std::launch::async, [&, c, fraction, total] {
      writer.write_blocks(blocks[c], n_blocks[c]);
      progress.update(fraction, total);
    });
  }
  if (writing.valid()) writing.get();
  return total;
}

struct LineChunk {
  std::vector<std::string> lines = std::vector<std::string>(chunk_size);
  std::vector<std::uint64_t> numbers = std::vector<std::uint64_t>(chunk_size);
  std::uint64_t first = 0, n = 0;
  double fraction = -1;
};

struct JobChunk {
  std::vector<Job> jobs;
  std::uint64_t first = 0, n = 0;
  double fraction = -1;
};

template <int N>
int check_pairs_csv(const Input& in, const CheckOptions& opt, const Window& w, const Queries& q, Format format,
                    int threads) {
  const PairColumns<N> columns = pair_columns<N>(in);
  LineReader reader(in.path);
  std::string header_line;
  std::uint64_t line_number = 0;
  reader.next(header_line, line_number);  // header
  Output out(opt.output);
  Progress progress(opt.common.progress, "pairs");
  const auto t_start = std::chrono::steady_clock::now();
  RecordWriter writer(out, format,
                      format == Format::json ? json_header(in, w, q, "") : csv_header(in.dim, true, q));
  std::uint64_t next_index = 0;
  auto read = [&](LineChunk& ch) {
    std::size_t n = 0;
    while (n < chunk_size && reader.next(ch.lines[n], ch.numbers[n])) ++n;
    ch.first = next_index;
    ch.n = n;
    next_index += n;
    ch.fraction = reader.size() ? static_cast<double>(reader.bytes_read()) / static_cast<double>(reader.size()) : -1.0;
    return n > 0;
  };
  auto process = [&](const LineChunk& ch, std::vector<BlockOut>& blocks) {
    return process_blocks(ch.n, threads, blocks, [&](std::size_t k, BlockOut& o, RowScratch& scratch) {
      const auto ab = parse_pair_row<N>(ch.lines[k], ch.numbers[k], columns, in.path, scratch);
      const std::string* a = columns.a.id >= 0 ? &ab.first.id : nullptr;
      const std::string* b = columns.b.id >= 0 ? &ab.second.id : nullptr;
      add_record<N>(o, format, ch.first + k, ch.numbers[k], a, b, evaluate<N>(ab.first, ab.second, w, q, in.path), q);
    });
  };
  const std::uint64_t total = run_pipeline<LineChunk>(read, process, writer, progress);
  if (total == 0) throw BadInput(in.path + ": no pairs (the file has only a header)");
  progress.finish();
  if (format == Format::json) out.write(json_footer(writer.any(), total, total, writer.counts, q));
  out.commit();
  if (opt.stats) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    std::fprintf(stderr, "ellipsect: %llu pairs in %.3f s (%.4g pairs/s, %d threads)\n",
                 static_cast<unsigned long long>(total), s, static_cast<double>(total) / s, threads);
  }
  return exit_ok;
}

// Where check's pairs come from, read on the reading stage only: fill(jobs, max) appends up
// to max jobs and returns how many; fraction() tells how far it has got.
class PairSource {
public:
  virtual ~PairSource() = default;
  virtual std::size_t fill(std::vector<Job>& jobs, std::size_t max) = 0;
  virtual double fraction() const = 0;
};

// The pairs of a pairs file (columns a, b: ids of bodies or obstacles), in its order.
class FilePairs final : public PairSource {
public:
  FilePairs(const std::string& path, std::unordered_map<std::string, std::uint32_t> ids, std::uint32_t bodies)
      : ids_(std::move(ids)), file_(path, ids_, bodies) {}
  std::size_t fill(std::vector<Job>& jobs, std::size_t max) override {
    read_.clear();
    const std::size_t k = file_.read(read_, max);
    for (const auto& [i, j] : read_) jobs.push_back({i, j, false});
    return k;
  }
  double fraction() const override { return file_.progress(); }

private:
  std::unordered_map<std::string, std::uint32_t> ids_;  // before file_, which refers to it
  PairsFile file_;
  std::vector<IndexPair> read_;
};

// A list of pairs: the scene's own, or the broad phase's candidates.
class ListedPairs final : public PairSource {
public:
  explicit ListedPairs(std::vector<IndexPair> pairs) : pairs_(std::move(pairs)) {}
  std::size_t fill(std::vector<Job>& jobs, std::size_t max) override {
    std::size_t k = 0;
    for (; k < max && pos_ < pairs_.size(); ++k, ++pos_) jobs.push_back({pairs_[pos_].first, pairs_[pos_].second, false});
    return k;
  }
  double fraction() const override {
    return pairs_.empty() ? 1.0 : static_cast<double>(pos_) / static_cast<double>(pairs_.size());
  }

private:
  std::vector<IndexPair> pairs_;
  std::size_t pos_ = 0;
};

// Every pair (i, j), i < j < n, in order; with the broad phase's sorted candidates, a pair
// that is not one of them is deduced separated.
class AllPairs final : public PairSource {
public:
  AllPairs(std::uint32_t n, std::optional<std::vector<IndexPair>> candidates)
      : n_(n), candidates_(std::move(candidates)) {}
  std::size_t fill(std::vector<Job>& jobs, std::size_t max) override {
    std::size_t k = 0;
    while (k < max && n_ >= 2 && i_ + 1 < n_) {
      bool deduced = false;
      if (candidates_) {
        const std::vector<IndexPair>& c = *candidates_;
        while (pos_ < c.size() && c[pos_] < IndexPair{i_, j_}) ++pos_;
        deduced = !(pos_ < c.size() && c[pos_] == IndexPair{i_, j_});
      }
      jobs.push_back({i_, j_, deduced});
      ++k;
      if (++j_ == n_) {
        ++i_;
        j_ = i_ + 1;
      }
    }
    return k;
  }
  double fraction() const override {
    const std::uint64_t all = std::uint64_t(n_) * (n_ - 1) / 2;
    const double i = i_, n = n_;
    return all == 0 ? 1.0 : (i * n - i * (i + 1) / 2) / static_cast<double>(all);
  }

private:
  std::uint32_t n_;
  std::optional<std::vector<IndexPair>> candidates_;
  std::size_t pos_ = 0;
  std::uint32_t i_ = 0, j_ = 1;
};

// The body pairs of `bodies`, then every body against every obstacle: (0, n), (0, n + 1), ...
class WithObstacles final : public PairSource {
public:
  WithObstacles(std::unique_ptr<PairSource> bodies, std::uint32_t n, std::uint64_t obstacles)
      : bodies_(std::move(bodies)), n_(n), obstacles_(obstacles) {}
  std::size_t fill(std::vector<Job>& jobs, std::size_t max) override {
    std::size_t k = bodies_->fill(jobs, max);
    for (; k < max && next_ < n_ * obstacles_; ++k, ++next_)
      jobs.push_back({static_cast<std::uint32_t>(next_ / obstacles_), static_cast<std::uint32_t>(n_ + next_ % obstacles_),
                      false});
    return k;
  }
  double fraction() const override {
    return next_ == 0 ? bodies_->fraction() : static_cast<double>(next_) / static_cast<double>(n_ * obstacles_);
  }

private:
  std::unique_ptr<PairSource> bodies_;
  std::uint64_t n_, obstacles_, next_ = 0;
};

// The pairs check runs and how the summary speaks of them: a pairs file, the scene's list,
// or all pairs (reported all, or only the broad phase's candidates with the others counted
// as separated), then the obstacle pairs.
struct PairPlan {
  std::unique_ptr<PairSource> source;
  std::string mode;
  std::uint64_t total = 0;     // pairs the summary speaks for (a pairs file: counted as read)
  std::uint64_t unlisted = 0;  // pairs left out by the broad phase and not listed
  bool from_file = false;
};

template <int N>
PairPlan plan_pairs(const BodyScene<N>& scene, std::size_t n_obstacles, const CheckOptions& opt, const Window& w,
                    const Queries& q) {
  const auto n = static_cast<std::uint32_t>(scene.bodies.size());
  PairPlan plan;
  if (!opt.common.pairs_file.empty()) {
    plan.source = std::make_unique<FilePairs>(opt.common.pairs_file, id_index<N>(scene.bodies, scene.obstacles), n);
    plan.mode = "pairs file";
    plan.from_file = true;
    return plan;
  }
  if (scene.pairs_listed) {
    plan.source = std::make_unique<ListedPairs>(scene.pairs);
    plan.mode = "listed";
    plan.total = scene.pairs.size();
    return plan;
  }
  const std::uint64_t all_pairs = std::uint64_t(n) * (n - 1) / 2, obstacle_pairs = std::uint64_t(n) * n_obstacles;
  plan.total = all_pairs + obstacle_pairs;
  std::string report = opt.report;
  if (report == "auto") report = n <= report_all_limit ? "all" : "candidates";
  if (!opt.broad_phase) report = "all";
  std::optional<std::vector<IndexPair>> candidates;
  if (opt.broad_phase) candidates = broad_phase<N>(scene.bodies, w, q.contact);
  if (report == "candidates") {
    plan.mode = "broad-phase candidates";
    plan.unlisted = all_pairs - candidates->size();
    plan.source = std::make_unique<ListedPairs>(std::move(*candidates));
  } else {
    plan.mode = opt.broad_phase ? "all pairs" : "all pairs, no broad phase";
    plan.source = std::make_unique<AllPairs>(n, std::move(candidates));
  }
  if (obstacle_pairs > 0) plan.source = std::make_unique<WithObstacles>(std::move(plan.source), n, n_obstacles);
  return plan;
}

template <int N>
int check_bodies(const Input& in, const CheckOptions& opt, const Window& w, const Queries& q, Format format,
                 int threads) {
  const auto t_start = std::chrono::steady_clock::now();
  const BodyScene<N> scene = load_bodies<N>(in);
  const auto& bodies = scene.bodies;
  const std::uint64_t n = bodies.size();
  std::vector<Obstacle<N>> obstacles;  // at the window start
  for (const auto& o : scene.obstacles) obstacles.push_back(obstacle_at<N>(o, w.t0, in.path));

  const PairPlan plan = plan_pairs<N>(scene, obstacles.size(), opt, w, q);
  PairSource& source = *plan.source;
  const std::string& pair_mode = plan.mode;
  std::uint64_t total_pairs = plan.total;

  Output out(opt.output);
  Progress progress(opt.common.progress, "pairs");
  std::string extra = "  \"bodies\": " + std::to_string(n) + ",\n";
  if (!obstacles.empty()) extra += "  \"obstacles\": " + std::to_string(obstacles.size()) + ",\n";
  extra += "  \"pair_source\": ";
  append_json_string(extra, pair_mode);
  extra += ",\n";
  RecordWriter writer(out, format, format == Format::json ? json_header(in, w, q, extra) : csv_header(in.dim, false, q));
  // A pair left out by the broad phase is separated, with no contact; its distance is
  // computed.
  const PairResult<N> sep = separated_result<N>();
  Queries distance_only;
  distance_only.options = q.options;
  distance_only.relation = false;
  distance_only.distance = true;
  std::uint64_t next_index = 0;
  auto read = [&](JobChunk& ch) {
    ch.jobs.clear();
    ch.jobs.reserve(chunk_size);
    ch.n = source.fill(ch.jobs, chunk_size);
    ch.first = next_index;
    next_index += ch.n;
    ch.fraction = source.fraction();
    return ch.n > 0;
  };
  auto process = [&](const JobChunk& ch, std::vector<BlockOut>& blocks) {
    return process_blocks(ch.n, threads, blocks, [&](std::size_t k, BlockOut& o, RowScratch&) {
      const Job& jb = ch.jobs[k];
      const Body<N>& a = bodies[jb.i];
      if (jb.j >= n) {
        const Obstacle<N>& ob = obstacles[jb.j - n];
        add_record<N>(o, format, ch.first + k, 0, &a.id, &ob.id, evaluate<N>(a, ob, w, q, in.path), q);
        return;
      }
      const Body<N>& b = bodies[jb.j];
      PairResult<N> r = jb.deduced ? sep : evaluate<N>(a, b, w, q, in.path);
      if (jb.deduced && q.distance) r.distance = evaluate<N>(a, b, w, distance_only, in.path).distance;
      add_record<N>(o, format, ch.first + k, 0, &a.id, &b.id, r, q);
    });
  };
  const std::uint64_t index = run_pipeline<JobChunk>(read, process, writer, progress);
  writer.start();
  progress.finish();
  if (plan.from_file) total_pairs = index;
  Counters c = writer.counts;
  c.relation[static_cast<std::size_t>(Relation::separated)] += q.relation ? plan.unlisted : 0;
  c.contact[static_cast<std::size_t>(ContactStatus::no_contact_in_window)] += q.contact ? plan.unlisted : 0;
  c.distance[static_cast<std::size_t>(DistanceStatus::separated)] += q.distance ? plan.unlisted : 0;
  if (format == Format::json) out.write(json_footer(writer.any(), total_pairs, index, c, q));
  out.commit();
  if (opt.stats) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    std::fprintf(stderr, "ellipsect: %llu bodies, %llu pairs (%s), %llu listed, in %.3f s (%d threads)\n",
                 static_cast<unsigned long long>(n), static_cast<unsigned long long>(total_pairs), pair_mode.c_str(),
                 static_cast<unsigned long long>(index), s, threads);
  }
  return exit_ok;
}

}  // namespace

template <int N>
PairResult<N> evaluate(const Body<N>& a, const Body<N>& b, const Window& window, const Queries& queries,
                       const std::string& file) {
  PairResult<N> r;
  if (window.t0 == 0.0) {
    if (queries.relation) r.relation = classify(a.shape, b.shape, queries.options);
    if (queries.contact) r.contact = first_contact(a.shape, a.motion, b.shape, b.motion, window.t1, queries.options);
    if (queries.distance) r.distance = signed_distance(a.shape, b.shape, queries.options);
    return r;
  }
  // Move (and turn) both bodies to t0; search [t0, t1] as [0, t1 - t0] from there.
  const Ellipsoid<double, N> a0 = shape_at<N>(a, window.t0, file), b0 = shape_at<N>(b, window.t0, file);
  if (queries.relation) r.relation = classify(a0, b0, queries.options);
  if (queries.distance) r.distance = signed_distance(a0, b0, queries.options);
  if (queries.contact) {
    r.contact = first_contact(a0, a.motion, b0, b.motion, window.t1 - window.t0, queries.options);
    r.contact.time += window.t0;
  }
  return r;
}

template <int N>
PairResult<N> evaluate(const Body<N>& a, const Obstacle<N>& b, const Window& window, const Queries& queries,
                       const std::string& file) {
  const Ellipsoid<double, N> a0 = shape_at<N>(a, window.t0, file);
  PairResult<N> r;
  std::visit(
      [&](const auto& shape) {
        using S = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<S, TriangleMesh<double, N>>) {
          r.mesh = true;
          if (queries.relation) {
            const MeshRelation m = classify(a0, shape, queries.options);
            r.relation = m.relation;
            r.relation_triangle = m.triangle;
          }
          if (queries.contact) {
            const MeshContact<double, N> m = first_contact(a0, a.motion, shape, b.velocity, window.t1 - window.t0, queries.options);
            r.contact = m.contact;
            r.contact_triangle = m.triangle;
          }
          if (queries.distance) {
            const MeshDistance<double, N> m = signed_distance(a0, shape, queries.options);
            r.distance = m.distance;
            r.distance_triangle = m.triangle;
          }
        } else {
          if (queries.relation) r.relation = classify(a0, shape, queries.options);
          if (queries.contact) r.contact = first_contact(a0, a.motion, shape, b.velocity, window.t1 - window.t0, queries.options);
          if (queries.distance) r.distance = signed_distance(a0, shape, queries.options);
        }
      },
      b.shape);
  if (queries.contact) r.contact.time += window.t0;
  return r;
}

template <int N>
PairResult<N> separated_result() {
  PairResult<N> r;
  r.relation = Relation::separated;
  r.contact.status = ContactStatus::no_contact_in_window;
  r.contact.time = std::numeric_limits<double>::quiet_NaN();
  r.contact.point.setConstant(std::numeric_limits<double>::quiet_NaN());
  r.contact.normal.setConstant(std::numeric_limits<double>::quiet_NaN());
  r.contact.iterations = 0;
  return r;
}

Window effective_window(const Input& in, const Common& common) {
  if (common.window) return *common.window;
  return in.window;
}

template <int N>
PairSet<N> load_pair_set(const Input& in, const Common& common, const Window& window, bool swept, std::size_t limit,
                         std::uint64_t row) {
  PairSet<N> set;
  if (in.kind == InputKind::pairs_csv) {
    if (!common.pairs_file.empty()) throw UsageError("--pairs applies to bodies scenes, not to a pairs CSV");
    load_pair_rows<N>(in, limit, set.bodies, set.pairs, row);
    return set;
  }
  BodyScene<N> scene = load_bodies<N>(in);
  set.bodies = std::move(scene.bodies);
  set.obstacles = std::move(scene.obstacles);
  const auto n = static_cast<std::uint32_t>(set.bodies.size());
  if (!common.pairs_file.empty()) {
    const auto ids = id_index<N>(set.bodies, set.obstacles);
    PairsFile pf(common.pairs_file, ids, n);
    while (set.pairs.size() < limit && pf.read(set.pairs, limit - set.pairs.size()) > 0) {
    }
  } else if (scene.pairs_listed) {
    set.pairs = std::move(scene.pairs);
  } else {
    set.pairs = broad_phase<N>(set.bodies, window, swept);
    set.pairs_from_broad_phase = true;
    for (std::uint32_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < set.obstacles.size(); ++k)
        set.pairs.emplace_back(i, n + static_cast<std::uint32_t>(k));
  }
  if (set.pairs.size() > limit) set.pairs.resize(limit);
  return set;
}

int run_check(const CheckOptions& opt) {
  Input in = open_input(opt.common.scene);
  in.read_mesh_files = opt.common.read_mesh_files;
  const Window w = effective_window(in, opt.common);
  Queries q = resolve_queries(opt.queries, in.has_velocity);
  q.triangles = in.has_mesh;
  q.options = opt.options;
  const Format format = opt.format == "csv" ? Format::csv : Format::json;
  const int threads = resolve_threads(opt.common.threads);
  if (in.kind == InputKind::pairs_csv) {
    if (!opt.common.pairs_file.empty()) throw UsageError("--pairs applies to bodies scenes, not to a pairs CSV");
    return in.dim == 2 ? check_pairs_csv<2>(in, opt, w, q, format, threads)
                       : check_pairs_csv<3>(in, opt, w, q, format, threads);
  }
  return in.dim == 2 ? check_bodies<2>(in, opt, w, q, format, threads) : check_bodies<3>(in, opt, w, q, format, threads);
}

template PairResult<2> evaluate<2>(const Body<2>&, const Body<2>&, const Window&, const Queries&, const std::string&);
template PairResult<3> evaluate<3>(const Body<3>&, const Body<3>&, const Window&, const Queries&, const std::string&);
template PairResult<2> evaluate<2>(const Body<2>&, const Obstacle<2>&, const Window&, const Queries&,
                                   const std::string&);
template PairResult<3> evaluate<3>(const Body<3>&, const Obstacle<3>&, const Window&, const Queries&,
                                   const std::string&);
template PairResult<2> separated_result<2>();
template PairResult<3> separated_result<3>();
template PairSet<2> load_pair_set<2>(const Input&, const Common&, const Window&, bool, std::size_t, std::uint64_t);
template PairSet<3> load_pair_set<3>(const Input&, const Common&, const Window&, bool, std::size_t, std::uint64_t);

}  // namespace ellipsect::cli
