// Batches of bodies from numpy arrays (Ellipses, Ellipsoids), batch.hpp's Pairs prepared
// from two of them (ellipsect.pairs), and the queries over pairs: the library's batch
// functions (batch.hpp: overlap, classify, first_contact, and every other pair query;
// overlapping_pairs), their answers converted to arrays. Arrays are checked (type, dtype,
// shape, contiguity, rows) before any work; the GIL is released while the library runs.
#include "common.hpp"
#include "docs.hpp"

#include <pybind11/stl.h>

#include <ellipsect/ellipsect.hpp>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace ellipsect::python {

namespace {

// The argument name and index for a factory's field at row `row`: "radii[1]" -> "radii[17, 1]",
// "quaternion.x" -> "quaternions[17, 1]", "angle" -> "angles[17]".
// "axes(0,1)" -> "rotations[17, 0, 1]".
std::string row_field(const std::string& field, py::ssize_t row) {
  const std::size_t cut = field.find_first_of("[.(");
  const std::string head = field.substr(0, cut);
  const std::string arg = head == "center"       ? "centers"
                          : head == "angle"      ? "angles"
                          : head == "quaternion" ? "quaternions"
                          : head == "axes"       ? "rotations"
                                                 : head;
  std::string index = std::to_string(row);
  if (cut != std::string::npos && field[cut] == '[')
    index += ", " + field.substr(cut + 1, field.size() - cut - 2);
  else if (cut != std::string::npos && field[cut] == '(')
    for (const char ch : "," + field.substr(cut + 1, field.size() - cut - 2))
      index += ch == ',' ? ", " : std::string(1, ch);
  else if (cut != std::string::npos)
    index += ", " + std::to_string(std::string("wxyz").find(field[cut + 1]));
  return arg + "[" + index + "]";
}

// n answers of a library batch function, call(out), with the GIL released.
template <class R, class Call>
std::vector<R> batch_answers(std::size_t n, const Call& call) {
  std::vector<R> out(n);
  py::gil_scoped_release release;
  call(std::span<R>(out));
  return out;
}

// n bodies from rows by the library's factory over arrays, make(out) (shapes.hpp), with the
// GIL released; its RowInputError raised as InputError naming the argument, row and column.
template <int N, class Make>
Bodies<N> bodies_from(py::ssize_t n, const Make& make) {
  Bodies<N> out;
  out.items.resize(std::size_t(n));
  try {
    py::gil_scoped_release release;
    make(std::span<Ellipsoid<double, N>>(out.items));
  } catch (const RowInputError& e) {
    throw InputError(row_field(e.field(), py::ssize_t(e.row())), e.detail());
  }
  return out;
}

template <int N>
Vec<double, N> row_vec(const double* p) {
  return Eigen::Map<const Vec<double, N>>(p);
}

// A checked array's n rows of `per_row` values as a span (empty for a missing argument).
std::span<const double> values(const std::optional<py::array_t<double>>& data, py::ssize_t n, int per_row) {
  return data ? std::span<const double>(data->data(), std::size_t(n) * std::size_t(per_row))
              : std::span<const double>();
}

// checked() for an optional argument (None: absent).
std::optional<py::array_t<double>> checked_if(py::handle obj, const std::string& name,
                                              std::vector<py::ssize_t> trailing, py::ssize_t& rows,
                                              const std::string& rows_from) {
  if (obj.is_none()) return std::nullopt;
  return checked(obj, name, std::move(trailing), rows, rows_from);
}

// The orientation rows (quaternions, or N x N rotations), and how the library reads them:
// normalized (shapes.hpp, Orientations) when asked or when the array holds fewer digits than
// float64 (float32 rows are ~6e-8 off, beyond the 1e-9 the float64 factories accept).
struct Orientation {
  std::optional<py::array_t<double>> array;
  std::span<const double> rows;
  Orientations read = Orientations::as_given;
};

Orientation orientation(py::handle obj, const std::string& name, std::vector<py::ssize_t> trailing, py::ssize_t& n,
                        bool normalize) {
  Orientation out;
  out.array = checked_if(obj, name, trailing, n, "centers");
  if (!out.array) return out;
  out.rows = std::span<const double>(out.array->data(), std::size_t(out.array->size()));
  const py::dtype given = py::reinterpret_borrow<py::array>(numbers(obj, name)).dtype();
  if (normalize || (given.kind() == 'f' && given.itemsize() < 8)) out.read = Orientations::normalized;
  return out;
}

Bodies<2> make_ellipses(py::handle centers, py::handle radii, py::handle angles, py::handle rotations,
                        bool normalize) {
  py::ssize_t n = -1;
  const auto c = checked(centers, "centers", {2}, n, "");
  const auto r = checked(radii, "radii", {2}, n, "centers");
  if (!angles.is_none() && !rotations.is_none()) throw py::value_error("Ellipses: give angles or rotations, not both");
  if (!rotations.is_none()) {
    const Orientation m = orientation(rotations, "rotations", {2, 2}, n, normalize);
    return bodies_from<2>(n, [&](std::span<Ellipse2<double>> out) {
      ellipsect::make_bodies<double, 2>(values(c, n, 2), m.rows, values(r, n, 2), out, m.read);
    });
  }
  const auto a = checked_if(angles, "angles", {}, n, "centers");
  return bodies_from<2>(n, [&](std::span<Ellipse2<double>> out) {
    ellipsect::make_ellipses<double>(values(c, n, 2), values(a, n, 1), values(r, n, 2), out);
  });
}

Bodies<3> make_ellipsoids(py::handle centers, py::handle radii, py::handle quaternions, py::handle rotations,
                          bool normalize) {
  py::ssize_t n = -1;
  const auto c = checked(centers, "centers", {3}, n, "");
  const auto r = checked(radii, "radii", {3}, n, "centers");
  if (!quaternions.is_none() && !rotations.is_none())
    throw py::value_error("Ellipsoids: give quaternions or rotations, not both");
  const Orientation o = rotations.is_none()
                            ? orientation(quaternions, "quaternions", {4}, n, normalize)
                            : orientation(rotations, "rotations", {3, 3}, n, normalize);
  return bodies_from<3>(n, [&](std::span<Ellipsoid3<double>> out) {
    if (rotations.is_none())
      ellipsect::make_ellipsoids<double>(values(c, n, 3), o.rows, values(r, n, 3), out, o.read);
    else
      ellipsect::make_bodies<double, 3>(values(c, n, 3), o.rows, values(r, n, 3), out, o.read);
  });
}

// A (n, dims...) float64 array filled by fill(i, row pointer).
template <class T = double, class Fill>
py::array_t<T> rows_of(std::size_t n, std::vector<py::ssize_t> dims, const Fill& fill) {
  dims.insert(dims.begin(), py::ssize_t(n));
  py::array_t<T> out(dims);
  py::ssize_t row = 1;
  for (std::size_t k = 1; k < dims.size(); ++k) row *= dims[k];
  T* p = out.mutable_data();
  for (std::size_t i = 0; i < n; ++i) fill(i, p + py::ssize_t(i) * row);
  return out;
}

template <int N>
py::array_t<double> centers_of(const Bodies<N>& b) {
  return rows_of(b.items.size(), {N},
                 [&](std::size_t i, double* p) { Eigen::Map<Vec<double, N>>{p} = b.items[i].center(); });
}

template <int N>
py::array_t<double> radii_of(const Bodies<N>& b) {
  return rows_of(b.items.size(), {N},
                 [&](std::size_t i, double* p) { Eigen::Map<Vec<double, N>>{p} = b.items[i].radii(); });
}

template <int N>
py::array_t<double> rotations_of(const Bodies<N>& b) {
  return rows_of(b.items.size(), {N, N}, [&](std::size_t i, double* p) {
    Eigen::Map<Eigen::Matrix<double, N, N, Eigen::RowMajor>>{p} = b.items[i].axes();
  });
}

// Pickled as (centers, radii, rotations), which rebuild every body bit for bit (from_axes
// keeps axes that are orthonormal to working precision as given).
template <int N>
py::tuple state_of(const Bodies<N>& b) {
  return py::make_tuple(centers_of(b), radii_of(b), rotations_of(b));
}

template <int N>
py::class_<Bodies<N>> def_bodies(py::module_& m, const char* name, const char* scalar) {
  using B = Bodies<N>;
  py::class_<B> c(m, name,
                  (std::string("A batch of ") + scalar + " bodies, validated, one per row (shapes.hpp); they "
                   "pickle bit for bit.").c_str());
  c.def("__len__", [](const B& b) { return b.items.size(); }, "The number of bodies.")
      .def("__getitem__",
           [scalar](const B& b, py::ssize_t i) {
             const auto n = py::ssize_t(b.items.size());
             if (i < -n || i >= n) throw py::index_error(std::string(scalar) + " index out of range");
             return b.items[std::size_t(i < 0 ? i + n : i)];
           },
           py::arg("i"),
           docs::doc("Body i (negative: from the end).", "i: the index.", scalar, "IndexError: i out of range.")
               .c_str())
      .def("take",
           [](const B& b, const ArrayLike& indices_like) {
             const auto indices = integers(indices_like, "indices");
             if (indices.ndim() != 1) throw py::value_error("indices: expected a 1-D array");
             const auto n = std::int64_t(b.items.size());
             B out;
             out.items.reserve(std::size_t(indices.size()));
             for (const std::int64_t i : std::span(indices.data(), std::size_t(indices.size()))) {
               if (i < -n || i >= n) throw py::index_error("indices: " + std::to_string(i) + " out of range");
               out.items.push_back(b.items[std::size_t(i < 0 ? i + n : i)]);
             }
             return out;
           },
           py::arg("indices"),
           docs::doc("The bodies at `indices`, in that order.",
                     "indices: a 1-D array_like of integers (negative ones count from the end).", "The same type.",
                     "TypeError: indices that are not integers (1.7 is not truncated).\nValueError: not 1-D.\n"
                     "IndexError: an index out of range.")
               .c_str())
      .def_property_readonly("centers", &centers_of<N>, "numpy.ndarray: (n, N) float64, a copy.")
      .def_property_readonly("radii", &radii_of<N>, "numpy.ndarray: (n, N) float64, a copy.")
      .def_property_readonly("rotations", &rotations_of<N>,
                             "numpy.ndarray: (n, N, N) float64, a copy: the axes of body i are the columns of rotations[i].");
  return c;
}

template <int N>
std::size_t paired(const Bodies<N>& a, const Bodies<N>& b) {
  if (a.items.size() != b.items.size())
    throw py::value_error("b: expected " + std::to_string(a.items.size()) + " bodies, as a, got " +
                          std::to_string(b.items.size()));
  return a.items.size();
}

template <int N>
std::span<const Ellipsoid<double, N>> span_of(const Bodies<N>& b) {
  return b.items;
}

// namedtuples, def_batch
py::object contact_arrays, distance_arrays, gradient_arrays, contact_gradient_arrays, contact_point_jacobian_arrays,
    closest_approach_gradient_arrays;

// Velocities and time windows of n moving pairs, checked.
template <int N>
struct Motion {
  std::vector<Vec<double, N>> velocity_a, velocity_b;
  std::vector<double> t_max;
};

template <int N>
Motion<N> motion_of(std::size_t n, py::handle velocity_a, py::handle velocity_b, py::handle t_max) {
  py::ssize_t rows = static_cast<py::ssize_t>(n);
  const auto va_array = checked(velocity_a, "velocity_a", {N}, rows, "a");
  const auto vb_array = checked(velocity_b, "velocity_b", {N}, rows, "a");
  const double *va = va_array.data(), *vb = vb_array.data();
  Motion<N> m;
  const py::array window = numbers(t_max, "t_max");  // a number (Python or numpy scalar), or one per pair
  if (window.ndim() == 0) {
    m.t_max.assign(n, *py::array_t<double, py::array::forcecast>::ensure(window).data());
  } else {
    const auto t = checked(window, "t_max", {}, rows, "a");
    m.t_max.assign(t.data(), t.data() + n);
  }
  m.velocity_a.resize(n);
  m.velocity_b.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    m.velocity_a[i] = row_vec<N>(va + i * N);
    m.velocity_b[i] = row_vec<N>(vb + i * N);
  }
  return m;
}

// The answers of the three batch functions as arrays; run(span out) calls the library with
// the GIL released.
template <class Run>
py::array_t<bool> overlap_array(std::size_t n, const Run& run) {
  py::array_t<bool> out(static_cast<py::ssize_t>(n));
  bool* p = out.mutable_data();
  py::gil_scoped_release release;
  run(std::span<bool>(p, n));
  return out;
}

// Relation is one byte (classify.hpp): the answers are written once, into memory the
// returned int8 array then owns (no zero fill, no copy).
template <class Run>
py::array_t<std::int8_t> classify_array(std::size_t n, const Run& run) {
  static_assert(sizeof(Relation) == sizeof(std::int8_t));
  auto relations = std::make_unique_for_overwrite<Relation[]>(n);
  {
    py::gil_scoped_release release;
    run(std::span<Relation>(relations.get(), n));
  }
  const py::capsule owner(relations.get(), [](void* p) { delete[] static_cast<Relation*>(p); });
  const auto* data = reinterpret_cast<const std::int8_t*>(relations.release());
  return py::array_t<std::int8_t>(static_cast<py::ssize_t>(n), data, owner);
}

// Contacts as arrays of T (float64, or float32 for float pairs).
template <class T, int N, class Run>
ContactArraysObject contact_array(std::size_t n, const Run& run) {
  py::array_t<std::int8_t> status(static_cast<py::ssize_t>(n));
  py::array_t<T> time(static_cast<py::ssize_t>(n));
  py::array_t<T> point({py::ssize_t(n), py::ssize_t(N)}), normal({py::ssize_t(n), py::ssize_t(N)});
  std::int8_t* s = status.mutable_data();
  T *t = time.mutable_data(), *p = point.mutable_data(), *q = normal.mutable_data();
  {
    py::gil_scoped_release release;
    std::vector<Contact<T, N>> out(n);
    run(std::span<Contact<T, N>>(out));
    for (std::size_t i = 0; i < n; ++i) {
      s[i] = static_cast<std::int8_t>(out[i].status);
      t[i] = out[i].time;
      Eigen::Map<Vec<T, N>>{p + i * N} = out[i].point;
      Eigen::Map<Vec<T, N>>{q + i * N} = out[i].normal;
    }
  }
  return py::reinterpret_steal<ContactArraysObject>(contact_arrays(status, time, point, normal).release());
}

// The bodies rounded to float by the batch factory (make_bodies<float, N>: the single-body
// checks, axes re-orthonormalized in float where rounding moved them); a body that leaves
// float's range raises InputError naming it, e.g. "a[17].radii[0]".
template <int N>
std::vector<Ellipsoid<float, N>> rounded_to_float(const Bodies<N>& bodies, const std::string& name) {
  const std::size_t n = bodies.items.size();
  std::vector<float> centers(n * N), rotations(n * N * N), radii(n * N);
  for (std::size_t i = 0; i < n; ++i) {
    const Ellipsoid<double, N>& x = bodies.items[i];
    Eigen::Map<Vec<float, N>>{centers.data() + i * N} = x.center().template cast<float>();
    Eigen::Map<Eigen::Matrix<float, N, N, Eigen::RowMajor>>{rotations.data() + i * N * N} = x.axes().template cast<float>();
    Eigen::Map<Vec<float, N>>{radii.data() + i * N} = x.radii().template cast<float>();
  }
  std::vector<Ellipsoid<float, N>> out(n);
  try {
    make_bodies<float, N>(centers, rotations, radii, out);
  } catch (const RowInputError& e) {
    throw InputError(name + "[" + std::to_string(e.row()) + "]." + e.field(), e.detail() + " in float32");
  }
  return out;
}

// Pairs in T from double bodies (float: each body rounded to float, velocities and t_max too).
template <class T, int N>
Pairs<T, N> pairs_in(const Bodies<N>& a, const Bodies<N>& b, const Motion<N>* motion) {
  Pairs<T, N> out;
  if constexpr (std::is_same_v<T, double>) {
    py::gil_scoped_release release;
    if (motion)
      out.assign(span_of(a), motion->velocity_a, span_of(b), motion->velocity_b, motion->t_max);
    else
      out.assign(span_of(a), span_of(b));
  } else {
    const std::vector<Ellipsoid<float, N>> fa = rounded_to_float(a, "a"), fb = rounded_to_float(b, "b");
    py::gil_scoped_release release;
    if (motion) {
      const std::size_t n = fa.size();
      std::vector<Vec<float, N>> va(n), vb(n);
      std::vector<float> t(n);
      for (std::size_t i = 0; i < n; ++i) {
        va[i] = motion->velocity_a[i].template cast<float>();
        vb[i] = motion->velocity_b[i].template cast<float>();
        t[i] = float(motion->t_max[i]);
      }
      out.assign(std::span<const Ellipsoid<float, N>>(fa), va, std::span<const Ellipsoid<float, N>>(fb), vb, t);
    } else {
      out.assign(std::span<const Ellipsoid<float, N>>(fa), std::span<const Ellipsoid<float, N>>(fb));
    }
  }
  return out;
}

// Pairs pickled as their bodies (centers, rotations, radii of a, then of b, in T), velocities
// and windows, which the batch factory (axes kept as given) and assign rebuild bit for bit.
template <class T, int N>
py::tuple pairs_state(const Pairs<T, N>& pairs) {
  const std::size_t n = pairs.size();
  py::list state;
  for (const bool first : {true, false}) {
    const auto body = [&](std::size_t i) -> const Ellipsoid<T, N>& { return first ? pairs.a(i) : pairs.b(i); };
    state.append(rows_of<T>(n, {N}, [&](std::size_t i, T* p) { Eigen::Map<Vec<T, N>>{p} = body(i).center(); }));
    state.append(rows_of<T>(n, {N, N}, [&](std::size_t i, T* p) {
      Eigen::Map<Eigen::Matrix<T, N, N, Eigen::RowMajor>>{p} = body(i).axes();
    }));
    state.append(rows_of<T>(n, {N}, [&](std::size_t i, T* p) { Eigen::Map<Vec<T, N>>{p} = body(i).radii(); }));
  }
  state.append(rows_of<T>(n, {N}, [&](std::size_t i, T* p) { Eigen::Map<Vec<T, N>>{p} = pairs.velocity_a(i); }));
  state.append(rows_of<T>(n, {N}, [&](std::size_t i, T* p) { Eigen::Map<Vec<T, N>>{p} = pairs.velocity_b(i); }));
  state.append(rows_of<T>(n, {}, [&](std::size_t i, T* p) { *p = pairs.t_max(i); }));
  return py::tuple(state);
}

template <class T, int N>
Pairs<T, N> pairs_from_state(const py::tuple& state) {
  if (state.size() != 9) throw py::value_error("pickled Pairs: expected 9 arrays");
  std::vector<py::array_t<T, py::array::c_style | py::array::forcecast>> arrays;
  for (const py::handle x : state)
    arrays.push_back(py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(x));
  const auto span = [&](std::size_t k) { return std::span<const T>(arrays[k].data(), std::size_t(arrays[k].size())); };
  const std::size_t n = span(8).size();
  if (span(6).size() != n * N || span(7).size() != n * N) throw py::value_error("pickled Pairs: inconsistent sizes");
  std::vector<Ellipsoid<T, N>> a(n), b(n);
  make_bodies<T, N>(span(0), span(1), span(2), a);
  make_bodies<T, N>(span(3), span(4), span(5), b);
  const auto velocities = [&](std::size_t k) {
    std::vector<Vec<T, N>> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = Eigen::Map<const Vec<T, N>>(span(k).data() + i * N);
    return v;
  };
  Pairs<T, N> out;
  out.assign(std::span<const Ellipsoid<T, N>>(a), velocities(6), std::span<const Ellipsoid<T, N>>(b), velocities(7),
             span(8));
  return out;
}

// overlap, classify, first_contact and the GPU forms over Pairs<T, N>, bound as class `name`.
template <class T, int N>
void def_pairs_queries(py::module_& m, const std::string& name, const char* dtype) {
  using P = Pairs<T, N>;
  py::class_<P>(m, name.c_str(),
                ("Pairs prepared once for repeated overlap / classify / first_contact (batch.hpp's Pairs), in " +
                 std::string(dtype) + ".")
                    .c_str())
      .def("__len__", &P::size, "The number of pairs.")
      .def_property_readonly("dtype", [dtype](const P&) { return py::dtype(dtype); },
                             "numpy.dtype: numpy.float64 or numpy.float32: the precision of its columns.")
      .def(py::pickle(&pairs_state<T, N>, &pairs_from_state<T, N>));
  m.def("overlap",
        [](const P& pairs, const Options& o, int threads) {
          return overlap_array(pairs.size(), [&](std::span<bool> out) { overlap(pairs, out, {o, threads}); });
        },
        py::arg("pairs"), options_arg(), py::arg("threads") = 0,
        docs::doc("Whether the bodies of each prepared pair share a point (batch.hpp).", docs::pairs_arg,
                  "bool array (n,).", docs::no_overload)
            .c_str());
  m.def("classify",
        [](const P& pairs, const Options& o, int threads) {
          return classify_array(pairs.size(), [&](std::span<Relation> out) { classify(pairs, out, {o, threads}); });
        },
        py::arg("pairs"), options_arg(), py::arg("threads") = 0,
        docs::doc("The relation of the bodies of each prepared pair (batch.hpp).", docs::pairs_arg,
                  "int8 array (n,) of Relation values.", docs::no_overload)
            .c_str());
  m.def("overlap_on_gpu",
        [](const P& pairs, const Options& o, int threads) {
          Backend backend{};
          auto out = overlap_array(pairs.size(),
                                   [&](std::span<bool> s) { backend = overlap_on_gpu(pairs, s, {o, threads}); });
          return py::make_tuple(out, std::string(to_string(backend)));
        },
        py::arg("pairs"), options_arg(), py::arg("threads") = 0,
        docs::doc("overlap(pairs) with the filter on a CUDA GPU where there is one (gpu.hpp).", docs::pairs_arg,
                  "(flags, backend): the bool array (n,) and 'gpu' or 'cpu', where the filter ran.", docs::no_overload)
            .c_str());
  m.def("classify_on_gpu",
        [](const P& pairs, const Options& o, int threads) {
          Backend backend{};
          auto out = classify_array(pairs.size(),
                                    [&](std::span<Relation> s) { backend = classify_on_gpu(pairs, s, {o, threads}); });
          return py::make_tuple(out, std::string(to_string(backend)));
        },
        py::arg("pairs"), options_arg(), py::arg("threads") = 0,
        docs::doc("classify(pairs) with the filter on a CUDA GPU where there is one (gpu.hpp).", docs::pairs_arg,
                  "(relations, backend): the int8 array (n,) and 'gpu' or 'cpu', where the filter ran.",
                  docs::no_overload)
            .c_str());
  m.def("first_contact",
        [](const P& pairs, const Options& o, int threads) {
          return contact_array<T, N>(pairs.size(), [&](std::span<Contact<T, N>> out) {
            first_contact(pairs, out, {o, threads});
          });
        },
        py::arg("pairs"), options_arg(), py::arg("threads") = 0,
        docs::doc("First contact of each prepared moving pair in its window (batch.hpp).", docs::pairs_arg,
                  "ContactArrays(status int8 (n,), time (n,), point (n, N), normal (n, N)), in the pairs' dtype.",
                  docs::no_overload)
            .c_str());
}

template <int N>
void def_batch_queries(py::module_& m) {
  using B = Bodies<N>;
  const std::string suffix = std::to_string(N);
  def_pairs_queries<double, N>(m, "Pairs" + suffix, "float64");
  def_pairs_queries<float, N>(m, "Pairs" + suffix + "f", "float32");
  m.def("pairs",
        [](const B& a, const B& b, const std::optional<ArrayLike>& velocity_a_given,
           const std::optional<ArrayLike>& velocity_b_given, const ArrayLike& t_max,
           const py::object& dtype) -> PairsObject<N> {
          const py::handle velocity_a = or_none(velocity_a_given), velocity_b = or_none(velocity_b_given);
          const std::size_t n = paired(a, b);
          const py::dtype type = py::dtype::from_args(dtype);
          const bool single = type.kind() == 'f' && type.itemsize() == 4;
          if (!single && !(type.kind() == 'f' && type.itemsize() == 8))
            throw py::type_error("dtype: expected float64 or float32, got " + std::string(py::str(py::handle(type))));
          const bool moving = !velocity_a.is_none() || !velocity_b.is_none();
          const Motion<N> motion = moving ? motion_of<N>(n, velocity_a, velocity_b, t_max) : Motion<N>{};
          const Motion<N>* moves = moving ? &motion : nullptr;
          py::object out =
              single ? py::cast(pairs_in<float, N>(a, b, moves)) : py::cast(pairs_in<double, N>(a, b, moves));
          return py::reinterpret_steal<PairsObject<N>>(out.release());
        },
        py::arg("a"), py::arg("b"), py::arg("velocity_a") = py::none(), py::arg("velocity_b") = py::none(),
        py::arg("t_max") = 0.0, py::arg("dtype") = py::dtype::of<double>(),
        docs::doc("The pairs (a[i], b[i]) prepared once for overlap, classify and first_contact (batch.hpp's Pairs).",
                  "a, b: two Ellipses or two Ellipsoids of equal length.\nvelocity_a, velocity_b: (n, N) velocities "
                  "for first_contact (None: static pairs).\nt_max: the window [0, t_max], a number or (n,).\n"
                  "dtype: float64, or float32 (every body, velocity and window rounded to float; overlap and classify "
                  "then filter in float, first_contact returns float32 arrays).",
                  "Pairs2 / Pairs3 (float64), Pairs2f / Pairs3f (float32).",
                  "TypeError: another dtype, or arrays not of numbers.\nValueError: lengths or shapes that differ.\n"
                  "InputError: a body that leaves float's range (float32), named: b[17].radii[0].")
            .c_str());
  m.def("overlap",
        [](const B& a, const B& b, const Options& o, int threads) {
          return overlap_array(paired(a, b), [&](std::span<bool> out) {
            overlap<double, N>(span_of(a), span_of(b), out, {o, threads});
          });
        },
        py::arg("a"), py::arg("b"), options_arg(), py::arg("threads") = 0,
        docs::doc("Whether the bodies of each pair share a point (batch.hpp).", docs::batch_pair, "bool array (n,).",
                  docs::batch_raises)
            .c_str());
  m.def("classify",
        [](const B& a, const B& b, const Options& o, int threads) {
          return classify_array(paired(a, b), [&](std::span<Relation> out) {
            classify<double, N>(span_of(a), span_of(b), out, {o, threads});
          });
        },
        py::arg("a"), py::arg("b"), options_arg(), py::arg("threads") = 0,
        docs::doc("The relation of the bodies of each pair (batch.hpp).", docs::batch_pair,
                  "int8 array (n,) of Relation values.", docs::batch_raises)
            .c_str());
  m.def("first_contact",
        [](const B& a, const ArrayLike& velocity_a, const B& b, const ArrayLike& velocity_b, const ArrayLike& t_max,
           const Options& o, int threads) {
          const std::size_t n = paired(a, b);
          const Motion<N> motion = motion_of<N>(n, velocity_a, velocity_b, t_max);
          return contact_array<double, N>(n, [&](std::span<Contact<double, N>> out) {
            first_contact<double, N>(span_of(a), motion.velocity_a, span_of(b), motion.velocity_b, motion.t_max, out,
                                     {o, threads});
          });
        },
        py::arg("a"), py::arg("velocity_a"), py::arg("b"), py::arg("velocity_b"), py::arg("t_max"),
        options_arg(), py::arg("threads") = 0,
        docs::doc("First contact of each pair of moving bodies in [0, t_max] (batch.hpp).",
                  "a, b: two Ellipses or two Ellipsoids of equal length.\nvelocity_a, velocity_b: (n, N).\n"
                  "t_max: a number or (n,).\n" + docs::options + "\n" + docs::threads,
                  "ContactArrays(status int8 (n,), time (n,), point (n, N), normal (n, N)).",
                  "TypeError: arrays not of numbers.\nValueError: lengths or shapes that differ.")
            .c_str());
  using E = std::span<const Ellipsoid<double, N>>;
  using Query = void (*)(E, E, std::span<Distance<double, N>>, const BatchOptions&);
  for (const auto& [name, query] : {std::pair<const char*, Query>{"distance", &distance<double, N>},
                                    std::pair<const char*, Query>{"signed_distance", &signed_distance<double, N>}}) {
    m.def(name,
          [query](const B& a, const B& b, const Options& o, int threads) {
            const std::size_t n = paired(a, b);
            const auto r = batch_answers<Distance<double, N>>(
                n, [&](auto out) { query(a.items, b.items, out, BatchOptions{o, threads}); });
            py::array_t<std::int8_t> status(static_cast<py::ssize_t>(n));
            py::array_t<double> dist(static_cast<py::ssize_t>(n));
            py::array_t<double> pa({py::ssize_t(n), py::ssize_t(N)}), pb({py::ssize_t(n), py::ssize_t(N)}),
                normal({py::ssize_t(n), py::ssize_t(N)});
            std::int8_t* s = status.mutable_data();
            double *d = dist.mutable_data(), *x = pa.mutable_data(), *y = pb.mutable_data(),
                   *z = normal.mutable_data();
            for (std::size_t i = 0; i < n; ++i) {
              s[i] = static_cast<std::int8_t>(r[i].status);
              d[i] = r[i].distance;
              Eigen::Map<Vec<double, N>>{x + i * N} = r[i].point_a;
              Eigen::Map<Vec<double, N>>{y + i * N} = r[i].point_b;
              Eigen::Map<Vec<double, N>>{z + i * N} = r[i].normal;
            }
            return py::reinterpret_steal<DistanceArraysObject>(
                distance_arrays(status, dist, pa, pb, normal).release());
          },
          py::arg("a"), py::arg("b"), options_arg(), py::arg("threads") = 0,
          docs::doc(std::string(name) + " of each pair, on all cores (batch.hpp, distance.hpp).",
                    docs::batch_pair,
                    "DistanceArrays(status int8 (n,), distance (n,), point_a, point_b, normal (n, N)).",
                    docs::batch_raises)
              .c_str());
  }
  m.def("overlapping_pairs",
        [](const B& bodies, const Options& o, int threads, std::optional<std::array<double, N>> size) {
          // Columns: i, j, then (in a periodic box) the image of j that meets i.
          const int columns = size ? 2 + N : 2;
          std::vector<ImagePair<N>> pairs;
          {
            py::gil_scoped_release release;
            if (size) {
              pairs = overlapping_pairs<double, N>(span_of(bodies), PeriodicBox<N>{*size}, {o, threads});
            } else {
              for (const auto& [i, j] : overlapping_pairs<double, N>(span_of(bodies), {o, threads}))
                pairs.push_back({i, j, {}});
            }
          }
          py::array_t<std::int64_t> out({py::ssize_t(pairs.size()), py::ssize_t(columns)});
          std::int64_t* p = out.mutable_data();
          for (const ImagePair<N>& pair : pairs) {
            *p++ = pair.i;
            *p++ = pair.j;
            if (size)
              for (int k = 0; k < N; ++k) *p++ = pair.image[k];
          }
          return out;
        },
        py::arg("bodies"), options_arg(), py::arg("threads") = 0, py::arg("box") = py::none(),
        docs::doc("Every pair of bodies that overlap (broad_phase.hpp).",
                  "bodies: Ellipses / Ellipsoids.\n" + docs::options + "\n" + docs::threads +
                      "\nbox: None, or the sides of a periodic box (N,).",
                  "(m, 2) int64 array of i < j, sorted; with box, (m, 2 + N): i, j and the image m of j (j translated "
                  "by m * box meets i).",
                  docs::no_overload)
            .c_str());
}

// ---- Value and gradient (gradient.hpp) --------------------------------------------------

// Rotation vectors of n rows: (n,) in 2D, (n, 3) in 3D.
template <int N>
py::array_t<double> rotation_array(std::size_t n) {
  return N == 2 ? py::array_t<double>(py::ssize_t(n)) : py::array_t<double>({py::ssize_t(n), py::ssize_t(3)});
}
template <int N>
void put_rotation(double* rows, std::size_t i, const RotationVector<double, N>& w) {
  if constexpr (N == 2)
    rows[i] = w;
  else
    Eigen::Map<Vec<double, 3>>{rows + i * 3} = w;
}

// One body's gradients over n pairs: center (n, N), orientation (rotation_array), radii (n, N).
template <int N>
struct GradientColumns {
  py::array_t<double> center, orientation, radii;
  explicit GradientColumns(std::size_t n)
      : center({py::ssize_t(n), py::ssize_t(N)}), orientation(rotation_array<N>(n)), radii({py::ssize_t(n), py::ssize_t(N)}) {}
  // Pointers taken with the GIL held; put() runs without it.
  struct Rows {
    double *center, *orientation, *radii;
    void put(std::size_t i, const BodyGradient<double, N>& g) const {
      Eigen::Map<Vec<double, N>>{center + i * N} = g.center;
      Eigen::Map<Vec<double, N>>{radii + i * N} = g.radii;
      put_rotation<N>(orientation, i, g.orientation);
    }
  };
  Rows rows() { return {center.mutable_data(), orientation.mutable_data(), radii.mutable_data()}; }
};

// A point's Jacobians over n pairs, entry [i, j, k] = d point_j / d parameter_k of pair i: by
// one body's center and radii (n, N, N), its orientation ((n, N) in 2D, (n, N, 3) in 3D);
// velocity and angular_velocity by its motion, shaped the same.
template <int N>
struct JacobianColumns {
  py::array_t<double> center, orientation, radii, velocity, angular_velocity;
  static py::array_t<double> square(std::size_t n) { return py::array_t<double>({py::ssize_t(n), py::ssize_t(N), py::ssize_t(N)}); }
  static py::array_t<double> turns(std::size_t n) {
    return N == 2 ? py::array_t<double>({py::ssize_t(n), py::ssize_t(N)})
                  : py::array_t<double>({py::ssize_t(n), py::ssize_t(N), py::ssize_t(3)});
  }
  explicit JacobianColumns(std::size_t n)
      : center(square(n)), orientation(turns(n)), radii(square(n)), velocity(square(n)), angular_velocity(turns(n)) {}
  struct Rows {
    double *center, *orientation, *radii, *velocity, *angular_velocity;
    template <class M>
    static void put(double* rows, std::size_t i, const M& m) {
      constexpr int r = M::RowsAtCompileTime, c = M::ColsAtCompileTime;
      Eigen::Map<Eigen::Matrix<double, r, c, c == 1 ? Eigen::ColMajor : Eigen::RowMajor>>{rows + i * r * c} = m;
    }
    void put(std::size_t i, const BodyJacobian<double, N>& j, const Mat<double, N>& v, const TurnJacobian<double, N>& w) const {
      put(center, i, j.center);
      put(orientation, i, j.orientation);
      put(radii, i, j.radii);
      put(velocity, i, v);
      put(angular_velocity, i, w);
    }
  };
  Rows rows() {
    return {center.mutable_data(), orientation.mutable_data(), radii.mutable_data(), velocity.mutable_data(),
            angular_velocity.mutable_data()};
  }
};

// Angular velocities of n bodies ((n,) in 2D, (n, 3) in 3D), their row count checked against
// the argument rows_from; None: not turning.
template <int N>
std::vector<RotationVector<double, N>> angular_velocities(py::handle given, std::size_t n, const std::string& name,
                                                          const std::string& rows_from = "a") {
  RotationVector<double, N> still;
  if constexpr (N == 2)
    still = 0.0;
  else
    still = Vec<double, 3>::Zero();
  std::vector<RotationVector<double, N>> out(n, still);
  if (given.is_none()) return out;
  py::ssize_t rows = static_cast<py::ssize_t>(n);
  const auto w = checked(given, name, N == 2 ? std::vector<py::ssize_t>{} : std::vector<py::ssize_t>{3}, rows, rows_from);
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (N == 2)
      out[i] = w.data()[i];
    else
      out[i] = row_vec<3>(w.data() + 3 * i);
  }
  return out;
}

inline const std::string gradient_fields =
    "center_a (n, N), orientation_a ((n,) angles in 2D, (n, 3) world rotation vectors in 3D: "
    "quaternion_gradient carries them to quaternions), radii_a (n, N), and the same for b";

// The gradients of static pair queries: signed_distance_gradient and perram_wertheim_gradient
// (2D and 3D), overlap_area_gradient and iou_gradient (2D).
template <int N>
void def_pair_gradients(py::module_& m) {
  using B = Bodies<N>;
  using E = std::span<const Ellipsoid<double, N>>;
  // query: the library's batch function, answers g with gradients g.a, g.b; read(g) -> {status, value}.
  auto static_query = [&m]<class R>(const char* name, void (*query)(E, E, std::span<R>, const BatchOptions&),
                                    auto read, const std::string& summary, const std::string& value,
                                    const std::string& pair = docs::batch_pair) {
    m.def(name,
          [query, read](const B& a, const B& b, const Options& o, int threads) {
            const std::size_t n = paired(a, b);
            const auto g = batch_answers<R>(n, [&](auto out) { query(a.items, b.items, out, BatchOptions{o, threads}); });
            py::array_t<std::int8_t> status(static_cast<py::ssize_t>(n));
            py::array_t<double> values(static_cast<py::ssize_t>(n));
            GradientColumns<N> ga(n), gb(n);
            std::int8_t* s = status.mutable_data();
            double* v = values.mutable_data();
            const auto ra = ga.rows(), rb = gb.rows();
            for (std::size_t i = 0; i < n; ++i) {
              const auto [status_i, value_i] = read(g[i]);
              s[i] = static_cast<std::int8_t>(status_i);
              v[i] = value_i;
              ra.put(i, g[i].a);
              rb.put(i, g[i].b);
            }
            return py::reinterpret_steal<GradientArraysObject>(
                gradient_arrays(status, values, ga.center, ga.orientation, ga.radii, gb.center, gb.orientation,
                                gb.radii)
                    .release());
          },
          py::arg("a"), py::arg("b"), options_arg(), py::arg("threads") = 0,
          docs::doc(summary, pair,
                    "GradientArrays(status int8 (n,), value (n,): " + value + ", " + gradient_fields + ").",
                    docs::batch_raises)
              .c_str());
  };
  static_query(
      "signed_distance_gradient",
      &signed_distance_gradient<double, N>,
      [](const DistanceGradient<double, N>& g) { return std::pair{g.value.status, g.value.distance}; },
      "The signed distance of each pair and its derivatives by both bodies' parameters (distance.hpp).",
      "the signed distance, status DistanceStatus");
  static_query(
      "perram_wertheim_gradient",
      &perram_wertheim_gradient<double, N>,
      [](const ContactFunctionGradient<double, N>& g) { return std::pair{g.value.status, g.value.f}; },
      "The Perram-Wertheim F of each pair and its derivatives by both bodies' parameters (contact_function.hpp).",
      "F, status ContactFunctionStatus");
  if constexpr (N == 2) {
    static_query(
        "overlap_area_gradient",
        &overlap_area_gradient<double>,
        [](const OverlapAreaGradient<double>& g) { return std::pair{g.value.relation, g.value.area}; },
        "The overlap area of each pair of ellipses and its derivatives by both bodies' parameters "
        "(intersect2.hpp).",
        "the area, status the Relation",
        "a, b: two Ellipses of equal length; pair i is (a[i], b[i]).\n" + docs::options + "\n" + docs::threads);
    static_query(
        "iou_gradient",
        &intersection_over_union_gradient<double>,
        [](const IouGradient<double>& g) { return std::pair{g.relation, g.value}; },
        "The intersection over union of each pair of ellipses and its derivatives by both bodies' parameters "
        "(intersect2.hpp).",
        "the IoU, status the Relation",
        "a, b: two Ellipses of equal length; pair i is (a[i], b[i]).\n" + docs::options + "\n" + docs::threads);
  }
}

// closest_approach_gradient: sigma along each pair's direction and its derivatives.
template <int N>
void def_closest_approach_gradient(py::module_& m) {
  using B = Bodies<N>;
  m.def("closest_approach_gradient",
        [](const B& a, const B& b, const ArrayLike& direction, const Options& o, int threads) {
          const std::size_t n = paired(a, b);
          py::ssize_t rows = static_cast<py::ssize_t>(n);
          const auto d = checked(direction, "direction", {N}, rows, "a");
          std::vector<Vec<double, N>> directions(n);
          for (std::size_t i = 0; i < n; ++i) directions[i] = row_vec<N>(d.data() + i * N);
          const auto g = batch_answers<ClosestApproachGradient<double, N>>(n, [&](auto out) {
            closest_approach_gradient<double, N>(a.items, b.items, directions, out, BatchOptions{o, threads});
          });
          py::array_t<std::int8_t> status(static_cast<py::ssize_t>(n));
          py::array_t<double> sigma(static_cast<py::ssize_t>(n));
          py::array_t<double> by_direction({py::ssize_t(n), py::ssize_t(N)});
          GradientColumns<N> ga(n), gb(n);
          std::int8_t* s = status.mutable_data();
          double *v = sigma.mutable_data(), *du = by_direction.mutable_data();
          const auto ra = ga.rows(), rb = gb.rows();
          for (std::size_t i = 0; i < n; ++i) {
            s[i] = static_cast<std::int8_t>(g[i].value.status);
            v[i] = g[i].value.distance;
            ra.put(i, g[i].a);
            rb.put(i, g[i].b);
            Eigen::Map<Vec<double, N>>{du + i * N} = g[i].direction;
          }
          return py::reinterpret_steal<ClosestApproachGradientArraysObject>(
              closest_approach_gradient_arrays(status, sigma, ga.center, ga.orientation, ga.radii, gb.center,
                                               gb.orientation, gb.radii, by_direction)
                  .release());
        },
        py::arg("a"), py::arg("b"), py::arg("direction"), options_arg(), py::arg("threads") = 0,
        docs::doc("How far each b may move along its direction until it touches a, and the derivatives of that "
                  "distance by both bodies' parameters and by the direction (contact_function.hpp).",
                  docs::batch_pair + "\ndirection: (n, N), finite and nonzero, any length.",
                  "ClosestApproachGradientArrays(status int8 (n,) of ContactFunctionStatus, value (n,): sigma, " +
                      gradient_fields + " (0 by the centers: b is placed relative to a), direction (n, N)).",
                  docs::batch_raises + "\nInputError: a row of direction that is not finite or is zero, named by "
                                       "its row.")
            .c_str());
}

// first_contact_gradient: the contact time under linear or rigid motion, its derivatives by
// the bodies and motions, and the contact point's Jacobian.
template <int N>
void def_contact_gradient(py::module_& m) {
  using B = Bodies<N>;
  m.def("first_contact_gradient",
        [](const B& a, const ArrayLike& velocity_a, const B& b, const ArrayLike& velocity_b, const ArrayLike& t_max,
           const std::optional<ArrayLike>& angular_velocity_a, const std::optional<ArrayLike>& angular_velocity_b,
           const Options& o, int threads) {
          const std::size_t n = paired(a, b);
          const Motion<N> motion = motion_of<N>(n, velocity_a, velocity_b, t_max);
          const bool rigid = angular_velocity_a || angular_velocity_b;
          const auto wa = angular_velocities<N>(or_none(angular_velocity_a), n, "angular_velocity_a");
          const auto wb = angular_velocities<N>(or_none(angular_velocity_b), n, "angular_velocity_b");
          const auto g = batch_answers<ContactGradient<double, N>>(n, [&](auto out) {
            const BatchOptions batch{o, threads};
            if (rigid) {
              std::vector<RigidMotion<double, N>> ma(n), mb(n);
              for (std::size_t i = 0; i < n; ++i)
                ma[i] = {motion.velocity_a[i], wa[i]}, mb[i] = {motion.velocity_b[i], wb[i]};
              first_contact_gradient<double, N>(a.items, ma, b.items, mb, motion.t_max, out, batch);
            } else {
              first_contact_gradient<double, N>(a.items, motion.velocity_a, b.items, motion.velocity_b, motion.t_max,
                                                out, batch);
            }
          });
          py::array_t<std::int8_t> status(static_cast<py::ssize_t>(n));
          py::array_t<double> time(static_cast<py::ssize_t>(n));
          GradientColumns<N> ga(n), gb(n);
          py::array_t<double> dva({py::ssize_t(n), py::ssize_t(N)}), dvb({py::ssize_t(n), py::ssize_t(N)});
          py::array_t<double> dwa = rotation_array<N>(n), dwb = rotation_array<N>(n);
          py::array_t<double> point({py::ssize_t(n), py::ssize_t(N)});
          JacobianColumns<N> ja(n), jb(n);
          std::int8_t* s = status.mutable_data();
          double *t = time.mutable_data(), *va = dva.mutable_data(), *vb = dvb.mutable_data(),
                 *wa_out = dwa.mutable_data(), *wb_out = dwb.mutable_data(), *x = point.mutable_data();
          const auto ra = ga.rows(), rb = gb.rows();
          const auto pa = ja.rows(), pb = jb.rows();
          for (std::size_t i = 0; i < n; ++i) {
            s[i] = static_cast<std::int8_t>(g[i].value.status);
            t[i] = g[i].value.time;
            ra.put(i, g[i].a);
            rb.put(i, g[i].b);
            Eigen::Map<Vec<double, N>>{va + i * N} = g[i].velocity_a;
            Eigen::Map<Vec<double, N>>{vb + i * N} = g[i].velocity_b;
            put_rotation<N>(wa_out, i, g[i].angular_velocity_a);
            put_rotation<N>(wb_out, i, g[i].angular_velocity_b);
            Eigen::Map<Vec<double, N>>{x + i * N} = g[i].value.point;
            pa.put(i, g[i].point.a, g[i].point.velocity_a, g[i].point.angular_velocity_a);
            pb.put(i, g[i].point.b, g[i].point.velocity_b, g[i].point.angular_velocity_b);
          }
          const py::object jacobian = contact_point_jacobian_arrays(
              ja.center, ja.orientation, ja.radii, jb.center, jb.orientation, jb.radii, ja.velocity, jb.velocity,
              ja.angular_velocity, jb.angular_velocity);
          return py::reinterpret_steal<ContactGradientArraysObject>(
              contact_gradient_arrays(status, time, ga.center, ga.orientation, ga.radii, gb.center, gb.orientation,
                                      gb.radii, dva, dvb, dwa, dwb, point, jacobian)
                  .release());
        },
        py::arg("a"), py::arg("velocity_a"), py::arg("b"), py::arg("velocity_b"), py::arg("t_max"),
        py::arg("angular_velocity_a") = py::none(), py::arg("angular_velocity_b") = py::none(), options_arg(),
        py::arg("threads") = 0,
        docs::doc("The first contact time of each pair of moving bodies and its derivatives by both bodies' "
                  "parameters and motions (contact.hpp): linear motion, or rigid motion where an angular velocity "
                  "is given.",
                  "a, b: two Ellipses or two Ellipsoids of equal length.\nvelocity_a, velocity_b: (n, N).\n"
                  "t_max: a number or (n,).\nangular_velocity_a, angular_velocity_b: None (not turning), (n,) "
                  "rates in 2D, (n, 3) in 3D.\n" + docs::options + "\n" + docs::threads,
                  "ContactGradientArrays(status int8 (n,) of ContactStatus, time (n,), " + gradient_fields +
                      ", velocity_a, velocity_b (n, N), angular_velocity_a, angular_velocity_b ((n,) or (n, 3)): of "
                      "the time; point (n, N); point_jacobian: ContactPointJacobianArrays(center_a, orientation_a, "
                      "radii_a, center_b, orientation_b, radii_b, velocity_a, velocity_b, angular_velocity_a, "
                      "angular_velocity_b), entry [i, j, k] the derivative of point j of pair i by parameter k: "
                      "(n, N, N), the orientations and angular velocities (n, 2) in 2D, (n, 3, 3) in 3D); "
                      "the derivatives are 0 for overlapping_at_start and NaN where the time has none.",
                  "TypeError: arrays not of numbers.\nValueError: lengths or shapes that differ.")
            .c_str());
}

// earliest_contact among n bodies with velocities (n, dim) and, optionally, angular
// velocities ((n,) in 2D, (n, 3) in 3D), in open space or a periodic box.
template <int N>
void def_earliest_contact(py::module_& m) {
  m.def("earliest_contact",
        [](const Bodies<N>& bodies, const ArrayLike& velocities, double t_max,
           const std::optional<ArrayLike>& angular_velocities, std::optional<std::array<double, N>> size,
           const Options& o) {
          py::ssize_t rows = static_cast<py::ssize_t>(bodies.items.size());
          const auto v_array = checked(velocities, "velocities", {N}, rows, "bodies");
          const auto w = python::angular_velocities<N>(or_none(angular_velocities), bodies.items.size(),
                                                       "angular_velocities", "bodies");
          const double* v = v_array.data();
          std::vector<RigidMotion<double, N>> motions(bodies.items.size());
          for (std::size_t i = 0; i < motions.size(); ++i) {
            motions[i].velocity = row_vec<N>(v + i * N);
            motions[i].angular_velocity = w[i];
          }
          PairContact<double, N> e;
          {
            py::gil_scoped_release release;
            e = size ? earliest_contact<double, N>(span_of(bodies), motions, t_max, PeriodicBox<N>{*size}, o)
                     : earliest_contact<double, N>(span_of(bodies), motions, t_max, o);
          }
          return py::make_tuple(e.pair.i, e.pair.j, py::tuple(py::cast(e.pair.image)), e.contact);
        },
        py::arg("bodies"), py::arg("velocities"), py::arg("t_max"),
        py::arg("angular_velocities") = py::none(), py::arg("box") = py::none(), options_arg(),
        docs::doc("The first contact among all pairs of bodies moving with constant linear and angular velocities "
                  "in [0, t_max] (broad_phase.hpp).",
                  "bodies: Ellipses / Ellipsoids.\nvelocities: (n, N).\nt_max: the window's end.\n"
                  "angular_velocities: None, (n,) in 2D or (n, 3) in 3D.\nbox: None, or the sides of a periodic box "
                  "(N,).\n" + docs::options,
                  "(i, j, image, Contact): the pair, the image of j (j translated by image * box meets i; zeros "
                  "without box) and the contact.",
                  "TypeError: arrays not of numbers.\nValueError: shapes or row counts that differ from bodies.")
            .c_str());
}

// overlap_area and iou over pairs of ellipses.
void def_areas(py::module_& m) {
  using B = Bodies<2>;
  using E = std::span<const Ellipse2<double>>;
  using Query = void (*)(E, E, std::span<double>, const BatchOptions&);
  const Query area = [](E a, E b, std::span<double> out, const BatchOptions& o) {
    std::vector<OverlapArea<double>> areas(out.size());
    overlap_area<double>(a, b, areas, o);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = areas[i].area;
  };
  for (const auto& [name, query] : {std::pair<const char*, Query>{"overlap_area", area},
                                    std::pair<const char*, Query>{"iou", &intersection_over_union<double>}}) {
    m.def(name,
          [query](const B& a, const B& b, const Options& o, int threads) {
            const std::size_t n = paired(a, b);
            py::array_t<double> out(static_cast<py::ssize_t>(n));
            const std::span<double> values(out.mutable_data(), n);
            py::gil_scoped_release release;
            query(a.items, b.items, values, BatchOptions{o, threads});
            return out;
          },
          py::arg("a"), py::arg("b"), options_arg(), py::arg("threads") = 0,
          docs::doc(std::string(name) + " of each pair of ellipses, on all cores (batch.hpp, intersect2.hpp).",
                    "a, b: two Ellipses of equal length.\n" + docs::options + "\n" + docs::threads,
                    "float64 array (n,).", docs::batch_raises)
              .c_str());
  }
}

}  // namespace

void def_batch(py::module_& m) {
  py::object namedtuple = py::module_::import("collections").attr("namedtuple");
  contact_arrays = namedtuple("ContactArrays", py::make_tuple("status", "time", "point", "normal"),
                              py::arg("module") = "ellipsect");
  distance_arrays = namedtuple("DistanceArrays", py::make_tuple("status", "distance", "point_a", "point_b", "normal"),
                               py::arg("module") = "ellipsect");
  gradient_arrays = namedtuple("GradientArrays",
                               py::make_tuple("status", "value", "center_a", "orientation_a", "radii_a", "center_b",
                                              "orientation_b", "radii_b"),
                               py::arg("module") = "ellipsect");
  contact_gradient_arrays =
      namedtuple("ContactGradientArrays",
                 py::make_tuple("status", "time", "center_a", "orientation_a", "radii_a", "center_b", "orientation_b",
                                "radii_b", "velocity_a", "velocity_b", "angular_velocity_a", "angular_velocity_b",
                                "point", "point_jacobian"),
                 py::arg("module") = "ellipsect");
  closest_approach_gradient_arrays =
      namedtuple("ClosestApproachGradientArrays",
                 py::make_tuple("status", "value", "center_a", "orientation_a", "radii_a", "center_b",
                                "orientation_b", "radii_b", "direction"),
                 py::arg("module") = "ellipsect");
  contact_point_jacobian_arrays =
      namedtuple("ContactPointJacobianArrays",
                 py::make_tuple("center_a", "orientation_a", "radii_a", "center_b", "orientation_b", "radii_b",
                                "velocity_a", "velocity_b", "angular_velocity_a", "angular_velocity_b"),
                 py::arg("module") = "ellipsect");
  m.attr("ContactArrays") = contact_arrays;
  m.attr("DistanceArrays") = distance_arrays;
  m.attr("GradientArrays") = gradient_arrays;
  m.attr("ContactGradientArrays") = contact_gradient_arrays;
  m.attr("ContactPointJacobianArrays") = contact_point_jacobian_arrays;
  m.attr("ClosestApproachGradientArrays") = closest_approach_gradient_arrays;

  def_bodies<2>(m, "Ellipses", "Ellipse")
      .def(py::init([](const ArrayLike& centers, const ArrayLike& radii, const std::optional<ArrayLike>& angles,
                       const std::optional<ArrayLike>& rotations, bool normalize) {
             return make_ellipses(centers, radii, or_none(angles), or_none(rotations), normalize);
           }),
           py::arg("centers"), py::arg("radii"),
           py::arg("angles") = py::none(), py::arg("rotations") = py::none(), py::arg("normalize") = false,
           docs::doc("n ellipses from arrays, one per row, by the library's batch factory (shapes.hpp).",
                     "centers: (n, 2).\nradii: (n, 2).\nangles: (n,) radians, or rotations: (n, 2, 2), the axes as "
                     "columns.\nnormalize: make each rotation within float32's tolerance (1e-5) orthonormal first "
                     "(automatic for float32 rotations).\nArrays: any array_like of real numbers; a C-contiguous "
                     "float64 array is read without a copy.",
                     "Ellipses.",
                     "TypeError: an array that is not real numbers.\nValueError: a wrong shape or row count, or "
                     "both angles and rotations.\nInputError: the first bad value, named by argument, row and "
                     "column: centers[4, 1], rotations[3, 0, 1].")
               .c_str())
      .def(py::pickle(&state_of<2>,
                      [](const py::tuple& t) { return make_ellipses(t[0], t[1], py::none(), t[2], false); }));
  def_bodies<3>(m, "Ellipsoids", "Ellipsoid")
      .def(py::init([](const ArrayLike& centers, const ArrayLike& radii, const std::optional<ArrayLike>& quaternions,
                       const std::optional<ArrayLike>& rotations, bool normalize) {
             return make_ellipsoids(centers, radii, or_none(quaternions), or_none(rotations), normalize);
           }),
           py::arg("centers"), py::arg("radii"),
           py::arg("quaternions") = py::none(), py::arg("rotations") = py::none(), py::arg("normalize") = false,
           docs::doc("n ellipsoids from arrays, one per row, by the library's batch factory (shapes.hpp).",
                     "centers: (n, 3).\nradii: (n, 3).\nquaternions: (n, 4) as (w, x, y, z), or rotations: "
                     "(n, 3, 3), the axes as columns.\nnormalize: divide each quaternion within float32's tolerance "
                     "(1e-5) of unit norm by its norm, make each such rotation orthonormal, first (automatic for "
                     "float32 arrays).\nArrays: any array_like of real numbers; a C-contiguous float64 array is read "
                     "without a copy.",
                     "Ellipsoids.",
                     "TypeError: an array that is not real numbers.\nValueError: a wrong shape or row count, or "
                     "both quaternions and rotations.\nInputError: the first bad value, named by argument, row and "
                     "column: quaternions[1], rotations[3, 0, 1].")
               .c_str())
      .def(py::pickle(&state_of<3>,
                      [](const py::tuple& t) { return make_ellipsoids(t[0], t[1], py::none(), t[2], false); }));
  def_batch_queries<2>(m);
  def_batch_queries<3>(m);
  def_pair_gradients<2>(m);
  def_pair_gradients<3>(m);
  def_closest_approach_gradient<2>(m);
  def_closest_approach_gradient<3>(m);
  def_contact_gradient<2>(m);
  def_contact_gradient<3>(m);
  m.def(
      "quaternion_gradient",
      [](const ArrayLike& quaternions, const ArrayLike& gradient) {
        py::ssize_t rows = -1;
        const auto q = checked(quaternions, "quaternions", {4}, rows, "quaternions");
        const auto g = checked(gradient, "gradient", {3}, rows, "quaternions");
        return rows_of(std::size_t(rows), {4}, [&](std::size_t i, double* p) {
          Eigen::Map<Vec<double, 4>>{p} = quaternion_gradient<double>(row_vec<4>(q.data() + 4 * i),
                                                                       row_vec<3>(g.data() + 3 * i));
        });
      },
      py::arg("quaternions"), py::arg("gradient"),
      docs::doc("Gradients by world rotation vectors carried to quaternions (w, x, y, z) (gradient.hpp).",
                "quaternions: (n, 4), any nonzero norms (the bodies' axes are those of q / |q|).\ngradient: (n, 3), "
                "e.g. orientation_a of a GradientArrays.",
                "float64 array (n, 4).", "TypeError: arrays not of numbers.\nValueError: shapes that differ.")
          .c_str());
  m.def(
      "gpu_info",
      [] {
        const GpuInfo info = gpu_info();
        py::dict d;
        d["built"] = info.built;
        d["devices"] = info.devices;
        d["name"] = info.name;
        return d;
      },
      docs::doc("The CUDA path of the batch filter (gpu.hpp).", "(none)",
                "{'built': the library holds the CUDA path, 'devices': CUDA devices present, 'name': the current "
                "one's}.")
          .c_str());
  def_earliest_contact<2>(m);
  def_earliest_contact<3>(m);
  def_areas(m);
}

void def_errors(py::module_& m) {
  static py::handle type = py::exception<InputError>(m, "InputError", PyExc_ValueError).release();
  type.attr("__doc__") = "A bad input value: a ValueError whose `field` names it (radii[1], centers[4, 1]).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = type(e.what());
      error.attr("field") = e.field();
      PyErr_SetObject(type.ptr(), error.ptr());
    }
  });
}

}  // namespace ellipsect::python
