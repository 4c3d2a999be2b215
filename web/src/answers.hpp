// The answers shown by the demo page, one function per demo, shared by the WebAssembly
// binding (web/src/binding.cpp) and the native program the browser test compares with
// (web/tests/native_answers.cpp). Each calls the library and lists its results as named
// values; nothing here is computed that the library does not answer, except the
// coordinate changes of the swept demo's reduced frame.
//
// Inputs are named numbers (Params); an ellipse "x" is x.cx, x.cy, x.angle, x.r0, x.r1,
// a circle x.cx, x.cy, x.r; an ellipsoid x.cx, x.cy, x.cz, x.yaw, x.pitch, x.roll, x.r0,
// x.r1, x.r2 (web/src/answers.cpp: pair3d, motion3d). Missing names throw std::out_of_range; invalid shapes come
// back as {error: field, message: text} (the library's InputError).
#pragma once

#include <map>
#include <memory>
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
// "relation", "slide", "mesh_slide", "geometry", "pair3d", "motion3d", "mesh_slide3d", "packing" (a
// LivePacking run to jamming, or to params "collisions"), "packing_check". Throws std::invalid_argument for another name.
Answer answer(std::string_view demo, const Params& params);

template <int N>
struct LiveRun;

// A packing growing to jamming (the packing module's Compression), run a bounded number of
// collisions at a time (the page runs it slice by slice): params dim (2, 3), n (bodies),
// aspect (largest radius over the others, >= 1), rate (growth, thermal speeds per largest
// diameter), pressure (reduced pressure at which it is jammed), seed. Throws InputError
// naming the field.
class LivePacking {
public:
  explicit LivePacking(const Params& params);
  ~LivePacking();
  void advance(int collisions);  // up to this many collisions; none once ended
  Answer state() const;          // status (compressing, jammed, ...), collisions, density, pressure, ...
  Answer bodies() const;         // the bodies to draw; once ended, the contacts too

  using Run = std::variant<std::unique_ptr<LiveRun<2>>, std::unique_ptr<LiveRun<3>>>;

private:
  Run run_;
};

}  // namespace ellipsect::web
