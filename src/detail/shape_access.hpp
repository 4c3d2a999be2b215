// The one door to Ellipsoid's unchecked constructor (the class names ShapeAccess its friend),
// for library code whose fields are validated already or derived exactly from a valid body:
// the factories' good path (src/shapes.cpp) and the power-of-two rescaling (scale.hpp).
#pragma once

#include <ellipsect/shapes.hpp>

namespace ellipsect::detail {

struct ShapeAccess {
  template <class T, int N>
  static Ellipsoid<T, N> unchecked(const Vec<T, N>& center, const Mat<T, N>& axes, const Vec<T, N>& radii) noexcept {
    return Ellipsoid<T, N>(center, axes, radii);
  }
};

}  // namespace ellipsect::detail
