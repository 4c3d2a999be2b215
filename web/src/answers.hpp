// The answers shown by the demo page, one function per demo, shared by the WebAssembly
// binding (web/src/binding.cpp) and the native program the browser test compares with
// (web/tests/native_answers.cpp). Each calls the library and lists its results as named
// values; nothing here is computed that the library does not answer, except the
// coordinate changes of the swept demo's reduced frame.
//
// Inputs are named numbers (Params); an ellipse "x" is x.cx, x.cy, x.angle, x.r0, x.r1,
// a circle x.cx, x.cy, x.r. Missing names throw std::out_of_range; invalid shapes come
// back as {error: field, message: text} (the library's InputError).
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace ellipsect::web {

using Params = std::map<std::string, double, std::less<>>;
// A number, a label, or a list of numbers (a point: x, y; a polygon: x0, y0, x1, y1, ...).
using Value = std::variant<double, std::string, std::vector<double>>;
using Answer = std::vector<std::pair<std::string, Value>>;

// Names of the demos: "ellipse_circle", "segment_circle", "polygonal", "swept",
// "relation", "slide", "mesh_slide", "geometry". Throws std::invalid_argument for another name.
Answer answer(std::string_view demo, const Params& params);

}  // namespace ellipsect::web
