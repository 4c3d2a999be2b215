// jam_packing (packing.hpp) from Python: radii as an (n, N) array in, a Packing namedtuple of
// arrays out; the compression runs with the GIL released.
#include "common.hpp"
#include "docs.hpp"

#include <ellipsect/packing.hpp>

namespace ellipsect::python {

namespace {

py::object packing_tuple;

template <int N>
py::object jam(const py::array_t<double>& rows, const PackingOptions& options) {
  const std::vector<Vec<double, N>> radii = rows_of<N>(rows);
  Packing<N> p;
  {
    py::gil_scoped_release release;
    p = jam_packing<N>(radii, options);
  }
  const auto n = static_cast<py::ssize_t>(p.bodies.size());
  constexpr py::ssize_t dim = N;
  py::array_t<double> centers({n, dim}), axes({n, dim, dim}), body_radii({n, dim});
  py::array_t<double> box(dim), history({static_cast<py::ssize_t>(p.history.size()), py::ssize_t{2}});
  py::array_t<std::int64_t> contacts({static_cast<py::ssize_t>(p.contacts.size()), dim + 2});
  for (py::ssize_t i = 0; i < n; ++i) {
    const auto& b = p.bodies[std::size_t(i)];
    for (int k = 0; k < N; ++k) {
      centers.mutable_at(i, k) = b.center()[k];
      body_radii.mutable_at(i, k) = b.radii()[k];
      for (int c = 0; c < N; ++c) axes.mutable_at(i, k, c) = b.axes()(k, c);
    }
  }
  for (int k = 0; k < N; ++k) box.mutable_at(k) = p.box.size[k];
  for (std::size_t k = 0; k < p.history.size(); ++k)
    for (int c = 0; c < 2; ++c) history.mutable_at(py::ssize_t(k), c) = p.history[k][std::size_t(c)];
  for (std::size_t k = 0; k < p.contacts.size(); ++k) {
    const auto q = py::ssize_t(k);
    contacts.mutable_at(q, 0) = p.contacts[k].i;
    contacts.mutable_at(q, 1) = p.contacts[k].j;
    for (int c = 0; c < N; ++c) contacts.mutable_at(q, 2 + c) = p.contacts[k].image[std::size_t(c)];
  }
  return packing_tuple(std::string(to_string(p.status)), box, centers, axes, body_radii, p.density, p.pressure,
                       p.collisions, p.rebuilds, p.time, contacts, p.mean_contacts, p.rattlers,
                       p.mean_contacts_without_rattlers, p.overlapping, p.predictions_overlapping, p.predictions_stopped,
                       history);
}

}  // namespace

void def_packing(py::module_& m) {
  packing_tuple = py::module_::import("collections")
                      .attr("namedtuple")("Packing",
                                          py::make_tuple("status", "box", "centers", "axes", "radii", "density",
                                                         "pressure", "collisions", "rebuilds", "time", "contacts",
                                                         "mean_contacts", "rattlers", "mean_contacts_without_rattlers",
                                                         "overlapping", "predictions_overlapping",
                                                         "predictions_stopped", "history"),
                                          py::arg("module") = "ellipsect");
  m.attr("Packing") = packing_tuple;
  m.def(
      "jam_packing",
      [](const ArrayLike& radii, std::uint64_t seed, double initial_density, const std::optional<std::vector<std::pair<double, double>>>& schedule,
         double pressure, std::uint64_t max_collisions, double contact_gap, double skin, int collisions_per_update) {
        py::ssize_t n = -1;
        const py::array a = numbers(radii, "radii");
        if (a.ndim() != 2 || (a.shape(1) != 2 && a.shape(1) != 3))
          throw py::value_error("radii: expected shape (n, 2) or (n, 3)");
        const int dim = int(a.shape(1));
        const auto rows = checked(radii, "radii", {dim}, n, "radii");
        PackingOptions o;
        o.seed = seed;
        o.initial_density = initial_density;
        if (schedule) {
          std::vector<GrowthStage> stages;
          for (const auto& [from, rate] : *schedule) stages.push_back({from, rate});
          o.schedule = GrowthSchedule(std::move(stages));
        }
        o.pressure = pressure;
        o.max_collisions = max_collisions;
        o.contact_gap = contact_gap;
        o.skin = skin;
        o.collisions_per_update = collisions_per_update;
        return dim == 2 ? jam<2>(rows, o) : jam<3>(rows, o);
      },
      py::arg("radii"), py::arg("seed") = 1, py::arg("initial_density") = 0.2,
      py::arg("schedule") = py::none(),
      py::arg("pressure") = 1e6,
      py::arg("max_collisions") = std::uint64_t(1'000'000'000), py::arg("contact_gap") = 0.0,
      py::arg("skin") = 0.1, py::arg("collisions_per_update") = 20,
      docs::doc("A jammed packing by Lubachevsky-Stillinger compression (packing.hpp): the bodies at random in a "
                "periodic cube (square), grown by event-driven dynamics until the reduced pressure passes `pressure`.",
                "radii: (n, 2) ellipses or (n, 3) ellipsoids, each body's radii (their shapes; the scale is set by "
                "initial_density).\nseed: the random start.\ninitial_density: packing fraction of the start.\n"
                "schedule: [(from_pressure, rate), ...]: the growth rate (thermal speeds per largest diameter) from "
                "each reduced pressure on (None: [(0.0, 0.01)]).\npressure: the reduced pressure that counts as jammed.\nmax_collisions: "
                "stop there (status collision_limit).\ncontact_gap: contacts are pairs with Perram-Wertheim mu - 1 "
                "below it (0: 100 / pressure).\nskin: neighbor-list skin, of the largest radius.\n"
                "collisions_per_update: per body, between thermostat and pressure updates.",
                "Packing: status ('jammed', 'collision_limit' or 'no_start': no room for the random start, no bodies), box (N,), centers (n, N), axes (n, N, N; columns "
                "the axes), radii (n, N), density, pressure, collisions, rebuilds, time, contacts (m, 2 + N: i, j and "
                "the image of j), mean_contacts, rattlers, mean_contacts_without_rattlers, overlapping (pairs "
                "classify finds overlapping at the end: 0), predictions_overlapping, predictions_stopped (0), "
                "history (k, 2: density and reduced pressure after each update).",
                "InputError: a radius or an option out of range, named (radii[i], initial_density, schedule[k], pressure, "
                "max_collisions, contact_gap, skin, collisions_per_update).\nValueError: radii of the wrong shape.")
          .c_str());
}

}  // namespace ellipsect::python
