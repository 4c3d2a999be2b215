// The obstacles a body is queried against, in one list: a half-space (half-plane), a
// triangle, an oriented box, a capsule and a triangle mesh, each with its type, factory and
// queries in its own header (half_space.hpp, triangle.hpp, box.hpp, capsule.hpp, mesh.hpp)
// and source file (src/obstacles/). Code that handles every obstacle (the program's scenes,
// the Python bindings) takes them from here: a new obstacle joins this list.
#pragma once

#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mesh.hpp>
#include <ellipsect/triangle.hpp>

#include <string_view>
#include <variant>

namespace ellipsect {

template <template <class, int> class... Shapes>
struct ObstacleList {
  // Any one of them.
  template <class T, int N>
  using Variant = std::variant<Shapes<T, N>...>;
  // f.template operator()<Shape<T, N>>() for each, in the list's order.
  template <class T, int N, class F>
  static void for_each(F&& f) {
    (f.template operator()<Shapes<T, N>>(), ...);
  }
};

using Obstacles = ObstacleList<HalfSpace, Triangle, Box, Capsule, TriangleMesh>;

template <class T, int N>
using AnyObstacle = Obstacles::Variant<T, N>;

// Calls f.template operator()<Shape>() for each obstacle type Shape of T in N dimensions.
template <class T, int N, class F>
void for_each_obstacle(F&& f) {
  Obstacles::for_each<T, N>(f);
}

// Its name, as the program's scenes give an obstacle's "type": "half_space", "triangle",
// "box", "capsule", "mesh".
template <class Shape>
inline constexpr std::string_view obstacle_name = {};
template <class T, int N>
inline constexpr std::string_view obstacle_name<HalfSpace<T, N>> = "half_space";
template <class T, int N>
inline constexpr std::string_view obstacle_name<Triangle<T, N>> = "triangle";
template <class T, int N>
inline constexpr std::string_view obstacle_name<Box<T, N>> = "box";
template <class T, int N>
inline constexpr std::string_view obstacle_name<Capsule<T, N>> = "capsule";
template <class T, int N>
inline constexpr std::string_view obstacle_name<TriangleMesh<T, N>> = "mesh";

}  // namespace ellipsect
