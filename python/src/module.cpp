// The Python module `ellipsect._ellipsect`: argument checks and conversions around the
// library, nothing else (every number comes from the C++ functions). Scalar bodies and
// results are double; the enums are Python IntEnums (common.hpp).
#include "common.hpp"

#include <ellipsect/ellipsect.hpp>

#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <sstream>

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

template <int N>
std::string body_repr(const Ellipsoid<double, N>& e) {
  std::ostringstream s;
  s.precision(17);
  s << (N == 2 ? "Ellipse" : "Ellipsoid") << "(center=[";
  for (int k = 0; k < N; ++k) s << (k ? ", " : "") << e.center()[k];
  s << "], radii=[";
  for (int k = 0; k < N; ++k) s << (k ? ", " : "") << e.radii()[k];
  s << "])";
  return s.str();
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
               "Body whose principal directions are the columns of `axes` (orthonormal).")
      .def_static("from_quadric",
                  [](const Row<N>& center, const Rows<N>& M) { return E::from_quadric(vec<N>(center), mat<N>(M)); },
                  py::arg("center"), py::arg("M"), "Body {x : (x - center)^T M (x - center) <= 1}.")
      .def_static("ball", [](const Row<N>& center, double radius) { return make_ball<double, N>(vec<N>(center), radius); },
                  py::arg("center"), py::arg("radius"))
      .def_property_readonly("center", [](const E& e) { return to_array<N>(e.center()); })
      .def_property_readonly("axes", [](const E& e) { return to_array<N>(e.axes()); },
                             "Principal directions, as columns.")
      .def_property_readonly("radii", [](const E& e) { return to_array<N>(e.radii()); })
      .def("quadric", [](const E& e) { return to_array<N>(e.quadric()); })
      .def("translated", [](const E& e, const Row<N>& offset) { return e.translated(vec<N>(offset)); },
           py::arg("offset"))
      .def("__repr__", &body_repr<N>)
      .def(py::pickle([](const E& e) { return py::make_tuple(to_array<N>(e.center()), to_array<N>(e.axes()),
                                                             to_array<N>(e.radii())); },
                      [](const py::tuple& t) {
                        return E::from_axes(vec<N>(t[0].cast<Row<N>>()), mat<N>(t[1].cast<Rows<N>>()),
                                            vec<N>(t[2].cast<Row<N>>()));
                      }));
}

// HalfPlane (N = 2) and HalfSpace (N = 3): { x : normal . (x - point) <= 0 } (half_space.hpp).
template <int N>
void def_half_space(py::module_& m, const char* name) {
  using H = HalfSpace<double, N>;
  py::class_<H>(m, name, "A validated half-space {x : normal . (x - point) <= 0} (half_space.hpp).")
      .def(py::init([](const Row<N>& point, const Row<N>& normal) {
             return make_half_space<double, N>(vec<N>(point), vec<N>(normal));
           }),
           py::arg("point"), py::arg("normal"), "The normal (outward, any length) is stored as a unit vector.")
      .def_property_readonly("point", [](const H& h) { return to_array<N>(h.point()); })
      .def_property_readonly("normal", [](const H& h) { return to_array<N>(h.normal()); })
      .def("translated", [](const H& h, const Row<N>& offset) { return h.translated(vec<N>(offset)); },
           py::arg("offset"))
      .def("__repr__",
           [name](const H& h) {
             std::ostringstream s;
             s.precision(17);
             s << name << "(point=[";
             for (int k = 0; k < N; ++k) s << (k ? ", " : "") << h.point()[k];
             s << "], normal=[";
             for (int k = 0; k < N; ++k) s << (k ? ", " : "") << h.normal()[k];
             s << "])";
             return s.str();
           })
      .def(py::pickle([](const H& h) { return py::make_tuple(to_array<N>(h.point()), to_array<N>(h.normal())); },
                      [](const py::tuple& t) {
                        return make_half_space<double, N>(vec<N>(t[0].cast<Row<N>>()), vec<N>(t[1].cast<Row<N>>()));
                      }));
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
  py::class_<Tr>(m, name, "A triangle: the convex hull of three points, degenerate ones included (triangle.hpp).")
      .def(py::init([](const Row<N>& v0, const Row<N>& v1, const Row<N>& v2) {
             return make_triangle<double, N>(vec<N>(v0), vec<N>(v1), vec<N>(v2));
           }),
           py::arg("v0"), py::arg("v1"), py::arg("v2"))
      .def_property_readonly("vertices", vertices, "The vertices, one per row.")
      .def("translated", [](const Tr& t, const Row<N>& offset) { return t.translated(vec<N>(offset)); },
           py::arg("offset"))
      .def("__repr__",
           [name](const Tr& t) {
             std::ostringstream s;
             s.precision(17);
             s << name << "(";
             for (int k = 0; k < 3; ++k) {
               s << (k ? ", [" : "[");
               for (int i = 0; i < N; ++i) s << (i ? ", " : "") << t.vertex(k)[i];
               s << "]";
             }
             s << ")";
             return s.str();
           })
      .def(py::pickle([](const Tr& t) { return py::make_tuple(to_array<N>(t.vertex(0)), to_array<N>(t.vertex(1)),
                                                              to_array<N>(t.vertex(2))); },
                      [](const py::tuple& t) {
                        return make_triangle<double, N>(vec<N>(t[0].cast<Row<N>>()), vec<N>(t[1].cast<Row<N>>()),
                                                        vec<N>(t[2].cast<Row<N>>()));
                      }));
  using M = TriangleMesh<double, N>;
  py::class_<M>(m, ("TriangleMesh" + std::to_string(N)).c_str(),
                "Triangles sharing vertices, with a box hierarchy for the queries (mesh.hpp).")
      .def(py::init([](py::handle vertices, py::handle triangles) {
             py::ssize_t rows = -1;
             const double* v = checked(vertices, "vertices", {N}, rows, "vertices");
             if (!py::isinstance<py::array>(triangles))
               throw py::type_error("triangles: expected a numpy array of integers");
             const auto a = py::reinterpret_borrow<py::array>(triangles);
             const char kind = a.dtype().kind();
             if (kind != 'i' && kind != 'u')
               throw py::type_error("triangles: expected an integer dtype, got " + std::string(py::str(a.dtype())));
             if (a.ndim() != 2 || a.shape(1) != 3)
               throw py::value_error("triangles: expected shape (n, 3), got " +
                                     shape_text(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim())));
             const auto t = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
             py::gil_scoped_release release;
             return M::from_arrays(std::span<const double>(v, std::size_t(rows) * N),
                                   std::span<const std::int64_t>(t.data(), std::size_t(t.size())));
           }),
           py::arg("vertices"), py::arg("triangles"),
           "vertices: float64 array (n, N); triangles: integer array (m, 3) of vertex indices.")
      .def_property_readonly("vertex_count", &M::vertex_count)
      .def_property_readonly("triangle_count", &M::triangle_count)
      .def("__len__", &M::triangle_count)
      .def("triangle", &M::triangle, py::arg("k"))
      .def("__repr__", [](const M& mesh) {
        return "TriangleMesh" + std::to_string(N) + "(vertices=" + std::to_string(mesh.vertex_count()) +
               ", triangles=" + std::to_string(mesh.triangle_count()) + ")";
      });
}

// Box2 / Box3: an oriented rectangle or box (box.hpp).
template <int N>
void def_box(py::module_& m, const char* name) {
  using B = Box<double, N>;
  py::class_<B>(m, name, "A validated oriented box {center + axes u : |u_i| <= half_extents_i} (box.hpp).")
      .def(py::init([](const Row<N>& center, const Row<N>& half_extents, std::optional<Rows<N>> axes) {
             return make_box<double, N>(vec<N>(center), axes ? mat<N>(*axes) : Mat<double, N>::Identity(),
                                        vec<N>(half_extents));
           }),
           py::arg("center"), py::arg("half_extents"), py::arg("axes") = py::none(),
           "Axes: orthonormal columns (default: the coordinate axes).")
      .def_property_readonly("center", [](const B& b) { return to_array<N>(b.center()); })
      .def_property_readonly("axes", [](const B& b) { return to_array<N>(b.axes()); })
      .def_property_readonly("half_extents", [](const B& b) { return to_array<N>(b.half_extents()); })
      .def("corner", [](const B& b, int k) {
             if (k < 0 || k >= (1 << N)) throw py::index_error("corner: k must be in [0, " + std::to_string(1 << N) + ")");
             return to_array<N>(b.corner(k));
           }, py::arg("k"))
      .def("translated", [](const B& b, const Row<N>& offset) { return b.translated(vec<N>(offset)); },
           py::arg("offset"))
      .def("__repr__", [name](const B& b) {
        std::ostringstream s;
        s.precision(17);
        s << name << "(center=[";
        for (int k = 0; k < N; ++k) s << (k ? ", " : "") << b.center()[k];
        s << "], half_extents=[";
        for (int k = 0; k < N; ++k) s << (k ? ", " : "") << b.half_extents()[k];
        s << "])";
        return s.str();
      });
}

template <int N>
void def_capsule(py::module_& m, const char* name) {
  using C = Capsule<double, N>;
  py::class_<C>(m, name, "A validated capsule {x : dist(x, [p0, p1]) <= radius} (capsule.hpp).")
      .def(py::init([](const Row<N>& p0, const Row<N>& p1, double radius) {
             return make_capsule<double, N>(vec<N>(p0), vec<N>(p1), radius);
           }),
           py::arg("p0"), py::arg("p1"), py::arg("radius"))
      .def_property_readonly("p0", [](const C& c) { return to_array<N>(c.point(0)); })
      .def_property_readonly("p1", [](const C& c) { return to_array<N>(c.point(1)); })
      .def_property_readonly("radius", &C::radius)
      .def("translated", [](const C& c, const Row<N>& offset) { return c.translated(vec<N>(offset)); },
           py::arg("offset"))
      .def("__repr__", [name](const C& c) {
        std::ostringstream s;
        s.precision(17);
        s << name << "(p0=[";
        for (int k = 0; k < N; ++k) s << (k ? ", " : "") << c.point(0)[k];
        s << "], p1=[";
        for (int k = 0; k < N; ++k) s << (k ? ", " : "") << c.point(1)[k];
        s << "], radius=" << c.radius() << ")";
        return s.str();
      });
}

template <int N>
void def_results(py::module_& m, const char* suffix) {
  const std::string s = suffix;
  using C = Contact<double, N>;
  py::class_<C>(m, ("Contact" + s).c_str(), "first_contact's answer (see contact.hpp).")
      .def_property_readonly("status", [](const C& c) { return c.status; })
      .def_property_readonly("time", [](const C& c) { return c.time; })
      .def_property_readonly("point", [](const C& c) { return to_array<N>(c.point); })
      .def_property_readonly("normal", [](const C& c) { return to_array<N>(c.normal); }, "Unit, from a towards b.")
      .def_property_readonly("iterations", [](const C& c) { return c.iterations; })
      .def("__repr__", [](const C& c) {
        return "Contact(status=" + std::string(to_string(c.status)) + ", time=" + std::to_string(c.time) + ")";
      });
  using S = Slide<double, N>;
  py::class_<S>(m, ("Slide" + s).c_str(), "collide_and_slide's answer (see slide.hpp).")
      .def_property_readonly("status", [](const S& r) { return r.status; })
      .def_property_readonly("body", [](const S& r) { return r.body; }, "The body where it ends.")
      .def_property_readonly("moved", [](const S& r) { return to_array<N>(r.moved); })
      .def_property_readonly("contacts", [](const S& r) { return r.contacts; })
      .def_property_readonly("last_contact", [](const S& r) { return r.last_contact; },
                             "Index of the last half-space or triangle hit, or -1.")
      .def("__repr__", [](const S& r) {
        return "Slide(status=" + std::string(to_string(r.status)) + ", contacts=" + std::to_string(r.contacts) + ")";
      });
  using MC = MeshContact<double, N>;
  py::class_<MC>(m, ("MeshContact" + s).c_str(), "first_contact's answer against a mesh (see mesh.hpp).")
      .def_property_readonly("contact", [](const MC& c) { return c.contact; })
      .def_property_readonly("triangle", [](const MC& c) { return c.triangle; }, "The triangle hit, or -1.")
      .def("__repr__", [](const MC& c) {
        return "MeshContact(status=" + std::string(to_string(c.contact.status)) + ", time=" +
               std::to_string(c.contact.time) + ", triangle=" + std::to_string(c.triangle) + ")";
      });
  using MD = MeshDistance<double, N>;
  py::class_<MD>(m, ("MeshDistance" + s).c_str(), "distance / signed_distance's answer against a mesh (see mesh.hpp).")
      .def_property_readonly("distance", [](const MD& d) { return d.distance; })
      .def_property_readonly("triangle", [](const MD& d) { return d.triangle; }, "The nearest (deepest) triangle, or -1.")
      .def("__repr__", [](const MD& d) {
        return "MeshDistance(status=" + std::string(to_string(d.distance.status)) + ", distance=" +
               std::to_string(d.distance.distance) + ", triangle=" + std::to_string(d.triangle) + ")";
      });
  using D = Distance<double, N>;
  py::class_<D>(m, ("Distance" + s).c_str(), "distance / signed_distance's answer (see distance.hpp).")
      .def_property_readonly("status", [](const D& d) { return d.status; })
      .def_property_readonly("distance", [](const D& d) { return d.distance; })
      .def_property_readonly("point_a", [](const D& d) { return to_array<N>(d.point_a); })
      .def_property_readonly("point_b", [](const D& d) { return to_array<N>(d.point_b); })
      .def_property_readonly("normal", [](const D& d) { return to_array<N>(d.normal); })
      .def_property_readonly("iterations", [](const D& d) { return d.iterations; })
      .def("__repr__", [](const D& d) {
        return "Distance(status=" + std::string(to_string(d.status)) + ", distance=" + std::to_string(d.distance) +
               ")";
      });
  using P = ClosestPoint<double, N>;
  py::class_<P>(m, ("ClosestPoint" + s).c_str(), "closest_point's answer (see point.hpp).")
      .def_property_readonly("point", [](const P& p) { return to_array<N>(p.point); })
      .def_property_readonly("signed_distance", [](const P& p) { return p.signed_distance; });
  using A = ClosestApproach<double, N>;
  py::class_<A>(m, ("ClosestApproach" + s).c_str(), "closest_approach's answer (see contact_function.hpp).")
      .def_property_readonly("status", [](const A& a) { return a.status; })
      .def_property_readonly("distance", [](const A& a) { return a.distance; })
      .def_property_readonly("distance_lower", [](const A& a) { return a.distance_lower; })
      .def_property_readonly("point", [](const A& a) { return to_array<N>(a.point); })
      .def_property_readonly("normal", [](const A& a) { return to_array<N>(a.normal); }, "Unit, from a towards b.")
      .def_property_readonly("lambda_", [](const A& a) { return a.lambda; })
      .def_property_readonly("iterations", [](const A& a) { return a.iterations; })
      .def("__repr__", [](const A& a) {
        return "ClosestApproach(status=" + std::string(to_string(a.status)) + ", distance=" + std::to_string(a.distance) +
               ")";
      });
}

// Rigid motion (contact.hpp's RigidMotion): the angular velocity is a rate in 2D, a
// 3-vector in 3D; None for a body that does not turn.
template <int N>
using AngularVelocity = std::optional<std::conditional_t<N == 2, double, Row<3>>>;

template <int N>
RigidMotion<double, N> motion(const Row<N>& v, const AngularVelocity<N>& w) {
  RigidMotion<double, N> out{vec<N>(v)};
  if (w) {
    if constexpr (N == 2) out.angular_velocity = *w;
    else out.angular_velocity = vec<3>(*w);
  }
  return out;
}

// first_contact of a body and a moving shape S (half_space.hpp, box.hpp, capsule.hpp,
// triangle.hpp, mesh.hpp); with angular_velocity_a, the body in rigid motion (the shape does
// not turn). `extra`: further pybind11 attributes (a call guard).
template <int N, class S, class... Extra>
void def_shape_contact(py::module_& m, const std::string& doc, const Extra&... extra) {
  using E = Ellipsoid<double, N>;
  m.def("first_contact",
        [](const E& a, const Row<N>& va, const S& b, const Row<N>& vb, double t_max, const Options& o,
           const AngularVelocity<N>& wa) {
          if (!wa) return first_contact(a, vec<N>(va), b, vec<N>(vb), t_max, o);
          return first_contact(a, motion<N>(va, wa), b, vec<N>(vb), t_max, o);
        },
        py::arg("a"), py::arg("velocity_a"), py::arg("b"), py::arg("velocity_b"), py::arg("t_max"),
        py::arg("options") = Options{}, py::kw_only(), py::arg("angular_velocity_a") = py::none(),
        (doc + " With angular_velocity_a, the body under rigid motion (contact.hpp).").c_str(), extra...);
}

// The scalar queries of both dimensions.
template <int N>
void def_queries(py::module_& m) {
  using E = Ellipsoid<double, N>;
  m.def("classify", py::overload_cast<const E&, const E&, const Options&>(&classify<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("overlap", py::overload_cast<const E&, const E&, const Options&>(&overlap<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("first_contact",
        [](const E& a, const Row<N>& va, const E& b, const Row<N>& vb, double t_max, const Options& o,
           const AngularVelocity<N>& wa, const AngularVelocity<N>& wb) {
          if (!wa && !wb) return first_contact(a, vec<N>(va), b, vec<N>(vb), t_max, o);
          return first_contact(a, motion<N>(va, wa), b, motion<N>(vb, wb), t_max, o);
        },
        py::arg("a"), py::arg("velocity_a"), py::arg("b"), py::arg("velocity_b"), py::arg("t_max"),
        py::arg("options") = Options{}, py::kw_only(), py::arg("angular_velocity_a") = py::none(),
        py::arg("angular_velocity_b") = py::none(),
        "First contact in [0, t_max]; with an angular velocity, under rigid motion (contact.hpp).");
  m.def("body_at",
        [](const E& body, const Row<N>& velocity, const AngularVelocity<N>& angular_velocity, double t) {
          return body_at(body, motion<N>(velocity, angular_velocity), t);
        },
        py::arg("body"), py::arg("velocity"), py::arg("angular_velocity"), py::arg("t"),
        "The body at time t of its rigid motion (contact.hpp).");
  m.def("distance", py::overload_cast<const E&, const E&, const Options&>(&distance<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("signed_distance", py::overload_cast<const E&, const E&, const Options&>(&signed_distance<double, N>),
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  m.def("closest_point", [](const E& body, const Row<N>& x) { return closest_point(body, vec<N>(x)); },
        py::arg("body"), py::arg("x"));
  m.def("perram_wertheim", py::overload_cast<const E&, const E&, const Options&>(&perram_wertheim<double, N>),
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  m.def("closest_approach",
        [](const E& a, const E& b, const Row<N>& direction, const Options& o) {
          return closest_approach(a, b, vec<N>(direction), o);
        },
        py::arg("a"), py::arg("b"), py::arg("direction"), py::arg("options") = Options{});
  // A body against a half-space (half_space.hpp).
  using H = HalfSpace<double, N>;
  m.def("classify", py::overload_cast<const E&, const H&, const Options&>(&classify<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("overlap", py::overload_cast<const E&, const H&, const Options&>(&overlap<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("distance", py::overload_cast<const E&, const H&, const Options&>(&distance<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("signed_distance", py::overload_cast<const E&, const H&, const Options&>(&signed_distance<double, N>),
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  def_shape_contact<N, H>(m, "First contact of a body and a moving half-space in [0, t_max].");
  m.def("collide_and_slide",
        [](const E& body, const Row<N>& displacement, const std::vector<H>& world, const Options& o) {
          py::gil_scoped_release release;
          return collide_and_slide(body, vec<N>(displacement), std::span<const H>(world), o);
        },
        py::arg("body"), py::arg("displacement"), py::arg("world"), py::arg("options") = Options{},
        "Move the body by the displacement through a list of half-spaces, sliding along what it touches "
        "(slide.hpp).");
  // A body against a box (box.hpp).
  using Bx = Box<double, N>;
  m.def("classify", py::overload_cast<const E&, const Bx&, const Options&>(&classify<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("overlap", py::overload_cast<const E&, const Bx&, const Options&>(&overlap<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("distance", py::overload_cast<const E&, const Bx&, const Options&>(&distance<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("signed_distance", py::overload_cast<const E&, const Bx&, const Options&>(&signed_distance<double, N>),
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  def_shape_contact<N, Bx>(m, "First contact of a body and a moving box in [0, t_max].");
  // A body against a capsule (capsule.hpp).
  using Cp = Capsule<double, N>;
  m.def("classify", py::overload_cast<const E&, const Cp&, const Options&>(&classify<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("overlap", py::overload_cast<const E&, const Cp&, const Options&>(&overlap<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("distance", py::overload_cast<const E&, const Cp&, const Options&>(&distance<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("signed_distance", py::overload_cast<const E&, const Cp&, const Options&>(&signed_distance<double, N>),
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  def_shape_contact<N, Cp>(m, "First contact of a body and a moving capsule in [0, t_max].");
  // A body against a triangle (triangle.hpp) and a mesh (mesh.hpp).
  using Tr = Triangle<double, N>;
  using TM = TriangleMesh<double, N>;
  m.def("classify", py::overload_cast<const E&, const Tr&, const Options&>(&classify<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("overlap", py::overload_cast<const E&, const Tr&, const Options&>(&overlap<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("distance", py::overload_cast<const E&, const Tr&, const Options&>(&distance<double, N>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("signed_distance", py::overload_cast<const E&, const Tr&, const Options&>(&signed_distance<double, N>),
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  using MeshQuery = MeshDistance<double, N> (*)(const E&, const TM&, const Options&) noexcept;
  for (const auto& named : {std::pair<const char*, MeshQuery>{"distance", &distance<double, N>},
                            std::pair<const char*, MeshQuery>{"signed_distance", &signed_distance<double, N>}}) {
    const MeshQuery query = named.second;
    m.def(
        named.first,
        [query](const E& a, const TM& b, const Options& o) {
          py::gil_scoped_release release;
          return query(a, b, o);
        },
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  }
  def_shape_contact<N, Tr>(m, "First contact of a body and a moving triangle in [0, t_max].");
  m.def("classify",
        [](const E& a, const TM& b, const Options& o) {
          py::gil_scoped_release release;
          return classify(a, b, o);
        },
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  m.def("overlap",
        [](const E& a, const TM& b, const Options& o) {
          py::gil_scoped_release release;
          return overlap(a, b, o);
        },
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  def_shape_contact<N, TM>(m, "First contact of a body and a moving mesh in [0, t_max], with the triangle.",
                           py::call_guard<py::gil_scoped_release>());
  m.def("collide_and_slide",
        [](const E& body, const Row<N>& displacement, const TM& world, const Options& o) {
          py::gil_scoped_release release;
          return collide_and_slide(body, vec<N>(displacement), world, o);
        },
        py::arg("body"), py::arg("displacement"), py::arg("world"), py::arg("options") = Options{},
        "Move the body by the displacement through a triangle mesh, sliding along what it touches (slide.hpp).");
}

void def_two_d(py::module_& m) {
  using E = Ellipse2<double>;
  using B = BoundaryIntersection<double>;
  py::class_<B>(m, "BoundaryIntersection", "intersect_boundaries' answer (see intersect2.hpp).")
      .def_property_readonly("status", [](const B& b) { return b.status; })
      .def_property_readonly("count", [](const B& b) { return b.count; })
      .def_property_readonly("points",
                             [](const B& b) {
                               py::array_t<double> out({py::ssize_t(b.count), py::ssize_t(2)});
                               for (int i = 0; i < b.count; ++i)
                                 for (int k = 0; k < 2; ++k) out.mutable_at(i, k) = b.points[std::size_t(i)][k];
                               return out;
                             },
                             "(count, 2) array, counter-clockwise along a.")
      .def_property_readonly("kinds", [](const B& b) {
        return std::vector<CrossingKind>(b.kinds.begin(), b.kinds.begin() + b.count);
      });
  using A = OverlapArea<double>;
  py::class_<A>(m, "OverlapArea", "overlap_area's answer (see intersect2.hpp).")
      .def_property_readonly("area", [](const A& a) { return a.area; })
      .def_property_readonly("relation", [](const A& a) { return a.relation; });
  using C = Circle<double>;
  py::class_<C>(m, "Circle", "The closed disk of Niemitalo's tests; radius 0 is a point.")
      .def(py::init([](const Row<2>& center, double radius) { return make_circle<double>(vec<2>(center), radius); }),
           py::arg("center"), py::arg("radius"))
      .def_property_readonly("center", [](const C& c) { return to_array<2>(c.center()); })
      .def_property_readonly("radius", &C::radius)
      .def("ellipse", &C::ellipse);
  using S = SegmentCircle;
  py::class_<S>(m, "SegmentCircle")
      .def_property_readonly("verdict", [](const S& s) { return s.verdict; })
      .def_property_readonly("side", [](const S& s) { return s.side; });
  using P = PolygonalOverlap<double>;
  py::class_<P>(m, "PolygonalOverlap", "Niemitalo's verdict with its level and certified band (polygonal2.hpp).")
      .def_property_readonly("verdict", [](const P& p) { return p.verdict; })
      .def_property_readonly("level", [](const P& p) { return p.level; })
      .def_property_readonly("iterations", [](const P& p) { return p.iterations; })
      .def_property_readonly("gap_lo", [](const P& p) { return p.gap_lo; })
      .def_property_readonly("gap_hi", [](const P& p) { return p.gap_hi; });
  using Q = QuarticPoint<double>;
  py::class_<Q>(m, "QuarticPoint", "closest_point_quartic / closest_point_closed_form's answer (quartic2.hpp).")
      .def_property_readonly("status", [](const Q& q) { return q.status; })
      .def_property_readonly("point", [](const Q& q) { return to_array<2>(q.point); })
      .def_property_readonly("distance", [](const Q& q) { return q.distance; });

  m.def("intersect_boundaries", &intersect_boundaries<double>, py::arg("a"), py::arg("b"),
        py::arg("options") = Options{});
  m.def("overlap_area", py::overload_cast<const E&, const E&, const Options&>(&overlap_area<double>), py::arg("a"),
        py::arg("b"), py::arg("options") = Options{});
  m.def("iou", py::overload_cast<const E&, const E&, const Options&>(&intersection_over_union<double>),
        py::arg("a"), py::arg("b"), py::arg("options") = Options{});
  m.def("segment_circle",
        [](const Row<2>& a, const Row<2>& b, const C& c) { return segment_circle<double>(vec<2>(a), vec<2>(b), c); },
        py::arg("a"), py::arg("b"), py::arg("circle"));
  m.def("polygonal_overlap", py::overload_cast<const E&, const C&, int>(&polygonal_overlap<double>),
        py::arg("ellipse"), py::arg("circle"), py::arg("max_level") = 10);
  m.def("polygonal_overlap", py::overload_cast<const E&, const E&, int>(&polygonal_overlap<double>), py::arg("a"),
        py::arg("b"), py::arg("max_level") = 10);
  m.def("circle_cover_overlap", &circle_cover_overlap<double>, py::arg("ellipse"), py::arg("circle"),
        py::arg("max_level") = 10);
  m.def("niemitalo_error_bound", py::overload_cast<const E&, int>(&niemitalo_error_bound<double>),
        py::arg("ellipse"), py::arg("level"));
  m.def("closest_point_quartic",
        [](const E& e, const Row<2>& x) { return closest_point_quartic<double>(e, vec<2>(x)); }, py::arg("ellipse"),
        py::arg("x"));
  m.def("closest_point_closed_form",
        [](const E& e, const Row<2>& x) { return closest_point_closed_form<double>(e, vec<2>(x)); },
        py::arg("ellipse"), py::arg("x"));
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
  using MaxIterations = decltype(Options::max_iterations);
  using MaxMotionSteps = decltype(Options::max_motion_steps);
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
  py::class_<Options>(m, "Options", "Tolerance and iteration caps, validated (options.hpp).")
      .def(py::init([cap](double tolerance, const py::object& max_iterations, const py::object& max_motion_steps) {
             return Options{tolerance, cap(std::type_identity<MaxIterations>{}, max_iterations),
                            cap(std::type_identity<MaxMotionSteps>{}, max_motion_steps)};
           }),
           py::arg("tolerance") = double(Options{}.tolerance), py::arg("max_iterations") = int(Options{}.max_iterations),
           py::arg("max_motion_steps") = int(Options{}.max_motion_steps))
      .def_property(
          "tolerance", [](const Options& o) { return double(o.tolerance); },
          [](Options& o, double tolerance) { o.tolerance = tolerance; })
      .def_property(
          "max_iterations", [](const Options& o) { return int(o.max_iterations); },
          [cap](Options& o, const py::object& n) { o.max_iterations = cap(std::type_identity<MaxIterations>{}, n); })
      .def_property(
          "max_motion_steps", [](const Options& o) { return int(o.max_motion_steps); },
          [cap](Options& o, const py::object& n) { o.max_motion_steps = cap(std::type_identity<MaxMotionSteps>{}, n); })
      .def(py::pickle(
          [](const Options& o) {
            return py::make_tuple(double(o.tolerance), int(o.max_iterations), int(o.max_motion_steps));
          },
          [cap](const py::tuple& t) {
            return Options{t[0].cast<double>(), cap(std::type_identity<MaxIterations>{}, t[1]),
                           cap(std::type_identity<MaxMotionSteps>{}, t[2])};
          }));

  py::class_<Ellipse2<double>> ellipse(m, "Ellipse", "A validated ellipse (shapes.hpp).");
  ellipse.def(py::init([](const Row<2>& center, const Row<2>& radii, std::optional<double> angle,
                          std::optional<Rows<2>> rotation) {
                if (angle && rotation) throw py::value_error("Ellipse: give angle or rotation, not both");
                if (rotation) return Ellipse2<double>::from_axes(vec<2>(center), mat<2>(*rotation), vec<2>(radii));
                return make_ellipse<double>(vec<2>(center), angle.value_or(0.0), vec<2>(radii));
              }),
              py::arg("center"), py::arg("radii"), py::arg("angle") = py::none(), py::arg("rotation") = py::none(),
              "Ellipse whose first axis makes `angle` radians with x (or whose axes are the columns of "
              "`rotation`).");
  def_body<2>(ellipse);
  py::class_<Ellipsoid3<double>> ellipsoid(m, "Ellipsoid", "A validated ellipsoid (shapes.hpp).");
  ellipsoid.def(py::init([](const Row<3>& center, const Row<3>& radii, std::optional<Row<4>> quaternion,
                            std::optional<Rows<3>> rotation) {
                  if (quaternion && rotation) throw py::value_error("Ellipsoid: give quaternion or rotation, not both");
                  if (rotation) return make_ellipsoid<double>(vec<3>(center), mat<3>(*rotation), vec<3>(radii));
                  const Row<4> q = quaternion.value_or(Row<4>{1, 0, 0, 0});
                  return make_ellipsoid<double>(vec<3>(center), Quat<double>(q[0], q[1], q[2], q[3]), vec<3>(radii));
                }),
                py::arg("center"), py::arg("radii"), py::arg("quaternion") = py::none(),
                py::arg("rotation") = py::none(),
                "Ellipsoid rotated by a unit quaternion (w, x, y, z), or with axes the columns of `rotation`.");
  def_body<3>(ellipsoid);
  def_half_space<2>(m, "HalfPlane");
  def_half_space<3>(m, "HalfSpace");
  def_box<2>(m, "Box2");
  def_box<3>(m, "Box3");
  def_capsule<2>(m, "Capsule2");
  def_capsule<3>(m, "Capsule3");
  def_triangle<2>(m, "Triangle2");
  def_triangle<3>(m, "Triangle3");
  py::class_<MeshRelation>(m, "MeshRelation", "classify's answer against a mesh (see mesh.hpp).")
      .def_property_readonly("relation", [](const MeshRelation& r) { return r.relation; })
      .def_property_readonly("triangle", [](const MeshRelation& r) { return r.triangle; },
                             "The lowest-index triangle with that relation, or -1.")
      .def("__repr__", [](const MeshRelation& r) {
        return "MeshRelation(relation=" + std::string(to_string(r.relation)) + ", triangle=" +
               std::to_string(r.triangle) + ")";
      });

  using F = ContactFunction<double>;
  py::class_<F>(m, "ContactFunction", "perram_wertheim's answer (see contact_function.hpp).")
      .def_property_readonly("status", [](const F& f) { return f.status; })
      .def_property_readonly("f", [](const F& f) { return f.f; })
      .def_property_readonly("f_upper", [](const F& f) { return f.f_upper; })
      .def_property_readonly("lambda_", [](const F& f) { return f.lambda; }, "The maximizing lambda (weight of b).")
      .def_property_readonly("iterations", [](const F& f) { return f.iterations; })
      .def("__repr__", [](const F& f) {
        return "ContactFunction(status=" + std::string(to_string(f.status)) + ", f=" + std::to_string(f.f) + ")";
      });
  def_results<2>(m, "2");
  def_results<3>(m, "3");
  def_queries<2>(m);
  def_queries<3>(m);
  def_two_d(m);
}

}  // namespace ellipsect::python

PYBIND11_MODULE(_ellipsect, m) {
  m.doc() = "ellipsect: exact collision queries between ellipses and ellipsoids (C++ library bindings)";
  ellipsect::python::def_errors(m);
  ellipsect::python::def_scalar(m);
  ellipsect::python::def_batch(m);
  m.def("simd_target", &ellipsect::simd_target, "The instruction set the batch functions use (batch.hpp).");
}
