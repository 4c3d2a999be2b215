#pragma once

namespace ellipsect {
inline constexpr const char* version = "0.1.0";
}  // namespace ellipsect
