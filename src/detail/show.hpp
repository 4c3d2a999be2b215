// A number as InputError messages quote it: 17 significant digits (round-trips a double).
#pragma once

#include <sstream>
#include <string>

namespace ellipsect::detail {

template <class T>
std::string show(T v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

}  // namespace ellipsect::detail
