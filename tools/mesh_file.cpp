#include "mesh_file.hpp"

#include "common.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>

namespace ellipsect::cli {

namespace {

constexpr std::size_t max_quoted = 40;  // longest token quoted in a message

[[noreturn]] void fail_line(const std::string& name, std::uint64_t line, const std::string& what) {
  throw BadInput(name + ":" + std::to_string(line) + ": " + what);
}

std::string quoted(std::string_view s) {
  std::string q(s.substr(0, max_quoted));
  for (char& c : q)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = '?';
  return "\"" + q + (s.size() > max_quoted ? "...\"" : "\"");
}

// Calls line_fn(line, number) for each line of `text` (line breaks \n, \r\n or \r removed),
// with the line cut at the first '#' when `comments`.
template <class LineFn>
void for_each_line(std::string_view text, bool comments, const LineFn& line_fn) {
  std::uint64_t number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (comments) line = line.substr(0, line.find('#'));
    line_fn(line, number);
  }
}

// The blank-separated tokens of a line.
void split_tokens(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; };
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
}

// The little-endian 32-bit word at bytes[at].
std::uint32_t le32(std::string_view bytes, std::size_t at) {
  std::uint32_t w = 0;
  for (std::size_t b = 4; b-- > 0;) w = w << 8 | static_cast<unsigned char>(bytes[at + b]);
  return w;
}

// A finite coordinate, or BadInput naming the line and what it is.
double coordinate(std::string_view token, const std::string& name, std::uint64_t line, const std::string& what) {
  double x = 0;
  if (!parse_double(token, x)) fail_line(name, line, what + ": not a number: " + quoted(token));
  if (!std::isfinite(x)) fail_line(name, line, what + ": must be finite, got " + quoted(token));
  return x;
}

}  // namespace

MeshArrays parse_obj(std::string_view text, const std::string& name) {
  MeshArrays m;
  std::vector<std::string_view> t;
  std::vector<std::int64_t> face;
  for_each_line(text, true, [&](std::string_view line, std::uint64_t number) {
    split_tokens(line, t);
    if (t.empty()) return;
    if (t[0] == "v") {
      if (t.size() < 4)
        fail_line(name, number, "v: expected x y z, got " + std::to_string(t.size() - 1) + " numbers");
      static const char* const axes[3] = {"x", "y", "z"};
      for (std::size_t i = 0; i < 3; ++i)
        m.vertices.push_back(coordinate(t[i + 1], name, number, std::string("v: ") + axes[i]));
    } else if (t[0] == "f") {
      if (t.size() < 4)
        fail_line(name, number, "f: a face needs at least 3 vertices, got " + std::to_string(t.size() - 1));
      const auto count = static_cast<std::int64_t>(m.vertices.size() / 3);
      face.clear();
      for (std::size_t k = 1; k < t.size(); ++k) {
        // i, i/t, i//n or i/t/n: the vertex index is the part before the first '/'.
        const std::string_view field = t[k].substr(0, t[k].find('/'));
        const std::string what = "f: vertex " + std::to_string(k) + " of the face";
        std::int64_t index = 0;
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), index);
        if (field.empty() || ec != std::errc() || end != field.data() + field.size())
          fail_line(name, number, what + ": not a vertex index: " + quoted(t[k]));
        if (index == 0) fail_line(name, number, what + ": index 0 (OBJ indices start at 1; negative ones count back)");
        const std::int64_t zero_based = index > 0 ? index - 1 : count + index;
        if (zero_based < 0 || zero_based >= count)
          fail_line(name, number, what + ": index " + std::string(field) + " refers to no vertex (" +
                                      std::to_string(count) + " read so far; vertices come before the faces using them)");
        face.push_back(zero_based);
      }
      for (std::size_t k = 1; k + 1 < face.size(); ++k) {
        m.triangles.push_back(face[0]);
        m.triangles.push_back(face[k]);
        m.triangles.push_back(face[k + 1]);
      }
    }
  });
  if (m.triangles.empty()) throw BadInput(name + ": no faces (an OBJ mesh needs f lines)");
  return m;
}

MeshArrays parse_stl(std::string_view bytes, const std::string& name) {
  constexpr std::size_t header = 84, record = 50;
  MeshArrays m;
  if (bytes.size() >= header) {
    const std::uint32_t count = le32(bytes, 80);
    if (header + record * std::uint64_t{count} == bytes.size()) {
      if (count == 0) throw BadInput(name + ": no triangles (a binary STL with a triangle count of 0)");
      m.vertices.reserve(9 * std::size_t{count});
      for (std::size_t k = 0; k < count; ++k)
        for (std::size_t j = 0; j < 3; ++j) {
          for (std::size_t i = 0; i < 3; ++i) {
            // Little-endian IEEE single precision, after the 12 bytes of the normal.
            const std::size_t at = header + k * record + 12 + 12 * j + 4 * i;
            const float x = std::bit_cast<float>(le32(bytes, at));
            if (!std::isfinite(x))
              throw BadInput(name + ": triangle " + std::to_string(k) + ", vertex " + std::to_string(j) +
                             ", coordinate " + std::to_string(i) + ": must be finite, got " + number_string(x) +
                             " (binary STL)");
            m.vertices.push_back(x);
          }
          m.triangles.push_back(static_cast<std::int64_t>(3 * k + j));
        }
      return m;
    }
  }
  const std::size_t first = std::min(bytes.find_first_not_of(" \t\r\n"), bytes.size());
  const bool text = bytes.substr(first, 5) == "solid" && bytes.find('\0') == std::string_view::npos;
  if (!text) {
    if (bytes.size() < header)
      throw BadInput(name + ": truncated binary STL: " + std::to_string(bytes.size()) +
                     " bytes, less than its 84-byte header (an ASCII STL begins with \"solid\")");
    const std::uint32_t count = le32(bytes, 80);
    throw BadInput(name + ": truncated binary STL: its header counts " + std::to_string(count) +
                   " triangles (84 + 50 * " + std::to_string(count) + " = " +
                   std::to_string(header + record * std::uint64_t{count}) + " bytes), the file has " +
                   std::to_string(bytes.size()) + " bytes");
  }
  // ASCII: solid, then facets of `facet normal ...`, `outer loop`, three vertices, `endloop`,
  // `endfacet`, then endsolid (more solids may follow).
  enum State { outside, in_solid, in_facet, in_loop, loop_done } state = outside;
  int loop_vertices = 0;
  std::uint64_t last = 0;
  std::vector<std::string_view> t;
  for_each_line(bytes, false, [&](std::string_view line, std::uint64_t number) {
    split_tokens(line, t);
    last = number;
    if (t.empty()) return;
    const std::string_view key = t[0];
    const auto expect = [&](State s, const char* what) {
      if (state != s) fail_line(name, number, quoted(key) + " " + what);
    };
    if (key == "solid") {
      expect(outside, "inside a solid (a solid ends with endsolid)");
      state = in_solid;
    } else if (key == "endsolid") {
      expect(in_solid, "inside a facet (a facet ends with endfacet)");
      state = outside;
    } else if (key == "facet") {
      expect(in_solid, "outside a solid, or inside a facet");
      state = in_facet;
    } else if (key == "outer") {
      expect(in_facet, "outside a facet, or a second loop in one facet");
      if (t.size() != 2 || t[1] != "loop") fail_line(name, number, "expected \"outer loop\"");
      state = in_loop;
      loop_vertices = 0;
    } else if (key == "vertex") {
      expect(in_loop, "outside an outer loop");
      if (t.size() != 4) fail_line(name, number, "vertex: expected x y z, got " + std::to_string(t.size() - 1) + " numbers");
      if (++loop_vertices > 3) fail_line(name, number, "vertex: a facet has 3 vertices, this is the 4th");
      static const char* const axes[3] = {"x", "y", "z"};
      for (std::size_t i = 0; i < 3; ++i)
        m.vertices.push_back(coordinate(t[i + 1], name, number, std::string("vertex: ") + axes[i]));
    } else if (key == "endloop") {
      expect(in_loop, "outside an outer loop");
      if (loop_vertices != 3)
        fail_line(name, number, "endloop: a facet has 3 vertices, this one " + std::to_string(loop_vertices));
      const auto v = static_cast<std::int64_t>(m.vertices.size() / 3);
      for (std::int64_t j = 3; j >= 1; --j) m.triangles.push_back(v - j);
      state = loop_done;
    } else if (key == "endfacet") {
      expect(loop_done, "before the facet's endloop");
      state = in_solid;
    } else {
      fail_line(name, number, "unexpected " + quoted(key) +
                                  " (ASCII STL has solid, facet, outer loop, vertex, endloop, endfacet, endsolid)");
    }
  });
  if (state != outside && state != in_solid) fail_line(name, last, "the file ends inside a facet");
  if (m.triangles.empty()) throw BadInput(name + ": no triangles (an ASCII STL needs facets)");
  return m;
}

MeshArrays read_mesh_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw IoError(path + ": cannot open: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw IoError(path + ": not a regular file");
  const std::string bytes = read_file(path);
  std::string lower = path.substr(path.size() >= 4 ? path.size() - 4 : 0);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == ".obj") return parse_obj(bytes, path);
  if (lower == ".stl") return parse_stl(bytes, path);
  throw BadInput(path + ": unknown mesh file type (the name must end in .obj or .stl)");
}

}  // namespace ellipsect::cli
