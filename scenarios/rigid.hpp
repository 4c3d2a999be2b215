// Seeded pairs of bodies in rigid motion (constant linear and angular velocity), shared by
// the tests and the benchmarks: scenarios.hpp's translating cases with spin added, and
// cases built for rotation (tumbling needles and pancakes, a spinning needle's tip sweeping
// past a small body).
#pragma once

#include <ellipsect/contact.hpp>

#include "scenarios/scenarios.hpp"

#include <limits>
#include <sstream>
#include <string>

namespace ellipsect::scenarios {

enum class Spin { random, slow, fast, needles, brief, grazing, scaled_small, scaled_large };
constexpr std::array<Spin, 8> spins = {Spin::random,  Spin::slow,    Spin::fast,         Spin::needles,
                                       Spin::brief,   Spin::grazing, Spin::scaled_small, Spin::scaled_large};

inline const char* name(Spin s) {
  switch (s) {
    case Spin::random: return "random";
    case Spin::slow: return "slow_spin";
    case Spin::fast: return "fast_spin";
    case Spin::needles: return "needles_pancakes";
    case Spin::brief: return "brief";
    case Spin::grazing: return "grazing";
    case Spin::scaled_small: return "scaled_small";
    case Spin::scaled_large: return "scaled_large";
  }
  return "?";
}

template <int N>
struct Moving {
  Ellipsoid<double, N> a, b;
  RigidMotion<double, N> ma, mb;
  double t_max;
  double size;   // largest radii summed
  double speed;  // relative speed scale: |v_b - v_a| + spin * size
};

template <int N>
using Omega = decltype(RigidMotion<double, N>::angular_velocity);

template <int N>
Omega<N> spin_of(scenarios::detail::Rng& rng, double rate) {
  if constexpr (N == 2) {
    return scenarios::detail::uniform(rng, 0, 1) < 0.5 ? -rate : rate;
  } else {
    return scenarios::detail::unit_vector<3>(rng) * rate;
  }
}

template <int N>
double magnitude_of(const Omega<N>& w) {
  if constexpr (N == 2) {
    return std::abs(w);
  } else {
    return w.norm();
  }
}

template <int N>
Moving<N> make_moving(Spin kind, std::uint64_t seed) {
  namespace sd = scenarios::detail;
  sd::Rng rng(seed * 0x2545F4914F6CDD1Dull + static_cast<std::uint64_t>(kind));
  const scenarios::Category base = kind == Spin::scaled_small   ? scenarios::Category::scaled_small
                                   : kind == Spin::scaled_large ? scenarios::Category::scaled_large
                                   : kind == Spin::grazing      ? scenarios::Category::grazing
                                                                : scenarios::Category::random;
  scenarios::Case<N> c = scenarios::make_case<N>(base, seed);
  if (kind == Spin::needles) {  // thin bodies, roughly aimed at each other
    const double thin = 1e-3;
    auto shape = [&](double size) {
      Vec<double, N> r = Vec<double, N>::Constant(size * thin);
      r[0] = size;
      if (N == 3 && sd::uniform(rng, 0, 1) < 0.5) r[1] = size;  // a pancake
      return r;
    };
    const Vec<double, N> ra = shape(sd::log_uniform(rng, 0.5, 2)), rb = shape(sd::log_uniform(rng, 0.5, 2));
    const Vec<double, N> ca = sd::unit_vector<N>(rng);
    const double reach = ra.maxCoeff() + rb.maxCoeff();
    c.a = sd::body<N>(ca, sd::rotation<N>(rng), ra);
    c.b = sd::body<N>(ca + sd::unit_vector<N>(rng) * reach * sd::uniform(rng, 1.05, 3), sd::rotation<N>(rng), rb);
    sd::random_motion(rng, c);
  } else if (kind == Spin::brief) {  // a spinning needle; a small ball crossing near its reach
    const double length = sd::log_uniform(rng, 0.5, 2), r = length * sd::uniform(rng, 0.02, 0.1);
    Vec<double, N> ra = Vec<double, N>::Constant(length * 1e-2);
    ra[0] = length;
    c.a = sd::body<N>(Vec<double, N>::Zero(), sd::rotation<N>(rng), ra);
    const Vec<double, N> u = sd::unit_vector<N>(rng);
    const double reach = length + r * sd::uniform(rng, 0.2, 0.9);  // dips into the swept disc
    Vec<double, N> t = sd::unit_vector<N>(rng);
    t = (t - t.dot(u) * u).normalized();
    const double pass = sd::uniform(rng, 5, 50) * length;  // crossing speed
    c.b = sd::body<N>(u * reach - t * pass * 0.5, sd::rotation<N>(rng), Vec<double, N>::Constant(r));
    c.va.setZero();
    c.vb = t * pass;
    c.t_max = 1.0;
  }
  Moving<N> m{c.a, c.b, {c.va}, {c.vb}, c.t_max, 0, 0};
  m.size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
  const double v = (c.vb - c.va).norm();
  // Rates relative to the pair's own time scale size / v.
  const double base_rate = v > 0 ? v / m.size : 1.0;
  double rate_a = 0, rate_b = 0;
  switch (kind) {
    case Spin::slow: rate_a = base_rate * 1e-3; rate_b = base_rate * sd::uniform(rng, 0, 1e-3); break;
    case Spin::fast: {
      // Several turns before the bodies can meet: the time to close the gap, in turns.
      const double gap_time = std::max((c.b.center() - c.a.center()).norm() - m.size, 0.1 * m.size) / std::max(v, 1e-300);
      rate_a = 2 * M_PI * sd::uniform(rng, 3, 10) / gap_time;
      rate_b = rate_a * sd::uniform(rng, 0, 1);
      break;
    }
    case Spin::brief: rate_a = sd::uniform(rng, 5, 30); break;
    default: rate_a = base_rate * sd::log_uniform(rng, 0.05, 3); rate_b = base_rate * sd::log_uniform(rng, 0.05, 3); break;
  }
  m.ma.angular_velocity = spin_of<N>(rng, rate_a);
  m.mb.angular_velocity = spin_of<N>(rng, rate_b);
  if constexpr (N == 3) {
    if (kind == Spin::brief) {  // the needle turns in a plane through the ball's path
      const Vec<double, 3> u = m.b.center().normalized(), k = u.cross(m.mb.velocity).normalized();
      const Vec<double, 3> long_axis = Eigen::AngleAxisd(sd::uniform(rng, -M_PI, M_PI), k) * u;
      Mat<double, 3> axes;
      axes << long_axis, k, long_axis.cross(k);
      m.a = sd::body<3>(m.a.center(), axes, m.a.radii());
      m.ma.angular_velocity = k * rate_a * (sd::uniform(rng, 0, 1) < 0.5 ? -1 : 1);
    }
  }
  m.speed = v + rate_a * c.a.radii().maxCoeff() + rate_b * c.b.radii().maxCoeff();
  return m;
}

// make_moving's pair with its bodies growing (RigidMotion::growth): rates from 0.05 to 2 times
// the pair's own rate speed / size, one body at rest in size in a third of the cases. `still`:
// the centers at rest (the spins kept), so that growth alone closes the gap, at rates that
// bring the bodies together at about t = 0.1 to 10 (an unbounded window).
template <int N>
Moving<N> make_growing(Spin kind, std::uint64_t seed, bool still) {
  namespace sd = scenarios::detail;
  Moving<N> m = make_moving<N>(kind, seed);
  sd::Rng rng(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(kind) + (still ? 101 : 0));
  double base = m.speed / m.size;
  if (still) {
    m.ma.velocity.setZero();
    m.mb.velocity.setZero();
    m.t_max = std::numeric_limits<double>::infinity();
    const double gap = std::max((m.b.center() - m.a.center()).norm() - m.size, 1e-3 * m.size);
    base = gap / m.size;
  }
  const double lo = still ? 0.1 : 0.05, hi = still ? 10 : 2;
  m.ma.growth = base * sd::log_uniform(rng, lo, hi);
  m.mb.growth = base * sd::log_uniform(rng, lo, hi);
  const double one = sd::uniform(rng, 0, 1);
  if (one < 1.0 / 6) m.ma.growth = 0;
  else if (one < 1.0 / 3) m.mb.growth = 0;
  const double v = (m.mb.velocity - m.ma.velocity).norm();
  m.speed = v + magnitude_of<N>(m.ma.angular_velocity) * m.a.radii().maxCoeff() +
            magnitude_of<N>(m.mb.angular_velocity) * m.b.radii().maxCoeff() + m.ma.growth * m.a.radii().maxCoeff() +
            m.mb.growth * m.b.radii().maxCoeff();
  return m;
}

template <int N>
std::string describe_moving(Spin kind, std::uint64_t seed, const Moving<N>& m) {
  std::ostringstream s;
  s.precision(17);
  s << "N=" << N << " " << name(kind) << " seed=" << seed << "\n  a: c=" << m.a.center().transpose()
    << " r=" << m.a.radii().transpose() << "\n  b: c=" << m.b.center().transpose() << " r=" << m.b.radii().transpose()
    << "\n  axes a=" << m.a.axes().reshaped().transpose() << "\n  axes b=" << m.b.axes().reshaped().transpose()
    << "\n  va=" << m.ma.velocity.transpose() << " vb=" << m.mb.velocity.transpose() << " t_max=" << m.t_max
    << "\n  wa=" << Vec<double, N == 2 ? 1 : 3>(m.ma.angular_velocity).transpose()
    << " wb=" << Vec<double, N == 2 ? 1 : 3>(m.mb.angular_velocity).transpose() << "\n  ga=" << m.ma.growth
    << " gb=" << m.mb.growth;
  return s.str();
}

}  // namespace ellipsect::scenarios
