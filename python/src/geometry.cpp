// enclosing_ellipsoid (geometry.hpp) from Python: points as an (n, N) array, or bodies, boxes,
// capsules or a mesh, in; an Enclosing namedtuple out (the body an Ellipse or Ellipsoid); the
// solve runs with the GIL released.
#include "common.hpp"
#include "docs.hpp"

#include <ellipsect/geometry.hpp>

namespace ellipsect::python {

namespace {

py::object enclosing_tuple;

// The namedtuple of a solve's answer.
template <int N>
py::object enclosing_of(const EnclosingEllipsoid<double, N>& e) {
  py::array_t<std::int64_t> support(static_cast<py::ssize_t>(e.support.size()));
  py::array_t<double> weights(static_cast<py::ssize_t>(e.weights.size()));
  py::array_t<double> points({static_cast<py::ssize_t>(e.support.size()), py::ssize_t(N)});
  for (std::size_t k = 0; k < e.support.size(); ++k) {
    support.mutable_at(py::ssize_t(k)) = std::int64_t(e.support[k]);
    weights.mutable_at(py::ssize_t(k)) = e.weights[k];
    Eigen::Map<Vec<double, N>>{points.mutable_data() + k * N} = e.support_points[k];
  }
  return enclosing_tuple(std::string(to_string(e.status)), py::cast(e.body), e.volume_gap, e.iterations, e.passes,
                         support, points, weights);
}

// The solve of `input` without the GIL, its row errors named as the Python argument.
template <int N, class Input>
py::object enclose(const Input& input, const EnclosingOptions& options) {
  EnclosingEllipsoid<double, N> e;
  try {
    py::gil_scoped_release release;
    e = enclosing_ellipsoid<double, N>(input, options);
  } catch (const RowInputError& error) {
    throw InputError("points[" + std::to_string(error.row()) + "]", error.detail());
  }
  return enclosing_of<N>(e);
}

EnclosingOptions enclosing_options(double volume_gap, std::int64_t max_enclosing_iterations) {
  EnclosingOptions o;
  o.volume_gap = volume_gap;
  o.max_enclosing_iterations = max_enclosing_iterations;
  return o;
}

// The overloads of shapes, in N dimensions: bodies (an Ellipses / Ellipsoids array or a list
// of Ellipse / Ellipsoid), boxes, capsules (lists), a mesh.
template <int N>
void def_shape_overloads(py::module_& m, const std::string& doc) {
  const auto def = [&](auto call) {
    m.def("enclosing_ellipsoid", call, py::arg("shapes"), py::arg("volume_gap") = 1e-9,
          py::arg("max_enclosing_iterations") = 1'000'000, doc.c_str());
  };
  def([](const Bodies<N>& b, double gap, std::int64_t cap) { return enclose<N>(b.items, enclosing_options(gap, cap)); });
  def([](const std::vector<Ellipsoid<double, N>>& b, double gap, std::int64_t cap) {
    return enclose<N>(b, enclosing_options(gap, cap));
  });
  def([](const std::vector<Box<double, N>>& b, double gap, std::int64_t cap) { return enclose<N>(b, enclosing_options(gap, cap)); });
  def([](const std::vector<Capsule<double, N>>& c, double gap, std::int64_t cap) {
    return enclose<N>(c, enclosing_options(gap, cap));
  });
  def([](const Mesh<N>& mesh, double gap, std::int64_t cap) {
    return enclose<N>(static_cast<const TriangleMesh<double, N>&>(mesh), enclosing_options(gap, cap));
  });
}

}  // namespace

void def_inscribed(py::module_& m);  // below

void def_geometry(py::module_& m) {
  enclosing_tuple = py::module_::import("collections")
                        .attr("namedtuple")("Enclosing",
                                            py::make_tuple("status", "body", "volume_gap", "iterations", "passes",
                                                           "support", "support_points", "weights"),
                                            py::arg("module") = "ellipsect");
  m.attr("Enclosing") = enclosing_tuple;
  // The shapes first: an array of numbers matches none of them.
  const std::string shapes_doc = docs::doc(
      "The minimum-volume ellipse or ellipsoid holding shapes (geometry.hpp): every shape inside the body as stored "
      "(bodies by the exact classification), its volume within a certified volume_gap of the minimum.",
      "shapes: Ellipses / Ellipsoids, or a list of Ellipse / Ellipsoid (their union), of Box2 / Box3 (their "
      "corners), of Capsule2 / Capsule3 (their end balls); or a TriangleMesh2 / TriangleMesh3 (its vertices).\n"
      "volume_gap, max_enclosing_iterations: as for points.",
      "Enclosing, support naming the body, box, capsule or vertex of each support point.",
      "InputError: no shapes (bodies, boxes, capsules, mesh); shapes within 1e-9 of their extent from a line or "
      "plane.");
  def_shape_overloads<2>(m, shapes_doc);
  def_shape_overloads<3>(m, shapes_doc);
  m.def(
      "enclosing_ellipsoid",
      [](const ArrayLike& points, double volume_gap, std::int64_t max_enclosing_iterations) {
        int dim = 0;
        const auto rows = point_rows(points, dim);
        const EnclosingOptions o = enclosing_options(volume_gap, max_enclosing_iterations);
        return dim == 2 ? enclose<2>(rows_of<2>(rows), o) : enclose<3>(rows_of<3>(rows), o);
      },
      py::arg("points"), py::arg("volume_gap") = 1e-9, py::arg("max_enclosing_iterations") = 1'000'000,
      docs::doc("The minimum-volume ellipse or ellipsoid holding every point (geometry.hpp): every point inside the "
                "body as stored, certified; its volume within a certified volume_gap of the minimum.",
                "points: (n, 2) or (n, 3), at least N + 1 points spanning the plane or space.\nvolume_gap: the gap "
                "to reach, vol(body) <= (1 + volume_gap) min volume, in [1e-12, 1].\nmax_enclosing_iterations: the "
                "weight updates of the solve, in [1, 10000000].",
                "Enclosing: status ('optimal', 'rounding_limited': the body as stored cannot carry the requested "
                "gap, volume_gap says how much; 'did_not_converge'), body (Ellipse or Ellipsoid), volume_gap (a "
                "certified bound), iterations, passes, support (the indices of the points that carry the "
                "certificate), support_points (those points, (k, N)), weights (theirs).",
                "InputError: a point that is not finite (points[i]); fewer than N + 1 points, or points within 1e-9 "
                "of their extent from a line or plane (points); an option out of range, named.\nValueError: "
                "points of the wrong shape.\nTypeError: points that are not real numbers.")
          .c_str());
  m.def(
      "enclosing_ellipsoids",
      [](const std::vector<py::object>& clouds, double volume_gap, std::int64_t max_enclosing_iterations, int threads) {
        int dim = 0;
        const auto rows = cloud_rows(clouds, dim);
        const EnclosingOptions o = enclosing_options(volume_gap, max_enclosing_iterations);
        py::list out;
        const auto each = [&]<int N>() {
          const auto solve = [&](const std::vector<Vec<double, N>>& p) { return enclosing_ellipsoid<double, N>(p, o); };
          for (const auto& e : for_each_cloud<N, EnclosingEllipsoid<double, N>>(rows, threads, solve))
            out.append(enclosing_of<N>(e));
        };
        if (dim == 3) each.template operator()<3>(); else each.template operator()<2>();
        return out;
      },
      py::arg("clouds"), py::arg("volume_gap") = 1e-9, py::arg("max_enclosing_iterations") = 1'000'000,
      py::arg("threads") = 0,
      docs::doc("enclosing_ellipsoid of each cloud, the clouds shared out over the library's worker pool.",
                "clouds: a list of (n_i, 2) or (n_i, 3) arrays, all of one N.\nvolume_gap, "
                "max_enclosing_iterations: as for one cloud.\nthreads: 0 every hardware thread, 1 the caller alone.",
                "list of Enclosing, in the clouds' order (the same answers as one by one).",
                "InputError: as for one cloud, the first failing cloud named (clouds[k], clouds[k][i]).\nValueError: "
                "a cloud of the wrong shape, or of another N than those before it (clouds[k]).")
          .c_str());
  def_inscribed(m);
}

// ---- inscribed_ellipsoid (geometry.hpp): a list of HalfPlane / HalfSpace, or normals and offsets
// (n . x <= b), in; an Inscribed namedtuple out; the solve runs with the GIL released. And
// hull_half_spaces: points in, the hull's faces out.

namespace {

py::object inscribed_tuple;

template <int N>
py::object inscribe(const std::vector<HalfSpace<double, N>>& half_spaces, double volume_gap,
                    std::int64_t max_inscribed_iterations) {
  InscribedOptions o;
  o.volume_gap = volume_gap;
  o.max_inscribed_iterations = max_inscribed_iterations;
  InscribedEllipsoid<double, N> e;
  {
    py::gil_scoped_release release;
    e = inscribed_ellipsoid<double, N>(std::span<const HalfSpace<double, N>>(half_spaces), o);
  }
  py::array_t<std::int64_t> active(static_cast<py::ssize_t>(e.active.size()));
  py::array_t<double> weights(static_cast<py::ssize_t>(e.weights.size()));
  for (std::size_t k = 0; k < e.active.size(); ++k) {
    active.mutable_at(py::ssize_t(k)) = std::int64_t(e.active[k]);
    weights.mutable_at(py::ssize_t(k)) = e.weights[k];
  }
  return inscribed_tuple(std::string(to_string(e.status)), py::cast(e.body), e.volume_gap, e.iterations, active, weights);
}

// The half-spaces n . x <= b of rows of normals and offsets: through the point b n / |n|^2.
template <int N>
std::vector<HalfSpace<double, N>> from_rows(const py::array_t<double>& normals, const py::array_t<double>& offsets) {
  std::vector<HalfSpace<double, N>> out;
  for (py::ssize_t i = 0; i < normals.shape(0); ++i) {
    const Vec<double, N> n = Eigen::Map<const Vec<double, N>>(normals.data() + i * N);
    const double b = offsets.data()[i];
    if (!std::isfinite(b)) throw InputError("offsets[" + std::to_string(i) + "]", "must be finite");
    const double n2 = n.squaredNorm();
    if (!(n2 > 0) || !std::isfinite(n2))
      throw InputError("normals[" + std::to_string(i) + "]", "must be finite and not zero (its square norm in range)");
    out.push_back(make_half_space<double, N>(Vec<double, N>(n * (b / n2)), n));
  }
  return out;
}

// The hull's faces without the GIL, a point's row error named as the argument's.
template <int N>
py::list hull_of(const py::array_t<double>& rows) {
  const std::vector<Vec<double, N>> points = rows_of<N>(rows);
  std::vector<HalfSpace<double, N>> faces;
  try {
    py::gil_scoped_release release;
    faces = hull_half_spaces<double, N>(points);
  } catch (const RowInputError& error) {
    throw InputError("points[" + std::to_string(error.row()) + "]", error.detail());
  }
  py::list out;
  for (const auto& f : faces) out.append(py::cast(f));
  return out;
}

}  // namespace

void def_inscribed(py::module_& m) {
  inscribed_tuple = py::module_::import("collections")
                        .attr("namedtuple")("Inscribed",
                                            py::make_tuple("status", "body", "volume_gap", "iterations", "active",
                                                           "weights"),
                                            py::arg("module") = "ellipsect");
  m.attr("Inscribed") = inscribed_tuple;
  const std::string returns =
      "Inscribed: status ('optimal'; 'rounding_limited': the body as stored cannot carry the requested gap, "
      "volume_gap says how much; 'did_not_converge'; 'unbounded'; 'empty': then body is the default unit ball and "
      "volume_gap infinite), body (Ellipse or Ellipsoid, inside every half-space by the exact classification), "
      "volume_gap (certified: max volume <= (1 + volume_gap) volume of body), iterations (Newton steps), active "
      "(the indices of the half-spaces the body touches), weights (their dual weights, summing to 1).";
  const std::string options_doc =
      "volume_gap: the gap to reach, in [1e-12, 1].\nmax_inscribed_iterations: the barrier's Newton steps, in [1, "
      "1000000].";
  const auto def_list = [&](auto call) {
    m.def("inscribed_ellipsoid", call, py::arg("half_spaces"), py::arg("volume_gap") = 1e-9,
          py::arg("max_inscribed_iterations") = 10000,
          docs::doc("The maximum-volume ellipse or ellipsoid inside a bounded polytope (geometry.hpp): inside every "
                    "half-space as stored, certified; its volume within a certified volume_gap of the maximum.",
                    "half_spaces: a list of HalfPlane or HalfSpace, at least N + 1.\n" + options_doc, returns,
                    "InputError: fewer than N + 1 half-spaces (half_spaces); a polytope too thin for an ellipsoid of "
                    "aspect ratio 1e8 (half_spaces); an option out of range, named.")
              .c_str());
  };
  def_list([](const std::vector<HalfSpace<double, 2>>& h, double gap, std::int64_t cap) { return inscribe<2>(h, gap, cap); });
  def_list([](const std::vector<HalfSpace<double, 3>>& h, double gap, std::int64_t cap) { return inscribe<3>(h, gap, cap); });
  m.def(
      "inscribed_ellipsoid",
      [](const ArrayLike& normals, const ArrayLike& offsets, double volume_gap, std::int64_t max_inscribed_iterations) {
        const py::array a = numbers(normals, "normals");
        if (a.ndim() != 2 || (a.shape(1) != 2 && a.shape(1) != 3))
          throw py::value_error("normals: expected shape (n, 2) or (n, 3), got " +
                                shape_text(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim())));
        const int dim = int(a.shape(1));
        py::ssize_t n = -1;
        const auto rows = checked(normals, "normals", {dim}, n, "normals");
        const auto b = checked(offsets, "offsets", {}, n, "normals");
        return dim == 2 ? inscribe<2>(from_rows<2>(rows, b), volume_gap, max_inscribed_iterations)
                        : inscribe<3>(from_rows<3>(rows, b), volume_gap, max_inscribed_iterations);
      },
      py::arg("normals"), py::arg("offsets"), py::arg("volume_gap") = 1e-9, py::arg("max_inscribed_iterations") = 10000,
      docs::doc("The maximum-volume ellipse or ellipsoid inside the polytope {x : normals[i] . x <= offsets[i]} "
                "(geometry.hpp), as for half-spaces (each the HalfPlane / HalfSpace through offsets[i] normals[i] / "
                "|normals[i]|^2).",
                "normals: (n, 2) or (n, 3), n >= N + 1, any length, not zero.\noffsets: (n,).\n" + options_doc, returns,
                "InputError: a zero or non-finite normal (normals[i]) or offset (offsets[i]); as for half-spaces."
                "\nValueError: arrays of the wrong shapes.\nTypeError: arrays that are not real numbers.")
          .c_str());
  m.def(
      "hull_half_spaces",
      [](const ArrayLike& points) {
        int dim = 0;
        const auto rows = point_rows(points, dim);
        return dim == 2 ? hull_of<2>(rows) : hull_of<3>(rows);
      },
      py::arg("points"),
      docs::doc("The faces of the points' convex hull as outward half-spaces (geometry.hpp): which points are "
                "vertices is exact; each normal rounded to double, its plane through the face's deepest vertex. "
                "Given to inscribed_ellipsoid, they give the largest ellipse or ellipsoid in the hull.",
                "points: (n, 2) or (n, 3), at least N + 1, not all on a line (2D) or plane (3D).",
                "list of HalfPlane (2D: the edges, counterclockwise) or HalfSpace (3D: the facets, coplanar "
                "triangles merged).",
                "InputError: a point that is not finite (points[i]); fewer than N + 1 points, or all on a line or "
                "plane (points).\nValueError: points of the wrong shape.\nTypeError: points that are not real "
                "numbers.")
          .c_str());
}

}  // namespace ellipsect::python
