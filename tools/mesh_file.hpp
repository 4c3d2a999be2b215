// Triangle meshes read from files: Wavefront OBJ and STL (ASCII or binary), 3D only.
//
// Every problem is a BadInput whose message starts with the file's name, then the line (OBJ,
// ASCII STL) or the triangle (binary STL): "cube.obj:12: f: vertex index 9 is out of range
// (the file has 8 vertices)", "cube.stl: truncated binary STL: ...".
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ellipsect::cli {

// The arrays of TriangleMesh::from_arrays: three coordinates per vertex, three vertex
// indices per triangle.
struct MeshArrays {
  std::vector<double> vertices;
  std::vector<std::int64_t> triangles;
};

// OBJ text: `v x y z [w]` lines give vertices (extra numbers, such as colors, ignored), `f`
// lines faces of three or more vertices, each `i`, `i/t`, `i//n` or `i/t/n` (1-based; negative
// i counts back from the last vertex read so far); a face of k > 3 vertices becomes the fan
// (0, j, j + 1), j = 1 .. k - 2. Every other line (vt, vn, g, o, s, usemtl, comments) is
// ignored. At least one face.
MeshArrays parse_obj(std::string_view text, const std::string& name);

// STL bytes: binary when the size is exactly 84 + 50 n for the triangle count n at byte 80,
// else ASCII when the text begins with "solid" (facets of `outer loop`, three `vertex x y z`,
// `endloop`), else a truncated binary file. Every triangle gets its own three vertices
// (STL shares none); normals and attribute bytes are ignored. At least one triangle.
MeshArrays parse_stl(std::string_view bytes, const std::string& name);

// Reads `path` (a regular file: IoError otherwise, or when it cannot be read) and parses
// it by its extension, .obj or .stl (any case).
MeshArrays read_mesh_file(const std::string& path);

}  // namespace ellipsect::cli
