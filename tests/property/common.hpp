// Glue between the library, the scenarios and the high-precision reference.
#pragma once

#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/reference/bridge.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>

namespace ellipsect::testing {

namespace ref = ellipsect::reference;

using reference::from_ref;
using reference::to_ref;

inline Relation mirrored(Relation r) {
  if (r == Relation::a_contains_b) return Relation::b_contains_a;
  if (r == Relation::b_contains_a) return Relation::a_contains_b;
  return r;
}

// A case's identity for failure messages: rerun it with make_case(category, seed).
template <int N>
std::string describe(const scenarios::Case<N>& c) {
  std::ostringstream s;
  s.precision(17);
  s << "N=" << N << " category=" << scenarios::name(c.category) << " seed=" << c.seed << "\n  a: c=" << c.a.center().transpose()
    << " r=" << c.a.radii().transpose() << "\n  b: c=" << c.b.center().transpose() << " r=" << c.b.radii().transpose()
    << "\n  va=" << c.va.transpose() << " vb=" << c.vb.transpose() << " t_max=" << c.t_max;
  return s.str();
}

// Counts per category and outcome, printed at the end of a test so the mix stays visible.
class Tally {
public:
  void add(std::string_view category, std::string_view outcome) { counts_[std::string(category)][std::string(outcome)]++; }
  void print(const std::string& title) const {
    std::ostringstream s;
    s << title << "\n";
    for (const auto& [cat, outcomes] : counts_) {
      s << "  " << cat << ":";
      for (const auto& [o, n] : outcomes) s << " " << o << "=" << n;
      s << "\n";
    }
    std::printf("%s", s.str().c_str());
  }
  int count(const std::string& category, const std::string& outcome) const {
    const auto c = counts_.find(category);
    if (c == counts_.end()) return 0;
    const auto o = c->second.find(outcome);
    return o == c->second.end() ? 0 : o->second;
  }

private:
  std::map<std::string, std::map<std::string, int>> counts_;
};

}  // namespace ellipsect::testing
