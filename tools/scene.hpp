// Scenes: reading and validating the JSON and CSV scene formats (docs/scene-format.md).
//
// Every error is a BadInput whose message starts with the file, then the line (CSV) or the
// JSON path, then the field: "scene.json: $.bodies[2].radii[1]: must be > 0, got -1",
// "pairs.csv:17: column a_rx: must be > 0, got -1".
#pragma once

#include "csv.hpp"

#include <ellipsect/broad_phase.hpp>
#include <ellipsect/shapes.hpp>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace ellipsect::cli {

inline constexpr double infinity = std::numeric_limits<double>::infinity();

// A body as read from a scene: its shape at time 0 and its constant velocity.
template <int N>
struct Body {
  std::string id;  // empty for bodies of a pairs CSV without a_id / b_id columns
  Ellipsoid<double, N> shape;
  Vec<double, N> velocity;
};

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
  bool has_velocity = false;  // some body has a velocity (field or column)
  bool window_given = false;  // the scene sets a time window
  Window window;
  std::string title;                 // JSON "title", else the file name
  nlohmann::json json;               // kind json
  std::vector<std::string> columns;  // kind *_csv: header fields
  std::uint64_t header_line = 0;     // kind *_csv: line number of the header
};

// Opens a scene: JSON when the name ends in .json (or, with another ending, the first
// character is '{'), else CSV; a CSV header with a_x is a pairs CSV, with x a bodies CSV.
Input open_input(const std::string& path);

template <int N>
struct BodyScene {
  std::vector<Body<N>> bodies;
  bool pairs_listed = false;     // JSON "pairs" present
  std::vector<IndexPair> pairs;  // indices into bodies, file order
};

// Bodies (and listed pairs) of a JSON scene or a bodies CSV.
template <int N>
BodyScene<N> load_bodies(const Input& in);

// Map from body id to index.
template <int N>
std::unordered_map<std::string, std::uint32_t> id_index(const std::vector<Body<N>>& bodies);

// A pairs file: CSV with columns a,b (body ids), one pair per row, streamed.
class PairsFile {
public:
  PairsFile(const std::string& path, const std::unordered_map<std::string, std::uint32_t>& ids);
  // Appends up to `max` pairs to `out`; returns how many (0 at the end).
  std::size_t read(std::vector<IndexPair>& out, std::size_t max);
  double progress() const;
  std::uint64_t rows() const noexcept { return rows_; }

private:
  LineReader reader_;
  const std::unordered_map<std::string, std::uint32_t>& ids_;
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
