// to_string of an enum from the table of its names, in the enum's order.
#pragma once

#include <cstddef>
#include <string_view>

namespace ellipsect::detail {

template <class E, std::size_t K>
constexpr std::string_view name_of(E e, const std::string_view (&names)[K]) noexcept {
  const auto k = static_cast<std::size_t>(e);
  return k < K ? names[k] : "?";
}

}  // namespace ellipsect::detail
