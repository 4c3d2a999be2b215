// Event-driven hard bodies in a periodic box, and the jammed packings their compression
// reaches (Lubachevsky-Stillinger; for ellipsoids Donev, Torquato and Stillinger, J.
// Comput. Phys. 202 (2005) 737 and 765).
//
// HardBodies: ellipses (N = 2) or ellipsoids (N = 3) fly with constant linear and angular
// velocity between collisions (as in Donev et al., the angular velocity is held constant
// rather than following Euler's equations) and collide elastically at the point and normal
// first_contact reports; all radii may grow at one rate (RigidMotion::growth), the bodies
// keeping their shapes. Built on the library's queries alone: neighbor lists from the
// periodic candidate_pairs, predictions from first_contact under rigid motion with growth.
//
// Scheme: neighbor lists of bounding balls padded by a skin s are rebuilt whenever a body's
// center has moved, plus its largest radius has grown, s / 2 from the last rebuild (an
// event of its own), so that a pair not listed cannot touch before the next rebuild; each
// listed pair's next contact is predicted up to the earlier of the two bodies' rebuild
// events and kept in a priority queue, stamped with the bodies' collision counts (a stale
// prediction is dropped when it comes up). A pair that has just collided touches at the
// start of its next prediction: it is predicted from the moment its gap clears the tangency
// band (a relative 1e-9 of its size, reached at the separation rate).
//
// Growth (Lubachevsky-Stillinger): every body's radii are scale(t) times its radii at
// scale 1, scale growing at the rate `expansion` per unit time. A collision then reverses
// the normal velocity of the contact points relative to the surfaces' own growth: with w =
// (expansion / scale) n . (c_j - c_i) the rate at which growth closes the gap, the gap's rate
// -a before (a = n . (u_j - u_i) - w < 0, u the contact points' velocities) becomes +|a|
// after, which adds kinetic energy; `rescale` takes it back out.
//
// A module of its own, outside the core's umbrella header: link ellipsect::packing. Built on
// the core's public queries alone.
#pragma once

#include <ellipsect/broad_phase.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <array>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <queue>
#include <span>
#include <string_view>
#include <vector>

namespace ellipsect {

// One body of a HardBodies system: its shape at its own time `time` (center not wrapped
// into the box between rebuilds), its motion, mass, and its collision count.
template <int N>
struct HardBody {
  Ellipsoid<double, N> shape;
  RigidMotion<double, N> motion;  // growth: the system's, relative to the shape at `time`
  double time = 0.0;
  double mass = 1.0;
  std::uint64_t collisions = 0;
};

// A collision (or, with i == j, body i's rebuild event).
template <int N>
struct HardEvent {
  double time;
  std::uint32_t i, j;
  std::array<std::int32_t, N> image;  // j meets i through this image of the box
  std::uint64_t stamp_i, stamp_j;
  Vec<double, N> r_i, r_j, normal;  // the contact point from each center, the normal from i to j
  bool operator>(const HardEvent& o) const { return time > o.time; }
};

// What step() found: the next collision, or nothing left to happen (no body moves, spins or
// grows, or none of them ever meets another).
enum class HardStatus {
  collided,  // event: the collision, processed
  no_event   // event unset; the system is unchanged
};
std::string_view to_string(HardStatus s) noexcept;

template <int N>
struct HardStep {
  HardStatus status = HardStatus::no_event;
  HardEvent<N> event{};
};

// Totals the dynamics conserves (without growth), and the sum of |m v| (the scale of the
// momentum's rounding).
template <int N>
struct HardTotals {
  double energy;
  Vec<double, N> momentum;
  double momentum_scale;
};

template <int N>
class HardBodies {
public:
  // Bodies at time 0 (non-overlapping; each smaller than a quarter of the box side), their
  // velocities and angular velocities (growth ignored: `expansion` sets it), masses 1; the
  // skin as a fraction of the largest radius (refreshed at every rebuild); `expansion` the
  // rate of the scale of all radii (0: rigid bodies), the given radii at scale 1. Throws
  // InputError naming the field (sizes, box, skin, expansion).
  HardBodies(std::span<const Ellipsoid<double, N>> bodies, std::span<const RigidMotion<double, N>> motions,
             const PeriodicBox<N>& box, double skin = 0.5, double expansion = 0.0);

  // Processes events up to the next collision and returns it (status collided); status
  // no_event where none is left.
  HardStep<N> step();

  // Every body at time t (>= the last event's; default: now), centers wrapped into the box.
  std::vector<Ellipsoid<double, N>> shapes_at(double t) const;
  std::vector<Ellipsoid<double, N>> shapes() const { return shapes_at(now_); }
  HardTotals<N> totals() const;
  // Twice the kinetic energy per degree of freedom of the centers (k T, m <v^2> / N).
  double temperature() const;

  // All bodies to now; velocities and angular velocities times `factor`; the expansion set
  // anew (its scale continuous); every prediction made afresh.
  void rescale(double factor, double expansion);

  // The time of the next event (collision or rebuild): no pair touches in between.
  double next_event();

  double now() const { return now_; }
  // The scale of the radii at time t.
  double scale_at(double t) const { return scale_ + expansion_ * (t - scale_time_); }
  double expansion() const { return expansion_; }
  const PeriodicBox<N>& box() const { return box_; }
  std::size_t size() const { return bodies_.size(); }
  std::uint64_t collisions() const { return collisions_; }
  // Sum over collisions of the impulse times n . (c_j - c_i): the collisional virial.
  double virial() const { return virial_; }
  // Predictions that found a pair overlapping, or stopped (did_not_converge): 0 in a sound run.
  std::size_t overlaps() const { return overlaps_; }
  std::size_t stopped() const { return stopped_; }
  std::size_t rebuilds() const { return rebuilds_; }

private:
  double growth_at(double t) const { return expansion_ / scale_at(t); }
  Ellipsoid<double, N> wrapped(const Ellipsoid<double, N>& s) const;
  Ellipsoid<double, N> image_of(const HardBody<N>& b, const std::array<std::int32_t, N>& image) const;
  void advance(HardBody<N>& b, double t);
  void collide(const HardEvent<N>& e);
  void predict(std::uint32_t i, std::uint32_t j, const std::array<std::int32_t, N>& image);
  void schedule_rebuild(std::uint32_t i);
  void rebuild(double t);

  std::vector<HardBody<N>> bodies_;
  PeriodicBox<N> box_;
  double skin_fraction_, skin_ = 0.0, now_ = 0.0;
  double scale_ = 1.0, scale_time_ = 0.0, expansion_ = 0.0;  // scale(t) = scale_ + expansion_ (t - scale_time_)
  std::uint64_t collisions_ = 0;
  double virial_ = 0.0;
  std::size_t rebuilds_ = 0, overlaps_ = 0, stopped_ = 0;
  std::vector<Vec<double, N>> anchor_;  // centers at the last rebuild
  std::vector<double> anchor_radius_;   // largest radii at the last rebuild
  std::vector<double> exit_;            // each body's rebuild time
  std::vector<std::vector<std::pair<std::uint32_t, std::array<std::int32_t, N>>>> neighbors_;
  std::priority_queue<HardEvent<N>, std::vector<HardEvent<N>>, std::greater<>> queue_;
};

// ---- Jammed packings ---------------------------------------------------------------------

// The growth rate as reduced pressure rises: `rate` applies from reduced pressure `from` on.
struct GrowthStage {
  double from = 0.0;
  double rate = 1e-2;
};

namespace detail {
inline constexpr char max_collisions_field[] = "max_collisions";
inline constexpr char collisions_per_update_field[] = "collisions_per_update";
inline constexpr RealRange initial_density_range{"initial_density", 0.0, 0.5, false, false};
inline constexpr RealRange pressure_range{"pressure", 1.0, std::numeric_limits<double>::infinity(), false, false};
inline constexpr RealRange contact_gap_range{"contact_gap", 0.0, std::numeric_limits<double>::infinity(), true, false};
inline constexpr RealRange skin_range{"skin", 0.0, std::numeric_limits<double>::infinity(), false, false};
}  // namespace detail

// The growth schedule: stages with `from` increasing from 0 (the first at 0 or above) and
// rates finite and > 0; anything else throws InputError("schedule[k]") for the first bad
// stage k, or InputError("schedule") where there is none.
class GrowthSchedule {
public:
  GrowthSchedule(std::initializer_list<GrowthStage> stages) : GrowthSchedule(std::vector<GrowthStage>(stages)) {}
  explicit GrowthSchedule(std::vector<GrowthStage> stages);
  const std::vector<GrowthStage>& stages() const noexcept { return stages_; }
  // The rate of the last stage whose `from` the pressure has reached (the first stage's below it).
  double rate_at(double pressure) const noexcept;

private:
  std::vector<GrowthStage> stages_;
};

// Each field is validated as Options' are, where it is constructed or assigned: InputError
// naming the field, with the value and the range.
struct PackingOptions {
  std::uint64_t seed = 1;
  // Packing fraction of the random start, in (0, 0.5).
  RealOption<detail::initial_density_range> initial_density = 0.2;
  // The expansion rate d scale / dt in units of the thermal speed sqrt(kT / m) (kT = 1,
  // m = 1) over the largest diameter at scale 1, by reduced pressure.
  GrowthSchedule schedule = {{0.0, 1e-2}};
  // Jammed: reduced pressure p = PV / (N kT) beyond this, in (1, inf).
  RealOption<detail::pressure_range> pressure = 1e6;
  // The collisions to run at most, in [1, 2^62]: reaching it is PackingStatus::collision_limit.
  IterationCap<detail::max_collisions_field, std::uint64_t(1) << 62> max_collisions = std::uint64_t(1'000'000'000);
  // Contacts: pairs with mu - 1 below this, in [0, inf) (0: 100 / pressure).
  RealOption<detail::contact_gap_range> contact_gap = 0.0;
  // Neighbor-list skin, of the largest radius, in (0, inf).
  RealOption<detail::skin_range> skin = 0.1;
  // Per body, between thermostat and pressure updates, in [1, 1000000].
  IterationCap<detail::collisions_per_update_field, 1000000> collisions_per_update = 20;
};

enum class PackingStatus {
  jammed,           // reduced pressure reached options.pressure
  collision_limit,  // options.max_collisions reached first
  no_start,         // the random start found no room for a body in 1000 tries: bodies empty
  compressing       // Compression only: neither yet
};
std::string_view to_string(PackingStatus s) noexcept;

template <int N>
struct Packing {
  PackingStatus status = PackingStatus::collision_limit;
  PeriodicBox<N> box{};
  std::vector<Ellipsoid<double, N>> bodies;  // centers wrapped into [0, size)
  double density = 0.0;                      // packing fraction (sum of volumes / box volume)
  double pressure = 0.0;                     // reduced pressure over the last update
  std::uint64_t collisions = 0;
  std::size_t rebuilds = 0;                  // of the neighbor lists
  double time = 0.0;                         // of the bodies: between the last collision and the next event
  std::vector<ImagePair<N>> contacts;        // pairs with Perram-Wertheim mu - 1 < contact gap
  double mean_contacts = 0.0;                // 2 |contacts| / bodies
  std::size_t rattlers = 0;                  // bodies left with fewer than N + 1 contacts, removed in turn
  double mean_contacts_without_rattlers = 0.0;
  std::size_t overlapping = 0;               // pairs classify finds overlapping at the end (0)
  std::size_t predictions_overlapping = 0, predictions_stopped = 0;  // HardBodies' counts (0)
  // (density, reduced pressure) after each update
  std::vector<std::array<double, 2>> history;
};

// The compression, a bounded number of collisions at a time (for a caller that shows it
// as it goes; jam_packing runs one to its end). The start: N bodies with the given radii
// (their shapes; the scale is chosen so that the start has options.initial_density) at
// random non-overlapping positions and orientations in a cube (square) box, random
// velocities and angular velocities at kT = 1. Then HardBodies with expansion; every
// `collisions_per_update` collisions per body the reduced pressure p = 1 + virial /
// (N d kT dt) over the interval, the velocities rescaled to kT = 1, the growth rate from
// the schedule at p, until p reaches options.pressure (jammed) or the collisions
// options.max_collisions (collision_limit). Throws InputError naming the radius
// (radii[i]), or "radii" for fewer than two bodies or too few for the box (each under an
// eighth of its side); the options are valid by their types. Or from the caller's start:
// bodies at scale 1 in `box` (as HardBodies takes them), velocities and angular velocities
// (rescaled to kT = 1 first; not all at rest: InputError "motions"), options.seed and
// options.initial_density unused.
template <int N>
class Compression {
public:
  explicit Compression(std::span<const Vec<double, N>> radii, const PackingOptions& options = {});
  Compression(std::span<const Ellipsoid<double, N>> bodies, std::span<const RigidMotion<double, N>> motions,
              const PeriodicBox<N>& box, const PackingOptions& options = {});

  // Runs up to `collisions` more collisions, fewer where the compression ends on the way.
  void advance(std::uint64_t collisions);
  PackingStatus status() const noexcept { return status_; }  // compressing until it ends
  // The bodies' system (not at no_start, where there is none: std::logic_error).
  const HardBodies<N>& system() const;
  // The packing fraction at time t (>= the last event's).
  double density_at(double t) const;
  // The reduced pressure of the last update (NaN before the first), and (density, p) of each.
  double pressure() const noexcept { return pressure_; }
  const std::vector<std::array<double, 2>>& history() const noexcept { return history_; }
  // The packing as it stands (jam_packing's answer once ended): the bodies halfway to the
  // next event, where no pair touches, their contacts, rattlers and checks.
  Packing<N> packing();

private:
  // d scale / dt for a schedule rate, in thermal speeds per largest diameter.
  double expansion(double rate) const noexcept { return rate / (2 * largest_); }
  void begin(std::span<const Ellipsoid<double, N>> bodies, std::span<const RigidMotion<double, N>> motions);
  void start_interval();
  void update();

  PackingOptions options_;
  PeriodicBox<N> box_{};
  double total_ = 0.0, box_volume_ = 0.0, largest_ = 0.0;  // volume at scale 1; largest radius
  std::optional<HardBodies<N>> system_;
  PackingStatus status_ = PackingStatus::compressing;
  double pressure_ = std::numeric_limits<double>::quiet_NaN(), t_last_ = 0.0, virial_last_ = 0.0;
  std::uint64_t next_update_ = 0;
  std::vector<std::array<double, 2>> history_;
};

// Compression(radii, options) run to its end: its packing().
template <int N>
Packing<N> jam_packing(std::span<const Vec<double, N>> radii, const PackingOptions& options = {});

}  // namespace ellipsect
