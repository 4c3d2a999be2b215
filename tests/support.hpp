// Shared test helpers: case counts and scale, InputError expectations, the exact mode's
// options, a count of wrong answers.
#pragma once

#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace ellipsect::testing {

// Number of random cases for a property test: `n` scaled by ELLIPSECT_CASE_SCALE (the
// sanitizer pass runs a fraction), at least 20.
inline int cases(int n) {
  const char* s = std::getenv("ELLIPSECT_CASE_SCALE");
  const double scale = s != nullptr ? std::atof(s) : 1.0;
  return std::max(20, static_cast<int>(n * scale));
}

// Whether the property tests run their full case counts (ELLIPSECT_CASE_SCALE unset or
// >= 1): only then are the shares of outcomes in a mix checked, which at the sanitizer pass's
// 20 cases per category depend on the order in which the compiler evaluates the random draws
// in one expression.
inline bool full_case_counts() {
  const char* s = std::getenv("ELLIPSECT_CASE_SCALE");
  return s == nullptr || std::atof(s) >= 1.0;
}

// Runs f, expects InputError whose field() is `field`, named in the message.
template <class F>
void expect_field(F&& f, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "no InputError for " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(": " + field + ": "), std::string::npos) << e.what();
  }
}

// Runs f: the message of the InputError it throws, or "no error".
template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// The exact mode's options (classify.hpp).
inline constexpr Options exact_options{.tolerance = Tolerance::exact};

// Answers checked against expected ones, counted per query; report() prints the counts and
// fails once, listing the first wrong answers, where any is wrong. Values: bool, or an enum
// with a to_string (Relation, ContactStatus, DistanceStatus).
class AnswerCount {
public:
  template <class V>
  void check(const std::string& where, const std::string& query, V want, V got) {
    auto& [checked, wrong] = per_query_[query];
    ++checked;
    if (want == got) return;
    ++wrong;
    if (lines_.size() < 60) lines_.push_back(where + ": " + query + " want " + str(want) + ", got " + str(got));
  }
  int wrong() const {
    int n = 0;
    for (const auto& [query, counts] : per_query_) n += counts.second;
    return n;
  }
  void report(const std::string& title) const {
    std::ostringstream s;
    int checked = 0;
    for (const auto& [query, counts] : per_query_) {
      s << "\n  " << query << ": " << counts.second << " wrong of " << counts.first;
      checked += counts.first;
    }
    if (wrong() == 0) {
      std::printf("%s: %d answers, none wrong%s\n", title.c_str(), checked, s.str().c_str());
      return;
    }
    std::ostringstream f;
    f << title << ": " << wrong() << " wrong answers of " << checked << s.str() << "\nthe first " << lines_.size()
      << ":";
    for (const auto& line : lines_) f << "\n  " << line;
    ADD_FAILURE() << f.str();
  }

private:
  static std::string str(bool b) { return b ? "true" : "false"; }
  template <class E>
  static std::string str(E e) {
    return std::string(to_string(e));
  }
  std::map<std::string, std::pair<int, int>> per_query_;
  std::vector<std::string> lines_;
};

}  // namespace ellipsect::testing
