// JavaScript binding of the demo answers (answers.hpp): Module.answer(demo, params) takes
// a plain object of numbers and returns a plain object of numbers, strings and
// Float64Arrays; the page's one live packing (answers.hpp's LivePacking) is
// Module.packingStart(params) (its state, or {error, message}), packingAdvance(collisions),
// packingState() and packingBodies(). Conversion only.
#include "answers.hpp"

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace {

using emscripten::val;
using namespace ellipsect::web;

val to_js(const Value& v) {
  if (const double* d = std::get_if<double>(&v)) return val(*d);
  if (const std::string* s = std::get_if<std::string>(&v)) return val(*s);
  const auto& list = std::get<std::vector<double>>(v);
  // A copy out of the wasm heap (the view dies with the vector).
  return val(emscripten::typed_memory_view(list.size(), list.data())).call<val>("slice");
}

Params to_params(const val& params) {
  Params p;
  const val keys = val::global("Object").call<val>("keys", params);
  const int n = keys["length"].as<int>();
  for (int i = 0; i < n; ++i) {
    const std::string key = keys[i].as<std::string>();
    p.emplace(key, params[key].as<double>());
  }
  return p;
}

val to_js(const Answer& answer) {
  val out = val::object();
  for (const auto& [name, value] : answer) out.set(name, to_js(value));
  return out;
}

val answer_js(const std::string& demo, const val& params) { return to_js(answer(demo, to_params(params))); }

std::optional<LivePacking> live;

val packing_start(const val& params) {
  live.reset();
  try {
    live.emplace(to_params(params));
  } catch (const ellipsect::InputError& e) {
    return to_js(Answer{{"error", e.field()}, {"message", std::string(e.what())}});
  }
  return to_js(live->state());
}
void packing_advance(int collisions) { live.value().advance(collisions); }
val packing_state() { return to_js(live.value().state()); }
val packing_bodies() { return to_js(live.value().bodies()); }

}  // namespace

EMSCRIPTEN_BINDINGS(ellipsect_web) {
  emscripten::function("answer", &answer_js);
  emscripten::function("packingStart", &packing_start);
  emscripten::function("packingAdvance", &packing_advance);
  emscripten::function("packingState", &packing_state);
  emscripten::function("packingBodies", &packing_bodies);
}
