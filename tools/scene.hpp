// Scenes: reading and validating the JSON and CSV scene formats (docs/scene-format.md).
//
// Every error is a BadInput whose message starts with the file, then the line (CSV) or the
// JSON path, then the field: "scene.json: $.bodies[2].radii[1]: must be > 0, got -1",
// "pairs.csv:17: column a_rx: must be > 0, got -1".
#pragma once

#include "csv.hpp"

#include <ellipsect/broad_phase.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/obstacles.hpp>
#include <ellipsect/shapes.hpp>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

namespace ellipsect::cli {

inline constexpr double infinity = std::numeric_limits<double>::infinity();

// A body as read from a scene: its shape at time 0 and its rigid motion (contact.hpp): a
// constant velocity and a constant angular velocity about its center (CSV bodies: zero).
template <int N>
struct Body {
  std::string id;  // empty for bodies of a pairs CSV without a_id / b_id columns
  Ellipsoid<double, N> shape;
  RigidMotion<double, N> motion;
};

// True when the body turns: a non-zero angular velocity.
template <int N>
bool turns(const Body<N>& b) {
  if constexpr (N == 2) {
    return b.motion.angular_velocity != 0.0;
  } else {
    return !b.motion.angular_velocity.isZero(0.0);
  }
}

// True when the body moves or turns.
template <int N>
bool moves(const Body<N>& b) {
  return !b.motion.velocity.isZero() || turns<N>(b);
}

// The body's shape at time t: moved by t * velocity and, when it turns, turned about its
// center (the library's body_at). Throws BadInput naming the scene `file` and the body where
// that leaves the range of double.
template <int N>
Ellipsoid<double, N> shape_at(const Body<N>& b, double t, const std::string& file);

// An obstacle of a JSON scene: a half-space (half-plane), a triangle, an oriented box, a
// capsule (stadium in 2D) or a triangle mesh, moving as a whole at a constant velocity
// (`shape` is its place at time 0).
template <int N>
struct Obstacle {
  std::string id;
  AnyObstacle<double, N> shape;  // one of ellipsect/obstacles.hpp's list
  Vec<double, N> velocity;
};

// "half_space", "triangle", "box", "capsule" or "mesh" (obstacle_name): the obstacle's `type`
// in the scene.
template <int N>
const char* obstacle_type(const Obstacle<N>& o);

// The obstacle at time t: shape moved by t * velocity (a mesh rebuilt, its triangles keeping
// their indices). Throws BadInput naming the scene `file` and the obstacle where that leaves
// the range of double.
template <int N>
Obstacle<N> obstacle_at(const Obstacle<N>& o, double t, const std::string& file);

// The time window [t0, t1] (t1 may be +infinity) in which first contact is searched; the
// relation is reported at t0.
struct Window {
  double t0 = 0.0;
  double t1 = infinity;
};

enum class InputKind { json, bodies_csv, pairs_csv };

using ellipsect::IndexPair;  // (i, j) indices into a scene's bodies

// A scene file opened and its header understood (JSON parsed; CSV header read).
struct Input {
  std::string path;
  InputKind kind = InputKind::json;
  int dim = 0;
  bool has_velocity = false;  // something moves: a velocity or angular velocity (field or column)
  bool window_given = false;  // the scene sets a time window
  Window window;
  std::string title;                 // JSON "title", else the file name
  nlohmann::json json;               // kind json
  std::vector<std::string> columns;  // kind *_csv: header fields
  std::uint64_t header_line = 0;     // kind *_csv: line number of the header
  bool has_obstacles = false;        // kind json: an "obstacles" array with at least one
  bool has_mesh = false;             // kind json: some obstacle is a mesh
  bool read_mesh_files = true;       // false: a mesh "file" is bad input (the scene fuzz target)
};

// Opens a scene: JSON when the name ends in .json (or, with another ending, the first
// character is '{'), else CSV; a CSV header with a_x is a pairs CSV, with x a bodies CSV.
Input open_input(const std::string& path);

// Pair (i, j) of a scene with n bodies: bodies i and j when j < n, else body i and obstacle
// j - n (an obstacle is always second).
template <int N>
struct BodyScene {
  std::vector<Body<N>> bodies;
  std::vector<Obstacle<N>> obstacles;  // JSON only
  bool pairs_listed = false;     // JSON "pairs" present
  std::vector<IndexPair> pairs;  // file order
};

// Bodies, obstacles (and listed pairs) of a JSON scene, or the bodies of a bodies CSV. Mesh
// files are read relative to the scene's directory.
template <int N>
BodyScene<N> load_bodies(const Input& in);

// Map from id to index: bodies 0..n-1, then obstacles n, n + 1, ...
template <int N>
std::unordered_map<std::string, std::uint32_t> id_index(const std::vector<Body<N>>& bodies,
                                                        const std::vector<Obstacle<N>>& obstacles = {});

// A pairs file: CSV with columns a,b (ids), one pair per row, streamed. `bodies`: the
// number of bodies; ids at or after it (id_index) are obstacles, allowed in column b only.
class PairsFile {
public:
  PairsFile(const std::string& path, const std::unordered_map<std::string, std::uint32_t>& ids, std::uint32_t bodies);
  // Appends up to `max` pairs to `out`; returns how many (0 at the end).
  std::size_t read(std::vector<IndexPair>& out, std::size_t max);
  double progress() const;
  std::uint64_t rows() const noexcept { return rows_; }

private:
  LineReader reader_;
  const std::unordered_map<std::string, std::uint32_t>& ids_;
  std::uint32_t bodies_;
  int col_a_ = -1, col_b_ = -1;
  std::size_t n_columns_ = 0;
  std::uint64_t rows_ = 0;
  std::string line_, scratch_;
  std::vector<std::string_view> fields_;
};

// Column indices of one body in a CSV (-1: absent).
template <int N>
struct BodyColumns {
  std::string prefix;  // "", "a_" or "b_"
  int id = -1;
  int center[N];
  int radii[N];
  int angle = -1;  // 2D
  int q[4];        // 3D: qw, qx, qy, qz
  int velocity[N];
};

template <int N>
struct PairColumns {
  BodyColumns<N> a, b;
  std::size_t count = 0;  // fields per row
};

template <int N>
PairColumns<N> pair_columns(const Input& in);

// Scratch space for row parsing (one per thread).
struct RowScratch {
  std::vector<std::string_view> fields;
  std::string unquoted;
};

// Parses and validates one data row of a pairs CSV.
template <int N>
std::pair<Body<N>, Body<N>> parse_pair_row(std::string_view line, std::uint64_t line_number,
                                           const PairColumns<N>& columns, const std::string& path,
                                           RowScratch& scratch);

// Reads up to `limit` rows of a pairs CSV into memory (for render and bench): bodies
// 2k and 2k+1 form pair k.
template <int N>
void load_pair_rows(const Input& in, std::size_t limit, std::vector<Body<N>>& bodies, std::vector<IndexPair>& pairs,
                    std::uint64_t first_row = 1);

}  // namespace ellipsect::cli
