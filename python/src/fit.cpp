// fit_ellipsoid (geometry.hpp) from Python: points as an (n, N) array in, a Fit namedtuple out
// (the bodies Ellipse or Ellipsoid, the covariance a (P, P) array); the fit runs with the GIL
// released.
#include "common.hpp"
#include "docs.hpp"

#include <ellipsect/geometry.hpp>

namespace ellipsect::python {

namespace {

py::object fit_tuple;

// A fit as the namedtuple.
template <int N>
py::object fit_of(const EllipsoidFit<double, N>& f) {
  constexpr int P = EllipsoidFit<double, N>::parameters;
  py::array_t<double> covariance({P, P});
  for (int i = 0; i < P; ++i)
    for (int j = 0; j < P; ++j) covariance.mutable_at(i, j) = f.covariance(i, j);
  return fit_tuple(std::string(to_string(f.status)), py::cast(f.body), f.rms_residual, f.max_residual, covariance,
                   f.rank, f.iterations, py::cast(f.algebraic), f.algebraic_rms_residual);
}

// The fit without the GIL, its row errors named as the Python argument.
template <int N>
py::object fit(const std::vector<Vec<double, N>>& points, const FitOptions& options) {
  EllipsoidFit<double, N> f;
  try {
    py::gil_scoped_release release;
    f = fit_ellipsoid<double, N>(points, options);
  } catch (const RowInputError& error) {
    throw InputError("points[" + std::to_string(error.row()) + "]", error.detail());
  }
  return fit_of<N>(f);
}

FitOptions fit_options(double fit_tolerance, int max_fit_iterations) {
  FitOptions o;
  o.fit_tolerance = fit_tolerance;
  o.max_fit_iterations = max_fit_iterations;
  return o;
}

}  // namespace

void def_fit(py::module_& m) {
  fit_tuple = py::module_::import("collections")
                  .attr("namedtuple")("Fit",
                                      py::make_tuple("status", "body", "rms_residual", "max_residual", "covariance",
                                                     "rank", "iterations", "algebraic", "algebraic_rms_residual"),
                                      py::arg("module") = "ellipsect");
  m.attr("Fit") = fit_tuple;
  m.def(
      "fit_ellipsoid",
      [](const ArrayLike& points, double fit_tolerance, int max_fit_iterations) {
        int dim = 0;
        const auto rows = point_rows(points, dim);
        const FitOptions o = fit_options(fit_tolerance, max_fit_iterations);
        return dim == 2 ? fit<2>(rows_of<2>(rows), o) : fit<3>(rows_of<3>(rows), o);
      },
      py::arg("points"), py::arg("fit_tolerance") = 1e-8, py::arg("max_fit_iterations") = 200,
      docs::doc("The least-squares ellipse or ellipsoid of points (geometry.hpp): the sum of squared orthogonal "
                "distances minimized from an algebraic fit (Halir-Flusser 2D, Li-Griffiths 3D) by "
                "Levenberg-Marquardt on closest_point's exact distances.",
                "points: (n, 2) or (n, 3), at least 5 (2D) or 9 (3D) points, not on a line or plane.\n"
                "fit_tolerance: the stationarity to reach, in [1e-15, 1e-3].\nmax_fit_iterations: the "
                "Levenberg-Marquardt steps, in [1, 100000].",
                "Fit: status ('converged', 'did_not_converge', 'not_an_ellipse': a hyperbola, parabola or line "
                "pair fits the points markedly better, or the ellipse runs away), body (Ellipse or Ellipsoid), "
                "rms_residual and max_residual (orthogonal distances to the body as stored), covariance ((5, 5) "
                "or (9, 9): center, orientation, radii), rank (of the Jacobian), iterations, algebraic (the "
                "direct fit) and algebraic_rms_residual (its residual, never below rms_residual).",
                "InputError: a point that is not finite (points[i]); fewer than 5 (9) points, or points within "
                "1e-8 of their spread from a line or plane (points); an option out of range, named.\nValueError: "
                "points of the wrong shape.\nTypeError: points that are not real numbers.")
          .c_str());
  m.def(
      "fit_ellipsoids",
      [](const std::vector<py::object>& clouds, double fit_tolerance, int max_fit_iterations, int threads) {
        int dim = 0;
        const auto rows = cloud_rows(clouds, dim);
        const FitOptions o = fit_options(fit_tolerance, max_fit_iterations);
        py::list out;
        const auto each = [&]<int N>() {
          const auto solve = [&](const std::vector<Vec<double, N>>& p) { return fit_ellipsoid<double, N>(p, o); };
          for (const auto& f : for_each_cloud<N, EllipsoidFit<double, N>>(rows, threads, solve)) out.append(fit_of<N>(f));
        };
        if (dim == 3) each.template operator()<3>(); else each.template operator()<2>();
        return out;
      },
      py::arg("clouds"), py::arg("fit_tolerance") = 1e-8, py::arg("max_fit_iterations") = 200, py::arg("threads") = 0,
      docs::doc("fit_ellipsoid of each cloud, the clouds shared out over the library's worker pool.",
                "clouds: a list of (n_i, 2) or (n_i, 3) arrays, all of one N.\nfit_tolerance, max_fit_iterations: as "
                "for one cloud.\nthreads: 0 every hardware thread, 1 the caller alone.",
                "list of Fit, in the clouds' order (the same answers as one by one).",
                "InputError: as for one cloud, the first failing cloud named (clouds[k], clouds[k][i]).\nValueError: "
                "a cloud of the wrong shape, or of another N than those before it (clouds[k]).")
          .c_str());
}

}  // namespace ellipsect::python
