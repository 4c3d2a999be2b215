#include "scene.hpp"

#include "common.hpp"
#include "mesh_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <set>

namespace ellipsect::cli {

namespace {

using json = nlohmann::json;

// Largest accepted | |q| - 1 | for quaternions and max |R^T R - I| for rotation matrices;
// within it the value is normalized (orthonormalized), beyond it rejected.
constexpr double orientation_tolerance = 1e-6;

// Deepest nesting of arrays and objects a JSON scene may have (a scene uses 5: the scene, its
// bodies, a body, its rotation, a row). Deeper text is rejected before it is parsed, so that no
// step (parsing, copying, printing, destroying) ever recurses as deep as the input.
constexpr int max_json_depth = 64;

// Longest excerpt of a JSON value quoted in an error message.
constexpr std::size_t max_excerpt = 60;

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw BadInput(where + ": " + what); }

// Ids are UTF-8 (JSON requires it; CSV ids are checked here), so every output can carry them.
void check_utf8(const std::string& where, std::string_view id) {
  const std::size_t bad = invalid_utf8_at(id);
  if (bad == std::string_view::npos) return;
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(id[bad])));
  fail(where, "not valid UTF-8 (byte " + std::string(hex) + " at offset " + std::to_string(bad) +
                  " of the id; save the file as UTF-8)");
}

std::string base_name(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool ends_with(const std::string& s, std::string_view suffix) {
  if (s.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

// Line and column (1-based) of byte offset `pos` in `text`.
std::pair<std::size_t, std::size_t> line_column(const std::string& text, std::size_t pos) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < pos && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return {line, col};
}

// Offset of the first '[' or '{' nested deeper than max_json_depth in `text` (strings
// skipped), or npos.
std::size_t too_deep_at(const std::string& text) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (ch == '\\') {
        escaped = true;
      } else if (ch == '"') {
        in_string = false;
      }
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > max_json_depth) return i;
    } else if (ch == ']' || ch == '}') {
      --depth;  // unbalanced text is the parser's to report
    }
  }
  return std::string::npos;
}

bool blank(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; });
}

// ---------------------------------------------------------------------------------------
// Orientation and shape construction (shared by JSON and CSV)
// ---------------------------------------------------------------------------------------

struct Orientation {
  enum Kind { none, angle, direction, quaternion, rotation } kind = none;
  double angle_value = 0.0;
  double v[9] = {};        // direction (2), quaternion (w, x, y, z), rotation rows (N x N)
  std::function<std::string()> where;  // location for error messages (built only on error)
};

template <int N>
Mat<double, N> checked_rotation(const Orientation& o) {
  Mat<double, N> R;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) R(i, j) = o.v[i * N + j];
  const double dev = (R.transpose() * R - Mat<double, N>::Identity()).cwiseAbs().maxCoeff();
  if (!(dev <= orientation_tolerance))
    fail(o.where(), "not a rotation matrix: max |R^T R - I| = " + number_string(dev) + " exceeds " +
                      number_string(orientation_tolerance));
  if (R.determinant() < 0) fail(o.where(), "is a reflection (determinant -1), not a rotation");
  // Orthonormal to rounding (as the program's enclose and fit write them): taken as given, bit
  // for bit. Farther: made exact by the library's normalization (shapes.hpp: the polar
  // factor), as Python's.
  if (dev <= 8 * N * std::numeric_limits<double>::epsilon()) return R;
  return normalized_rotation<double, N>(R);
}

template <int N>
Ellipsoid<double, N> build_shape(const Vec<double, N>& center, const Vec<double, N>& radii, const Orientation& o,
                                 const std::function<std::string()>& body_where) {
  try {
    if constexpr (N == 2) {
      double angle = 0.0;
      switch (o.kind) {
        case Orientation::none: break;
        case Orientation::angle: angle = o.angle_value; break;
        case Orientation::direction:
          if (o.v[0] == 0.0 && o.v[1] == 0.0) fail(o.where(), "the direction is the zero vector");
          angle = std::atan2(o.v[1], o.v[0]);
          break;
        case Orientation::rotation: {
          const Mat<double, 2> R = checked_rotation<2>(o);
          return Ellipsoid<double, 2>::from_axes(center, R, radii);
        }
        case Orientation::quaternion: fail(o.where(), "a quaternion orients a 3D body; this scene is 2D");
      }
      return make_ellipse<double>(center, angle, radii);
    } else {
      switch (o.kind) {
        case Orientation::none: return make_ellipsoid<double>(center, Mat<double, 3>(Mat<double, 3>::Identity()), radii);
        case Orientation::quaternion: {
          const Eigen::Vector4d q(o.v[0], o.v[1], o.v[2], o.v[3]);
          const double norm = q.norm();
          if (!(std::abs(norm - 1.0) <= orientation_tolerance))
            fail(o.where(), "not a unit quaternion: |q| = " + number_string(norm) +
                              " (quaternions are rejected unless | |q| - 1 | <= 1e-6; write them with more digits, "
                              "or use a rotation matrix)");
          return make_ellipsoid<double>(center, normalized_quaternion<double>(Quat<double>(q[0], q[1], q[2], q[3])), radii);
        }
        case Orientation::rotation: return make_ellipsoid<double>(center, checked_rotation<3>(o), radii);
        case Orientation::angle: fail(o.where(), "an angle orients a 2D body; this scene is 3D (use quaternion or rotation)");
        case Orientation::direction: fail(o.where(), "a direction orients a 2D body; this scene is 3D (use quaternion or rotation)");
      }
      fail(o.where(), "unknown orientation");
    }
  } catch (const InputError& e) {
    // Validated above; the library's own check is the last word.
    throw BadInput(body_where() + ": " + e.what());
  }
}

// ---------------------------------------------------------------------------------------
// JSON
// ---------------------------------------------------------------------------------------

struct JsonCtx {
  const std::string& file;
  std::string at(const std::string& path) const { return file + ": " + path; }
};

// A value quoted in an error message: its JSON text, cut to max_excerpt bytes (at a UTF-8
// character boundary).
std::string excerpt(const json& j) {
  std::string s = j.dump();
  if (s.size() <= max_excerpt) return s;
  std::size_t n = max_excerpt - 3;
  while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
  s.resize(n);
  return s + "...";
}

std::string describe_type(const json& j) {
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_boolean()) return "a boolean";
  if (j.is_null()) return "null";
  if (j.is_array()) return "an array";
  return "an object";
}

double json_number(const JsonCtx& c, const json& j, const std::string& path) {
  if (!j.is_number()) fail(c.at(path), "expected a number, got " + describe_type(j));
  const double x = j.get<double>();
  if (!std::isfinite(x)) fail(c.at(path), "must be finite, got " + number_string(x));
  return x;
}

template <int N>
Vec<double, N> json_vector(const JsonCtx& c, const json& j, const std::string& path, const char* what_dim_from) {
  if (!j.is_array()) fail(c.at(path), "expected an array of " + std::to_string(N) + " numbers, got " + describe_type(j));
  if (j.size() != static_cast<std::size_t>(N))
    fail(c.at(path), "has " + std::to_string(j.size()) + " components, but the scene is " + std::to_string(N) +
                         "D (" + what_dim_from + "); 2D and 3D bodies cannot be mixed in one scene");
  Vec<double, N> v;
  for (int i = 0; i < N; ++i) v[i] = json_number(c, j[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]");
  return v;
}

void check_keys(const JsonCtx& c, const json& obj, const std::string& path, std::initializer_list<const char*> allowed) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      fail(c.at(path + "." + it.key()), "unknown key (allowed here: " + list + ")");
    }
  }
}

std::string json_id(const JsonCtx& c, const json& j, const std::string& path) {
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s.empty()) fail(c.at(path), "must not be empty");
    return s;
  }
  if (j.is_number_integer()) return j.dump();
  fail(c.at(path), "expected a string (or an integer), got " + describe_type(j));
}

// The orientation keys of a body or box at `path` (at most one of angle, direction,
// quaternion, rotation); none: the coordinate axes.
template <int N>
Orientation json_orientation(const JsonCtx& c, const json& jb, const std::string& path, const std::string& dim_from) {
  Orientation o;
  int orientations = 0;
  for (const char* key : {"angle", "direction", "quaternion", "rotation"}) {
    if (!jb.contains(key)) continue;
    ++orientations;
    const std::string kpath = path + "." + key;
    if (orientations > 1) fail(c.at(kpath), "give at most one of angle, direction, quaternion, rotation");
    o.where = [w = c.at(kpath)] { return w; };
    const json& jo = jb[key];
    const std::string k = key;
    if (k == "angle") {
      o.kind = Orientation::angle;
      o.angle_value = json_number(c, jo, kpath);
      if (N != 2) fail(c.at(kpath), "an angle orients a 2D body; this scene is 3D (use quaternion or rotation)");
    } else if (k == "direction") {
      if (N != 2) fail(c.at(kpath), "a direction orients a 2D body; this scene is 3D (use quaternion or rotation)");
      const Vec<double, 2> d = json_vector<2>(c, jo, kpath, dim_from.c_str());
      o.kind = Orientation::direction;
      o.v[0] = d[0];
      o.v[1] = d[1];
    } else if (k == "quaternion") {
      if (N != 3) fail(c.at(kpath), "a quaternion orients a 3D body; this scene is 2D (use angle)");
      if (!jo.is_array() || jo.size() != 4)
        fail(c.at(kpath), "expected an array of 4 numbers [w, x, y, z], got " +
                              (jo.is_array() ? std::to_string(jo.size()) + " elements" : describe_type(jo)));
      o.kind = Orientation::quaternion;
      for (std::size_t i = 0; i < 4; ++i) o.v[i] = json_number(c, jo[i], kpath + "[" + std::to_string(i) + "]");
    } else {
      if (!jo.is_array() || jo.size() != static_cast<std::size_t>(N))
        fail(c.at(kpath), "expected " + std::to_string(N) + " rows of " + std::to_string(N) + " numbers");
      o.kind = Orientation::rotation;
      for (int i = 0; i < N; ++i) {
        const std::string rpath = kpath + "[" + std::to_string(i) + "]";
        const json& row = jo[static_cast<std::size_t>(i)];
        if (!row.is_array() || row.size() != static_cast<std::size_t>(N))
          fail(c.at(rpath), "expected a row of " + std::to_string(N) + " numbers");
        for (int j = 0; j < N; ++j)
          o.v[i * N + j] = json_number(c, row[static_cast<std::size_t>(j)], rpath + "[" + std::to_string(j) + "]");
      }
    }
  }
  return o;
}

// A body's angular velocity at `path`: one number in 2D (radians per unit time,
// counterclockwise), an array of 3 in 3D (the axis times the rate).
template <int N>
decltype(RigidMotion<double, N>::angular_velocity) json_angular_velocity(const JsonCtx& c, const json& j,
                                                                         const std::string& path,
                                                                         const std::string& dim_from) {
  if constexpr (N == 2) {
    if (j.is_array())
      fail(c.at(path), "expected a number (a 2D body turns in its plane: radians per unit time, counterclockwise), "
                       "got an array");
    return json_number(c, j, path);
  } else {
    if (j.is_number())
      fail(c.at(path), "expected an array of 3 numbers (a 3D body turns about an axis: the axis times the rate), "
                       "got a number");
    return json_vector<3>(c, j, path, dim_from.c_str());
  }
}

template <int N>
Body<N> json_body(const JsonCtx& c, const json& jb, std::size_t index, const std::string& dim_from) {
  const std::string path = "$.bodies[" + std::to_string(index) + "]";
  if (!jb.is_object()) fail(c.at(path), "expected an object, got " + describe_type(jb));
  check_keys(c, jb, path,
             {"id", "center", "radii", "radius", "angle", "direction", "quaternion", "rotation", "velocity",
              "angular_velocity", "comment"});
  if (!jb.contains("id")) fail(c.at(path + ".id"), "missing (every body needs an id)");
  std::string id = json_id(c, jb["id"], path + ".id");
  if (!jb.contains("center")) fail(c.at(path + ".center"), "missing");
  const Vec<double, N> center = json_vector<N>(c, jb["center"], path + ".center", dim_from.c_str());
  Vec<double, N> radii;
  if (jb.contains("radii") && jb.contains("radius"))
    fail(c.at(path + ".radius"), "give either radii or radius, not both");
  if (jb.contains("radii")) {
    radii = json_vector<N>(c, jb["radii"], path + ".radii", dim_from.c_str());
    for (int i = 0; i < N; ++i)
      if (!(radii[i] > 0))
        fail(c.at(path + ".radii[" + std::to_string(i) + "]"), "must be > 0, got " + number_string(radii[i]));
  } else if (jb.contains("radius")) {
    const double r = json_number(c, jb["radius"], path + ".radius");
    if (!(r > 0)) fail(c.at(path + ".radius"), "must be > 0, got " + number_string(r));
    radii.setConstant(r);
  } else {
    fail(c.at(path + ".radii"), "missing (give radii, or radius for a circle or sphere)");
  }
  const Orientation o = json_orientation<N>(c, jb, path, dim_from);
  RigidMotion<double, N> motion;
  if (jb.contains("velocity"))
    motion.velocity = json_vector<N>(c, jb["velocity"], path + ".velocity", dim_from.c_str());
  if (jb.contains("angular_velocity"))
    motion.angular_velocity = json_angular_velocity<N>(c, jb["angular_velocity"], path + ".angular_velocity", dim_from);
  return Body<N>{std::move(id), build_shape<N>(center, radii, o, [w = c.at(path)] { return w; }), motion};
}

// What an InputError says of its field, without the "ellipsect: <field>: " prefix.
std::string input_error_detail(const InputError& e) {
  const std::string prefix = "ellipsect: " + e.field() + ": ";
  const std::string what = e.what();
  return what.starts_with(prefix) ? what.substr(prefix.size()) : what;
}

const json& required(const JsonCtx& c, const json& j, const std::string& path, const char* key) {
  if (!j.contains(key)) fail(c.at(path + "." + key), "missing");
  return j[key];
}

// The `index` of a mesh's triangle array at `path`: an integer (its range is from_arrays'
// to check).
std::int64_t json_index(const JsonCtx& c, const json& j, const std::string& path) {
  if (!j.is_number_integer()) fail(c.at(path), "expected a vertex index (an integer), got " + describe_type(j));
  if (j.is_number_unsigned() && j.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX))
    fail(c.at(path), "vertex index " + j.dump() + " is out of range");
  return j.get<std::int64_t>();
}

// The mesh file an obstacle names, read relative to the scene's directory.
template <int N>
TriangleMesh<double, N> json_mesh_file(const JsonCtx& c, const json& jf, const std::string& path, const Input& in) {
  if (!jf.is_string()) fail(c.at(path), "expected a file name, got " + describe_type(jf));
  if constexpr (N == 2) {
    fail(c.at(path), "mesh files (OBJ, STL) are 3D and this scene is 2D; give a 2D mesh inline (vertices, triangles)");
  } else {
    if (!in.read_mesh_files) fail(c.at(path), "mesh files are not read here");
    std::string file = jf.get<std::string>();
    const auto slash = in.path.find_last_of('/');
    if (!file.starts_with('/') && slash != std::string::npos) file = in.path.substr(0, slash + 1) + file;
    try {
      const MeshArrays m = read_mesh_file(file);
      return TriangleMesh<double, 3>::from_arrays(m.vertices, m.triangles);
    } catch (const IoError& e) {
      throw IoError(c.at(path) + ": " + e.what());
    } catch (const BadInput& e) {
      fail(c.at(path), e.what());
    } catch (const InputError& e) {
      fail(c.at(path), file + ": " + e.field() + ": " + input_error_detail(e));
    }
  }
}

template <int N>
Obstacle<N> json_obstacle(const JsonCtx& c, const json& jo, std::size_t index, const std::string& dim_from,
                          const Input& in) {
  const std::string path = "$.obstacles[" + std::to_string(index) + "]";
  const char* dim = dim_from.c_str();
  if (!jo.is_object()) fail(c.at(path), "expected an object, got " + describe_type(jo));
  Obstacle<N> o{json_id(c, required(c, jo, path, "id"), path + ".id"), {}, Vec<double, N>::Zero()};
  const json& jt = required(c, jo, path, "type");
  const std::string type = jt.is_string() ? jt.get<std::string>() : std::string();
  if (jo.contains("velocity")) o.velocity = json_vector<N>(c, jo["velocity"], path + ".velocity", dim);
  // The library's InputErrors name its fields as this format does ("normal", "vertices[1][0]",
  // "half_extents[2]", "radius", "triangles[4][1]"): they are reported under the obstacle's path.
  try {
    if (type == obstacle_name<HalfSpace<double, N>>) {
      check_keys(c, jo, path, {"id", "type", "point", "normal", "velocity", "comment"});
      o.shape = make_half_space<double, N>(json_vector<N>(c, required(c, jo, path, "point"), path + ".point", dim),
                                           json_vector<N>(c, required(c, jo, path, "normal"), path + ".normal", dim));
    } else if (type == obstacle_name<Triangle<double, N>>) {
      check_keys(c, jo, path, {"id", "type", "vertices", "velocity", "comment"});
      const json& jv = required(c, jo, path, "vertices");
      if (!jv.is_array() || jv.size() != 3)
        fail(c.at(path + ".vertices"), "expected 3 vertices, got " +
                                           (jv.is_array() ? std::to_string(jv.size()) : describe_type(jv)));
      std::array<Vec<double, N>, 3> v;
      for (std::size_t k = 0; k < 3; ++k)
        v[k] = json_vector<N>(c, jv[k], path + ".vertices[" + std::to_string(k) + "]", dim);
      o.shape = make_triangle<double, N>(v[0], v[1], v[2]);
    } else if (type == obstacle_name<Box<double, N>>) {
      check_keys(c, jo, path,
                 {"id", "type", "center", "half_extents", "angle", "direction", "quaternion", "rotation", "velocity",
                  "comment"});
      const Vec<double, N> center = json_vector<N>(c, required(c, jo, path, "center"), path + ".center", dim);
      const Vec<double, N> half =
          json_vector<N>(c, required(c, jo, path, "half_extents"), path + ".half_extents", dim);
      // The axes exactly as a body with this orientation has them.
      const Mat<double, N> axes =
          build_shape<N>(center, Vec<double, N>::Ones(), json_orientation<N>(c, jo, path, dim_from),
                         [w = c.at(path)] { return w; })
              .axes();
      o.shape = make_box<double, N>(center, axes, half);
    } else if (type == obstacle_name<Capsule<double, N>>) {
      check_keys(c, jo, path, {"id", "type", "p0", "p1", "radius", "velocity", "comment"});
      const Vec<double, N> p0 = json_vector<N>(c, required(c, jo, path, "p0"), path + ".p0", dim);
      const Vec<double, N> p1 = json_vector<N>(c, required(c, jo, path, "p1"), path + ".p1", dim);
      o.shape = make_capsule<double, N>(p0, p1, json_number(c, required(c, jo, path, "radius"), path + ".radius"));
    } else if (type == obstacle_name<TriangleMesh<double, N>>) {
      check_keys(c, jo, path, {"id", "type", "vertices", "triangles", "file", "velocity", "comment"});
      if (jo.contains("file")) {
        if (jo.contains("vertices") || jo.contains("triangles"))
          fail(c.at(path + ".file"), "give either a file or vertices and triangles, not both");
        o.shape = json_mesh_file<N>(c, jo["file"], path + ".file", in);
      } else {
        const json& jv = required(c, jo, path, "vertices");
        const json& jt3 = required(c, jo, path, "triangles");
        if (!jv.is_array()) fail(c.at(path + ".vertices"), "expected an array of vertices, got " + describe_type(jv));
        if (!jt3.is_array())
          fail(c.at(path + ".triangles"), "expected an array of [i, j, k] index triples, got " + describe_type(jt3));
        std::vector<double> vertices;
        vertices.reserve(jv.size() * N);
        for (std::size_t k = 0; k < jv.size(); ++k) {
          const Vec<double, N> v = json_vector<N>(c, jv[k], path + ".vertices[" + std::to_string(k) + "]", dim);
          vertices.insert(vertices.end(), v.data(), v.data() + N);
        }
        std::vector<std::int64_t> triangles;
        triangles.reserve(jt3.size() * 3);
        for (std::size_t k = 0; k < jt3.size(); ++k) {
          const std::string tpath = path + ".triangles[" + std::to_string(k) + "]";
          if (!jt3[k].is_array() || jt3[k].size() != 3)
            fail(c.at(tpath), "expected 3 vertex indices [i, j, k], got " + excerpt(jt3[k]));
          for (std::size_t j = 0; j < 3; ++j)
            triangles.push_back(json_index(c, jt3[k][j], tpath + "[" + std::to_string(j) + "]"));
        }
        o.shape = TriangleMesh<double, N>::from_arrays(vertices, triangles);
      }
    } else {
      std::vector<std::string_view> names;
      for_each_obstacle<double, N>([&]<class S>() { names.push_back(obstacle_name<S>); });
      std::string known(names[0]);
      for (std::size_t k = 1; k < names.size(); ++k) (known += k + 1 < names.size() ? ", " : " or ") += names[k];
      fail(c.at(path + ".type"), "unknown obstacle type " + excerpt(jt) + " (" + known + ")");
    }
  } catch (const InputError& e) {
    fail(c.at(path + "." + e.field()), input_error_detail(e));
  }
  return o;
}

// The pair (i, j) of ids, checked: not one body twice, an obstacle only second.
void check_pair(const std::string& where, std::uint32_t i, std::uint32_t j, std::uint32_t bodies,
                const std::string& first_id) {
  if (i >= bodies)
    fail(where, "\"" + first_id + "\" is an obstacle: a pair is two bodies or a body and an obstacle, the obstacle second");
  if (i == j) fail(where, "pairs a body with itself");
}

Input open_json(const std::string& path) {
  Input in;
  in.path = path;
  in.kind = InputKind::json;
  const std::string text = read_file(path);
  if (blank(text)) fail(path, "empty file (expected a JSON scene)");
  if (const std::size_t deep = too_deep_at(text); deep != std::string::npos) {
    const auto [line, col] = line_column(text, deep);
    fail(path + ":" + std::to_string(line) + ":" + std::to_string(col),
         "arrays and objects nested deeper than " + std::to_string(max_json_depth) + " levels");
  }
  try {
    in.json = json::parse(text);
  } catch (const json::parse_error& e) {
    const auto [line, col] = line_column(text, e.byte == 0 ? 0 : e.byte - 1);
    std::string what = e.what();
    const auto colon = what.find(": ", what.find("column"));
    if (colon != std::string::npos) what = what.substr(colon + 2);
    fail(path + ":" + std::to_string(line) + ":" + std::to_string(col), "malformed JSON: " + what);
  } catch (const json::out_of_range& e) {
    // Number overflow (1e999): find the literal to point at it.
    std::string what = e.what();
    const auto q1 = what.find('\'');
    const auto q2 = what.rfind('\'');
    std::string where = path;
    if (q1 != std::string::npos && q2 > q1) {
      const std::string literal = what.substr(q1 + 1, q2 - q1 - 1);
      const auto pos = text.find(literal);
      if (pos != std::string::npos) {
        const auto [line, col] = line_column(text, pos);
        where += ":" + std::to_string(line) + ":" + std::to_string(col);
      }
      fail(where, "number " + literal + " is out of range (numbers must be finite)");
    }
    fail(where, std::string("malformed JSON: ") + e.what());
  }
  const JsonCtx c{path};
  const json& j = in.json;
  if (!j.is_object()) fail(c.at("$"), "expected a JSON object with a \"bodies\" array, got " + describe_type(j));
  check_keys(c, j, "$", {"dimension", "bodies", "obstacles", "pairs", "time_window", "title", "comment"});
  if (!j.contains("bodies")) fail(c.at("$.bodies"), "missing");
  const json& bodies = j["bodies"];
  if (!bodies.is_array()) fail(c.at("$.bodies"), "expected an array of bodies, got " + describe_type(bodies));
  if (bodies.empty()) fail(c.at("$.bodies"), "empty (a scene needs at least one body)");
  if (j.contains("dimension")) {
    const json& d = j["dimension"];
    if (!d.is_number_integer() || (d.get<long long>() != 2 && d.get<long long>() != 3))
      fail(c.at("$.dimension"), "must be 2 or 3, got " + excerpt(d));
    in.dim = static_cast<int>(d.get<long long>());
  } else {
    const json& b0 = bodies[0];
    if (!b0.is_object() || !b0.contains("center") || !b0["center"].is_array())
      fail(c.at("$.bodies[0].center"), "missing or not an array (it sets the scene's dimension)");
    const std::size_t n = b0["center"].size();
    if (n != 2 && n != 3)
      fail(c.at("$.bodies[0].center"), "has " + std::to_string(n) + " components; scenes are 2D or 3D");
    in.dim = static_cast<int>(n);
  }
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].is_object() && (bodies[i].contains("velocity") || bodies[i].contains("angular_velocity")))
      in.has_velocity = true;
  if (j.contains("obstacles")) {
    const json& obstacles = j["obstacles"];
    if (!obstacles.is_array()) fail(c.at("$.obstacles"), "expected an array of obstacles, got " + describe_type(obstacles));
    for (const json& o : obstacles) {
      in.has_obstacles = true;
      if (!o.is_object()) continue;  // load_bodies names it
      in.has_velocity = in.has_velocity || o.contains("velocity");
      in.has_mesh = in.has_mesh || (o.contains("type") && o["type"] == "mesh");
    }
  }
  if (j.contains("time_window")) {
    const json& w = j["time_window"];
    if (!w.is_array() || w.size() != 2)
      fail(c.at("$.time_window"), "expected [start, end] (end may be null for no end), got " + excerpt(w));
    in.window.t0 = json_number(c, w[0], "$.time_window[0]");
    in.window.t1 = w[1].is_null() ? infinity : json_number(c, w[1], "$.time_window[1]");
    if (!(in.window.t1 >= in.window.t0))
      fail(c.at("$.time_window[1]"), "the end " + number_string(in.window.t1) + " is before the start " +
                                         number_string(in.window.t0));
    in.window_given = true;
  }
  if (j.contains("title")) {
    if (!j["title"].is_string()) fail(c.at("$.title"), "expected a string, got " + describe_type(j["title"]));
    in.title = j["title"].get<std::string>();
  }
  if (in.title.empty()) in.title = base_name(path);
  return in;
}

// ---------------------------------------------------------------------------------------
// CSV
// ---------------------------------------------------------------------------------------

template <int N>
const char* axis_name(int i) {
  static const char* names[3] = {"x", "y", "z"};
  return names[i];
}

const char* const radius_names[3] = {"rx", "ry", "rz"};
const char* const velocity_names[3] = {"vx", "vy", "vz"};
const char* const quaternion_names[4] = {"qw", "qx", "qy", "qz"};

int find_column(const std::vector<std::string>& cols, const std::string& name) {
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (cols[i] == name) return static_cast<int>(i);
  return -1;
}

template <int N>
BodyColumns<N> body_columns(const Input& in, const std::string& prefix, std::vector<bool>& used, bool need_id) {
  const std::string where = in.path + ":" + std::to_string(in.header_line) + ": header";
  BodyColumns<N> m;
  m.prefix = prefix;
  auto take = [&](const std::string& name) {
    const int k = find_column(in.columns, prefix + name);
    if (k >= 0) used[static_cast<std::size_t>(k)] = true;
    return k;
  };
  m.id = take("id");
  if (need_id && m.id < 0) fail(where, "missing column " + prefix + "id");
  for (int i = 0; i < N; ++i) {
    m.center[i] = take(axis_name<N>(i));
    if (m.center[i] < 0) fail(where, "missing column " + prefix + axis_name<N>(i));
    m.radii[i] = take(radius_names[i]);
    if (m.radii[i] < 0) fail(where, "missing column " + prefix + radius_names[i]);
    m.velocity[i] = take(velocity_names[i]);
  }
  int nv = 0;
  for (int i = 0; i < N; ++i) nv += m.velocity[i] >= 0;
  if (nv != 0 && nv != N) fail(where, "velocity columns of " + (prefix.empty() ? std::string("the bodies") : prefix) +
                                          ": give all of " + prefix + "vx.." + prefix + velocity_names[N - 1] + " or none");
  m.angle = take("angle");
  for (int i = 0; i < 4; ++i) m.q[i] = take(quaternion_names[i]);
  int nq = 0;
  for (int i = 0; i < 4; ++i) nq += m.q[i] >= 0;
  if constexpr (N == 2) {
    if (nq > 0) fail(where, "column " + prefix + "q*: quaternions orient 3D bodies; this CSV is 2D (no z column)");
  } else {
    if (m.angle >= 0) fail(where, "column " + prefix + "angle: angles orient 2D bodies; this CSV is 3D (use qw,qx,qy,qz)");
    if (nq != 0 && nq != 4) fail(where, "quaternion columns: give all of " + prefix + "qw," + prefix + "qx," + prefix +
                                            "qy," + prefix + "qz or none");
  }
  return m;
}

void check_header(const Input& in, const std::vector<bool>& used, const std::string& expected) {
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!used[i])
      fail(in.path + ":" + std::to_string(in.header_line) + ": header", "unknown column \"" + in.columns[i] + "\" (expected: " + expected + ")");
}

template <int N>
std::string expected_columns(const std::string& prefix) {
  std::string s = prefix + "id, ";
  for (int i = 0; i < N; ++i) s += prefix + axis_name<N>(i) + ", ";
  for (int i = 0; i < N; ++i) s += prefix + radius_names[i] + ", ";
  s += N == 2 ? prefix + "angle, " : prefix + "qw, " + prefix + "qx, " + prefix + "qy, " + prefix + "qz, ";
  for (int i = 0; i < N; ++i) s += prefix + velocity_names[i] + (i + 1 < N ? ", " : "");
  return s;
}

struct RowCtx {
  const std::string& path;
  std::uint64_t line;
  const std::vector<std::string_view>& fields;
  std::string at(int col, const std::string& name) const {
    (void)col;
    return path + ":" + std::to_string(line) + ": column " + name;
  }
};

// True when the optional field is present and non-empty.
bool has_value(const RowCtx& r, int col) {
  return col >= 0 && !trim(r.fields[static_cast<std::size_t>(col)]).empty();
}

double row_number(const RowCtx& r, int col, const std::string& prefix, const char* name) {
  const std::string_view f = trim(r.fields[static_cast<std::size_t>(col)]);
  double x = 0;
  if (!f.empty() && parse_double(f, x) && std::isfinite(x)) return x;
  const std::string where = r.at(col, prefix + name);
  if (f.empty()) fail(where, "missing value");
  if (!parse_double(f, x)) fail(where, "not a number: \"" + std::string(f) + "\"");
  fail(where, "must be finite, got " + std::string(f));
}

template <int N>
Body<N> row_body(const RowCtx& r, const BodyColumns<N>& m) {
  const std::string& p = m.prefix;
  Vec<double, N> center, radii;
  RigidMotion<double, N> motion;
  for (int i = 0; i < N; ++i) {
    center[i] = row_number(r, m.center[i], p, axis_name<N>(i));
    radii[i] = row_number(r, m.radii[i], p, radius_names[i]);
    if (!(radii[i] > 0))
      fail(r.at(m.radii[i], p + radius_names[i]), "must be > 0, got " + number_string(radii[i]));
  }
  int nv = 0;
  for (int i = 0; i < N; ++i) nv += has_value(r, m.velocity[i]);
  if (nv != 0 && nv != N)
    fail(r.path + ":" + std::to_string(r.line) + ": columns " + p + "vx.." + p + velocity_names[N - 1],
         "give every velocity component or leave all empty");
  if (nv == N)
    for (int i = 0; i < N; ++i) motion.velocity[i] = row_number(r, m.velocity[i], p, velocity_names[i]);
  Orientation o;
  if constexpr (N == 2) {
    if (has_value(r, m.angle)) {
      o.kind = Orientation::angle;
      o.angle_value = row_number(r, m.angle, p, "angle");
      o.where = [&r, &m] { return r.at(m.angle, m.prefix + "angle"); };
    }
  } else {
    int nq = 0;
    for (int i = 0; i < 4; ++i) nq += has_value(r, m.q[i]);
    const auto qwhere = [&r, &p] {
      return r.path + ":" + std::to_string(r.line) + ": columns " + p + "qw," + p + "qx," + p + "qy," + p + "qz";
    };
    if (nq != 0 && nq != 4) fail(qwhere(), "give all four quaternion components or leave all empty");
    if (nq == 4) {
      o.kind = Orientation::quaternion;
      o.where = qwhere;
      for (int i = 0; i < 4; ++i) o.v[i] = row_number(r, m.q[i], p, quaternion_names[i]);
    }
  }
  std::string id;
  if (m.id >= 0) {
    id = std::string(trim(r.fields[static_cast<std::size_t>(m.id)]));
    if (id.empty() && p.empty()) fail(r.at(m.id, "id"), "missing value");
    check_utf8(r.at(m.id, p + "id"), id);
  }
  return Body<N>{std::move(id),
                 build_shape<N>(center, radii, o, [&r] { return r.path + ":" + std::to_string(r.line); }), motion};
}

void split_row(const std::string& path, std::uint64_t line_number, std::string_view line, std::size_t expected,
               RowScratch& s) {
  const std::string err = split_csv(line, s.fields, s.unquoted);
  if (err.empty() && s.fields.size() == expected) return;
  const std::string where = path + ":" + std::to_string(line_number);
  if (!err.empty()) fail(where, "malformed CSV: " + err);
  fail(where, "malformed CSV: " + std::to_string(s.fields.size()) + " fields, the header has " +
                    std::to_string(expected));
}

Input open_csv(const std::string& path) {
  Input in;
  in.path = path;
  in.title = base_name(path);
  LineReader reader(path);
  std::string line;
  std::uint64_t line_number = 0;
  if (!reader.next(line, line_number)) fail(path, "empty file (expected a CSV header line)");
  RowScratch s;
  const std::string err = split_csv(line, s.fields, s.unquoted);
  if (!err.empty()) fail(path + ":" + std::to_string(line_number), "malformed CSV header: " + err);
  std::set<std::string> seen;
  for (const auto f : s.fields) {
    std::string name(trim(f));
    if (name.empty()) fail(path + ":" + std::to_string(line_number), "malformed CSV header: an empty column name");
    if (!seen.insert(name).second) fail(path + ":" + std::to_string(line_number) + ": header", "column \"" + name + "\" appears twice");
    in.columns.push_back(std::move(name));
  }
  in.header_line = line_number;
  const std::string header_where = path + ":" + std::to_string(line_number) + ": header";
  auto has = [&](const char* name) { return find_column(in.columns, name) >= 0; };
  if (has("a_x") || has("b_x")) {
    in.kind = InputKind::pairs_csv;
    if (has("a_z") != has("b_z"))
      fail(header_where, std::string("column ") + (has("a_z") ? "a_z" : "b_z") +
                                 ": body " + (has("a_z") ? "a" : "b") +
                                 " is 3D but the other is 2D; 2D and 3D bodies cannot be mixed in one scene");
    in.dim = has("a_z") ? 3 : 2;
    in.has_velocity = has("a_vx") || has("b_vx");
  } else if (has("x")) {
    in.kind = InputKind::bodies_csv;
    in.dim = has("z") ? 3 : 2;
    in.has_velocity = has("vx");
  } else {
    fail(header_where, "neither a bodies CSV (columns id, x, y, ...) nor a pairs CSV (columns a_x, a_y, ..., b_x, ...)");
  }
  return in;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Public functions
// ---------------------------------------------------------------------------------------

Input open_input(const std::string& path) {
  if (ends_with(path, ".json")) return open_json(path);
  if (ends_with(path, ".csv")) return open_csv(path);
  // Sniff: JSON starts with '{'.
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError(path + ": cannot open: " + std::strerror(errno));
  char ch = 0;
  while (f.get(ch) && (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r')) {
  }
  if (f && ch == '{') return open_json(path);
  return open_csv(path);
}

template <int N>
std::unordered_map<std::string, std::uint32_t> id_index(const std::vector<Body<N>>& bodies,
                                                        const std::vector<Obstacle<N>>& obstacles) {
  std::unordered_map<std::string, std::uint32_t> ids;
  ids.reserve((bodies.size() + obstacles.size()) * 2);
  for (std::size_t i = 0; i < bodies.size(); ++i) ids.emplace(bodies[i].id, static_cast<std::uint32_t>(i));
  for (std::size_t k = 0; k < obstacles.size(); ++k)
    ids.emplace(obstacles[k].id, static_cast<std::uint32_t>(bodies.size() + k));
  return ids;
}

template <int N>
Ellipsoid<double, N> shape_at(const Body<N>& b, double t, const std::string& file) {
  if (t == 0.0 || !moves<N>(b)) return b.shape;
  try {
    return turns<N>(b) ? body_at<double, N>(b.shape, b.motion, t) : b.shape.translated(b.motion.velocity * t);
  } catch (const InputError& e) {
    throw BadInput(file + ": body " + b.id + " at t = " + number_string(t) + ": " + e.what());
  }
}

template <int N>
const char* obstacle_type(const Obstacle<N>& o) {
  return std::visit([](const auto& shape) { return obstacle_name<std::decay_t<decltype(shape)>>.data(); }, o.shape);
}

template <int N>
Obstacle<N> obstacle_at(const Obstacle<N>& o, double t, const std::string& file) {
  if (t == 0.0 || o.velocity.isZero()) return o;
  const Vec<double, N> offset = o.velocity * t;
  Obstacle<N> moved{o.id, {}, o.velocity};
  try {
    std::visit(
        [&](const auto& shape) {
          using S = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<S, TriangleMesh<double, N>>) {
            std::vector<double> vertices;
            std::vector<std::int64_t> triangles;
            vertices.reserve(shape.triangle_count() * 3 * N);
            for (std::size_t k = 0; k < shape.triangle_count(); ++k) {
              const Triangle<double, N> tri = shape.triangle(k);
              for (int j = 0; j < 3; ++j) {
                const Vec<double, N> v = tri.vertex(j) + offset;
                vertices.insert(vertices.end(), v.data(), v.data() + N);
                triangles.push_back(static_cast<std::int64_t>(3 * k) + j);
              }
            }
            moved.shape = TriangleMesh<double, N>::from_arrays(vertices, triangles);
          } else {
            moved.shape = shape.translated(offset);
          }
        },
        o.shape);
  } catch (const InputError& e) {
    throw BadInput(file + ": obstacle " + o.id + " at t = " + number_string(t) + ": " + e.what());
  }
  return moved;
}

template <int N>
BodyScene<N> load_bodies(const Input& in) {
  BodyScene<N> scene;
  if (in.kind == InputKind::json) {
    const JsonCtx c{in.path};
    const json& bodies = in.json["bodies"];
    const std::string dim_from =
        in.json.contains("dimension") ? "from $.dimension" : "from $.bodies[0].center";
    std::unordered_map<std::string, std::string> seen;  // id -> its JSON path
    const auto unique = [&](const std::string& id, const std::string& path) {
      const auto [it, fresh] = seen.emplace(id, path);
      if (!fresh) fail(c.at(path + ".id"), "duplicate id \"" + id + "\" (also " + it->second + ")");
    };
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      Body<N> b = json_body<N>(c, bodies[i], i, dim_from);
      unique(b.id, "$.bodies[" + std::to_string(i) + "]");
      scene.bodies.push_back(std::move(b));
    }
    if (in.has_obstacles) {
      const json& obstacles = in.json["obstacles"];
      for (std::size_t k = 0; k < obstacles.size(); ++k) {
        Obstacle<N> o = json_obstacle<N>(c, obstacles[k], k, dim_from, in);
        unique(o.id, "$.obstacles[" + std::to_string(k) + "]");
        scene.obstacles.push_back(std::move(o));
      }
    }
    if (in.json.contains("pairs")) {
      const json& pairs = in.json["pairs"];
      if (!pairs.is_array()) fail(c.at("$.pairs"), "expected an array of [id, id] pairs, got " + describe_type(pairs));
      scene.pairs_listed = true;
      const auto ids = id_index<N>(scene.bodies, scene.obstacles);
      const auto n_bodies = static_cast<std::uint32_t>(scene.bodies.size());
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        const std::string path = "$.pairs[" + std::to_string(k) + "]";
        const json& p = pairs[k];
        if (!p.is_array() || p.size() != 2) fail(c.at(path), "expected [id, id], got " + excerpt(p));
        std::uint32_t ij[2];
        std::string first_id;
        for (std::size_t s = 0; s < 2; ++s) {
          const std::string spath = path + "[" + std::to_string(s) + "]";
          const std::string id = json_id(c, p[s], spath);
          const auto it = ids.find(id);
          if (it == ids.end()) fail(c.at(spath), "unknown id \"" + id + "\" (no body or obstacle has it)");
          ij[s] = it->second;
          if (s == 0) first_id = id;
        }
        check_pair(c.at(path), ij[0], ij[1], n_bodies, first_id);
        scene.pairs.emplace_back(ij[0], ij[1]);
      }
    }
    return scene;
  }
  if (in.kind != InputKind::bodies_csv) fail(in.path, "expected a JSON scene or a bodies CSV");
  std::vector<bool> used(in.columns.size(), false);
  const BodyColumns<N> m = body_columns<N>(in, "", used, true);
  check_header(in, used, expected_columns<N>(""));
  LineReader reader(in.path);
  std::string line;
  std::uint64_t line_number = 0;
  reader.next(line, line_number);  // header
  RowScratch s;
  std::unordered_map<std::string, std::uint64_t> seen;
  while (reader.next(line, line_number)) {
    split_row(in.path, line_number, line, in.columns.size(), s);
    const RowCtx r{in.path, line_number, s.fields};
    Body<N> b = row_body<N>(r, m);
    const auto [it, fresh] = seen.emplace(b.id, line_number);
    if (!fresh)
      fail(in.path + ":" + std::to_string(line_number) + ": column id",
           "duplicate id \"" + b.id + "\" (also line " + std::to_string(it->second) + ")");
    if (scene.bodies.size() >= std::numeric_limits<std::uint32_t>::max())
      fail(in.path + ":" + std::to_string(line_number), "too many bodies");
    scene.bodies.push_back(std::move(b));
  }
  if (scene.bodies.empty()) fail(in.path, "no bodies (the file has only a header)");
  return scene;
}

PairsFile::PairsFile(const std::string& path, const std::unordered_map<std::string, std::uint32_t>& ids,
                     std::uint32_t bodies)
    : reader_(path), ids_(ids), bodies_(bodies) {
  std::uint64_t line_number = 0;
  if (!reader_.next(line_, line_number)) fail(path, "empty file (expected a CSV header line a,b)");
  const std::string err = split_csv(line_, fields_, scratch_);
  if (!err.empty()) fail(path + ":" + std::to_string(line_number), "malformed CSV header: " + err);
  n_columns_ = fields_.size();
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    const std::string_view f = trim(fields_[i]);
    if (f == "a") {
      col_a_ = static_cast<int>(i);
    } else if (f == "b") {
      col_b_ = static_cast<int>(i);
    } else {
      fail(path + ":" + std::to_string(line_number) + ": header", "unknown column \"" + std::string(f) + "\" (a pairs file has columns a,b: body ids)");
    }
  }
  if (col_a_ < 0 || col_b_ < 0) fail(path + ":" + std::to_string(line_number) + ": header", std::string("missing column ") + (col_a_ < 0 ? "a" : "b"));
}

std::size_t PairsFile::read(std::vector<IndexPair>& out, std::size_t max) {
  std::size_t n = 0;
  std::uint64_t line_number = 0;
  while (n < max && reader_.next(line_, line_number)) {
    const std::string where = reader_.path() + ":" + std::to_string(line_number);
    const std::string err = split_csv(line_, fields_, scratch_);
    if (!err.empty()) fail(where, "malformed CSV: " + err);
    if (fields_.size() != n_columns_)
      fail(where, "malformed CSV: " + std::to_string(fields_.size()) + " fields, the header has " +
                      std::to_string(n_columns_));
    std::uint32_t ij[2];
    for (int s = 0; s < 2; ++s) {
      const char* name = s == 0 ? "a" : "b";
      const std::string_view id = trim(fields_[static_cast<std::size_t>(s == 0 ? col_a_ : col_b_)]);
      if (id.empty()) fail(where + ": column " + name, "missing value");
      check_utf8(where + ": column " + name, id);
      const auto it = ids_.find(std::string(id));
      if (it == ids_.end()) fail(where + ": column " + name, "unknown id \"" + std::string(id) + "\" (no body or obstacle has it)");
      ij[s] = it->second;
    }
    check_pair(where, ij[0], ij[1], bodies_, std::string(trim(fields_[static_cast<std::size_t>(col_a_)])));
    out.emplace_back(ij[0], ij[1]);
    ++n;
    ++rows_;
  }
  if (n == 0 && rows_ == 0) fail(reader_.path(), "no pairs (the file has only a header)");
  return n;
}

double PairsFile::progress() const {
  return reader_.size() == 0 ? -1.0 : static_cast<double>(reader_.bytes_read()) / static_cast<double>(reader_.size());
}

template <int N>
PairColumns<N> pair_columns(const Input& in) {
  std::vector<bool> used(in.columns.size(), false);
  PairColumns<N> p{body_columns<N>(in, "a_", used, false), body_columns<N>(in, "b_", used, false), in.columns.size()};
  check_header(in, used, expected_columns<N>("a_") + ", and the same with b_");
  return p;
}

template <int N>
std::pair<Body<N>, Body<N>> parse_pair_row(std::string_view line, std::uint64_t line_number,
                                           const PairColumns<N>& columns, const std::string& path,
                                           RowScratch& scratch) {
  split_row(path, line_number, line, columns.count, scratch);
  const RowCtx r{path, line_number, scratch.fields};
  Body<N> a = row_body<N>(r, columns.a);
  Body<N> b = row_body<N>(r, columns.b);
  return {std::move(a), std::move(b)};
}

template <int N>
void load_pair_rows(const Input& in, std::size_t limit, std::vector<Body<N>>& bodies, std::vector<IndexPair>& pairs,
                    std::uint64_t first_row) {
  const PairColumns<N> columns = pair_columns<N>(in);
  LineReader reader(in.path);
  std::string line;
  std::uint64_t line_number = 0, row = 0;
  reader.next(line, line_number);  // header
  RowScratch s;
  while (pairs.size() < limit && reader.next(line, line_number)) {
    ++row;
    if (row < first_row) continue;
    auto ab = parse_pair_row<N>(line, line_number, columns, in.path, s);
    const auto k = static_cast<std::uint32_t>(bodies.size());
    bodies.push_back(std::move(ab.first));
    bodies.push_back(std::move(ab.second));
    pairs.emplace_back(k, k + 1);
  }
  if (row == 0) fail(in.path, "no pairs (the file has only a header)");
  if (pairs.empty()) fail(in.path, "row " + std::to_string(first_row) + " does not exist (the file has " + std::to_string(row) + " rows)");
}

#define ELLIPSECT_CLI_INSTANTIATE(N)                                                                        \
  template BodyScene<N> load_bodies<N>(const Input&);                                                        \
  template std::unordered_map<std::string, std::uint32_t> id_index<N>(const std::vector<Body<N>>&,          \
                                                                      const std::vector<Obstacle<N>>&);       \
  template Ellipsoid<double, N> shape_at<N>(const Body<N>&, double, const std::string&);                     \
  template const char* obstacle_type<N>(const Obstacle<N>&);                                                 \
  template Obstacle<N> obstacle_at<N>(const Obstacle<N>&, double, const std::string&);                       \
  template PairColumns<N> pair_columns<N>(const Input&);                                                     \
  template std::pair<Body<N>, Body<N>> parse_pair_row<N>(std::string_view, std::uint64_t, const PairColumns<N>&, \
                                                         const std::string&, RowScratch&);                    \
  template void load_pair_rows<N>(const Input&, std::size_t, std::vector<Body<N>>&, std::vector<IndexPair>&,    \
                                  std::uint64_t);
ELLIPSECT_CLI_INSTANTIATE(2)
ELLIPSECT_CLI_INSTANTIATE(3)

}  // namespace ellipsect::cli
