// The Python module `ellipsect._ellipsect`: argument checks and conversions around the
// library, nothing else (every number comes from the C++ functions). Scalar bodies and
// results are double; the enums are Python IntEnums (common.hpp).
#include "common.hpp"
#include "docs.hpp"

#include <ellipsect/ellipsect.hpp>

#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <optional>

namespace ellipsect::python {

namespace {

template <int N>
using Row = std::array<double, N>;
template <int N>
using Rows = std::array<std::array<double, N>, N>;  // a matrix as a sequence of rows

template <int N>
Vec<double, N> vec(const Row<N>& x) {
  return Eigen::Map<const Vec<double, N>>(x.data());
}

template <int N>
Mat<double, N> mat(const Rows<N>& m) {
  Mat<double, N> out;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) out(i, j) = m[std::size_t(i)][std::size_t(j)];
  return out;
}

// A rotation given as rows, made orthonormal first when asked (shapes.hpp, normalized_rotation).
template <int N>
Mat<double, N> normalized(const Rows<N>& m, bool normalize) {
  return normalize ? normalized_rotation<double, N>(mat<N>(m)) : mat<N>(m);
}

// The constructor call that rebuilds the body bit for bit (rotation: its axes as columns).
template <int N>
std::string body_repr(const Ellipsoid<double, N>& e) {
  return std::string(N == 2 ? "Ellipse" : "Ellipsoid") + "(center=" + text(e.center()) + ", radii=" + text(e.radii()) +
         ", rotation=" + text(e.axes()) + ")";
}

// Members common to Ellipse and Ellipsoid.
template <int N>
void def_body(py::class_<Ellipsoid<double, N>>& c) {
  using E = Ellipsoid<double, N>;
  c.def_static("from_axes",
               [](const Row<N>& center, const Rows<N>& axes, const Row<N>& radii) {
                 return E::from_axes(vec<N>(center), mat<N>(axes), vec<N>(radii));
               },
               py::arg("center"), py::arg("axes"), py::arg("radii"),
               docs::doc("The body whose principal directions are the columns of `axes` (shapes.hpp).",
                         "center: (N,).\naxes: (N, N), orthonormal columns (within 1e-9).\nradii: (N,), > 0.",
                         "The body.", "InputError: a bad value, named (center[i], axes, radii[i], radii).")
                   .c_str())
      .def_static("from_quadric",
                  [](const Row<N>& center, const Rows<N>& M) { return E::from_quadric(vec<N>(center), mat<N>(M)); },
                  py::arg("center"), py::arg("M"),
                  docs::doc("The body {x : (x - center)^T M (x - center) <= 1} (shapes.hpp).",
                            "center: (N,).\nM: (N, N), symmetric positive definite.", "The body.",
                            "InputError: a bad value, named (center[i], M).")
                      .c_str())
      .def_static("ball", [](const Row<N>& center, double radius) { return make_ball<double, N>(vec<N>(center), radius); },
                  py::arg("center"), py::arg("radius"),
                  docs::doc("A ball (circle, sphere).", "center: (N,).\nradius: > 0.", "The body.",
                            "InputError: a bad value, named (center[i], radius).")
                      .c_str())
      .def_property_readonly("center", [](const E& e) { return to_array<N>(e.center()); },
                             "numpy.ndarray: The center (N,), a copy.")
      .def_property_readonly("axes", [](const E& e) { return to_array<N>(e.axes()); },
                             "numpy.ndarray: The principal directions as columns (N, N), a copy.")
      .def_property_readonly("radii", [](const E& e) { return to_array<N>(e.radii()); },
                             "numpy.ndarray: The radii along the axes (N,), a copy.")
      .def("quadric", [](const E& e) { return to_array<N>(e.quadric()); },
           docs::doc("The quadric matrix M = axes diag(radii)^-2 axes^T.", "(none)", "(N, N) float64 array.").c_str())
      .def("translated", [](const E& e, const Row<N>& offset) { return e.translated(vec<N>(offset)); },
           py::arg("offset"),
           docs::doc("The same body moved by `offset`.", "offset: (N,).", "The moved body.",
                     "InputError: a center that leaves the finite range.")
               .c_str())
      .def("__repr__", &body_repr<N>)
      .def(py::pickle([](const E& e) { return py::make_tuple(to_array<N>(e.center()), to_array<N>(e.axes()),
                                                             to_array<N>(e.radii())); },
                      [](const py::tuple& t) {
                        return E::from_axes(vec<N>(t[0].cast<Row<N>>()), mat<N>(t[1].cast<Rows<N>>()),
                                            vec<N>(t[2].cast<Row<N>>()));
                      }));
  def_equality(c, [](const E& e) { return numbers_of(e.center(), e.axes(), e.radii()); });
  if constexpr (N == 2)
    c.def_property_readonly(
        "angle", [](const E& e) { return std::atan2(e.axes()(1, 0), e.axes()(0, 0)); },
        "float: The first axis's counterclockwise angle from the x axis, in (-pi, pi] (the angle the constructor "
        "takes, up to a multiple of pi: an ellipse is symmetric about its center).");
}

// HalfPlane (N = 2) and HalfSpace (N = 3): { x : normal . (x - point) <= 0 } (half_space.hpp).
template <int N>
void def_half_space(py::module_& m, const char* name) {
  using H = HalfSpace<double, N>;
  py::class_<H> c(m, name, "A validated half-space {x : normal . (x - point) <= 0} (half_space.hpp).");
  c.def(py::init([](const Row<N>& point, const Row<N>& normal) {
             return make_half_space<double, N>(vec<N>(point), vec<N>(normal));
           }),
           py::arg("point"), py::arg("normal"),
           docs::doc("The half-space {x : normal . (x - point) <= 0}.",
                     "point: a point of its boundary (N,).\nnormal: the outward normal (N,), any length (stored as a "
                     "unit vector).",
                     "The half-space.", "InputError: a non-finite value or a zero normal, named.")
               .c_str())
      .def_property_readonly("point", [](const H& h) { return to_array<N>(h.point()); },
                             "numpy.ndarray: A boundary point (N,).")
      .def_property_readonly("normal", [](const H& h) { return to_array<N>(h.normal()); },
                             "numpy.ndarray: The unit outward normal (N,).")
      .def("translated", [](const H& h, const Row<N>& offset) { return h.translated(vec<N>(offset)); },
           py::arg("offset"),
           docs::doc("The same half-space moved by `offset`.", "offset: (N,).", "The moved half-space.",
                     "InputError: a point that leaves the finite range.")
               .c_str())
      .def("__repr__",
           [name](const H& h) {
             return std::string(name) + "(point=" + text(h.point()) + ", normal=" + text(h.normal()) + ")";
           })
      .def(py::pickle([](const H& h) { return py::make_tuple(to_array<N>(h.point()), to_array<N>(h.normal())); },
                      [](const py::tuple& t) {
                        return make_half_space<double, N>(vec<N>(t[0].cast<Row<N>>()), vec<N>(t[1].cast<Row<N>>()));
                      }));
  def_equality(c, [](const H& h) { return numbers_of(h.point(), h.normal()); });
}

// Values stored `columns` per row as an (n, columns) array (a copy).
template <class T>
py::array_t<T> mesh_array(const std::vector<T>& values, int columns) {
  py::array_t<T> out({py::ssize_t(values.size()) / columns, py::ssize_t(columns)});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

// A mesh from vertices (n, N) and triangles (m, 3), the arrays kept.
template <int N>
Mesh<N> make_mesh(py::handle vertices, py::handle triangles) {
  py::ssize_t rows = -1;
  const auto v = checked(vertices, "vertices", {N}, rows, "vertices");
  const auto t = integers(triangles, "triangles");
  if (t.ndim() != 2 || t.shape(1) != 3)
    throw py::value_error("triangles: expected shape (n, 3), got " +
                          shape_text(std::vector<py::ssize_t>(t.shape(), t.shape() + t.ndim())));
  Mesh<N> out;
  out.vertices.assign(v.data(), v.data() + v.size());
  out.triangles.assign(t.data(), t.data() + t.size());
  py::gil_scoped_release release;
  static_cast<TriangleMesh<double, N>&>(out) = TriangleMesh<double, N>::from_arrays(out.vertices, out.triangles);
  return out;
}

// Triangle2 / Triangle3 (triangle.hpp) and TriangleMesh2 / TriangleMesh3 (mesh.hpp).
template <int N>
void def_triangle(py::module_& m, const char* name) {
  using Tr = Triangle<double, N>;
  const auto vertices = [](const Tr& t) {
    py::array_t<double> out({py::ssize_t(3), py::ssize_t(N)});
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < N; ++i) out.mutable_at(k, i) = t.vertex(k)[i];
    return out;
  };
  py::class_<Tr> c(m, name, "A triangle: the convex hull of three points, degenerate ones included (triangle.hpp).");
  c.def(py::init([](const Row<N>& v0, const Row<N>& v1, const Row<N>& v2) {
             return make_triangle<double, N>(vec<N>(v0), vec<N>(v1), vec<N>(v2));
           }),
           py::arg("v0"), py::arg("v1"), py::arg("v2"),
           docs::doc("The triangle with these vertices.", "v0, v1, v2: the vertices (N,).", "The triangle.",
                     "InputError: a non-finite vertex, named.")
               .c_str())
      .def_property_readonly("vertices", vertices, "numpy.ndarray: The vertices, one per row (3, N).")
      .def("translated", [](const Tr& t, const Row<N>& offset) { return t.translated(vec<N>(offset)); },
           py::arg("offset"),
           docs::doc("The same triangle moved by `offset`.", "offset: (N,).", "The moved triangle.",
                     "InputError: a vertex that leaves the finite range.")
               .c_str())
      .def("__repr__",
           [name](const Tr& t) {
             return std::string(name) + "(" + text(t.vertex(0)) + ", " + text(t.vertex(1)) + ", " + text(t.vertex(2)) +
                    ")";
           })
      .def(py::pickle([](const Tr& t) { return py::make_tuple(to_array<N>(t.vertex(0)), to_array<N>(t.vertex(1)),
                                                              to_array<N>(t.vertex(2))); },
                      [](const py::tuple& t) {
                        return make_triangle<double, N>(vec<N>(t[0].cast<Row<N>>()), vec<N>(t[1].cast<Row<N>>()),
                                                        vec<N>(t[2].cast<Row<N>>()));
                      }));
  def_equality(c, [](const Tr& t) { return numbers_of(t.vertex(0), t.vertex(1), t.vertex(2)); });
  using M = Mesh<N>;
  py::class_<M>(m, ("TriangleMesh" + std::to_string(N)).c_str(),
                "Triangles sharing vertices, with a box hierarchy for the queries (mesh.hpp).")
      .def(py::init([](const ArrayLike& vertices, const ArrayLike& triangles) {
             return make_mesh<N>(vertices, triangles);
           }),
           py::arg("vertices"), py::arg("triangles"),
           docs::doc("The mesh of these triangles.",
                     "vertices: array_like of numbers (n, N).\ntriangles: array_like of integers (m, 3), vertex indices.",
                     "The mesh.",
                     "TypeError: vertices not numbers, triangles not integers.\nValueError: a wrong shape.\n"
                     "InputError: a non-finite vertex or an index outside the vertices, named "
                     "(vertices[i][j], triangles[k][j]).")
               .c_str())
      .def_property_readonly("vertex_count", [](const M& mesh) { return mesh.vertex_count(); },
                             "int: The number of vertices.")
      .def_property_readonly("triangle_count", [](const M& mesh) { return mesh.triangle_count(); },
                             "int: The number of triangles.")
      .def_property_readonly("vertices", [](const M& mesh) { return mesh_array<double>(mesh.vertices, N); },
                             "numpy.ndarray: The vertices it was built from, (n, N) float64 (a copy).")
      .def_property_readonly("triangles", [](const M& mesh) { return mesh_array<std::int64_t>(mesh.triangles, 3); },
                             "numpy.ndarray: The triangles it was built from, (m, 3) int64 vertex indices (a copy).")
      .def("__len__", [](const M& mesh) { return mesh.triangle_count(); }, "The number of triangles.")
      .def("triangle", [](const M& mesh, std::size_t k) { return mesh.triangle(k); }, py::arg("k"),
           docs::doc("Triangle k.", "k: its index.", "Triangle2 / Triangle3.", "InputError: k out of range.").c_str())
      .def("__repr__",
           [](const M& mesh) {
             return "TriangleMesh" + std::to_string(N) + "(vertices=" + std::to_string(mesh.vertex_count()) +
                    ", triangles=" + std::to_string(mesh.triangle_count()) + ")";
           })
      .def(py::pickle(
          [](const M& mesh) {
            return py::make_tuple(mesh_array<double>(mesh.vertices, N), mesh_array<std::int64_t>(mesh.triangles, 3));
          },
          [](const py::tuple& t) { return make_mesh<N>(t[0], t[1]); }));
}

// Box2 / Box3: an oriented rectangle or box (box.hpp).
template <int N>
void def_box(py::module_& m, const char* name) {
  using B = Box<double, N>;
  py::class_<B> c(m, name, "A validated oriented box {center + axes u : |u_i| <= half_extents_i} (box.hpp).");
  c.def(py::init([](const Row<N>& center, const Row<N>& half_extents, std::optional<Rows<N>> axes) {
             return make_box<double, N>(vec<N>(center), axes ? mat<N>(*axes) : Mat<double, N>::Identity(),
                                        vec<N>(half_extents));
           }),
           py::arg("center"), py::arg("half_extents"), py::arg("axes") = py::none(),
           docs::doc("The box {center + axes u : |u_i| <= half_extents_i}.",
                     "center: (N,).\nhalf_extents: (N,), > 0.\naxes: (N, N), orthonormal columns (default: the "
                     "coordinate axes).",
                     "The box.", "InputError: a bad value, named.")
               .c_str())
      .def_property_readonly("center", [](const B& b) { return to_array<N>(b.center()); },
                             "numpy.ndarray: The center (N,).")
      .def_property_readonly("axes", [](const B& b) { return to_array<N>(b.axes()); },
                             "numpy.ndarray: The axes as columns (N, N).")
      .def_property_readonly("half_extents", [](const B& b) { return to_array<N>(b.half_extents()); },
                             "numpy.ndarray: The half side lengths along the axes (N,).")
      .def("corner", [](const B& b, int k) {
             if (k < 0 || k >= (1 << N)) throw py::index_error("corner: k must be in [0, " + std::to_string(1 << N) + ")");
             return to_array<N>(b.corner(k));
           }, py::arg("k"),
           docs::doc("Corner k: bit i of k picks the sign along axis i.", "k: in [0, 2^N).", "The corner (N,).",
                     "IndexError: k out of range.")
               .c_str())
      .def("translated", [](const B& b, const Row<N>& offset) { return b.translated(vec<N>(offset)); },
           py::arg("offset"),
           docs::doc("The same box moved by `offset`.", "offset: (N,).", "The moved box.",
                     "InputError: a center that leaves the finite range.")
               .c_str())
      .def("__repr__",
           [name](const B& b) {
             return std::string(name) + "(center=" + text(b.center()) + ", half_extents=" + text(b.half_extents()) +
                    ", axes=" + text(b.axes()) + ")";
           })
      .def(py::pickle(
          [](const B& b) {
            return py::make_tuple(to_array<N>(b.center()), to_array<N>(b.half_extents()), to_array<N>(b.axes()));
          },
          [](const py::tuple& t) {
            return make_box<double, N>(vec<N>(t[0].cast<Row<N>>()), mat<N>(t[2].cast<Rows<N>>()),
                                       vec<N>(t[1].cast<Row<N>>()));
          }));
  def_equality(c, [](const B& b) { return numbers_of(b.center(), b.axes(), b.half_extents()); });
}

template <int N>
void def_capsule(py::module_& m, const char* name) {
  using C = Capsule<double, N>;
  py::class_<C> c(m, name, "A validated capsule {x : dist(x, [p0, p1]) <= radius} (capsule.hpp).");
  c.def(py::init([](const Row<N>& p0, const Row<N>& p1, double radius) {
             return make_capsule<double, N>(vec<N>(p0), vec<N>(p1), radius);
           }),
           py::arg("p0"), py::arg("p1"), py::arg("radius"),
           docs::doc("The capsule {x : dist(x, [p0, p1]) <= radius}.",
                     "p0, p1: the segment's ends (N,).\nradius: > 0.", "The capsule.",
                     "InputError: a bad value, named.")
               .c_str())
      .def_property_readonly("p0", [](const C& c) { return to_array<N>(c.point(0)); },
                             "numpy.ndarray: The segment's first end (N,).")
      .def_property_readonly("p1", [](const C& c) { return to_array<N>(c.point(1)); },
                             "numpy.ndarray: The segment's second end (N,).")
      .def_property_readonly("radius", &C::radius, "float: The radius.")
      .def("translated", [](const C& c, const Row<N>& offset) { return c.translated(vec<N>(offset)); },
           py::arg("offset"),
           docs::doc("The same capsule moved by `offset`.", "offset: (N,).", "The moved capsule.",
                     "InputError: a point that leaves the finite range.")
               .c_str())
      .def("__repr__",
           [name](const C& c) {
             return std::string(name) + "(p0=" + text(c.point(0)) + ", p1=" + text(c.point(1)) +
                    ", radius=" + number_text(c.radius()) + ")";
           })
      .def(py::pickle(
          [](const C& c) { return py::make_tuple(to_array<N>(c.point(0)), to_array<N>(c.point(1)), c.radius()); },
          [](const py::tuple& t) {
            return make_capsule<double, N>(vec<N>(t[0].cast<Row<N>>()), vec<N>(t[1].cast<Row<N>>()),
                                           t[2].cast<double>());
          }));
  def_equality(c, [](const C& x) { return numbers_of(x.point(0), x.point(1), x.radius()); });
}

// Results pickle by their fields: a dict from each field's name to its value (numbers,
// tuples of numbers, statuses by name, bodies and nested results as their own pickled
// objects), so that a pickle loads in a later version of the module and on any machine,
// whatever the struct's layout; fields the state lacks are an error naming them, fields it
// has beyond them (a later version's) are left.
template <int N>
void fields(Contact<double, N>& c, auto&& f) {
  f("status", c.status), f("time", c.time), f("point", c.point), f("normal", c.normal), f("iterations", c.iterations);
}
template <int N>
void fields(Slide<double, N>& r, auto&& f) {
  f("status", r.status), f("body", r.body), f("moved", r.moved), f("contacts", r.contacts),
      f("last_contact", r.last_contact);
}
template <int N>
void fields(MeshContact<double, N>& c, auto&& f) {
  f("contact", c.contact), f("triangle", c.triangle);
}
template <int N>
void fields(MeshDistance<double, N>& d, auto&& f) {
  f("distance", d.distance), f("triangle", d.triangle);
}
template <int N>
void fields(Distance<double, N>& d, auto&& f) {
  f("status", d.status), f("distance", d.distance), f("point_a", d.point_a), f("point_b", d.point_b),
      f("normal", d.normal), f("iterations", d.iterations);
}
template <int N>
void fields(ClosestPoint<double, N>& p, auto&& f) {
  f("point", p.point), f("signed_distance", p.signed_distance);
}
template <int N>
void fields(ClosestApproach<double, N>& a, auto&& f) {
  f("status", a.status), f("distance", a.distance), f("distance_lower", a.distance_lower), f("point", a.point),
      f("normal", a.normal), f("lambda", a.lambda), f("iterations", a.iterations);
}

inline void fields(BoundaryIntersection<double>& b, auto&& f) {
  f("status", b.status), f("count", b.count), f("points", b.points), f("kinds", b.kinds);
}
inline void fields(OverlapArea<double>& a, auto&& f) { f("area", a.area), f("relation", a.relation); }
inline void fields(SegmentCircle& c, auto&& f) { f("verdict", c.verdict), f("side", c.side); }
inline void fields(PolygonalOverlap<double>& p, auto&& f) {
  f("verdict", p.verdict), f("level", p.level), f("iterations", p.iterations), f("gap_lo", p.gap_lo),
      f("gap_hi", p.gap_hi);
}
inline void fields(QuarticPoint<double>& q, auto&& f) { f("status", q.status), f("point", q.point), f("distance", q.distance); }
inline void fields(MeshRelation& r, auto&& f) { f("relation", r.relation), f("triangle", r.triangle); }
inline void fields(ContactFunction<double>& c, auto&& f) {
  f("status", c.status), f("f", c.f), f("f_upper", c.f_upper), f("lambda", c.lambda), f("iterations", c.iterations);
}

template <class V>
py::object field_state(const V& v) {
  if constexpr (std::is_enum_v<V>) {
    return py::str(std::string(to_string(v)));
  } else if constexpr (std::is_arithmetic_v<V>) {
    return py::cast(v);
  } else if constexpr (requires { v.size(); v[0]; }) {  // a vector, or an array of them
    py::tuple t(std::size_t(v.size()));
    for (std::size_t i = 0; i < std::size_t(v.size()); ++i) t[i] = field_state(v[i]);
    return std::move(t);
  } else {
    return py::cast(v);  // a body or a nested result: its own class, pickled by its own fields
  }
}

template <class V>
void field_from_state(V& v, const py::handle& h, const std::string& where) {
  if constexpr (std::is_enum_v<V>) {
    const std::string name = h.cast<std::string>();
    for (int k = 0; k < 64; ++k)
      if (to_string(V(k)) == name) {
        v = V(k);
        return;
      }
    throw py::value_error(where + ": unknown status '" + name + "'");
  } else if constexpr (std::is_arithmetic_v<V>) {
    v = h.cast<V>();
  } else if constexpr (requires { v.size(); v[0]; }) {
    const auto items = h.cast<py::sequence>();
    if (items.size() != std::size_t(v.size()))
      throw py::value_error(where + ": expected " + std::to_string(v.size()) + " items");
    for (std::size_t i = 0; i < items.size(); ++i) field_from_state(v[i], items[i], where);
  } else {
    v = h.cast<V>();
  }
}

template <class X>
py::class_<X> result_class(py::module_& m, const std::string& name, const char* doc) {
  py::class_<X> c(m, name.c_str(), doc);
  c.def(py::pickle(
      [](const X& x) {
        py::dict state;
        fields(const_cast<X&>(x), [&](const char* field, const auto& v) { state[field] = field_state(v); });
        return state;
      },
      [name](const py::dict& state) {
        X x;
        fields(x, [&](const char* field, auto& v) {
          const std::string where = "pickled " + name + "." + field;
          if (!state.contains(field)) throw py::value_error(where + ": missing");
          field_from_state(v, state[field], where);
        });
        return x;
      }));
  return c;
}

template <int N>
void def_results(py::module_& m, const char* suffix) {
  const std::string s = suffix;
  using C = Contact<double, N>;
  result_class<C>(m, ("Contact" + s).c_str(), "first_contact's answer (see contact.hpp).")
      .def_property_readonly("status", [](const C& c) { return c.status; }, "ContactStatus: The outcome.")
      .def_property_readonly("time", [](const C& c) { return c.time; },
                             "float: The first contact time in [0, t_max] (NaN without contact).")
      .def_property_readonly("point", [](const C& c) { return to_array<N>(c.point); },
                             "numpy.ndarray: The contact point at that time, world frame (N,).")
      .def_property_readonly("normal", [](const C& c) { return to_array<N>(c.normal); },
                             "numpy.ndarray: Unit, from a towards b.")
      .def_property_readonly("iterations", [](const C& c) { return c.iterations; }, "int: Iterations used.")
      .def("__repr__", [](const C& c) {
        return "Contact(status=" + std::string(to_string(c.status)) + ", time=" + std::to_string(c.time) + ")";
      });
  using S = Slide<double, N>;
  result_class<S>(m, ("Slide" + s).c_str(), "collide_and_slide's answer (see slide.hpp).")
      .def_property_readonly("status", [](const S& r) { return r.status; }, "SlideStatus: The outcome.")
      .def_property_readonly("body", [](const S& r) { return r.body; },
                             (std::string(N == 2 ? "Ellipse" : "Ellipsoid") + ": The body where it ends.").c_str())
      .def_property_readonly("moved", [](const S& r) { return to_array<N>(r.moved); },
                             "numpy.ndarray: The displacement made (N,).")
      .def_property_readonly("contacts", [](const S& r) { return r.contacts; },
                             "int: The number of contacts on the way.")
      .def_property_readonly("last_contact", [](const S& r) { return r.last_contact; },
                             "int: Index of the last half-space or triangle hit, or -1.")
      .def("__repr__", [](const S& r) {
        return "Slide(status=" + std::string(to_string(r.status)) + ", contacts=" + std::to_string(r.contacts) + ")";
      });
  using MC = MeshContact<double, N>;
  result_class<MC>(m, ("MeshContact" + s).c_str(), "first_contact's answer against a mesh (see mesh.hpp).")
      .def_property_readonly("contact", [](const MC& c) { return c.contact; },
                             ("Contact" + s + ": The contact (Contact2 / Contact3).").c_str())
      .def_property_readonly("triangle", [](const MC& c) { return c.triangle; }, "int: The triangle hit, or -1.")
      .def("__repr__", [](const MC& c) {
        return "MeshContact(status=" + std::string(to_string(c.contact.status)) + ", time=" +
               std::to_string(c.contact.time) + ", triangle=" + std::to_string(c.triangle) + ")";
      });
  using MD = MeshDistance<double, N>;
  result_class<MD>(m, ("MeshDistance" + s).c_str(), "distance / signed_distance's answer against a mesh (see mesh.hpp).")
      .def_property_readonly("distance", [](const MD& d) { return d.distance; },
                             ("Distance" + s + ": The distance answer (Distance2 / Distance3).").c_str())
      .def_property_readonly("triangle", [](const MD& d) { return d.triangle; },
                             "int: The nearest (deepest) triangle, or -1.")
      .def("__repr__", [](const MD& d) {
        return "MeshDistance(status=" + std::string(to_string(d.distance.status)) + ", distance=" +
               std::to_string(d.distance.distance) + ", triangle=" + std::to_string(d.triangle) + ")";
      });
  using D = Distance<double, N>;
  result_class<D>(m, ("Distance" + s).c_str(), "distance / signed_distance's answer (see distance.hpp).")
      .def_property_readonly("status", [](const D& d) { return d.status; }, "DistanceStatus: The outcome.")
      .def_property_readonly("distance", [](const D& d) { return d.distance; },
                             "float: The distance (signed: negative for the penetration depth).")
      .def_property_readonly("point_a", [](const D& d) { return to_array<N>(d.point_a); },
                             "numpy.ndarray: The witness point on a (N,).")
      .def_property_readonly("point_b", [](const D& d) { return to_array<N>(d.point_b); },
                             "numpy.ndarray: The witness point on b (N,).")
      .def_property_readonly("normal", [](const D& d) { return to_array<N>(d.normal); },
                             "numpy.ndarray: Unit, from a towards b (N,).")
      .def_property_readonly("iterations", [](const D& d) { return d.iterations; }, "int: Iterations used.")
      .def("__repr__", [](const D& d) {
        return "Distance(status=" + std::string(to_string(d.status)) + ", distance=" + std::to_string(d.distance) +
               ")";
      });
  using P = ClosestPoint<double, N>;
  result_class<P>(m, ("ClosestPoint" + s).c_str(), "closest_point's answer (see point.hpp).")
      .def_property_readonly("point", [](const P& p) { return to_array<N>(p.point); },
                             "numpy.ndarray: The closest boundary point (N,).")
      .def_property_readonly("signed_distance", [](const P& p) { return p.signed_distance; },
                             "float: Its signed distance to x (negative inside).");
  using A = ClosestApproach<double, N>;
  result_class<A>(m, ("ClosestApproach" + s).c_str(), "closest_approach's answer (see contact_function.hpp).")
      .def_property_readonly("status", [](const A& a) { return a.status; }, "ContactFunctionStatus: The outcome.")
      .def_property_readonly("distance", [](const A& a) { return a.distance; }, "float: How far b moves until contact.")
      .def_property_readonly("distance_lower", [](const A& a) { return a.distance_lower; },
                             "float: A certified lower bound of distance.")
      .def_property_readonly("point", [](const A& a) { return to_array<N>(a.point); },
                             "numpy.ndarray: The contact point (N,).")
      .def_property_readonly("normal", [](const A& a) { return to_array<N>(a.normal); },
                             "numpy.ndarray: Unit, from a towards b.")
      .def_property_readonly("lambda_", [](const A& a) { return a.lambda; },
                             "float: The maximizing lambda of the contact function.")
      .def_property_readonly("iterations", [](const A& a) { return a.iterations; }, "int: Iterations used.")
      .def("__repr__", [](const A& a) {
        return "ClosestApproach(status=" + std::string(to_string(a.status)) + ", distance=" + std::to_string(a.distance) +
               ")";
      });
}

// Rigid motion (contact.hpp's RigidMotion): the angular velocity is a rate in 2D, a
// 3-vector in 3D; None for a body that does not turn; the growth rate of its radii.
template <int N>
using AngularVelocity = std::optional<std::conditional_t<N == 2, double, Row<3>>>;

template <int N>
RigidMotion<double, N> motion(const Row<N>& v, const AngularVelocity<N>& w, double growth = 0.0) {
  RigidMotion<double, N> out{vec<N>(v)};
  out.growth = growth;
  if (w) {
    if constexpr (N == 2) out.angular_velocity = *w;
    else out.angular_velocity = vec<3>(*w);
  }
  return out;
}

// Each obstacle's words in the docstrings: what it is called, its header, its containment
// relations.
template <class S>
struct ObstacleDocs;
template <int N>
struct ObstacleDocs<HalfSpace<double, N>> {
  static constexpr const char* label = "half-space";
  static constexpr const char* header = "half_space.hpp";
  static constexpr const char* containment = "b_contains_a: the body inside";
};
template <int N>
struct ObstacleDocs<Triangle<double, N>> {
  static constexpr const char* label = "triangle";
  static constexpr const char* header = "triangle.hpp";
  static constexpr const char* containment = "a_contains_b: the triangle inside the body";
};
template <int N>
struct ObstacleDocs<Box<double, N>> {
  static constexpr const char* label = "box";
  static constexpr const char* header = "box.hpp";
  static constexpr const char* containment = "containment both ways";
};
template <int N>
struct ObstacleDocs<Capsule<double, N>> {
  static constexpr const char* label = "capsule";
  static constexpr const char* header = "capsule.hpp";
  static constexpr const char* containment =
      "a_contains_b: the capsule inside the body, b_contains_a: the body inside the capsule";
};
template <int N>
struct ObstacleDocs<TriangleMesh<double, N>> {
  static constexpr const char* label = "triangle mesh";
  static constexpr const char* header = "mesh.hpp";
  static constexpr const char* containment = "the GIL is released";
};

// first_contact of a body and a moving shape S (half_space.hpp, box.hpp, capsule.hpp,
// triangle.hpp, mesh.hpp); with angular_velocity_a, the body in rigid motion (the shape does
// not turn). `extra`: further pybind11 attributes (a call guard).
template <int N, class S, class... Extra>
void def_shape_contact(py::module_& m, const std::string& shape, const std::string& returns, const Extra&... extra) {
  using E = Ellipsoid<double, N>;
  m.def("first_contact",
        [](const E& a, const Row<N>& va, const S& b, const Row<N>& vb, double t_max, const Options& o,
           const AngularVelocity<N>& wa, double ga) {
          if (!wa && ga == 0.0) return first_contact(a, vec<N>(va), b, vec<N>(vb), t_max, o);
          return first_contact(a, motion<N>(va, wa, ga), b, vec<N>(vb), t_max, o);
        },
        py::arg("a"), py::arg("velocity_a"), py::arg("b"), py::arg("velocity_b"), py::arg("t_max"),
        options_arg(), py::arg("angular_velocity_a") = py::none(), py::arg("growth_a") = 0.0,
        docs::doc("First contact of a moving body and a moving " + shape + " in [0, t_max] (contact.hpp).",
                  "a: the body (Ellipse / Ellipsoid).\nb: the " + shape + " (it moves at velocity_b and does not turn).\n" +
                      docs::motion + "\ngrowth_a: the body's radii scale as (1 + growth_a t) (>= 0).",
                  returns, docs::angular_raises)
            .c_str(),
        extra...);
}

// classify, overlap, distance and signed_distance of a body and a shape S, as the library
// names them; `call` wraps each call (the GIL released for meshes).
template <int N, class S, class Call>
void def_shape_queries(py::module_& m, const std::string& shape, const std::string& header,
                       const std::string& containment, const std::string& distance_returns, const Call& call) {
  using E = Ellipsoid<double, N>;
  const std::string args = "a: the body (Ellipse / Ellipsoid).\nb: the " + shape + ".\n" + docs::options;
  m.def("classify",
        [call](const E& a, const S& b, const Options& o) { return call([&] { return classify(a, b, o); }); },
        py::arg("a"), py::arg("b"), options_arg(),
        docs::doc("The relation of a body and a " + shape + " (" + header + "; " + containment + ").", args,
                  std::is_same_v<S, Mesh<N>> ? "MeshRelation: relation and the lowest-index triangle with it (-1: none)."
                                              : "Relation.",
                  docs::no_overload)
            .c_str());
  m.def("overlap", [call](const E& a, const S& b, const Options& o) { return call([&] { return overlap(a, b, o); }); },
        py::arg("a"), py::arg("b"), options_arg(),
        docs::doc("Whether a body and a " + shape + " share a point (" + header + ").", args, "bool.",
                  docs::no_overload)
            .c_str());
  m.def("distance",
        [call](const E& a, const S& b, const Options& o) { return call([&] { return distance(a, b, o); }); },
        py::arg("a"), py::arg("b"), options_arg(),
        docs::doc("Separation distance of a body and a " + shape + ", 0 when they meet (" + header + ").", args,
                  distance_returns, docs::no_overload)
            .c_str());
  m.def("signed_distance",
        [call](const E& a, const S& b, const Options& o) { return call([&] { return signed_distance(a, b, o); }); },
        py::arg("a"), py::arg("b"), options_arg(),
        docs::doc("Signed distance of a body and a " + shape + ": the separation, or minus the penetration depth (" +
                      header + ").",
                  args, distance_returns, docs::no_overload)
            .c_str());
}

// The scalar queries of both dimensions.
template <int N>
void def_queries(py::module_& m) {
  using E = Ellipsoid<double, N>;
  const std::string suffix = std::to_string(N);
  const auto plain = [](const auto& f) { return f(); };
  const auto released = [](const auto& f) {
    py::gil_scoped_release release;
    return f();
  };
  const std::string two = "a, b: two Ellipse, or two Ellipsoid.\n" + docs::options;
  m.def("classify", py::overload_cast<const E&, const E&, const Options&>(&classify<double, N>), py::arg("a"),
        py::arg("b"), options_arg(),
        docs::doc("The relation of two bodies (classify.hpp), certified near tangency.", two,
                  "Relation: separated, touching, overlapping, a_contains_b, b_contains_a or equal.", docs::no_overload)
            .c_str());
  m.def("overlap", py::overload_cast<const E&, const E&, const Options&>(&overlap<double, N>), py::arg("a"),
        py::arg("b"), options_arg(),
        docs::doc("Whether two bodies share a point (overlap.hpp).", two, "bool.", docs::no_overload).c_str());
  m.def("first_contact",
        [](const E& a, const Row<N>& va, const E& b, const Row<N>& vb, double t_max, const Options& o,
           const AngularVelocity<N>& wa, const AngularVelocity<N>& wb, double ga, double gb) {
          if (!wa && !wb && ga == 0.0 && gb == 0.0) return first_contact(a, vec<N>(va), b, vec<N>(vb), t_max, o);
          return first_contact(a, motion<N>(va, wa, ga), b, motion<N>(vb, wb, gb), t_max, o);
        },
        py::arg("a"), py::arg("velocity_a"), py::arg("b"), py::arg("velocity_b"), py::arg("t_max"),
        options_arg(), py::arg("angular_velocity_a") = py::none(),
        py::arg("angular_velocity_b") = py::none(), py::arg("growth_a") = 0.0, py::arg("growth_b") = 0.0,
        docs::doc("First contact of two moving bodies in [0, t_max] (contact.hpp); with an angular velocity or a "
                  "growth, under rigid motion with growth.",
                  "a, b: two Ellipse, or two Ellipsoid.\n" + docs::motion +
                      "\nangular_velocity_b: as angular_velocity_a, for b.\ngrowth_a, growth_b: each body's radii "
                      "scale as (1 + growth t) about its center (>= 0; 0: rigid).",
                  docs::contact_returns, docs::angular_raises)
            .c_str());
  m.def("body_at",
        [](const E& body, const Row<N>& velocity, const AngularVelocity<N>& angular_velocity, double t,
           double growth) { return body_at(body, motion<N>(velocity, angular_velocity, growth), t); },
        py::arg("body"), py::arg("velocity"), py::arg("angular_velocity"), py::arg("t"), py::arg("growth") = 0.0,
        docs::doc("The body at time t of its rigid motion (contact.hpp).",
                  "body: Ellipse / Ellipsoid at t = 0.\nvelocity: velocity of its center (N,).\n"
                  "angular_velocity: None, a rate in 2D, a 3-vector in 3D.\nt: the time.\ngrowth: its radii scale as "
                  "(1 + growth t) (>= 0).",
                  "Ellipse / Ellipsoid.",
                  "InputError: a center that leaves the finite range, a negative growth, radii scaled to 0.\n" +
                      docs::no_overload)
            .c_str());
  const std::string distance_returns = "Distance" + suffix +
                                       ": status (DistanceStatus), distance, point_a, point_b (witness points), "
                                       "normal (unit, from a towards b), iterations.";
  // A hint (the normal of an earlier answer, from a towards b) starts the descent near the
  // answer: the same answer and claims, only the cost changes (distance.hpp).
  using Hint = std::optional<Row<N>>;
  const std::string hinted = two + "\nhint: None, or a direction (N,) from a towards b, such as an earlier answer's "
                                   "normal for the same pair: the descent starts there (only the cost changes).";
  m.def(
      "distance",
      [](const E& a, const E& b, const Options& o, const Hint& hint) {
        return hint ? distance(a, b, o, vec<N>(*hint)) : distance(a, b, o);
      },
      py::arg("a"), py::arg("b"), options_arg(), py::arg("hint") = py::none(),
      docs::doc("Separation distance of two bodies, 0 when they meet (distance.hpp).", hinted, distance_returns,
                docs::no_overload)
          .c_str());
  m.def(
      "signed_distance",
      [](const E& a, const E& b, const Options& o, const Hint& hint) {
        return hint ? signed_distance(a, b, o, vec<N>(*hint)) : signed_distance(a, b, o);
      },
      py::arg("a"), py::arg("b"), options_arg(), py::arg("hint") = py::none(),
      docs::doc("Signed distance of two bodies: the separation, or minus the penetration depth (distance.hpp).", hinted,
                distance_returns, docs::no_overload)
          .c_str());
  m.def("closest_point", [](const E& body, const Row<N>& x) { return closest_point(body, vec<N>(x)); },
        py::arg("body"), py::arg("x"),
        docs::doc("The point of the body's boundary closest to x (point.hpp).",
                  "body: Ellipse / Ellipsoid.\nx: a point (N,).",
                  "ClosestPoint" + suffix + ": point, signed_distance (negative inside).", docs::no_overload)
            .c_str());
  m.def("perram_wertheim", py::overload_cast<const E&, const E&, const Options&>(&perram_wertheim<double, N>),
        py::arg("a"), py::arg("b"), options_arg(),
        docs::doc("Perram and Wertheim's contact function of two bodies (contact_function.hpp): f < 1 overlapping, "
                  "f = 1 touching, f > 1 separated.",
                  two, "ContactFunction: status, f, f_upper, lambda_, iterations.", docs::no_overload)
            .c_str());
  m.def("closest_approach",
        [](const E& a, const E& b, const Row<N>& direction, const Options& o) {
          return closest_approach(a, b, vec<N>(direction), o);
        },
        py::arg("a"), py::arg("b"), py::arg("direction"), options_arg(),
        docs::doc("How far b may move along `direction` until it touches a (contact_function.hpp).",
                  "a, b: two Ellipse, or two Ellipsoid.\ndirection: the direction of b's motion (N,).\n" + docs::options,
                  "ClosestApproach" + suffix + ": status, distance, distance_lower, point, normal, lambda_, iterations.",
                  docs::no_overload)
            .c_str());
  const std::string contact = "Contact" + suffix + ": as for two bodies.";
  // Every obstacle of ellipsect/obstacles.hpp's list, in its order.
  for_each_obstacle<double, N>([&]<class S>() {
    using D = ObstacleDocs<S>;
    if constexpr (std::is_same_v<S, TriangleMesh<double, N>>) {  // bound as Mesh<N>, with its arrays
      def_shape_queries<N, Mesh<N>>(m, D::label, D::header, D::containment,
                                    "MeshDistance" + suffix + ": distance (a Distance" + suffix +
                                        ") and the nearest (deepest) triangle.",
                                    released);
      def_shape_contact<N, Mesh<N>>(m, D::label, "MeshContact" + suffix + ": contact (a Contact" + suffix +
                                                     ") and the triangle hit (-1: none).",
                                    py::call_guard<py::gil_scoped_release>());
    } else {
      def_shape_queries<N, S>(m, D::label, D::header, D::containment, distance_returns, plain);
      def_shape_contact<N, S>(m, D::label, contact);
    }
  });
  using H = HalfSpace<double, N>;
  using TM = Mesh<N>;
  const std::string slide_returns = "Slide" + suffix +
                                    ": status (SlideStatus), body (where it ends), moved, contacts, last_contact.";
  m.def("collide_and_slide",
        [](const E& body, const Row<N>& displacement, const std::vector<H>& world, const Options& o) {
          py::gil_scoped_release release;
          return collide_and_slide(body, vec<N>(displacement), std::span<const H>(world), o);
        },
        py::arg("body"), py::arg("displacement"), py::arg("world"), options_arg(),
        docs::doc("Moves the body by the displacement through half-spaces, sliding along what it touches (slide.hpp).",
                  "body: Ellipse / Ellipsoid.\ndisplacement: the wanted motion (N,).\nworld: a list of HalfPlane / "
                  "HalfSpace.\n" + docs::options,
                  slide_returns, docs::no_overload)
            .c_str());
  m.def("collide_and_slide",
        [](const E& body, const Row<N>& displacement, const TM& world, const Options& o) {
          py::gil_scoped_release release;
          return collide_and_slide(body, vec<N>(displacement), world, o);
        },
        py::arg("body"), py::arg("displacement"), py::arg("world"), options_arg(),
        docs::doc("Moves the body by the displacement through a triangle mesh, sliding along what it touches "
                  "(slide.hpp).",
                  "body: Ellipse / Ellipsoid.\ndisplacement: the wanted motion (N,).\nworld: TriangleMesh2 / "
                  "TriangleMesh3.\n" + docs::options,
                  slide_returns, docs::no_overload)
            .c_str());
}

void def_two_d(py::module_& m) {
  using E = Ellipse2<double>;
  using B = BoundaryIntersection<double>;
  result_class<B>(m, "BoundaryIntersection", "intersect_boundaries' answer (see intersect2.hpp).")
      .def_property_readonly("status", [](const B& b) { return b.status; },
                             "BoundaryStatus: points, or equal boundaries.")
      .def_property_readonly("count", [](const B& b) { return b.count; }, "int: The number of points (0 to 4).")
      .def_property_readonly("points",
                             [](const B& b) {
                               py::array_t<double> out({py::ssize_t(b.count), py::ssize_t(2)});
                               for (int i = 0; i < b.count; ++i)
                                 for (int k = 0; k < 2; ++k) out.mutable_at(i, k) = b.points[std::size_t(i)][k];
                               return out;
                             },
                             "numpy.ndarray: (count, 2) array, counter-clockwise along a.")
      .def_property_readonly(
          "kinds", [](const B& b) { return std::vector<CrossingKind>(b.kinds.begin(), b.kinds.begin() + b.count); },
          "List[CrossingKind]: The kind of each point.");
  using A = OverlapArea<double>;
  result_class<A>(m, "OverlapArea", "overlap_area's answer (see intersect2.hpp).")
      .def_property_readonly("area", [](const A& a) { return a.area; }, "float: The shared area.")
      .def_property_readonly("relation", [](const A& a) { return a.relation; },
                             "Relation: The relation of the ellipses.")
      .def("__repr__", [](const A& a) {
        return "OverlapArea(relation=" + std::string(to_string(a.relation)) +
               ", area=" + py::repr(py::float_(a.area)).cast<std::string>() + ")";
      });
  using C = Circle<double>;
  py::class_<C> circle(m, "Circle", "The closed disk of Niemitalo's tests; radius 0 is a point.");
  circle.def(py::init([](const Row<2>& center, double radius) { return make_circle<double>(vec<2>(center), radius); }),
             py::arg("center"), py::arg("radius"),
             docs::doc("The disk of this center and radius.", "center: (2,).\nradius: >= 0.", "The circle.",
                       "InputError: a bad value, named (center[i], radius).")
                 .c_str())
      .def_property_readonly("center", [](const C& c) { return to_array<2>(c.center()); },
                             "numpy.ndarray: The center (2,).")
      .def_property_readonly("radius", &C::radius, "float: The radius.")
      .def("ellipse", &C::ellipse,
           docs::doc("The circle as an Ellipse.", "(none)", "Ellipse.", "InputError: radius 0 (a point).").c_str())
      .def("__repr__",
           [](const C& c) { return "Circle(center=" + text(c.center()) + ", radius=" + number_text(c.radius()) + ")"; })
      .def(py::pickle([](const C& c) { return py::make_tuple(to_array<2>(c.center()), c.radius()); },
                      [](const py::tuple& t) {
                        return make_circle<double>(vec<2>(t[0].cast<Row<2>>()), t[1].cast<double>());
                      }));
  def_equality(circle, [](const C& c) { return numbers_of(c.center(), c.radius()); });
  using S = SegmentCircle;
  result_class<S>(m, "SegmentCircle", "segment_circle's answer (polygonal2.hpp).")
      .def_property_readonly("verdict", [](const S& s) { return s.verdict; }, "Verdict: The answer.")
      .def_property_readonly("side", [](const S& s) { return s.side; }, "Side: The side of the circle's center.");
  using P = PolygonalOverlap<double>;
  result_class<P>(m, "PolygonalOverlap", "Niemitalo's verdict with its level and certified band (polygonal2.hpp).")
      .def_property_readonly("verdict", [](const P& p) { return p.verdict; }, "Verdict: The answer.")
      .def_property_readonly("level", [](const P& p) { return p.level; }, "int: The polygon level that decided.")
      .def_property_readonly("iterations", [](const P& p) { return p.iterations; }, "int: Iterations used.")
      .def_property_readonly("gap_lo", [](const P& p) { return p.gap_lo; },
                             "float: Lower end of the certified band of the gap.")
      .def_property_readonly("gap_hi", [](const P& p) { return p.gap_hi; },
                             "float: Upper end of the certified band of the gap.");
  using Q = QuarticPoint<double>;
  result_class<Q>(m, "QuarticPoint", "closest_point_quartic / closest_point_closed_form's answer (quartic2.hpp).")
      .def_property_readonly("status", [](const Q& q) { return q.status; }, "QuarticStatus: The outcome.")
      .def_property_readonly("point", [](const Q& q) { return to_array<2>(q.point); },
                             "numpy.ndarray: The closest boundary point (2,) (NaN unless outside).")
      .def_property_readonly("distance", [](const Q& q) { return q.distance; },
                             "float: Its distance to x (NaN unless outside).");

  const std::string two = "a, b: two Ellipse.\n" + docs::options;
  m.def("intersect_boundaries", &intersect_boundaries<double>, py::arg("a"), py::arg("b"),
        options_arg(),
        docs::doc("The points where the boundaries of two ellipses meet (intersect2.hpp).", two,
                  "BoundaryIntersection: status, count (0 to 4), points (count, 2) counter-clockwise along a, kinds.",
                  docs::no_overload)
            .c_str());
  m.def("overlap_area", py::overload_cast<const E&, const E&, const Options&>(&overlap_area<double>), py::arg("a"),
        py::arg("b"), options_arg(),
        docs::doc("The area two ellipses share (intersect2.hpp).", two, "OverlapArea: area, relation.",
                  docs::no_overload)
            .c_str());
  m.def("iou", py::overload_cast<const E&, const E&, const Options&>(&intersection_over_union<double>),
        py::arg("a"), py::arg("b"), options_arg(),
        docs::doc("Intersection over union of two ellipses (intersect2.hpp).", two, "float in [0, 1].",
                  docs::no_overload)
            .c_str());
  const std::string niemitalo = "PolygonalOverlap: verdict (Verdict), level, iterations, gap_lo, gap_hi.";
  m.def("segment_circle",
        [](const Row<2>& a, const Row<2>& b, const C& c) { return segment_circle<double>(vec<2>(a), vec<2>(b), c); },
        py::arg("a"), py::arg("b"), py::arg("circle"),
        docs::doc("Niemitalo's division-free test of a segment against a circle (polygonal2.hpp).",
                  "a, b: the segment's ends (2,).\ncircle: Circle.",
                  "SegmentCircle: verdict (Verdict) and side (Side) of the center.", docs::no_overload)
            .c_str());
  m.def("polygonal_overlap", py::overload_cast<const E&, const C&, int>(&polygonal_overlap<double>),
        py::arg("ellipse"), py::arg("circle"), py::arg("max_level") = 10,
        docs::doc("Niemitalo's test of an ellipse against a circle by inscribed and circumscribed polygons "
                  "(polygonal2.hpp).",
                  "ellipse: Ellipse.\ncircle: Circle.\nmax_level: the finest polygon level tried.", niemitalo,
                  docs::no_overload)
            .c_str());
  m.def("polygonal_overlap", py::overload_cast<const E&, const E&, int>(&polygonal_overlap<double>), py::arg("a"),
        py::arg("b"), py::arg("max_level") = 10,
        docs::doc("Niemitalo's polygon test of two ellipses (polygonal2.hpp).",
                  "a, b: two Ellipse.\nmax_level: the finest polygon level tried.", niemitalo, docs::no_overload)
            .c_str());
  m.def("circle_cover_overlap", &circle_cover_overlap<double>, py::arg("ellipse"), py::arg("circle"),
        py::arg("max_level") = 10,
        docs::doc("Niemitalo's test of an ellipse against a circle by covers of circles (polygonal2.hpp).",
                  "ellipse: Ellipse.\ncircle: Circle.\nmax_level: the finest level tried.", niemitalo,
                  docs::no_overload)
            .c_str());
  m.def("niemitalo_error_bound", py::overload_cast<const E&, int>(&niemitalo_error_bound<double>),
        py::arg("ellipse"), py::arg("level"),
        docs::doc("The largest gap between the ellipse and its level-`level` polygons (polygonal2.hpp).",
                  "ellipse: Ellipse.\nlevel: the polygon level.", "float.", docs::no_overload)
            .c_str());
  const std::string quartic = "QuarticPoint: status (QuarticStatus), point, distance (NaN unless outside).";
  m.def("closest_point_quartic",
        [](const E& e, const Row<2>& x) { return closest_point_quartic<double>(e, vec<2>(x)); }, py::arg("ellipse"),
        py::arg("x"),
        docs::doc("The closest boundary point to x by Niemitalo's quartic (quartic2.hpp).",
                  "ellipse: Ellipse.\nx: a point (2,).", quartic, docs::no_overload)
            .c_str());
  m.def("closest_point_closed_form",
        [](const E& e, const Row<2>& x) { return closest_point_closed_form<double>(e, vec<2>(x)); },
        py::arg("ellipse"), py::arg("x"),
        docs::doc("The closest boundary point to x by the published closed form (quartic2.hpp; kept with its "
                  "measured failure modes).",
                  "ellipse: Ellipse.\nx: a point (2,).", quartic, docs::no_overload)
            .c_str());
}

void def_enums(py::module_& m) {
  def_enum<Relation>(m, "Relation",
                     {{"separated", Relation::separated},
                      {"touching", Relation::touching},
                      {"overlapping", Relation::overlapping},
                      {"a_contains_b", Relation::a_contains_b},
                      {"b_contains_a", Relation::b_contains_a},
                      {"equal", Relation::equal}});
  def_enum<ContactStatus>(m, "ContactStatus",
                          {{"hit", ContactStatus::hit},
                           {"touching_at_start", ContactStatus::touching_at_start},
                           {"overlapping_at_start", ContactStatus::overlapping_at_start},
                           {"no_contact_in_window", ContactStatus::no_contact_in_window},
                           {"did_not_converge", ContactStatus::did_not_converge},
                           {"invalid_input", ContactStatus::invalid_input}});
  def_enum<DistanceStatus>(m, "DistanceStatus",
                           {{"separated", DistanceStatus::separated},
                            {"touching", DistanceStatus::touching},
                            {"overlapping", DistanceStatus::overlapping},
                            {"did_not_converge", DistanceStatus::did_not_converge}});
  def_enum<CrossingKind>(m, "CrossingKind",
                         {{"transverse", CrossingKind::transverse}, {"tangent", CrossingKind::tangent}});
  def_enum<BoundaryStatus>(m, "BoundaryStatus",
                           {{"points", BoundaryStatus::points}, {"equal", BoundaryStatus::equal}});
  def_enum<Verdict>(m, "Verdict",
                    {{"collision", Verdict::collision},
                     {"no_collision", Verdict::no_collision},
                     {"undecided", Verdict::undecided},
                     {"invalid_input", Verdict::invalid_input}});
  def_enum<Side>(m, "Side", {{"left", Side::left}, {"on_line", Side::on_line}, {"right", Side::right}});
  def_enum<ContactFunctionStatus>(m, "ContactFunctionStatus",
                                  {{"ok", ContactFunctionStatus::ok},
                                   {"concentric", ContactFunctionStatus::concentric},
                                   {"did_not_converge", ContactFunctionStatus::did_not_converge}});
  def_enum<SlideStatus>(m, "SlideStatus",
                        {{"moved", SlideStatus::moved},
                         {"slid", SlideStatus::slid},
                         {"blocked", SlideStatus::blocked},
                         {"overlapping_at_start", SlideStatus::overlapping_at_start},
                         {"invalid_input", SlideStatus::invalid_input}});
  def_enum<QuarticStatus>(m, "QuarticStatus",
                          {{"outside", QuarticStatus::outside},
                           {"inside", QuarticStatus::inside},
                           {"failed", QuarticStatus::failed},
                           {"invalid_input", QuarticStatus::invalid_input}});
}

}  // namespace

void def_scalar(py::module_& m) {
  def_enums(m);
  // Options: each field is validated by its C++ type, in the constructor, the setters and
  // unpickling alike (InputError naming the field). A cap is any Python integer (int, numpy
  // integers; a float is a TypeError), one beyond long long rejected with its digits.
  const auto cap = []<class Cap>(std::type_identity<Cap>, const py::handle& given) -> Cap {
    const auto value = py::reinterpret_steal<py::int_>(PyNumber_Index(given.ptr()));
    if (!value) throw py::error_already_set();
    int overflow = 0;
    const long long n = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0) {
      const std::string digits = py::str(py::handle(value));
      ellipsect::detail::reject_option(Cap::field, digits.c_str(), Cap::min, Cap::max);
    }
    return n;
  };
  // The caps in Options' order: the constructor's and the pickle's arguments after tolerance.
  static constexpr auto caps =
      std::make_tuple(&Options::max_contact_iterations, &Options::max_distance_iterations,
                      &Options::max_contact_function_iterations, &Options::max_slide_rounds,
                      &Options::max_motion_steps, &Options::max_slabs);
  using Given = std::array<py::object, std::tuple_size_v<decltype(caps)>>;
  // Options from a tolerance and the caps' Python values, each checked as it is set (the
  // first bad one, in Options' order, is named).
  const auto options_from = [cap](double tolerance, const Given& given) {
    Options o{tolerance};
    std::size_t k = 0;
    std::apply([&]<class... Cap>(Cap Options::*... member) { ((o.*member = cap(std::type_identity<Cap>{}, given[k++])), ...); },
               caps);
    return o;
  };
  const Options defaults;
  py::class_<Options> options(m, "Options", "Tolerance and one iteration cap per algorithm, validated (options.hpp).");
  options
      .def(py::init([options_from](double tolerance, const py::object& contact, const py::object& distance,
                                   const py::object& contact_function, const py::object& slide,
                                   const py::object& motion, const py::object& slabs) {
             return options_from(tolerance, {contact, distance, contact_function, slide, motion, slabs});
           }),
           py::arg("tolerance") = double(defaults.tolerance),
           py::arg("max_contact_iterations") = int(defaults.max_contact_iterations),
           py::arg("max_distance_iterations") = int(defaults.max_distance_iterations),
           py::arg("max_contact_function_iterations") = int(defaults.max_contact_function_iterations),
           py::arg("max_slide_rounds") = int(defaults.max_slide_rounds),
           py::arg("max_motion_steps") = int(defaults.max_motion_steps),
           py::arg("max_slabs") = int(defaults.max_slabs))
      .def_property(
          "tolerance", [](const Options& o) { return o.tolerance.value(); },
          [](Options& o, double tolerance) { o.tolerance = tolerance; });
  std::apply(
      [&]<class... Cap>(Cap Options::*... member) {
        (options.def_property(
             Cap::field, [member](const Options& o) { return int(o.*member); },
             [cap, member](Options& o, const py::object& n) { o.*member = cap(std::type_identity<Cap>{}, n); }),
         ...);
      },
      caps);
  options.def(py::pickle(
      [](const Options& o) {
        return std::apply([&](auto... member) { return py::make_tuple(o.tolerance.value(), int(o.*member)...); },
                          caps);
      },
      [options_from](const py::tuple& t) {
        Given given;
        for (std::size_t k = 0; k < given.size(); ++k) given[k] = t[k + 1];
        return options_from(t[0].cast<double>(), given);
      }));

  py::class_<Ellipse2<double>> ellipse(m, "Ellipse", "A validated ellipse (shapes.hpp).");
  ellipse.def(py::init([](const Row<2>& center, const Row<2>& radii, std::optional<double> angle,
                          std::optional<Rows<2>> rotation, bool normalize) {
                if (angle && rotation) throw py::value_error("Ellipse: give angle or rotation, not both");
                if (rotation)
                  return Ellipse2<double>::from_axes(vec<2>(center), normalized<2>(*rotation, normalize),
                                                     vec<2>(radii));
                return make_ellipse<double>(vec<2>(center), angle.value_or(0.0), vec<2>(radii));
              }),
              py::arg("center"), py::arg("radii"), py::arg("angle") = py::none(), py::arg("rotation") = py::none(),
              py::arg("normalize") = false,
              docs::doc("The ellipse whose first axis makes `angle` radians with x, or whose axes are the columns of "
                        "`rotation`.",
                        "center: (2,).\nradii: (2,), > 0, aspect ratio at most 1e8.\nangle: radians (default 0).\n"
                        "rotation: (2, 2), orthonormal columns (within 1e-9).\nnormalize: make a rotation within "
                        "float32's tolerance (1e-5) orthonormal first.",
                        "The ellipse.",
                        "InputError: a bad value, named (center[i], radii[i], radii, angle, axes).\n"
                        "ValueError: both angle and rotation.")
                  .c_str());
  def_body<2>(ellipse);
  py::class_<Ellipsoid3<double>> ellipsoid(m, "Ellipsoid", "A validated ellipsoid (shapes.hpp).");
  ellipsoid.def(py::init([](const Row<3>& center, const Row<3>& radii, std::optional<Row<4>> quaternion,
                            std::optional<Rows<3>> rotation, bool normalize) {
                  if (quaternion && rotation) throw py::value_error("Ellipsoid: give quaternion or rotation, not both");
                  if (rotation)
                    return make_ellipsoid<double>(vec<3>(center), normalized<3>(*rotation, normalize), vec<3>(radii));
                  const Row<4> q = quaternion.value_or(Row<4>{1, 0, 0, 0});
                  const Quat<double> given(q[0], q[1], q[2], q[3]);
                  return make_ellipsoid<double>(vec<3>(center), normalize ? normalized_quaternion(given) : given,
                                                vec<3>(radii));
                }),
                py::arg("center"), py::arg("radii"), py::arg("quaternion") = py::none(),
                py::arg("rotation") = py::none(), py::arg("normalize") = false,
                docs::doc("The ellipsoid rotated by a unit quaternion, or whose axes are the columns of `rotation`.",
                          "center: (3,).\nradii: (3,), > 0, aspect ratio at most 1e8.\nquaternion: (w, x, y, z), unit "
                          "norm within 1e-9 (default: no rotation).\nrotation: (3, 3), orthonormal columns (within "
                          "1e-9).\nnormalize: divide a quaternion within float32's tolerance (1e-5) of unit norm by "
                          "its norm, make such a rotation orthonormal, first.",
                          "The ellipsoid.",
                          "InputError: a bad value, named (center[i], radii[i], radii, quaternion.w, quaternion, "
                          "axes).\nValueError: both quaternion and rotation.")
                    .c_str());
  def_body<3>(ellipsoid);
  def_half_space<2>(m, "HalfPlane");
  def_half_space<3>(m, "HalfSpace");
  def_box<2>(m, "Box2");
  def_box<3>(m, "Box3");
  def_capsule<2>(m, "Capsule2");
  def_capsule<3>(m, "Capsule3");
  def_triangle<2>(m, "Triangle2");
  def_triangle<3>(m, "Triangle3");
  result_class<MeshRelation>(m, "MeshRelation", "classify's answer against a mesh (see mesh.hpp).")
      .def_property_readonly("relation", [](const MeshRelation& r) { return r.relation; },
                             "Relation: The relation to the whole mesh.")
      .def_property_readonly("triangle", [](const MeshRelation& r) { return r.triangle; },
                             "int: The lowest-index triangle with that relation, or -1.")
      .def("__repr__", [](const MeshRelation& r) {
        return "MeshRelation(relation=" + std::string(to_string(r.relation)) + ", triangle=" +
               std::to_string(r.triangle) + ")";
      });

  using F = ContactFunction<double>;
  result_class<F>(m, "ContactFunction", "perram_wertheim's answer (see contact_function.hpp).")
      .def_property_readonly("status", [](const F& f) { return f.status; }, "ContactFunctionStatus: The outcome.")
      .def_property_readonly("f", [](const F& f) { return f.f; },
                             "float: The contact function's value (a lower bound).")
      .def_property_readonly("f_upper", [](const F& f) { return f.f_upper; }, "float: An upper bound of the value.")
      .def_property_readonly("lambda_", [](const F& f) { return f.lambda; },
                             "float: The maximizing lambda (weight of b).")
      .def_property_readonly("iterations", [](const F& f) { return f.iterations; }, "int: Iterations used.")
      .def("__repr__", [](const F& f) {
        return "ContactFunction(status=" + std::string(to_string(f.status)) + ", f=" + std::to_string(f.f) + ")";
      });
  def_results<2>(m, "2");
  def_results<3>(m, "3");
  def_queries<2>(m);
  def_queries<3>(m);
  def_two_d(m);
}

void def_fit(py::module_& m);  // fit.cpp

}  // namespace ellipsect::python

PYBIND11_MODULE(_ellipsect, m) {
  m.doc() = "ellipsect: exact collision queries between ellipses and ellipsoids (C++ library bindings)";
  ellipsect::python::def_errors(m);
  ellipsect::python::def_scalar(m);
  ellipsect::python::def_batch(m);
  ellipsect::python::def_packing(m);
  ellipsect::python::def_geometry(m);
  ellipsect::python::def_fit(m);
  m.def("simd_target", &ellipsect::simd_target,
        ellipsect::python::docs::doc("The instruction set the batch functions use (batch.hpp).", "(none)", "str.")
            .c_str());
}
