// Shared pieces of the Python module: the enums as Python IntEnums, InputError as a
// ValueError subclass, Eigen values as numpy arrays.
#pragma once

#include <ellipsect/ellipsect.hpp>

#include <Eigen/SVD>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
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

// The name of the IntEnum that stands for the C++ enum E, for signatures and type stubs.
template <class E>
struct enum_name;
#define ELLIPSECT_ENUM_NAME(E) \
  template <>              \
  struct enum_name<E> {    \
    static constexpr auto name = py::detail::const_name(#E); \
  };
ELLIPSECT_ENUM_NAME(Relation)
ELLIPSECT_ENUM_NAME(ContactStatus)
ELLIPSECT_ENUM_NAME(DistanceStatus)
ELLIPSECT_ENUM_NAME(CrossingKind)
ELLIPSECT_ENUM_NAME(BoundaryStatus)
ELLIPSECT_ENUM_NAME(Verdict)
ELLIPSECT_ENUM_NAME(Side)
ELLIPSECT_ENUM_NAME(QuarticStatus)
ELLIPSECT_ENUM_NAME(ContactFunctionStatus)
ELLIPSECT_ENUM_NAME(SlideStatus)
#undef ELLIPSECT_ENUM_NAME

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
  cls.attr("__doc__") = std::string("The library's enum ellipsect::") + name + ", its names and values (to_string).";
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

// The shortest text that reads back as x, for reprs ("0.1", "3", "nan", "inf").
inline std::string number_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  return std::string(buffer, end);
}

// A vector as "[a, b]", a matrix as its rows "[[a, b], [c, d]]".
template <class Derived>
std::string text(const Eigen::MatrixBase<Derived>& x) {
  const auto row = [&](Eigen::Index i, bool along_row) {
    std::string s = "[";
    const Eigen::Index n = along_row ? x.cols() : x.rows();
    for (Eigen::Index k = 0; k < n; ++k) {
      if (k) s += ", ";
      s += number_text(double(along_row ? x(i, k) : x(k, i)));
    }
    return s += "]";
  };
  if (x.cols() == 1) return row(0, false);
  std::string s = "[";
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (i) s += ", ";
    s += row(i, true);
  }
  return s += "]";
}

// The values of Eigen vectors and matrices and of numbers, one after another.
template <class... Xs>
std::vector<double> numbers_of(const Xs&... xs) {
  std::vector<double> out;
  const auto add = [&out](const auto& x) {
    if constexpr (std::is_arithmetic_v<std::decay_t<decltype(x)>>)
      out.push_back(double(x));
    else
      for (Eigen::Index k = 0; k < x.size(); ++k) out.push_back(double(x.reshaped()(k)));
  };
  (add(xs), ...);
  return out;
}

// __eq__ and __hash__ of a value type: equal when numbers(x) are (== on each, so 0.0 equals -0.0).
template <class X, class Numbers>
void def_equality(py::class_<X>& c, Numbers numbers) {
  c.def(
       "__eq__",
       [numbers](const X& x, const py::object& other) -> py::object {
         if (!py::isinstance<X>(other)) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
         return py::bool_(numbers(x) == numbers(other.cast<const X&>()));
       },
       py::arg("other"))
      .def("__hash__", [numbers](const X& x) {
        py::list values;
        for (const double v : numbers(x)) values.append(v);
        return py::hash(py::tuple(values));
      });
}

void def_errors(py::module_& m);
inline std::string shape_text(const std::vector<py::ssize_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i)
    s += (i ? ", " : "") + (shape[i] < 0 ? std::string("n") : std::to_string(shape[i]));
  return s + (shape.size() == 1 ? ",)" : ")");
}

// An argument taken by numpy's array_like convention (numbers() below): any object, named
// numpy.typing.ArrayLike in signatures and type stubs.
inline bool any_object(PyObject*) { return true; }
class ArrayLike : public py::object {
public:
  PYBIND11_OBJECT_DEFAULT(ArrayLike, py::object, any_object)
};
// Results that are Python objects, named in signatures and type stubs by what they are:
// the namedtuples ContactArrays, DistanceArrays, GradientArrays, ContactGradientArrays and
// ClosestApproachGradientArrays, and
// the prepared pairs of either dtype.
class ContactArraysObject : public py::object {
public:
  PYBIND11_OBJECT_DEFAULT(ContactArraysObject, py::object, any_object)
};
class DistanceArraysObject : public py::object {
public:
  PYBIND11_OBJECT_DEFAULT(DistanceArraysObject, py::object, any_object)
};
class GradientArraysObject : public py::object {
public:
  PYBIND11_OBJECT_DEFAULT(GradientArraysObject, py::object, any_object)
};
class ContactGradientArraysObject : public py::object {
public:
  PYBIND11_OBJECT_DEFAULT(ContactGradientArraysObject, py::object, any_object)
};
class ClosestApproachGradientArraysObject : public py::object {
public:
  PYBIND11_OBJECT_DEFAULT(ClosestApproachGradientArraysObject, py::object, any_object)
};
template <int N>
class PairsObject : public py::object {
public:
  PYBIND11_OBJECT_DEFAULT(PairsObject, py::object, any_object)
};

// The `options` argument of every query, shown as Options() in signatures and stubs.
// The Ellipses / Ellipsoids classes (batch.cpp): n bodies, as the batch functions take them.
template <int N>
struct Bodies {
  std::vector<Ellipsoid<double, N>> items;
};

// TriangleMesh2 / TriangleMesh3 (module.cpp): a mesh with the arrays it was built from (the
// library keeps the triangles, not the index array), for the `vertices` and `triangles`
// properties and pickling.
template <int N>
struct Mesh : TriangleMesh<double, N> {
  std::vector<double> vertices;
  std::vector<std::int64_t> triangles;
};

inline py::arg_v options_arg() { return py::arg_v("options", Options{}, "Options()"); }

// An optional ArrayLike (None: absent) as a handle that is None when absent.
inline py::handle or_none(const std::optional<ArrayLike>& x) { return x ? py::handle(*x) : py::handle(Py_None); }

// Argument `name` as a numpy array of numbers, by numpy's array_like convention (lists and
// scalars through numpy.asarray): real kinds (float, integer, bool) pass, and so do object
// arrays that convert to float64; anything else is a TypeError naming the argument.
inline py::array numbers(py::handle obj, const std::string& name) {
  const auto numpy = py::module_::import("numpy");
  py::array a;
  try {
    a = py::isinstance<py::array>(obj) ? py::reinterpret_borrow<py::array>(obj) : py::array(numpy.attr("asarray")(obj));
    if (a.dtype().kind() == 'O') a = a.attr("astype")("float64");
  } catch (py::error_already_set& e) {
    throw py::type_error(name + ": expected an array_like of real numbers, got " +
                         std::string(py::str(py::type::handle_of(obj).attr("__name__"))) + " (" +
                         std::string(py::str(e.value())) + ")");
  }
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    throw py::type_error(name + ": expected real numbers, got dtype " + std::string(py::str(a.dtype())));
  return a;
}

// Argument `name` as a C-contiguous float64 array of shape (rows, trailing...): any array_like
// of real numbers of that shape (numbers()), converted (a copy) unless it is a C-contiguous
// float64 array already, which is used as it is. rows < 0 accepts any count and sets it.
// `rows_from` names the argument that set the count, for the message.
inline py::array_t<double> checked(py::handle obj, const std::string& name, std::vector<py::ssize_t> trailing,
                                   py::ssize_t& rows, const std::string& rows_from) {
  py::array a = numbers(obj, name);
  trailing.insert(trailing.begin(), rows);
  std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
  bool fits = shape.size() == trailing.size();
  for (std::size_t i = 1; fits && i < shape.size(); ++i) fits = shape[i] == trailing[i];
  if (!fits) throw py::value_error(name + ": expected shape " + shape_text(trailing) + ", got " + shape_text(shape));
  if (rows >= 0 && shape[0] != rows)
    throw py::value_error(name + ": expected " + std::to_string(rows) + " rows, as " + rows_from + ", got " +
                          std::to_string(shape[0]));
  rows = shape[0];
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);  // no copy when it fits
}

// Argument `name` as int64 indices: an array_like of integers (numpy's "safe" casting rule,
// as numpy.take applies it: floats are a TypeError, never truncated; an empty list passes).
inline py::array_t<std::int64_t> integers(py::handle obj, const std::string& name) {
  const auto numpy = py::module_::import("numpy");
  const py::array a = numbers(obj, name);
  if (a.size() > 0 && !numpy.attr("can_cast")(a.dtype(), "int64", "safe").cast<bool>())
    throw py::type_error(name + ": expected integers, got dtype " + std::string(py::str(a.dtype())));
  return py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
}

// The rows of a C-contiguous (n, N) float64 array (checked()) as points.
// `points` as (n, 2) or (n, 3) rows of doubles; dim set to their columns.
inline py::array_t<double> point_rows(py::handle points, int& dim, const std::string& name = "points") {
  const py::array a = numbers(points, name);
  if (a.ndim() != 2 || (a.shape(1) != 2 && a.shape(1) != 3))
    throw py::value_error(name + ": expected shape (n, 2) or (n, 3), got " +
                          shape_text(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim())));
  dim = int(a.shape(1));
  py::ssize_t n = -1;
  return checked(points, name, {dim}, n, name);
}

template <int N>
std::vector<Vec<double, N>> rows_of(const py::array_t<double>& rows) {
  const double* p = rows.data();
  std::vector<Vec<double, N>> out(static_cast<std::size_t>(rows.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Eigen::Map<const Vec<double, N>>(p + i * N);
  return out;
}

// A list of point clouds ((n_i, N) arrays of one N): the rows of each, its N in dim; errors
// name "clouds[k]".
inline std::vector<py::array_t<double>> cloud_rows(const std::vector<py::object>& clouds, int& dim) {
  std::vector<py::array_t<double>> out;
  dim = 0;
  for (std::size_t k = 0; k < clouds.size(); ++k) {
    int d = 0;
    const std::string name = "clouds[" + std::to_string(k) + "]";
    out.push_back(point_rows(clouds[k], d, name));
    if (dim != 0 && d != dim)
      throw py::value_error(name + ": " + std::to_string(d) + " columns, the clouds before it " + std::to_string(dim));
    dim = d;
  }
  return out;
}

// solve(points) for every cloud on the library's worker pool (`threads`: parallel.hpp's),
// without the GIL; results in the clouds' order. Where clouds fail, the first of them (by
// index) rethrows its InputError naming "clouds[k]" (its row: "clouds[k][i]").
template <int N, class Result, class Solve>
std::vector<Result> for_each_cloud(const std::vector<py::array_t<double>>& rows, int threads, Solve solve) {
  std::vector<std::vector<Vec<double, N>>> clouds;
  for (const auto& r : rows) clouds.push_back(rows_of<N>(r));
  std::vector<Result> out(clouds.size());
  std::vector<std::string> field(clouds.size()), detail(clouds.size());
  {
    py::gil_scoped_release release;
    parallel_for(clouds.size(), threads, [&](std::size_t k) {
      const std::string name = "clouds[" + std::to_string(k) + "]";
      try {
        out[k] = solve(clouds[k]);
      } catch (const RowInputError& e) {
        field[k] = name + "[" + std::to_string(e.row()) + "]", detail[k] = e.detail();
      } catch (const InputError& e) {
        field[k] = name, detail[k] = std::string(e.what()).substr(std::string("ellipsect: " + e.field() + ": ").size());
      }
    });
  }
  for (std::size_t k = 0; k < clouds.size(); ++k)
    if (!field[k].empty()) throw InputError(field[k], detail[k]);
  return out;
}

void def_scalar(py::module_& m);
void def_batch(py::module_& m);
void def_packing(py::module_& m);
void def_geometry(py::module_& m);

}  // namespace ellipsect::python

namespace pybind11::detail {

template <>
struct handle_type_name<ellipsect::python::ArrayLike> {
  static constexpr auto name = const_name("numpy.typing.ArrayLike");
};
template <>
struct handle_type_name<ellipsect::python::ContactArraysObject> {
  static constexpr auto name = const_name("ContactArrays");
};
template <>
struct handle_type_name<ellipsect::python::DistanceArraysObject> {
  static constexpr auto name = const_name("DistanceArrays");
};
template <>
struct handle_type_name<ellipsect::python::GradientArraysObject> {
  static constexpr auto name = const_name("GradientArrays");
};
template <>
struct handle_type_name<ellipsect::python::ContactGradientArraysObject> {
  static constexpr auto name = const_name("ContactGradientArrays");
};
template <>
struct handle_type_name<ellipsect::python::ClosestApproachGradientArraysObject> {
  static constexpr auto name = const_name("ClosestApproachGradientArrays");
};
template <int N>
struct handle_type_name<ellipsect::python::PairsObject<N>> {
  static constexpr auto name =
      const_name("Union[Pairs") + const_name<N>() + const_name(", Pairs") + const_name<N>() + const_name("f]");
};

// Fixed-size numbers (a point, a quaternion, a matrix as rows) take any sequence of numbers,
// named numpy.typing.ArrayLike in signatures and type stubs (pybind11's own name, List[float[2]],
// is not a type).
template <class Array, class Value, std::size_t Size>
struct array_like_caster : array_caster<Array, Value, false, Size> {
  static constexpr auto name = const_name("numpy.typing.ArrayLike");
};
template <std::size_t N>
using Row = std::array<double, N>;
template <>
struct type_caster<Row<2>> : array_like_caster<Row<2>, double, 2> {};
template <>
struct type_caster<Row<3>> : array_like_caster<Row<3>, double, 3> {};
template <>
struct type_caster<Row<4>> : array_like_caster<Row<4>, double, 4> {};
template <>
struct type_caster<std::array<Row<2>, 2>> : array_like_caster<std::array<Row<2>, 2>, Row<2>, 2> {};
template <>
struct type_caster<std::array<Row<3>, 3>> : array_like_caster<std::array<Row<3>, 3>, Row<3>, 3> {};

// A C++ enum of the library <-> its Python IntEnum (ints are accepted too).
template <class E>
struct type_caster<E, std::enable_if_t<ellipsect::python::is_bound_enum<E>>> {
  PYBIND11_TYPE_CASTER(E, ellipsect::python::enum_name<E>::name);
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
