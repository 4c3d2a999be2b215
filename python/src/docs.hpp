// Docstrings of the Python module: one builder and the phrases the functions share, so that
// every overload says what it takes, returns and raises (docs/python.md has the tables).
#pragma once

#include <string>

namespace ellipsect::python::docs {

inline std::string indented(const std::string& lines) {
  std::string out = "    ";
  for (const char c : lines) out += c == '\n' ? std::string("\n    ") : std::string(1, c);
  return out;
}

// "summary\n\nArgs:\n    ...\n\nReturns:\n    ...\n\nRaises:\n    ..." (Google style); `args` and
// `raises` hold one entry per line.
inline std::string doc(const std::string& summary, const std::string& args, const std::string& returns,
                       const std::string& raises = "") {
  std::string out = summary + "\n\nArgs:\n" + indented(args) + "\n\nReturns:\n" + indented(returns);
  if (!raises.empty()) out += "\n\nRaises:\n" + indented(raises);
  return out;
}

inline const std::string options = "options: Options, the tolerance and iteration caps (options.hpp).";
inline const std::string threads = "threads: threads to use, 0 for every core, 1 for the calling thread.";
inline const std::string no_overload = "TypeError: arguments of other types (no overload matches).";
inline const std::string batch_pair =
    "a, b: two Ellipses or two Ellipsoids of equal length; pair i is (a[i], b[i]).\n" + options + "\n" + threads;
inline const std::string batch_raises = "ValueError: a and b of different lengths.\n" + no_overload;
inline const std::string pairs_arg =
    "pairs: Pairs2 / Pairs3 (float64) or Pairs2f / Pairs3f (float32) from ellipsect.pairs.\n" + options + "\n" +
    threads;
inline const std::string motion =
    "velocity_a, velocity_b: constant velocities (N,).\n"
    "t_max: end of the time window [0, t_max].\n" +
    options +
    "\nangular_velocity_a: None (no turning) or the angular velocity: a rate (rad per unit time) in 2D, a "
    "3-vector in 3D; the body then moves rigidly about its center (contact.hpp).";
inline const std::string contact_returns =
    "Contact2 / Contact3: status (ContactStatus), time, point and normal (unit, from a towards b) at first "
    "contact, iterations.";
inline const std::string angular_raises =
    "TypeError: an angular velocity of the wrong shape or kind, or other argument types (a NaN gives status "
    "invalid_input).";

}  // namespace ellipsect::python::docs
