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
  static constexpr std::string_view names[] = {"jammed", "collision_limit", "no_start", "compressing"};  // in the enum's order
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
Compression<N>::Compression(std::span<const Vec<double, N>> radii, const PackingOptions& options) : options_(options) {
  if (radii.size() < 2) throw InputError("radii", "must hold at least two bodies");
  for (std::size_t i = 0; i < radii.size(); ++i)
    if (!radii[i].allFinite() || !(radii[i].minCoeff() > 0.0))
      throw InputError("radii[" + std::to_string(i) + "]", "must be finite and > 0");
  double total = 0.0, largest = 0.0;
  for (const auto& r : radii) total += volume<N>(r), largest = std::max(largest, r.maxCoeff());
  const double side = std::pow(total / options.initial_density, 1.0 / N);
  for (int k = 0; k < N; ++k) box_.size[k] = side;
  if (!(8 * largest < side)) throw InputError("radii", "too few bodies: each must be under an eighth of the box side");
  std::mt19937_64 rng(options.seed);
  const auto start = random_start<N>(radii, box_, rng);
  if (!start) {
    status_ = PackingStatus::no_start;
    return;
  }
  begin(*start, thermal_motions<N>(*start, rng));
}

template <int N>
Compression<N>::Compression(std::span<const Ellipsoid<double, N>> bodies,
                            std::span<const RigidMotion<double, N>> motions, const PeriodicBox<N>& box,
                            const PackingOptions& options)
    : options_(options), box_(box) {
  begin(bodies, motions);
}

template <int N>
void Compression<N>::begin(std::span<const Ellipsoid<double, N>> bodies, std::span<const RigidMotion<double, N>> motions) {
  for (const auto& b : bodies) total_ += volume<N>(b.radii()), largest_ = std::max(largest_, b.radii().maxCoeff());
  box_volume_ = 1.0;
  for (int k = 0; k < N; ++k) box_volume_ *= box_.size[k];
  system_.emplace(bodies, motions, box_, options_.skin, expansion(options_.schedule.stages().front().rate));
  if (!(system_->temperature() > 0.0)) throw InputError("motions", "must not all be at rest");
  system_->rescale(1.0 / std::sqrt(system_->temperature()), system_->expansion());
  start_interval();
}

template <int N>
void Compression<N>::advance(std::uint64_t collisions) {
  for (std::uint64_t k = 0; k < collisions && status_ == PackingStatus::compressing; ++k) {
    // Growing bodies always meet: an event is always ahead.
    if (system_->step().status != HardStatus::collided) throw std::logic_error("ellipsect: Compression: no event");
    if (system_->collisions() >= next_update_ || system_->collisions() >= options_.max_collisions) update();
  }
}

template <int N>
const HardBodies<N>& Compression<N>::system() const {
  if (!system_) throw std::logic_error("ellipsect: Compression: no start, no system");
  return *system_;
}

template <int N>
double Compression<N>::density_at(double t) const {
  return total_ * std::pow(system().scale_at(t), N) / box_volume_;
}

template <int N>
void Compression<N>::start_interval() {
  t_last_ = system_->now();
  virial_last_ = system_->virial();
  next_update_ = system_->collisions() + std::uint64_t(int(options_.collisions_per_update)) * system_->size();
}

// The reduced pressure over the interval, then jammed, at the cap, or the thermostat (kT = 1)
// and the schedule's rate at the pressure for the next interval.
template <int N>
void Compression<N>::update() {
  HardBodies<N>& s = *system_;
  const double dt = s.now() - t_last_, kt = (1.0 + s.temperature()) / 2;
  pressure_ = dt > 0.0 ? 1.0 + (s.virial() - virial_last_) / (N * double(s.size()) * kt * dt) : inf;
  history_.push_back({density_at(s.now()), pressure_});
  if (pressure_ >= options_.pressure) {
    status_ = PackingStatus::jammed;
  } else if (s.collisions() >= options_.max_collisions) {
    status_ = PackingStatus::collision_limit;
  } else {
    s.rescale(1.0 / std::sqrt(s.temperature()), expansion(options_.schedule.rate_at(pressure_)));
    start_interval();
  }
}

template <int N>
Packing<N> Compression<N>::packing() {
  Packing<N> out;
  out.status = status_;
  out.box = box_;
  if (!system_) return out;
  HardBodies<N>& s = *system_;
  // The pair that collided last has moved apart halfway to the next event (at the end of
  // the collision it touches to within rounding).
  const double next = s.next_event();
  out.time = std::isfinite(next) ? s.now() + (next - s.now()) / 2 : s.now();
  out.bodies = s.shapes_at(out.time);
  out.density = density_at(out.time);
  out.pressure = pressure_;
  out.history = history_;
  out.collisions = s.collisions();
  out.rebuilds = s.rebuilds();
  out.predictions_overlapping = s.overlaps();
  out.predictions_stopped = s.stopped();
  find_contacts<N>(out, options_.contact_gap > 0.0 ? double(options_.contact_gap) : 100.0 / options_.pressure);
  remove_rattlers<N>(out);
  return out;
}

template <int N>
Packing<N> jam_packing(std::span<const Vec<double, N>> radii, const PackingOptions& options) {
  Compression<N> c(radii, options);
  while (c.status() == PackingStatus::compressing) c.advance(std::uint64_t(options.max_collisions));
  return c.packing();
}

template class Compression<2>;
template class Compression<3>;
template Packing<2> jam_packing<2>(std::span<const Vec<double, 2>>, const PackingOptions&);
template Packing<3> jam_packing<3>(std::span<const Vec<double, 3>>, const PackingOptions&);

}  // namespace ellipsect
