// Event-driven hard bodies with growth and jammed packings (packing.hpp).
#include <ellipsect/classify.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/packing.hpp>

#include "detail/rigid_motion.hpp"
#include "detail/math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace ellipsect {

namespace {

template <int N>
using Spin = decltype(RigidMotion<double, N>::angular_velocity);

constexpr double inf = std::numeric_limits<double>::infinity();

// Principal moments of a uniform solid body of mass m along its axes (2D: about the normal).
template <int N>
Vec<double, N == 2 ? 1 : 3> inertia(const Ellipsoid<double, N>& s, double m) {
  const Vec<double, N> r2 = s.radii().cwiseProduct(s.radii());
  if constexpr (N == 2) {
    return Vec<double, 1>(m * (r2[0] + r2[1]) / 4);
  } else {
    return m / 5 * Vec<double, 3>(r2[1] + r2[2], r2[0] + r2[2], r2[0] + r2[1]);
  }
}

// I^-1 applied to a torque (2D: a scalar), in the world frame of shape s.
template <int N>
Spin<N> inverse_inertia(const Ellipsoid<double, N>& s, double m, const Spin<N>& torque) {
  if constexpr (N == 2)
    return torque / inertia<2>(s, m)[0];
  else
    return s.axes() * (s.axes().transpose() * torque).cwiseQuotient(inertia<3>(s, m));
}

// omega . I omega.
template <int N>
double spin_energy(const Ellipsoid<double, N>& s, double m, const Spin<N>& w) {
  if constexpr (N == 2) {
    return inertia<2>(s, m)[0] * w * w;
  } else {
    const Vec<double, 3> body = s.axes().transpose() * w;
    return body.dot(inertia<3>(s, m).cwiseProduct(body));
  }
}

template <int N>
Spin<N> cross(const Vec<double, N>& r, const Vec<double, N>& n) {
  if constexpr (N == 2)
    return r.x() * n.y() - r.y() * n.x();
  else
    return r.cross(n);
}

template <int N>
double dot_spin(const Spin<N>& x, const Spin<N>& y) {
  if constexpr (N == 2)
    return x * y;
  else
    return x.dot(y);
}

// Velocity of the material point at r from the center.
template <int N>
Vec<double, N> point_velocity(const RigidMotion<double, N>& m, const Vec<double, N>& r) {
  return m.velocity + detail::rigid::spin_cross<N>(m.angular_velocity, r);
}

template <int N>
double volume(const Vec<double, N>& radii) {
  return (N == 2 ? M_PI : 4.0 / 3.0 * M_PI) * radii.prod();
}

}  // namespace

template <int N>
HardBodies<N>::HardBodies(std::span<const Ellipsoid<double, N>> bodies, std::span<const RigidMotion<double, N>> motions,
                          const PeriodicBox<N>& box, double skin, double expansion)
    : box_(box), skin_fraction_(skin), expansion_(expansion) {
  if (motions.size() != bodies.size()) throw InputError("motions", "must be as many as the bodies");
  for (int k = 0; k < N; ++k)
    if (!(box.size[k] > 0.0) || !isfinite(box.size[k])) throw InputError("box.size", "must be finite and > 0");
  if (!(skin > 0.0) || !isfinite(skin)) throw InputError("skin", "must be finite and > 0");
  if (!(expansion >= 0.0) || !isfinite(expansion)) throw InputError("expansion", "must be finite and >= 0");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidMotion<double, N>& m = motions[i];
    if (!m.velocity.allFinite()) throw InputError("motions[" + std::to_string(i) + "].velocity", "must be finite");
    if (!detail::rigid::all_finite<N>(m.angular_velocity))
      throw InputError("motions[" + std::to_string(i) + "].angular_velocity", "must be finite");
    bodies_.push_back({bodies[i], {m.velocity, m.angular_velocity, expansion}, 0.0, 1.0, 0});
  }
  rebuild(0.0);
}

template <int N>
HardEvent<N> HardBodies<N>::step() {
  for (;;) {
    if (queue_.empty()) throw std::runtime_error("ellipsect: HardBodies: no event predicted");
    const HardEvent<N> e = queue_.top();
    queue_.pop();
    if (e.time < now_) throw std::logic_error("ellipsect: HardBodies: event times decrease");
    if (bodies_[e.i].collisions != e.stamp_i || bodies_[e.j].collisions != e.stamp_j) continue;
    now_ = e.time;
    if (e.i == e.j) {
      rebuild(now_);
      continue;
    }
    collide(e);
    return e;
  }
}

template <int N>
double HardBodies<N>::next_event() {
  while (!queue_.empty()) {
    const HardEvent<N>& e = queue_.top();
    if (bodies_[e.i].collisions == e.stamp_i && bodies_[e.j].collisions == e.stamp_j) return e.time;
    queue_.pop();
  }
  return inf;
}

template <int N>
std::vector<Ellipsoid<double, N>> HardBodies<N>::shapes_at(double t) const {
  std::vector<Ellipsoid<double, N>> out;
  out.reserve(bodies_.size());
  for (const auto& b : bodies_) out.push_back(wrapped(body_at(b.shape, b.motion, t - b.time)));
  return out;
}

template <int N>
HardTotals<N> HardBodies<N>::totals() const {
  HardTotals<N> t{0.0, Vec<double, N>::Zero(), 0.0};
  for (const auto& b : bodies_) {
    const auto s = body_at(b.shape, b.motion, now_ - b.time);
    t.energy += 0.5 * b.mass * b.motion.velocity.squaredNorm() + 0.5 * spin_energy<N>(s, b.mass, b.motion.angular_velocity);
    t.momentum += b.mass * b.motion.velocity;
    t.momentum_scale += b.mass * b.motion.velocity.norm();
  }
  return t;
}

template <int N>
double HardBodies<N>::temperature() const {
  double sum = 0.0;
  for (const auto& b : bodies_) sum += b.mass * b.motion.velocity.squaredNorm();
  return bodies_.empty() ? 0.0 : sum / double(N * bodies_.size());
}

template <int N>
void HardBodies<N>::rescale(double factor, double expansion) {
  if (!(factor > 0.0) || !isfinite(factor)) throw InputError("factor", "must be finite and > 0");
  if (!(expansion >= 0.0) || !isfinite(expansion)) throw InputError("expansion", "must be finite and >= 0");
  for (auto& b : bodies_) {
    advance(b, now_);
    b.motion.velocity *= factor;
    b.motion.angular_velocity *= factor;
  }
  scale_ = scale_at(now_);
  scale_time_ = now_;
  expansion_ = expansion;
  rebuild(now_);
}

template <int N>
Ellipsoid<double, N> HardBodies<N>::wrapped(const Ellipsoid<double, N>& s) const {
  Vec<double, N> shift;
  for (int k = 0; k < N; ++k) shift[k] = -floor(s.center()[k] / box_.size[k]) * box_.size[k];
  return shift.isZero(0) ? s : s.translated(shift);
}

template <int N>
Ellipsoid<double, N> HardBodies<N>::image_of(const HardBody<N>& b, const std::array<std::int32_t, N>& image) const {
  Vec<double, N> offset;
  for (int k = 0; k < N; ++k) offset[k] = image[k] * box_.size[k];
  return offset.isZero(0) ? b.shape : b.shape.translated(offset);
}

template <int N>
void HardBodies<N>::advance(HardBody<N>& b, double t) {
  if (t != b.time) b.shape = body_at(b.shape, b.motion, t - b.time);
  b.time = t;
  b.motion.growth = growth_at(t);
}

// The impulse along the normal that turns the gap's rate a (the contact points' normal
// velocity less the growth's closing w) into -a, with the bodies' masses and world inertia.
template <int N>
void HardBodies<N>::collide(const HardEvent<N>& e) {
  HardBody<N>& a = bodies_[e.i];
  HardBody<N>& b = bodies_[e.j];
  advance(a, now_);
  advance(b, now_);
  const Vec<double, N>& n = e.normal;
  const Vec<double, N> apart = image_of(b, e.image).center() - a.shape.center();
  const double rate = (point_velocity<N>(b.motion, e.r_j) - point_velocity<N>(a.motion, e.r_i)).dot(n) -
                      growth_at(now_) * n.dot(apart);
  const Spin<N> ta = cross<N>(e.r_i, n), tb = cross<N>(e.r_j, n);
  const double effective = 1.0 / a.mass + 1.0 / b.mass + dot_spin<N>(ta, inverse_inertia<N>(a.shape, a.mass, ta)) +
                           dot_spin<N>(tb, inverse_inertia<N>(b.shape, b.mass, tb));
  const double j = rate < 0.0 ? -2.0 * rate / effective : 0.0;
  a.motion.velocity -= j / a.mass * n;
  b.motion.velocity += j / b.mass * n;
  a.motion.angular_velocity -= j * inverse_inertia<N>(a.shape, a.mass, ta);
  b.motion.angular_velocity += j * inverse_inertia<N>(b.shape, b.mass, tb);
  virial_ += j * n.dot(apart);
  ++collisions_;
  ++a.collisions;
  ++b.collisions;
  for (const std::uint32_t k : {e.i, e.j}) {
    schedule_rebuild(k);
    for (const auto& [other, image] : neighbors_[k])
      if (k == e.i || other != e.i) predict(k, other, image);  // the pair itself once
  }
}

// The next contact of i and j (j through its image), up to the earlier rebuild of the two.
template <int N>
void HardBodies<N>::predict(std::uint32_t i, std::uint32_t j, const std::array<std::int32_t, N>& image) {
  HardBody<N>& a = bodies_[i];
  HardBody<N>& b = bodies_[j];
  advance(a, now_);
  advance(b, now_);
  const double end = std::min(exit_[i], exit_[j]);
  const Ellipsoid<double, N> b_image = image_of(b, image);
  for (double start = now_; start < end;) {
    const auto sa = body_at(a.shape, a.motion, start - now_);
    const auto sb = body_at(b_image, b.motion, start - now_);
    RigidMotion<double, N> ma = a.motion, mb = b.motion;
    ma.growth = mb.growth = growth_at(start);
    Contact<double, N> c = first_contact(sa, ma, sb, mb, end - start);
    if (c.status == ContactStatus::overlapping_at_start) {
      // Overlapping by no more than 1e-9 of the smaller radii (the bodies re-formed at another
      // time, or an elongated pair turning onto a second point right after a collision): the
      // contact of the signed distance, taken as touching. Deeper: counted, not predicted.
      const Distance<double, N> d = signed_distance(sa, sb);
      const double small = std::min(sa.radii().minCoeff(), sb.radii().minCoeff());
      if (!(d.distance >= -1e-9 * small)) {
        ++overlaps_;
        return;
      }
      c = {ContactStatus::touching_at_start, 0.0, Vec<double, N>((d.point_a + d.point_b) / 2), d.normal, 0};
    }
    if (c.status == ContactStatus::did_not_converge) ++stopped_;
    if (c.status != ContactStatus::hit && c.status != ContactStatus::touching_at_start) return;
    const Vec<double, N> ca = sa.center() + c.time * a.motion.velocity, cb = sb.center() + c.time * b.motion.velocity;
    const Vec<double, N> ra = c.point - ca, rb = c.point - cb;
    const double rate = (point_velocity<N>(b.motion, rb) - point_velocity<N>(a.motion, ra)).dot(c.normal) -
                        growth_at(start + c.time) * c.normal.dot(cb - ca);
    if (c.status == ContactStatus::hit || rate < 0.0) {
      queue_.push({start + c.time, i, j, image, a.collisions, b.collisions, ra, rb, c.normal});
      return;
    }
    // Touching and separating (the pair has just collided): look again once the gap has
    // cleared the tangency band.
    const double size = std::max(sa.radii().maxCoeff(), sb.radii().maxCoeff());
    start += std::max(1e-9 * size / rate, 1e-15 * abs(start));
  }
}

// Body i's rebuild event: when its center's displacement plus its largest radius's growth
// since the rebuild reach skin / 2 (without growth, exactly; with it, by the bound |d + v
// s| <= |d| + |v| s).
template <int N>
void HardBodies<N>::schedule_rebuild(std::uint32_t i) {
  const HardBody<N>& b = bodies_[i];
  const Vec<double, N> d = b.shape.center() + (now_ - b.time) * b.motion.velocity - anchor_[i];
  const Vec<double, N>& v = b.motion.velocity;
  const double radius = b.shape.radii().maxCoeff() * (scale_at(now_) / scale_at(b.time));
  const double grown = radius - anchor_radius_[i], growing = radius * growth_at(now_);
  if (growing == 0.0) {
    const double vv = v.squaredNorm(), dv = d.dot(v), c = d.squaredNorm() - 0.25 * skin_ * skin_;
    exit_[i] = vv > 0.0 ? now_ + (-dv + sqrt(std::max(0.0, dv * dv - vv * c))) / vv : inf;
  } else {
    exit_[i] = now_ + std::max(0.0, 0.5 * skin_ - d.norm() - grown) / (v.norm() + growing);
  }
  if (isfinite(exit_[i]))
    queue_.push({exit_[i], i, i, {}, b.collisions, b.collisions, Vec<double, N>::Zero(), Vec<double, N>::Zero(),
                 Vec<double, N>::Zero()});
}

// All bodies to time t, centers wrapped; neighbor lists of the balls of radius R + s / 2;
// every listed pair predicted afresh.
template <int N>
void HardBodies<N>::rebuild(double t) {
  ++rebuilds_;
  queue_ = {};
  double largest = 0.0;
  for (auto& b : bodies_) {
    advance(b, t);
    b.shape = wrapped(b.shape);
    largest = std::max(largest, b.shape.radii().maxCoeff());
  }
  skin_ = skin_fraction_ * largest;
  std::vector<Ellipsoid<double, N>> balls;
  balls.reserve(bodies_.size());
  anchor_.resize(bodies_.size());
  anchor_radius_.resize(bodies_.size());
  exit_.resize(bodies_.size());
  for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
    const auto& s = bodies_[i].shape;
    balls.push_back(make_ball<double, N>(s.center(), s.radii().maxCoeff() + 0.5 * skin_));
    anchor_[i] = s.center();
    anchor_radius_[i] = s.radii().maxCoeff();
    schedule_rebuild(i);
  }
  neighbors_.assign(bodies_.size(), {});
  for (const ImagePair<N>& p : candidate_pairs<double, N>(balls, box_)) {
    std::array<std::int32_t, N> back;
    for (int k = 0; k < N; ++k) back[k] = -p.image[k];
    neighbors_[p.i].push_back({p.j, p.image});
    neighbors_[p.j].push_back({p.i, back});
    predict(p.i, p.j, p.image);
  }
}

std::string_view to_string(PackingStatus s) noexcept {
  switch (s) {
    case PackingStatus::jammed: return "jammed";
    case PackingStatus::collision_limit: return "collision_limit";
  }
  return "?";
}

namespace {

// A uniformly random orientation.
template <int N>
Mat<double, N> random_axes(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  if constexpr (N == 2) {
    const double angle = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
    Mat<double, 2> a;
    a << cos(angle), -sin(angle), sin(angle), cos(angle);
    return a;
  } else {
    const Quat<double> q = Quat<double>(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    return q.toRotationMatrix();
  }
}

// Random non-overlapping placement in the box (each body against those placed, through the
// nearest image); InputError where 1000 tries per body do not find room.
template <int N>
std::vector<Ellipsoid<double, N>> random_start(std::span<const Vec<double, N>> radii, const PeriodicBox<N>& box,
                                               std::mt19937_64& rng) {
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
        for (int k = 0; k < N; ++k) d[k] -= box.size[k] * round(d[k] / box.size[k]);
        if (d.norm() > body.radii().maxCoeff() + o.radii().maxCoeff()) return false;
        return overlap(body, o.translated(Vec<double, N>(c + d - o.center())));
      });
      if (placed) out.push_back(body);
    }
    if (!placed) throw InputError("options.initial_density", "too high to place the bodies at random");
  }
  return out;
}

double rate_at(const std::vector<GrowthStage>& schedule, double pressure) {
  double rate = schedule.front().rate;
  for (const GrowthStage& s : schedule)
    if (pressure >= s.from) rate = s.rate;
  return rate;
}

}  // namespace

template <int N>
Packing<N> jam_packing(std::span<const Vec<double, N>> radii, const PackingOptions& options) {
  if (radii.size() < 2) throw InputError("radii", "must hold at least two bodies");
  for (std::size_t i = 0; i < radii.size(); ++i)
    if (!radii[i].allFinite() || !(radii[i].minCoeff() > 0.0))
      throw InputError("radii[" + std::to_string(i) + "]", "must be finite and > 0");
  if (!(options.initial_density > 0.0) || !(options.initial_density < 0.5))
    throw InputError("options.initial_density", "must be in (0, 0.5)");
  if (options.schedule.empty()) throw InputError("options.schedule", "must have at least one stage");
  for (std::size_t k = 0; k < options.schedule.size(); ++k) {
    const GrowthStage& s = options.schedule[k];
    if (!(s.rate > 0.0) || !isfinite(s.rate) || !(s.from >= 0.0) ||
        (k > 0 && !(s.from > options.schedule[k - 1].from)))
      throw InputError("options.schedule[" + std::to_string(k) + "]",
                       "rates must be finite and > 0, pressures increasing from 0");
  }
  if (!(options.pressure > 1.0) || !isfinite(options.pressure))
    throw InputError("options.pressure", "must be finite and > 1");
  if (!(options.contact_gap >= 0.0) || !isfinite(options.contact_gap))
    throw InputError("options.contact_gap", "must be finite and >= 0");
  if (!(options.skin > 0.0) || !isfinite(options.skin))
    throw InputError("options.skin", "must be finite and > 0");
  if (options.collisions_per_update < 1) throw InputError("options.collisions_per_update", "must be >= 1");

  std::mt19937_64 rng(options.seed);
  double total = 0.0, largest = 0.0;
  for (const auto& r : radii) total += volume<N>(r), largest = std::max(largest, r.maxCoeff());
  PeriodicBox<N> box;
  const double side = pow(total / options.initial_density, 1.0 / N);
  for (int k = 0; k < N; ++k) box.size[k] = side;
  if (!(8 * largest < side)) throw InputError("radii", "too few bodies: each must be under an eighth of the box side");
  const std::vector<Ellipsoid<double, N>> start = random_start<N>(radii, box, rng);

  // Velocities at kT = 1 (mass 1), no net momentum; angular velocities at kT = 1 per axis.
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<RigidMotion<double, N>> motions(start.size());
  Vec<double, N> mean = Vec<double, N>::Zero();
  for (std::size_t i = 0; i < start.size(); ++i) {
    for (int k = 0; k < N; ++k) motions[i].velocity[k] = normal(rng);
    mean += motions[i].velocity / double(start.size());
    const auto moments = inertia<N>(start[i], 1.0);
    if constexpr (N == 2) {
      motions[i].angular_velocity = normal(rng) / sqrt(moments[0]);
    } else {
      const Vec<double, 3> w(normal(rng) / sqrt(moments[0]), normal(rng) / sqrt(moments[1]),
                             normal(rng) / sqrt(moments[2]));
      motions[i].angular_velocity = start[i].axes() * w;
    }
  }
  for (auto& m : motions) m.velocity -= mean;

  // d scale / dt from the rate in thermal speeds per largest diameter.
  auto expansion = [&](double rate) { return rate / (2 * largest); };
  HardBodies<N> system(start, motions, box, options.skin, expansion(options.schedule.front().rate));
  {
    const double t = system.temperature();
    system.rescale(1.0 / sqrt(t), system.expansion());
  }

  Packing<N> out;
  out.box = box;
  const double n = double(start.size()), box_volume = pow(side, N);
  const std::uint64_t per_update = std::uint64_t(options.collisions_per_update) * start.size();
  double t_last = system.now(), virial_last = system.virial();
  for (;;) {
    const std::uint64_t target = system.collisions() + per_update;
    while (system.collisions() < target && system.collisions() < options.max_collisions) system.step();
    const double dt = system.now() - t_last, kt = (1.0 + system.temperature()) / 2;
    out.pressure = dt > 0.0 ? 1.0 + (system.virial() - virial_last) / (N * n * kt * dt) : inf;
    out.density = total * pow(system.scale_at(system.now()), N) / box_volume;
    out.history.push_back({out.density, out.pressure});
    if (out.pressure >= options.pressure) {
      out.status = PackingStatus::jammed;
      break;
    }
    if (system.collisions() >= options.max_collisions) break;
    system.rescale(1.0 / sqrt(system.temperature()), expansion(rate_at(options.schedule, out.pressure)));
    t_last = system.now();
    virial_last = system.virial();
  }

  // The packing halfway to the next event, where no pair touches: the pair that collided last
  // has moved apart (at the end of the collision it touches to within rounding).
  out.collisions = system.collisions();
  out.rebuilds = system.rebuilds();
  const double next = system.next_event();
  out.time = isfinite(next) ? system.now() + (next - system.now()) / 2 : system.now();
  out.bodies = system.shapes_at(out.time);
  out.density = total * pow(system.scale_at(out.time), N) / box_volume;
  out.predictions_overlapping = system.overlaps();
  out.predictions_stopped = system.stopped();
  // Contacts and the final check, on the candidate pairs of the final bodies grown by 1 + gap
  // about their centers: a pair with mu - 1 < gap overlaps when both are grown by mu, so the
  // boxes of the grown bodies meet (those of the bodies themselves need not).
  const double gap = options.contact_gap > 0.0 ? options.contact_gap : 100.0 / options.pressure;
  std::vector<int> count(start.size(), 0);
  std::vector<Ellipsoid<double, N>> grown;
  grown.reserve(out.bodies.size());
  for (const Ellipsoid<double, N>& s : out.bodies)
    grown.push_back(Ellipsoid<double, N>::from_axes(s.center(), s.axes(), s.radii() * (1.0 + gap)));
  for (const ImagePair<N>& p : candidate_pairs<double, N>(grown, box)) {
    Vec<double, N> offset;
    for (int k = 0; k < N; ++k) offset[k] = p.image[k] * box.size[k];
    const Ellipsoid<double, N>& a = out.bodies[p.i];
    const Ellipsoid<double, N> b = out.bodies[p.j].translated(offset);
    const Relation r = classify(a, b);
    if (r != Relation::separated && r != Relation::touching) ++out.overlapping;
    const ContactFunction<double> f = perram_wertheim(a, b);
    if (sqrt(f.f) - 1.0 < gap) {
      out.contacts.push_back(p);
      ++count[p.i];
      ++count[p.j];
    }
  }
  out.mean_contacts = 2.0 * double(out.contacts.size()) / n;
  // Rattlers: bodies with fewer than N + 1 contacts, removed with their contacts until none is
  // left among the rest.
  std::vector<bool> rattler(start.size(), false);
  std::size_t kept_contacts = out.contacts.size();
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 0; i < start.size(); ++i)
      if (!rattler[i] && count[i] <= N) rattler[i] = changed = true;
    if (!changed) break;
    std::fill(count.begin(), count.end(), 0);
    kept_contacts = 0;
    for (const ImagePair<N>& p : out.contacts)
      if (!rattler[p.i] && !rattler[p.j]) ++count[p.i], ++count[p.j], ++kept_contacts;
  }
  out.rattlers = std::size_t(std::count(rattler.begin(), rattler.end(), true));
  out.mean_contacts_without_rattlers =
      out.rattlers < start.size() ? 2.0 * double(kept_contacts) / (n - double(out.rattlers)) : 0.0;
  return out;
}

template class HardBodies<2>;
template class HardBodies<3>;
template Packing<2> jam_packing<2>(std::span<const Vec<double, 2>>, const PackingOptions&);
template Packing<3> jam_packing<3>(std::span<const Vec<double, 3>>, const PackingOptions&);

}  // namespace ellipsect
