// Shared pieces of the Python module: the enums as Python IntEnums, InputError as a
// ValueError subclass, Eigen values as numpy arrays, a parallel loop.
#pragma once

#include <ellipsect/ellipsect.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <initializer_list>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace ellipsect::python {

// The library's enums, each bound as a Python IntEnum.
template <class E>
inline constexpr bool is_bound_enum =
    std::is_same_v<E, Relation> || std::is_same_v<E, ContactStatus> || std::is_same_v<E, DistanceStatus> ||
    std::is_same_v<E, CrossingKind> || std::is_same_v<E, BoundaryStatus> || std::is_same_v<E, Verdict> ||
    std::is_same_v<E, Side> || std::is_same_v<E, QuarticStatus> || std::is_same_v<E, ContactFunctionStatus> ||
    std::is_same_v<E, SlideStatus>;

// The Python class (an enum.IntEnum) that stands for the C++ enum E; set by def_enum.
template <class E>
inline PyObject* enum_class = nullptr;

// Defines m.<name> as an IntEnum with the C++ enum's names and values; type_caster<E>
// then converts E to and from it.
template <class E>
void def_enum(py::module_& m, const char* name, std::initializer_list<std::pair<const char*, E>> values) {
  py::list members;
  for (const auto& [key, value] : values) members.append(py::make_tuple(key, static_cast<int>(value)));
  py::object cls = py::module_::import("enum").attr("IntEnum")(name, members, py::arg("module") = "ellipsect");
  m.attr(name) = cls;
  enum_class<E> = cls.release().ptr();
}

// An Eigen vector as a 1-D array, a matrix as a 2-D (row-major) array; copies.
template <int N, class Derived>
py::array_t<double> to_array(const Eigen::MatrixBase<Derived>& x) {
  if constexpr (Derived::ColsAtCompileTime == 1) {
    py::array_t<double> out(N);
    for (int i = 0; i < N; ++i) out.mutable_at(i) = double(x(i));
    return out;
  } else {
    py::array_t<double> out({N, N});
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) out.mutable_at(i, j) = double(x(i, j));
    return out;
  }
}

// Calls f(i) for every i in [0, n) on up to `threads` threads (0: every hardware thread),
// in chunks of 256; each i writes its own output slot, so results do not depend on the
// thread count.
template <class F>
void parallel_for(std::size_t n, int threads, const F& f) {
  constexpr std::size_t chunk = 256;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t workers = std::min(threads > 0 ? std::size_t(threads) : hardware, chunks);
  std::atomic<std::size_t> next{0};
  auto run = [&] {
    for (std::size_t c; (c = next.fetch_add(1)) < chunks;)
      for (std::size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) f(i);
  };
  std::vector<std::jthread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(run);
  run();
}

void def_errors(py::module_& m);
inline std::string shape_text(const std::vector<py::ssize_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i)
    s += (i ? ", " : "") + (shape[i] < 0 ? std::string("n") : std::to_string(shape[i]));
  return s + (shape.size() == 1 ? ",)" : ")");
}

// The data of argument `name`: a C-contiguous float64 numpy array of shape
// (rows, trailing...); rows < 0 accepts any count and sets it. `rows_from` names the
// argument that set the count, for the message.
inline const double* checked(py::handle obj, const std::string& name, std::vector<py::ssize_t> trailing, py::ssize_t& rows,
                      const std::string& rows_from) {
  if (!py::isinstance<py::array>(obj))
    throw py::type_error(name + ": expected a numpy array of float64, got " +
                         std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  const auto a = py::reinterpret_borrow<py::array>(obj);
  if (!py::isinstance<py::array_t<double>>(a))  // float64 in native byte order
    throw py::type_error(name + ": expected dtype float64, got " + std::string(py::str(a.dtype())));
  trailing.insert(trailing.begin(), rows);
  std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
  bool fits = shape.size() == trailing.size();
  for (std::size_t i = 1; fits && i < shape.size(); ++i) fits = shape[i] == trailing[i];
  if (!fits) throw py::value_error(name + ": expected shape " + shape_text(trailing) + ", got " + shape_text(shape));
  if (rows >= 0 && shape[0] != rows)
    throw py::value_error(name + ": expected " + std::to_string(rows) + " rows, as " + rows_from + ", got " +
                          std::to_string(shape[0]));
  if (!(a.flags() & py::array::c_style))
    throw py::value_error(name + ": must be C-contiguous (numpy.ascontiguousarray)");
  rows = shape[0];
  return static_cast<const double*>(a.data());
}

void def_scalar(py::module_& m);
void def_batch(py::module_& m);

}  // namespace ellipsect::python

namespace pybind11::detail {

// A C++ enum of the library <-> its Python IntEnum (ints are accepted too).
template <class E>
struct type_caster<E, std::enable_if_t<ellipsect::python::is_bound_enum<E>>> {
  PYBIND11_TYPE_CASTER(E, const_name("IntEnum"));
  bool load(handle src, bool) {
    if (ellipsect::python::enum_class<E> == nullptr || !PyLong_Check(src.ptr())) return false;
    value = static_cast<E>(src.cast<int>());
    return true;
  }
  static handle cast(E e, return_value_policy, handle) {
    return handle(ellipsect::python::enum_class<E>)(static_cast<int>(e)).release();
  }
};

}  // namespace pybind11::detail
