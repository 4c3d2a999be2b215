// Event-driven hard bodies with growth (packing.hpp).
#include <ellipsect/distance.hpp>
#include <ellipsect/packing.hpp>

#include "mechanics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ellipsect {

using packing::cross;
using packing::dot_spin;
using packing::finite_spin;
using packing::inverse_inertia;
using packing::point_velocity;
using packing::Spin;
using packing::spin_energy;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
}  // namespace

std::string_view to_string(HardStatus s) noexcept {
  switch (s) {
    case HardStatus::collided: return "collided";
    case HardStatus::no_event: return "no_event";
  }
  return "?";
}

template <int N>
HardBodies<N>::HardBodies(std::span<const Ellipsoid<double, N>> bodies, std::span<const RigidMotion<double, N>> motions,
                          const PeriodicBox<N>& box, double skin, double expansion)
    : box_(box), skin_fraction_(skin), expansion_(expansion) {
  if (motions.size() != bodies.size()) throw InputError("motions", "must be as many as the bodies");
  for (int k = 0; k < N; ++k)
    if (!(box.size[k] > 0.0) || !std::isfinite(box.size[k])) throw InputError("box.size", "must be finite and > 0");
  if (!(skin > 0.0) || !std::isfinite(skin)) throw InputError("skin", "must be finite and > 0");
  if (!(expansion >= 0.0) || !std::isfinite(expansion)) throw InputError("expansion", "must be finite and >= 0");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const RigidMotion<double, N>& m = motions[i];
    if (!m.velocity.allFinite()) throw InputError("motions[" + std::to_string(i) + "].velocity", "must be finite");
    if (!finite_spin<N>(m.angular_velocity))
      throw InputError("motions[" + std::to_string(i) + "].angular_velocity", "must be finite");
    bodies_.push_back({bodies[i], {m.velocity, m.angular_velocity, expansion}, 0.0, 1.0, 0});
  }
  rebuild(0.0);
}

template <int N>
HardStep<N> HardBodies<N>::step() {
  for (;;) {
    if (queue_.empty()) return {};
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
    return {HardStatus::collided, e};
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
  if (!(factor > 0.0) || !std::isfinite(factor)) throw InputError("factor", "must be finite and > 0");
  if (!(expansion >= 0.0) || !std::isfinite(expansion)) throw InputError("expansion", "must be finite and >= 0");
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
  for (int k = 0; k < N; ++k) shift[k] = -std::floor(s.center()[k] / box_.size[k]) * box_.size[k];
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
    start += std::max(1e-9 * size / rate, 1e-15 * std::abs(start));
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
    exit_[i] = vv > 0.0 ? now_ + (-dv + std::sqrt(std::max(0.0, dv * dv - vv * c))) / vv : inf;
  } else {
    exit_[i] = now_ + std::max(0.0, 0.5 * skin_ - d.norm() - grown) / (v.norm() + growing);
  }
  if (std::isfinite(exit_[i]))
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

template class HardBodies<2>;
template class HardBodies<3>;

}  // namespace ellipsect
