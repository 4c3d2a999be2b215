// Jammed packings by Lubachevsky-Stillinger compression of HardBodies (packing.hpp).
#include <ellipsect/classify.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/packing.hpp>

#include "mechanics.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

namespace ellipsect {

using packing::inertia;
using packing::volume;

std::string_view to_string(PackingStatus s) noexcept {
  static constexpr std::string_view names[] = {"jammed", "collision_limit", "no_start"};  // in the enum's order
  const auto k = static_cast<std::size_t>(s);
  return k < std::size(names) ? names[k] : "?";
}

GrowthSchedule::GrowthSchedule(std::vector<GrowthStage> stages) : stages_(std::move(stages)) {
  if (stages_.empty()) throw InputError("schedule", "must have at least one stage");
  for (std::size_t k = 0; k < stages_.size(); ++k) {
    const GrowthStage& s = stages_[k];
    if (!(s.rate > 0.0) || !std::isfinite(s.rate) || !(s.from >= 0.0) || !std::isfinite(s.from) ||
        (k > 0 && !(s.from > stages_[k - 1].from)))
      throw InputError("schedule[" + std::to_string(k) + "]", "rates must be finite and > 0, pressures increasing from 0");
  }
}

double GrowthSchedule::rate_at(double pressure) const noexcept {
  double rate = stages_.front().rate;
  for (const GrowthStage& s : stages_)
    if (pressure >= s.from) rate = s.rate;
  return rate;
}

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// A uniformly random orientation.
template <int N>
Mat<double, N> random_axes(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  if constexpr (N == 2) {
    const double angle = std::uniform_real_distribution<double>(-std::numbers::pi, std::numbers::pi)(rng);
    Mat<double, 2> a;
    a << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    return a;
  } else {
    const Quat<double> q = Quat<double>(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    return q.toRotationMatrix();
  }
}

// Random non-overlapping placement in the box (each body against those placed, through the
// nearest image); nothing where 1000 tries for a body do not find room.
template <int N>
std::optional<std::vector<Ellipsoid<double, N>>> random_start(std::span<const Vec<double, N>> radii,
                                                              const PeriodicBox<N>& box, std::mt19937_64& rng) {
  std::vector<Ellipsoid<double, N>> out;
  out.reserve(radii.size());
  for (std::size_t i = 0; i < radii.size(); ++i) {
    bool placed = false;
    for (int attempt = 0; attempt < 1000 && !placed; ++attempt) {
      Vec<double, N> c;
      for (int k = 0; k < N; ++k) c[k] = std::uniform_real_distribution<double>(0.0, box.size[k])(rng);
      const auto body = Ellipsoid<double, N>::from_axes(c, random_axes<N>(rng), radii[i]);
      placed = std::none_of(out.begin(), out.end(), [&](const Ellipsoid<double, N>& o) {
        Vec<double, N> d = o.center() - c;
        for (int k = 0; k < N; ++k) d[k] -= box.size[k] * std::round(d[k] / box.size[k]);
        if (d.norm() > body.radii().maxCoeff() + o.radii().maxCoeff()) return false;
        return overlap(body, o.translated(Vec<double, N>(c + d - o.center())));
      });
      if (placed) out.push_back(body);
    }
    if (!placed) return std::nullopt;
  }
  return out;
}

// Velocities at kT = 1 (mass 1), no net momentum; angular velocities at kT = 1 per axis.
template <int N>
std::vector<RigidMotion<double, N>> thermal_motions(const std::vector<Ellipsoid<double, N>>& start,
                                                    std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<RigidMotion<double, N>> motions(start.size());
  Vec<double, N> mean = Vec<double, N>::Zero();
  for (std::size_t i = 0; i < start.size(); ++i) {
    for (int k = 0; k < N; ++k) motions[i].velocity[k] = normal(rng);
    mean += motions[i].velocity / double(start.size());
    const auto moments = inertia<N>(start[i], 1.0);
    if constexpr (N == 2) {
      motions[i].angular_velocity = normal(rng) / std::sqrt(moments[0]);
    } else {
      const Vec<double, 3> w(normal(rng) / std::sqrt(moments[0]), normal(rng) / std::sqrt(moments[1]),
                             normal(rng) / std::sqrt(moments[2]));
      motions[i].angular_velocity = start[i].axes() * w;
    }
  }
  for (auto& m : motions) m.velocity -= mean;
  return motions;
}

// The compression: runs `system` in updates of collisions_per_update collisions per body,
// measuring the reduced pressure over each, rescaling to kT = 1 and setting the growth rate
// from the schedule, until jammed or at the collision cap; `out` gets the status, the last
// pressure and the history. `expansion(rate)`: d scale / dt for a schedule rate; `total`:
// the bodies' volume at scale 1.
template <int N, class Expansion>
void compress(HardBodies<N>& system, const PackingOptions& options, Expansion expansion, double total,
              double box_volume, Packing<N>& out) {
  const double n = double(system.size());
  const std::uint64_t per_update = std::uint64_t(int(options.collisions_per_update)) * system.size();
  const std::uint64_t cap = options.max_collisions;
  double t_last = system.now(), virial_last = system.virial();
  for (;;) {
    const std::uint64_t target = system.collisions() + per_update;
    while (system.collisions() < target && system.collisions() < cap)
      // Growing bodies always meet: an event is always ahead.
      if (system.step().status != HardStatus::collided) throw std::logic_error("ellipsect: jam_packing: no event");
    const double dt = system.now() - t_last, kt = (1.0 + system.temperature()) / 2;
    out.pressure = dt > 0.0 ? 1.0 + (system.virial() - virial_last) / (N * n * kt * dt) : inf;
    out.density = total * std::pow(system.scale_at(system.now()), N) / box_volume;
    out.history.push_back({out.density, out.pressure});
    if (out.pressure >= options.pressure) {
      out.status = PackingStatus::jammed;
      return;
    }
    if (system.collisions() >= cap) return;
    system.rescale(1.0 / std::sqrt(system.temperature()), expansion(options.schedule.rate_at(out.pressure)));
    t_last = system.now();
    virial_last = system.virial();
  }
}

// Contacts and the final check, on the candidate pairs of the final bodies grown by 1 + gap
// about their centers: a pair with mu - 1 < gap overlaps when both are grown by mu, so the
// boxes of the grown bodies meet (those of the bodies themselves need not).
template <int N>
void find_contacts(Packing<N>& out, double gap) {
  std::vector<Ellipsoid<double, N>> grown;
  grown.reserve(out.bodies.size());
  for (const Ellipsoid<double, N>& s : out.bodies)
    grown.push_back(Ellipsoid<double, N>::from_axes(s.center(), s.axes(), s.radii() * (1.0 + gap)));
  for (const ImagePair<N>& p : candidate_pairs<double, N>(grown, out.box)) {
    Vec<double, N> offset;
    for (int k = 0; k < N; ++k) offset[k] = p.image[k] * out.box.size[k];
    const Ellipsoid<double, N>& a = out.bodies[p.i];
    const Ellipsoid<double, N> b = out.bodies[p.j].translated(offset);
    const Relation r = classify(a, b);
    if (r != Relation::separated && r != Relation::touching) ++out.overlapping;
    const ContactFunction<double> f = perram_wertheim(a, b);
    if (std::sqrt(f.f) - 1.0 < gap) out.contacts.push_back(p);
  }
  out.mean_contacts = 2.0 * double(out.contacts.size()) / double(out.bodies.size());
}

// Rattlers: bodies with fewer than N + 1 contacts, removed with their contacts until none is
// left among the rest.
template <int N>
void remove_rattlers(Packing<N>& out) {
  const std::size_t n = out.bodies.size();
  std::vector<int> count(n, 0);
  for (const ImagePair<N>& p : out.contacts) ++count[p.i], ++count[p.j];
  std::vector<bool> rattler(n, false);
  std::size_t kept_contacts = out.contacts.size();
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 0; i < n; ++i)
      if (!rattler[i] && count[i] <= N) rattler[i] = changed = true;
    if (!changed) break;
    std::fill(count.begin(), count.end(), 0);
    kept_contacts = 0;
    for (const ImagePair<N>& p : out.contacts)
      if (!rattler[p.i] && !rattler[p.j]) ++count[p.i], ++count[p.j], ++kept_contacts;
  }
  out.rattlers = std::size_t(std::count(rattler.begin(), rattler.end(), true));
  out.mean_contacts_without_rattlers =
      out.rattlers < n ? 2.0 * double(kept_contacts) / double(n - out.rattlers) : 0.0;
}

}  // namespace

template <int N>
Packing<N> jam_packing(std::span<const Vec<double, N>> radii, const PackingOptions& options) {
  if (radii.size() < 2) throw InputError("radii", "must hold at least two bodies");
  for (std::size_t i = 0; i < radii.size(); ++i)
    if (!radii[i].allFinite() || !(radii[i].minCoeff() > 0.0))
      throw InputError("radii[" + std::to_string(i) + "]", "must be finite and > 0");
  double total = 0.0, largest = 0.0;
  for (const auto& r : radii) total += volume<N>(r), largest = std::max(largest, r.maxCoeff());
  Packing<N> out;
  const double side = std::pow(total / options.initial_density, 1.0 / N), box_volume = std::pow(side, N);
  for (int k = 0; k < N; ++k) out.box.size[k] = side;
  if (!(8 * largest < side)) throw InputError("radii", "too few bodies: each must be under an eighth of the box side");

  std::mt19937_64 rng(options.seed);
  const auto start = random_start<N>(radii, out.box, rng);
  if (!start) {
    out.status = PackingStatus::no_start;
    return out;
  }
  // d scale / dt from the rate in thermal speeds per largest diameter.
  const auto expansion = [&](double rate) { return rate / (2 * largest); };
  HardBodies<N> system(*start, thermal_motions<N>(*start, rng), out.box, options.skin,
                       expansion(options.schedule.stages().front().rate));
  system.rescale(1.0 / std::sqrt(system.temperature()), system.expansion());
  compress<N>(system, options, expansion, total, box_volume, out);

  // The packing halfway to the next event, where no pair touches: the pair that collided last
  // has moved apart (at the end of the collision it touches to within rounding).
  out.collisions = system.collisions();
  out.rebuilds = system.rebuilds();
  const double next = system.next_event();
  out.time = std::isfinite(next) ? system.now() + (next - system.now()) / 2 : system.now();
  out.bodies = system.shapes_at(out.time);
  out.density = total * std::pow(system.scale_at(out.time), N) / box_volume;
  out.predictions_overlapping = system.overlaps();
  out.predictions_stopped = system.stopped();
  find_contacts<N>(out, options.contact_gap > 0.0 ? double(options.contact_gap) : 100.0 / options.pressure);
  remove_rattlers<N>(out);
  return out;
}

template Packing<2> jam_packing<2>(std::span<const Vec<double, 2>>, const PackingOptions&);
template Packing<3> jam_packing<3>(std::span<const Vec<double, 3>>, const PackingOptions&);

}  // namespace ellipsect
