// first_contact under rigid motion against the 50-digit reference (tests/reference/
// rigid_contact_reference.hpp: certified sampling with a direction-free speed bound on the
// Perram-Wertheim scale and the support gap along the PW normal, then bracketing and
// bisection on the sign of mu - 1).
//
// Claims under test (contact.hpp):
//   the time is never later than the reference's first contact (every category, grazing
//   included), and a contact the reference finds in the window is never reported missing;
//   hit, approach not grazing (sine of the angle between the relative velocity of the
//   contact points and the contact plane >= 1e-3): time within 1e-12 relative or
//   1e-12 * scale / speed, point within 1e-10 * scale, normal within 1e-9 rad;
//   no contact in the window where the reference finds none;
// on: random pairs with moderate spin, slow spin, fast spin (several turns before contact),
// tumbling needles and pancakes (aspect 1e3), bodies that touch only briefly (a spinning
// needle's tip sweeping past a small body crossing its reach), grazing paths, and random
// pairs at scale 1e-6 and 1e6.
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>

#include "common.hpp"
#include "tests/reference/rigid_contact_reference.hpp"

#include <cmath>

namespace {

using namespace ellipsect;
using namespace ellipsect::testing;
using Real = ref::Real;

enum class Spin { random, slow, fast, needles, brief, grazing, scaled_small, scaled_large };
constexpr std::array<Spin, 8> spins = {Spin::random,  Spin::slow,    Spin::fast,         Spin::needles,
                                       Spin::brief,   Spin::grazing, Spin::scaled_small, Spin::scaled_large};

const char* name(Spin s) {
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
double rate_of(const Omega<N>& w) {
  if constexpr (N == 2) return std::abs(w);
  else return w.norm();
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
  Moving<N> m{c.a, c.b, {c.va, {}}, {c.vb, {}}, c.t_max, 0, 0};
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

template <int N>
std::string describe(Spin kind, std::uint64_t seed, const Moving<N>& m) {
  std::ostringstream s;
  s.precision(17);
  s << "N=" << N << " " << name(kind) << " seed=" << seed << "\n  a: c=" << m.a.center().transpose()
    << " r=" << m.a.radii().transpose() << "\n  b: c=" << m.b.center().transpose() << " r=" << m.b.radii().transpose()
    << "\n  axes a=" << m.a.axes().reshaped().transpose() << "\n  axes b=" << m.b.axes().reshaped().transpose()
    << "\n  va=" << m.ma.velocity.transpose() << " vb=" << m.mb.velocity.transpose() << " t_max=" << m.t_max
    << "\n  wa=" << Vec<double, N == 2 ? 1 : 3>(m.ma.angular_velocity).transpose()
    << " wb=" << Vec<double, N == 2 ? 1 : 3>(m.mb.angular_velocity).transpose();
  return s.str();
}

template <int N>
ref::RigidMotionRef<N> to_ref(const RigidMotion<double, N>& m) {
  return {m.velocity, m.angular_velocity};
}

template <int N>
void check_against_reference(int count_per_kind) {
  Tally tally;
  double worst_time = 0, worst_point = 0, worst_normal = 0;
  int unresolved = 0, compared = 0;
  for (Spin kind : spins) {
    const int count = kind == Spin::scaled_small || kind == Spin::scaled_large ? count_per_kind / 2 : count_per_kind;
    for (int i = 0; i < count; ++i) {
      const std::uint64_t seed = 7000 + static_cast<std::uint64_t>(i);
      const Moving<N> m = make_moving<N>(kind, seed);
      SCOPED_TRACE(describe<N>(kind, seed, m));
      const Contact<double, N> got = first_contact(m.a, m.ma, m.b, m.mb, m.t_max);
      const ref::RigidContact<N> want =
          ref::rigid_first_contact<N>(reference::to_ref<N>(m.a), to_ref<N>(m.ma), reference::to_ref<N>(m.b),
                                      to_ref<N>(m.mb), m.t_max, 1e-30, 6000);
      if (!want.resolved) {
        ++unresolved;
        tally.add(name(kind), "unresolved");
        continue;
      }
      tally.add(name(kind), std::string(to_string(got.status)));
      ASSERT_NE(got.status, ContactStatus::invalid_input);
      ASSERT_NE(got.status, ContactStatus::did_not_converge);
      const double time_scale = m.size / m.speed;
      if (want.kind == ref::ContactKind::overlapping_at_start || want.kind == ref::ContactKind::touching_at_start) {
        EXPECT_TRUE(got.status == ContactStatus::overlapping_at_start || got.status == ContactStatus::touching_at_start);
        continue;
      }
      if (want.kind == ref::ContactKind::none) {
        // A path passing within the tangency band may be reported as a touch.
        if (kind != Spin::grazing) EXPECT_EQ(got.status, ContactStatus::no_contact_in_window);
        continue;
      }
      const double t_ref = ref::to_double(want.time);
      // Never later than the first contact, never missing it.
      ASSERT_EQ(got.status, ContactStatus::hit) << "reference hit at " << t_ref;
      EXPECT_LE(got.time, t_ref + 1e-13 * std::max(t_ref, time_scale));
      if (kind == Spin::grazing || want.approach_sine < Real(1e-3)) continue;
      ++compared;
      const double time_error = std::abs(got.time - t_ref) / std::max(t_ref, time_scale);
      const double point_error = (got.point - ref::to_double<N>(want.point)).norm() / m.size;
      const double normal_error = (got.normal - ref::to_double<N>(want.normal)).norm();
      worst_time = std::max(worst_time, time_error);
      worst_point = std::max(worst_point, point_error);
      worst_normal = std::max(worst_normal, normal_error);
      EXPECT_LE(time_error, 1e-12) << "time " << got.time << " vs " << t_ref;
      EXPECT_LE(point_error, 1e-10);
      EXPECT_LE(normal_error, 1e-9);
    }
  }
  tally.print("rigid first_contact, N=" + std::to_string(N) + " (status per category)");
  std::printf("  compared %d hits; largest errors: time %.2g (relative), point %.2g (of scale), normal %.2g rad; "
              "%d reference cases unresolved\n",
              compared, worst_time, worst_point, worst_normal, unresolved);
  // The reference's sampling is slow where thin bodies slide along each other; those pairs
  // are left out (and counted), a tenth of the cases at most.
  EXPECT_LE(unresolved, count_per_kind * int(spins.size()) / 10);
}

TEST(RigidContactProperty, AgreesWithReference2D) { check_against_reference<2>(cases(30)); }
TEST(RigidContactProperty, AgreesWithReference3D) { check_against_reference<3>(cases(30)); }

}  // namespace
