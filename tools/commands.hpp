// The commands of the `ellipsect` program and the per-pair evaluation they share.
#pragma once

#include "output.hpp"
#include "scene.hpp"

#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>

#include <optional>
#include <string>
#include <vector>

namespace ellipsect::cli {

// Which answers `check` computes per pair, and with which Options. A new query family adds
// a flag here, a key in the JSON record and columns at the end of the CSV record.
struct Queries {
  bool relation = true;
  bool contact = false;
  bool distance = false;  // signed distance: separation, or minus the penetration depth
  bool triangles = false;  // the scene has meshes: CSV records end with the deciding triangles
  Options options;         // tolerance and iteration caps of every query
};

template <int N>
struct PairResult {
  Relation relation = Relation::separated;
  Contact<double, N> contact;
  Distance<double, N> distance;
  bool mesh = false;         // b is a mesh: the triangles below are its answer
  std::int64_t relation_triangle = -1;  // the triangle deciding the relation (-1: none)
  std::int64_t contact_triangle = -1;   // the triangle of the contact (-1: none)
  std::int64_t distance_triangle = -1;  // the triangle of the signed distance (-1: none)
};

// Evaluates one pair over the window: the relation and the signed distance at t0, and the
// first contact in [t0, t1] (bodies in rigid motion: the library's rigid first_contact, which
// answers with the translational one, bit for bit, where neither body turns; the contact time
// is absolute). A body moved or turned beyond the range of double at t0 is BadInput naming
// the scene `file` (shape_at).
template <int N>
PairResult<N> evaluate(const Body<N>& a, const Body<N>& b, const Window& window, const Queries& queries,
                       const std::string& file);

// The answer the broad phase implies for a pair it left out: separated, no contact (the
// distance is not implied; the caller evaluates it when asked).
template <int N>
PairResult<N> separated_result();

// Evaluates a body against an obstacle as `evaluate` does two bodies, `b` given as at the
// window start (obstacle_at(b, t0)): the relation and the signed distance at t0 and the
// first contact in [t0, t1] (absolute time; the normal from the body towards the obstacle),
// each from the library's query against that shape (the body in rigid motion, the obstacle
// at its velocity), with its triangle for meshes.
template <int N>
PairResult<N> evaluate(const Body<N>& a, const Obstacle<N>& b_at_t0, const Window& window, const Queries& queries,
                       const std::string& file);

// Settings common to the commands.
struct Common {
  std::string scene;
  std::string pairs_file;            // --pairs: a,b ids (bodies scenes)
  std::optional<Window> window;      // --window overrides the scene's
  int threads = 0;                   // 0: all hardware threads
  Progress::Mode progress = Progress::Mode::automatic;
  bool read_mesh_files = true;       // false: a scene naming a mesh file is bad input (fuzzing)
};

struct CheckOptions {
  Common common;
  std::string output;                 // "" or "-": stdout
  std::string format = "json";        // json | csv
  std::vector<std::string> queries;   // empty: relation, plus contact when there are velocities (never distance)
  std::string report = "auto";        // auto | all | candidates
  bool broad_phase = true;
  bool stats = false;
  Options options;                    // --tolerance, --max-iterations, --max-motion-steps
};

struct RenderOptions {
  Common common;
  std::string output;
  std::optional<double> time;
  std::string plane = "xy";
  int width = 800;
  std::uint64_t row = 1;  // pairs CSV: which row to draw
};

struct BenchOptions {
  Common common;
  std::vector<std::string> queries;  // overlap, classify, contact, distance
  double min_time = 0.5;
  std::size_t limit = 100000;
  std::string format = "text";       // text | json
  std::string output;
};

// enclose and fit: points (CSV with columns x, y [, z]) or a mesh file's vertices (.obj, .stl)
// in, a one-body JSON scene out.
struct GeometryOptions {
  std::string input;
  std::string output;                  // "" or "-": stdout
  std::string id;                      // the body's id in the scene
  double volume_gap = 1e-9;            // enclose, inscribe
  double fit_tolerance = 1e-8;         // fit
  std::int64_t max_iterations = 0;     // the command's cap (Enclosing-, Inscribed-, FitOptions)
};

int run_check(const CheckOptions& options);
int run_enclose(const GeometryOptions& options);
int run_inscribe(const GeometryOptions& options);
int run_fit(const GeometryOptions& options);
int run_render(const RenderOptions& options);
int run_bench(const BenchOptions& options);

// The window to use: --window, else the scene's, else [0, inf).
Window effective_window(const Input& in, const Common& common);

// Bodies and the pairs to evaluate (listed, from --pairs, or from the broad phase), for
// render and bench. `swept`: broad-phase boxes over the window.
template <int N>
struct PairSet {
  std::vector<Body<N>> bodies;
  std::vector<Obstacle<N>> obstacles;
  std::vector<IndexPair> pairs;        // (i, j): an obstacle when j >= bodies.size(), as in BodyScene
  bool pairs_from_broad_phase = false;  // the body pairs; then every body-obstacle pair follows
};

template <int N>
PairSet<N> load_pair_set(const Input& in, const Common& common, const Window& window, bool swept, std::size_t limit,
                         std::uint64_t row);

}  // namespace ellipsect::cli
