// JavaScript binding of the demo answers (answers.hpp): Module.answer(demo, params) takes
// a plain object of numbers and returns a plain object of numbers, strings and
// Float64Arrays. Conversion only.
#include "answers.hpp"

#include <emscripten/bind.h>
#include <emscripten/val.h>

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

val answer_js(const std::string& demo, const val& params) {
  Params p;
  const val keys = val::global("Object").call<val>("keys", params);
  const int n = keys["length"].as<int>();
  for (int i = 0; i < n; ++i) {
    const std::string key = keys[i].as<std::string>();
    p.emplace(key, params[key].as<double>());
  }
  val out = val::object();
  for (const auto& [name, value] : answer(demo, p)) out.set(name, to_js(value));
  return out;
}

}  // namespace

EMSCRIPTEN_BINDINGS(ellipsect_web) { emscripten::function("answer", &answer_js); }
