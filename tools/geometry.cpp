// `ellipsect enclose`, `inscribe` and `fit`: an ellipse or ellipsoid from points (a CSV of x, y
// or x, y, z columns) or a mesh file's vertices (OBJ, STL), written as a one-body JSON scene
// that the other commands read (docs/cli.md).
#include "commands.hpp"
#include "common.hpp"
#include "csv.hpp"
#include "mesh_file.hpp"
#include "output.hpp"

#include <ellipsect/geometry.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace ellipsect::cli {

namespace {

using Points = std::variant<std::vector<Vec<double, 2>>, std::vector<Vec<double, 3>>>;

constexpr std::string_view axis_names[] = {"x", "y", "z"};

std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  std::string e = dot == std::string::npos ? "" : path.substr(dot);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  return e;
}

// The points of a CSV: a header naming the columns x, y (and z; other columns ignored), then
// one point per row. BadInput names the file, the line and the column.
template <int N>
std::vector<Vec<double, N>> csv_points(LineReader& reader, const std::vector<int>& column, std::size_t width) {
  std::vector<Vec<double, N>> out;
  std::string line, scratch;
  std::uint64_t number = 0;
  std::vector<std::string_view> fields;
  while (reader.next(line, number)) {
    const std::string where = reader.path() + ":" + std::to_string(number) + ": ";
    if (const std::string bad = split_csv(line, fields, scratch); !bad.empty()) throw BadInput(where + bad);
    if (fields.size() != width)
      throw BadInput(where + "expected " + std::to_string(width) + " fields (as the header), got " +
                     std::to_string(fields.size()));
    Vec<double, N> p;
    for (int k = 0; k < N; ++k) {
      if (!parse_double(fields[std::size_t(column[std::size_t(k)])], p[k]) || !std::isfinite(p[k]))
        throw BadInput(where + std::string(axis_names[k]) + ": expected a finite number, got '" +
                       std::string(trim(fields[std::size_t(column[std::size_t(k)])])) + "'");
    }
    out.push_back(p);
  }
  return out;
}

Points read_points(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj" || ext == ".stl") {
    const MeshArrays mesh = read_mesh_file(path);
    std::vector<Vec<double, 3>> out(mesh.vertices.size() / 3);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec<double, 3>(mesh.vertices.data() + 3 * i);
    return out;
  }
  LineReader reader(path);
  std::string line, scratch;
  std::uint64_t number = 0;
  std::vector<std::string_view> fields;
  if (!reader.next(line, number)) throw BadInput(path + ": empty: expected a header with columns x, y (and z)");
  if (const std::string bad = split_csv(line, fields, scratch); !bad.empty())
    throw BadInput(path + ":" + std::to_string(number) + ": " + bad);
  std::vector<int> column(3, -1);
  for (std::size_t i = 0; i < fields.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (trim(fields[i]) == axis_names[k]) column[std::size_t(k)] = int(i);
  if (column[0] < 0 || column[1] < 0)
    throw BadInput(path + ":" + std::to_string(number) + ": header: expected columns x, y (and z) (got '" + line + "')");
  const std::size_t width = fields.size();
  if (column[2] < 0) return csv_points<2>(reader, column, width);
  return csv_points<3>(reader, column, width);
}

// The one-body scene: the body (center, radii, rotation: its axes as columns) and a comment
// with the command's answer.
template <int N>
void write_scene(const std::string& path, const std::string& id, const std::string& title, const Ellipsoid<double, N>& body,
                 const std::string& comment) {
  std::string out = "{\n  \"title\": ";
  append_json_string(out, title);
  out += ",\n  \"comment\": ";
  append_json_string(out, comment);
  out += ",\n  \"bodies\": [\n    {\"id\": ";
  append_json_string(out, id);
  const auto list = [&](const auto& v) {
    out += "[";
    for (int k = 0; k < N; ++k) {
      if (k) out += ", ";
      append_number(out, v[k]);
    }
    out += "]";
  };
  out += ", \"center\": ";
  list(body.center());
  out += ", \"radii\": ";
  list(body.radii());
  // A proper rotation (an axis negated where the axes are a reflection: the same body), whose
  // rows the scene reader takes as given (orthonormal to rounding).
  Mat<double, N> axes = body.axes();
  if (axes.determinant() < 0) axes.col(N - 1) = -axes.col(N - 1);
  out += ", \"rotation\": [";
  for (int i = 0; i < N; ++i) {
    if (i) out += ", ";
    list(Vec<double, N>(axes.row(i).transpose()));
  }
  out += "]}\n  ]\n}\n";
  Output file(path);
  file.write(out);
  file.commit();
}

// The library's InputError on the points as the file's BadInput.
template <class F>
auto on_points(const std::string& path, F f) {
  try {
    return f();
  } catch (const RowInputError& e) {
    throw BadInput(path + ": point " + std::to_string(e.row() + 1) + ": " + e.detail());
  } catch (const InputError& e) {
    throw BadInput(path + ": " + std::string(e.what()).substr(std::string("ellipsect: ").size()));
  }
}

// The options set (a bad value: UsageError), the points read, answered (answer(points,
// options): the body and the summary) and written as a scene titled `title` of the input.
template <class Options, class Set, class Answer>
int answer_points(const GeometryOptions& o, Set set, const std::string& title, Answer answer) {
  Options options;
  try {
    set(options);
  } catch (const InputError& e) {
    throw UsageError(std::string(e.what()).substr(std::string("ellipsect: ").size()));
  }
  std::visit(
      [&](const auto& points) {
        const auto [body, summary] = on_points(o.input, [&] { return answer(points, options); });
        write_scene(o.output, o.id, title + o.input, body, summary);
        std::fprintf(stderr, "%s\n", summary.c_str());
      },
      read_points(o.input));
  return exit_ok;
}

template <int N>
std::string points_count(const std::vector<Vec<double, N>>& points) {
  return std::to_string(points.size()) + " points";
}

}  // namespace

int run_enclose(const GeometryOptions& o) {
  const auto set = [&](EnclosingOptions& options) {
    options.volume_gap = o.volume_gap;
    options.max_enclosing_iterations = o.max_iterations;
  };
  return answer_points<EnclosingOptions>(o, set, "Enclosing ellipsoid of ", [](const auto& points, const auto& options) {
    const auto e = enclosing_ellipsoid(std::span(points), options);
    return std::pair(e.body, "enclose: " + std::string(to_string(e.status)) + ", volume within " +
                                 number_string(e.volume_gap) + " of the minimum (certified); every one of the " +
                                 points_count(points) + " inside; " + std::to_string(e.iterations) + " iterations");
  });
}

int run_inscribe(const GeometryOptions& o) {
  const auto set = [&](InscribedOptions& options) {
    options.volume_gap = o.volume_gap;
    options.max_inscribed_iterations = o.max_iterations;
  };
  return answer_points<InscribedOptions>(o, set, "Inscribed ellipsoid of the hull of ", [](const auto& points, const auto& options) {
    const auto faces = hull_half_spaces(std::span(points));
    const auto e = inscribed_ellipsoid(std::span(faces), options);
    if (e.status == InscribedStatus::unbounded || e.status == InscribedStatus::empty)
      throw InputError("points", "their hull " + std::string(e.status == InscribedStatus::empty ? "has no interior" : "is unbounded"));
    return std::pair(e.body, "inscribe: " + std::string(to_string(e.status)) + ", volume within " +
                                 number_string(e.volume_gap) + " of the maximum (certified); inside every one of the " +
                                 std::to_string(faces.size()) + " faces of the hull of the " + points_count(points) +
                                 "; " + std::to_string(e.iterations) + " iterations");
  });
}

int run_fit(const GeometryOptions& o) {
  const auto set = [&](FitOptions& options) {
    options.fit_tolerance = o.fit_tolerance;
    options.max_fit_iterations = o.max_iterations;
  };
  return answer_points<FitOptions>(o, set, "Least-squares ellipsoid of ", [](const auto& points, const auto& options) {
    const auto f = fit_ellipsoid(std::span(points), options);
    return std::pair(f.body, "fit: " + std::string(to_string(f.status)) + ", rms orthogonal residual " +
                                 number_string(f.rms_residual) + ", largest " + number_string(f.max_residual) +
                                 " over " + points_count(points) + "; " + std::to_string(f.iterations) + " iterations");
  });
}

}  // namespace ellipsect::cli
