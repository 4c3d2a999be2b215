// Event-driven dynamics of hard ellipses (N = 2) or ellipsoids (N = 3) in a periodic box:
// the bodies fly with constant linear and angular velocity (as in Donev, Torquato and
// Stillinger, J. Comput. Phys. 2005, the angular velocity is held constant between
// collisions rather than following Euler's equations) and collide elastically at the point
// and normal first_contact reports. Built on the library alone: neighbor lists from the
// periodic candidate_pairs, predictions from first_contact under rigid motion.
//
// Scheme: neighbor lists of bounding balls padded by a skin s are rebuilt whenever a body
// has moved s / 2 from where it stood at the last rebuild (an event of its own), so a pair
// that is not listed cannot touch before the next rebuild; each listed pair's next contact
// is predicted up to the earlier of the two bodies' rebuild events and kept in a priority
// queue, stamped with the bodies' collision counts (a stale prediction is dropped when it
// comes up). A pair that has just collided touches at the start of its next prediction: it
// is predicted from the moment its gap clears the tangency band (a relative 1e-9 of its
// size, reached at the separation speed), so a second contact within that instant would go
// unseen; the test's overlap check after every event would catch it.
#pragma once

#include <ellipsect/broad_phase.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <random>
#include <stdexcept>
#include <vector>

namespace hard_bodies {

using namespace ellipsect;

template <int N>
using Spin = std::conditional_t<N == 2, double, Vec<double, 3>>;

template <int N>
struct Body {
  Ellipsoid<double, N> shape;  // at time `time`, center not wrapped between rebuilds
  RigidMotion<double, N> motion;
  double time = 0.0;
  double mass = 1.0;
  Vec<double, N == 2 ? 1 : 3> inertia;  // principal moments, along the shape's axes
  std::uint64_t collisions = 0;
};

template <int N>
struct Event {
  double time;
  std::uint32_t i, j;  // j == i: body i's rebuild event
  std::array<std::int32_t, N> image;
  std::uint64_t stamp_i, stamp_j;
  Vec<double, N> r_i, r_j, normal;  // contact point from each center, normal from i to j
  bool operator>(const Event& o) const { return time > o.time; }
};

// Totals the dynamics conserves, and the sum of |m v| (the scale of the momentum's rounding).
template <int N>
struct Totals {
  double energy;
  Vec<double, N> momentum;
  double momentum_scale;
};

template <int N>
class Simulation {
public:
  // Identical bodies of radii `radii` on a lattice of n^N sites, spaced so that the packing
  // fraction is phi, aligned, with random velocities (zero total momentum) and spins.
  Simulation(int n, const Vec<double, N>& radii, double phi, unsigned seed) {
    const double volume = N == 2 ? M_PI * radii.prod() : 4.0 / 3.0 * M_PI * radii.prod();
    const double cell = std::pow(volume / phi / (std::pow(2.0, N) * radii.prod()), 1.0 / N);  // spacing / diameter
    if (!(cell > 1.0)) throw std::invalid_argument("packing fraction too high for an aligned lattice");
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int k = 0; k < N; ++k) box_.size[k] = n * 2.0 * radii[k] * cell;
    skin_ = 0.5 * radii.maxCoeff();
    int sites = 1;
    for (int k = 0; k < N; ++k) sites *= n;
    Vec<double, N> total = Vec<double, N>::Zero();
    for (int s = 0; s < sites; ++s) {
      Vec<double, N> c;
      for (int k = 0, code = s; k < N; ++k, code /= n) c[k] = (code % n + 0.5) * 2.0 * radii[k] * cell;
      Body<N> b{Ellipsoid<double, N>::from_axes(c, Mat<double, N>::Identity(), radii), {}, 0.0, volume, {}, 0};
      for (int k = 0; k < N; ++k) b.motion.velocity[k] = normal(rng);
      if constexpr (N == 2) {
        b.motion.angular_velocity = normal(rng);
        b.inertia[0] = volume * radii.squaredNorm() / 4.0;
      } else {
        b.motion.angular_velocity = Vec<double, 3>(normal(rng), normal(rng), normal(rng));
        const Vec<double, 3> r2 = radii.cwiseProduct(radii);
        b.inertia = volume / 5.0 * Vec<double, 3>(r2[1] + r2[2], r2[0] + r2[2], r2[0] + r2[1]);
      }
      total += b.motion.velocity;
      bodies_.push_back(b);
    }
    for (auto& b : bodies_) b.motion.velocity -= total / double(sites);
    rebuild(0.0);
  }

  // Processes the next collision (rebuilds on the way are not counted); returns it.
  Event<N> step() {
    for (;;) {
      if (queue_.empty()) throw std::runtime_error("no event predicted");
      const Event<N> e = queue_.top();
      queue_.pop();
      if (e.time < now_) throw std::logic_error("event times decrease");
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

  // Every body at time t (the current time by default), centers wrapped into the box.
  std::vector<Ellipsoid<double, N>> shapes_at(double t) const {
    std::vector<Ellipsoid<double, N>> out;
    for (const auto& b : bodies_) out.push_back(wrapped(body_at(b.shape, b.motion, t - b.time)));
    return out;
  }
  std::vector<Ellipsoid<double, N>> shapes() const { return shapes_at(now_); }

  Totals<N> totals() const {
    Totals<N> t{0.0, Vec<double, N>::Zero(), 0.0};
    for (const auto& b : bodies_) {
      const auto s = body_at(b.shape, b.motion, now_ - b.time);
      t.energy += 0.5 * b.mass * b.motion.velocity.squaredNorm() + 0.5 * spin_energy(b, s);
      t.momentum += b.mass * b.motion.velocity;
      t.momentum_scale += b.mass * b.motion.velocity.norm();
    }
    return t;
  }

  double now() const { return now_; }
  // Predictions that found a pair overlapping, or stopped (did_not_converge): 0 in a sound run.
  std::size_t overlaps() const { return overlaps_; }
  std::size_t stopped() const { return stopped_; }
  const PeriodicBox<N>& box() const { return box_; }
  std::size_t rebuilds() const { return rebuilds_; }

private:
  Ellipsoid<double, N> wrapped(const Ellipsoid<double, N>& s) const {
    Vec<double, N> shift;
    for (int k = 0; k < N; ++k) shift[k] = -std::floor(s.center()[k] / box_.size[k]) * box_.size[k];
    return shift.isZero(0) ? s : s.translated(shift);
  }

  // omega . I omega for the body's shape `s` (its axes at the current time).
  static double spin_energy(const Body<N>& b, const Ellipsoid<double, N>& s) {
    if constexpr (N == 2) {
      return b.inertia[0] * b.motion.angular_velocity * b.motion.angular_velocity;
    } else {
      const Vec<double, 3> w = s.axes().transpose() * b.motion.angular_velocity;
      return w.dot(b.inertia.cwiseProduct(w));
    }
  }

  // I^-1 applied to a torque (2D: a scalar), in the world frame of shape s.
  static Spin<N> inverse_inertia(const Body<N>& b, const Ellipsoid<double, N>& s, const Spin<N>& torque) {
    if constexpr (N == 2)
      return torque / b.inertia[0];
    else
      return s.axes() * (s.axes().transpose() * torque).cwiseQuotient(b.inertia);
  }

  static Spin<N> cross(const Vec<double, N>& r, const Vec<double, N>& n) {
    if constexpr (N == 2)
      return r.x() * n.y() - r.y() * n.x();
    else
      return r.cross(n);
  }
  static Vec<double, N> spin_cross(const Spin<N>& w, const Vec<double, N>& r) {
    if constexpr (N == 2)
      return Vec<double, 2>(-w * r.y(), w * r.x());
    else
      return w.cross(r);
  }

  // Velocity of the material point at r from the center.
  static Vec<double, N> point_velocity(const Body<N>& b, const Vec<double, N>& r) {
    return b.motion.velocity + spin_cross(b.motion.angular_velocity, r);
  }

  void advance(Body<N>& b, double t) {
    b.shape = body_at(b.shape, b.motion, t - b.time);
    b.time = t;
  }

  Ellipsoid<double, N> image_of(const Body<N>& b, const std::array<std::int32_t, N>& image) const {
    Vec<double, N> offset;
    for (int k = 0; k < N; ++k) offset[k] = image[k] * box_.size[k];
    return offset.isZero(0) ? b.shape : b.shape.translated(offset);
  }

  // Elastic collision: the impulse along the normal that reverses the normal velocity of
  // the contact points, with the bodies' masses and world inertia tensors.
  void collide(const Event<N>& e) {
    Body<N>& a = bodies_[e.i];
    Body<N>& b = bodies_[e.j];
    advance(a, now_);
    advance(b, now_);
    const Vec<double, N>& n = e.normal;
    const double approach = (point_velocity(b, e.r_j) - point_velocity(a, e.r_i)).dot(n);
    const Spin<N> ta = cross(e.r_i, n), tb = cross(e.r_j, n);
    const auto dot_spin = [](const Spin<N>& x, const Spin<N>& y) {
      if constexpr (N == 2)
        return x * y;
      else
        return x.dot(y);
    };
    const double effective = 1.0 / a.mass + 1.0 / b.mass + dot_spin(ta, inverse_inertia(a, a.shape, ta)) +
                             dot_spin(tb, inverse_inertia(b, b.shape, tb));
    const double j = approach < 0.0 ? -2.0 * approach / effective : 0.0;
    a.motion.velocity -= j / a.mass * n;
    b.motion.velocity += j / b.mass * n;
    a.motion.angular_velocity -= j * inverse_inertia(a, a.shape, ta);
    b.motion.angular_velocity += j * inverse_inertia(b, b.shape, tb);
    ++a.collisions;
    ++b.collisions;
    for (const std::uint32_t k : {e.i, e.j}) {
      schedule_rebuild(k);
      for (const auto& [other, image] : neighbors_[k])
        if (k == e.i || other != e.i) predict(k, other, image);  // the pair itself once
    }
  }

  // The next contact of i and j (j through its image), up to the earlier rebuild of the two.
  void predict(std::uint32_t i, std::uint32_t j, const std::array<std::int32_t, N>& image) {
    Body<N>& a = bodies_[i];
    Body<N>& b = bodies_[j];
    advance(a, now_);
    advance(b, now_);
    const double end = std::min(exit_[i], exit_[j]);
    const Ellipsoid<double, N> b_image = image_of(b, image);
    for (double start = now_; start < end;) {
      const auto sa = body_at(a.shape, a.motion, start - now_);
      const auto sb = body_at(b_image, b.motion, start - now_);
      const Contact<double, N> c = first_contact(sa, a.motion, sb, b.motion, end - start);
      if (c.status == ContactStatus::overlapping_at_start) ++overlaps_;
      if (c.status == ContactStatus::did_not_converge) ++stopped_;
      if (c.status != ContactStatus::hit && c.status != ContactStatus::touching_at_start) return;
      const Vec<double, N> ra = c.point - (sa.center() + c.time * a.motion.velocity);
      const Vec<double, N> rb = c.point - (sb.center() + c.time * b.motion.velocity);
      const double rate = (point_velocity(b, rb) - point_velocity(a, ra)).dot(c.normal);
      if (c.status == ContactStatus::hit || rate < 0.0) {
        queue_.push({start + c.time, i, j, image, a.collisions, b.collisions, ra, rb, c.normal});
        return;
      }
      // Touching and separating (the pair has just collided): look again once the gap has
      // cleared the tangency band.
      const double size = std::max(a.shape.radii().maxCoeff(), b.shape.radii().maxCoeff());
      start += std::max(1e-9 * size / rate, 1e-15 * std::abs(start));
    }
  }

  // Body i's rebuild event: when its center is skin / 2 from where it stood at the rebuild.
  void schedule_rebuild(std::uint32_t i) {
    const Body<N>& b = bodies_[i];
    const Vec<double, N> d = b.shape.center() + (now_ - b.time) * b.motion.velocity - anchor_[i];
    const Vec<double, N>& v = b.motion.velocity;
    const double vv = v.squaredNorm(), dv = d.dot(v), c = d.squaredNorm() - 0.25 * skin_ * skin_;
    exit_[i] = vv > 0.0 ? now_ + (-dv + std::sqrt(std::max(0.0, dv * dv - vv * c))) / vv
                        : std::numeric_limits<double>::infinity();
    if (std::isfinite(exit_[i])) queue_.push({exit_[i], i, i, {}, b.collisions, b.collisions, Vec<double, N>::Zero(), Vec<double, N>::Zero(),
                                            Vec<double, N>::Zero()});
  }

  // All bodies to time t, centers wrapped; neighbor lists of the balls of radius R + s / 2;
  // every listed pair predicted afresh.
  void rebuild(double t) {
    ++rebuilds_;
    queue_ = {};
    std::vector<Ellipsoid<double, N>> balls;
    for (auto& b : bodies_) {
      advance(b, t);
      b.shape = wrapped(b.shape);
      balls.push_back(make_ball<double, N>(b.shape.center(), b.shape.radii().maxCoeff() + 0.5 * skin_));
    }
    anchor_.resize(bodies_.size());
    exit_.resize(bodies_.size());
    for (std::uint32_t i = 0; i < bodies_.size(); ++i) {
      anchor_[i] = bodies_[i].shape.center();
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

  std::vector<Body<N>> bodies_;
  PeriodicBox<N> box_;
  double skin_ = 0.0, now_ = 0.0;
  std::size_t rebuilds_ = 0, overlaps_ = 0, stopped_ = 0;
  std::vector<Vec<double, N>> anchor_;  // centers at the last rebuild
  std::vector<double> exit_;            // each body's rebuild time
  std::vector<std::vector<std::pair<std::uint32_t, std::array<std::int32_t, N>>>> neighbors_;
  std::priority_queue<Event<N>, std::vector<Event<N>>, std::greater<>> queue_;
};

}  // namespace hard_bodies
