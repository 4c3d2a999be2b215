// Earliest contact and the periodic box (broad_phase.hpp): the answer equals the minimum of
// first_contact over every pair (and, in a periodic box, every image within two sides)
// by an all-pairs loop; periodic overlapping pairs equal the all-pairs, all-images loop;
// start statuses, stopped searches and bad input.
#include <ellipsect/broad_phase.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/distance.hpp>

#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace ellipsect {
namespace {
namespace ELLIPSECT_UNITY_ID {

template <class T, int N>
struct Scene {
  std::vector<Ellipsoid<T, N>> bodies;
  std::vector<RigidMotion<T, N>> motions;
};

// n bodies of radii in [0.1, 0.6] with centers in [0, side)^N whose bounding balls do not
// meet (nor their periodic images) unless !apart, speeds about 1, and spin (rate about `spin`) on every
// other body.
template <class T, int N>
Scene<T, N> random_scene(std::size_t n, unsigned seed, double side, double spin, bool apart = true) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(0.0, side), radius(0.1, 0.6), unit(-1.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Scene<T, N> s;
  for (std::size_t i = 0; i < n; ++i) {
    Vec<T, N> c, r;
    RigidMotion<T, N> m;
    for (int k = 0; k < N; ++k) {
      r[k] = T(radius(rng));
      m.velocity[k] = T(normal(rng));
    }
    for (bool clear = false; !clear;) {
      for (int k = 0; k < N; ++k) c[k] = T(coordinate(rng));
      clear = !apart || std::all_of(s.bodies.begin(), s.bodies.end(), [&](const Ellipsoid<T, N>& b) {
        Vec<double, N> d = (b.center() - c).template cast<double>();
        for (int k = 0; k < N; ++k) d[k] -= side * std::round(d[k] / side);
        return d.norm() > double(b.radii().maxCoeff() + r.maxCoeff());
      });
    }
    if constexpr (N == 2) {
      s.bodies.push_back(make_ellipse<T>(c, T(3.0 * unit(rng)), r));
      if (i % 2) m.angular_velocity = T(spin * normal(rng));
    } else {
      Eigen::Quaternion<T> q(T(unit(rng)), T(unit(rng)), T(unit(rng)), T(unit(rng)));
      if (q.norm() < T(0.1)) q = Eigen::Quaternion<T>::Identity();
      s.bodies.push_back(make_ellipsoid<T>(c, Quat<T>(q.normalized()), r));
      if (i % 2) m.angular_velocity = Vec<T, 3>(T(spin * normal(rng)), T(spin * normal(rng)), T(spin * normal(rng)));
    }
    s.motions.push_back(m);
  }
  return s;
}

template <int N>
std::vector<std::array<std::int32_t, N>> images(bool periodic) {
  std::vector<std::array<std::int32_t, N>> out{{}};
  if (!periodic) return out;
  out.clear();
  for (int code = 0; code < (N == 2 ? 25 : 125); ++code) {
    std::array<std::int32_t, N> m;
    for (int k = 0, c = code; k < N; ++k, c /= 5) m[k] = c % 5 - 2;
    out.push_back(m);
  }
  return out;
}

template <class T, int N>
Ellipsoid<T, N> moved(const Ellipsoid<T, N>& body, const std::type_identity_t<std::array<std::int32_t, N>>& image,
                      double side) {
  Vec<T, N> offset;
  for (int k = 0; k < N; ++k) offset[k] = T(image[k] * side);
  return offset.isZero(0) ? body : body.translated(offset);
}

// The all-pairs (all-images) minimum of first_contact, compared with earliest_contact.
// Returns whether the scene has a contact in the window.
template <class T, int N>
bool check_earliest(const Scene<T, N>& s, T t_max, const std::type_identity_t<PeriodicBox<N>>* box) {
  const double side = box ? box->size[0] : 0.0;
  T best = std::numeric_limits<T>::infinity();
  ImagePair<N> best_pair;
  for (std::uint32_t i = 0; i < s.bodies.size(); ++i)
    for (std::uint32_t j = i + 1; j < s.bodies.size(); ++j)
      for (const auto& m : images<N>(box != nullptr)) {
        const auto c = first_contact(s.bodies[i], s.motions[i], moved(s.bodies[j], m, side), s.motions[j], t_max);
        EXPECT_NE(c.status, ContactStatus::did_not_converge);
        EXPECT_NE(c.status, ContactStatus::overlapping_at_start);
        if (c.status == ContactStatus::hit && c.time < best) best = c.time, best_pair = {i, j, m};
      }
  const auto e = box ? earliest_contact<T, N>(s.bodies, s.motions, t_max, *box)
                     : earliest_contact<T, N>(s.bodies, s.motions, t_max);
  if (!std::isfinite(best)) {
    EXPECT_EQ(e.contact.status, ContactStatus::no_contact_in_window);
    return false;
  }
  EXPECT_EQ(e.contact.status, ContactStatus::hit);
  EXPECT_EQ(e.pair, best_pair);
  EXPECT_NEAR(e.contact.time, best, 1e-12 * double(best) * (std::is_same_v<T, float> ? 1e5 : 1.0));
  // The pair is in contact then (j through its image): within the accuracy of T.
  const auto a = body_at(s.bodies[e.pair.i], s.motions[e.pair.i], e.contact.time);
  const auto b = body_at(moved(s.bodies[e.pair.j], e.pair.image, side), s.motions[e.pair.j], e.contact.time);
  EXPECT_LE(double(distance(a, b).distance), (std::is_same_v<T, float> ? 1e-4 : 1e-9));
  return true;
}

TEST(EarliestContact, EqualsTheAllPairsMinimum) {
  int hits = 0;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    // Sparse scenes: the first contact is a few time units out, through the box's images.
    hits += check_earliest(random_scene<double, 2>(40, seed, 12.0, 0.0), 10.0, nullptr);
    hits += check_earliest(random_scene<double, 3>(40, seed, 6.0, 2.0), 10.0, nullptr);
    const PeriodicBox<2> box2{{12.0, 12.0}};
    const PeriodicBox<3> box3{{6.0, 6.0, 6.0}};
    auto s2 = random_scene<double, 2>(30, seed + 10, 12.0, 3.0);
    auto s3 = random_scene<double, 3>(30, seed + 10, 6.0, 3.0);
    hits += check_earliest(s2, 1.5, &box2);
    hits += check_earliest(s3, 1.5, &box3);
    hits += check_earliest(random_scene<float, 3>(30, seed + 20, 6.0, 1.0), 1.5f, &box3);
  }
  EXPECT_GE(hits, 12) << "scenes with a contact in the window, of 15";
}

TEST(EarliestContact, StartStatusesAndEmptyWindows) {
  using V = Vec<double, 2>;
  std::vector<Ellipse2<double>> bodies{make_ball<double, 2>(V(0, 0), 1.0), make_ball<double, 2>(V(2, 0), 1.0),
                                       make_ball<double, 2>(V(10, 0), 1.0), make_ball<double, 2>(V(11, 0), 1.0)};
  std::vector<RigidMotion<double, 2>> motions(4);
  auto e = earliest_contact<double, 2>(bodies, motions, 1.0);
  EXPECT_EQ(e.contact.status, ContactStatus::overlapping_at_start);
  EXPECT_EQ(e.pair, (ImagePair<2>{2, 3, {}}));
  bodies.resize(3);
  motions.resize(3);
  e = earliest_contact<double, 2>(bodies, motions, 1.0);
  EXPECT_EQ(e.contact.status, ContactStatus::touching_at_start);
  EXPECT_EQ(e.pair, (ImagePair<2>{0, 1, {}}));
  EXPECT_EQ(e.contact.time, 0.0);
  // Moving apart: no contact, ever.
  bodies[1] = make_ball<double, 2>(V(3, 0), 1.0);
  motions[1].velocity = V(1, 0);
  motions[2].velocity = V(1, 0);
  e = earliest_contact<double, 2>(bodies, motions, std::numeric_limits<double>::infinity());
  EXPECT_EQ(e.contact.status, ContactStatus::no_contact_in_window);
  EXPECT_TRUE(std::isnan(e.contact.time));
  // In a periodic box of side 20 the body at 10 moving right meets the one at 0 through
  // its image at -20 + ... : body 2 at 10 + t meets body 0's image; pair (0, 2), image of
  // body 2 is -1 (translated by -20, at -10 + t), touching body 0 when -10 + t = -2.
  const PeriodicBox<2> box{{20.0, 100.0}};
  e = earliest_contact<double, 2>(bodies, motions, 20.0, box);
  ASSERT_EQ(e.contact.status, ContactStatus::hit);
  EXPECT_EQ(e.pair, (ImagePair<2>{0, 2, {-1, 0}}));
  EXPECT_DOUBLE_EQ(e.contact.time, 8.0);
  EXPECT_NEAR(e.contact.point.x(), -1.0, 1e-12);
  // The window ends before that contact; an empty scene and one body have none.
  EXPECT_EQ((earliest_contact<double, 2>(bodies, motions, 7.9, box).contact.status),
            ContactStatus::no_contact_in_window);
  EXPECT_EQ((earliest_contact<double, 2>(std::span(bodies).first(1), std::span(motions).first(1), 5.0).contact.status),
            ContactStatus::no_contact_in_window);
  EXPECT_EQ((earliest_contact<double, 2>(bodies, motions, std::nan("")).contact.status),
            ContactStatus::invalid_input);
  EXPECT_EQ((earliest_contact<double, 2>(bodies, motions, -1.0).contact.status), ContactStatus::invalid_input);
}

// A search that stops gives did_not_converge and a lower bound on the true first contact.
TEST(EarliestContact, StoppedSearchGivesALowerBound) {
  auto s = random_scene<double, 3>(30, 5, 6.0, 20.0);
  Options few;
  few.max_motion_steps = 2;
  const auto exact = earliest_contact<double, 3>(s.bodies, s.motions, 10.0);
  ASSERT_EQ(exact.contact.status, ContactStatus::hit);
  const auto e = earliest_contact<double, 3>(s.bodies, s.motions, 10.0, few);
  ASSERT_EQ(e.contact.status, ContactStatus::did_not_converge);
  EXPECT_LE(e.contact.time, exact.contact.time);
  EXPECT_TRUE(std::isnan(e.contact.point.x()));
  // Too many slabs in a periodic box: the bound is the end of the last slab searched.
  const PeriodicBox<3> box{{6.0, 6.0, 6.0}};
  Options one;
  one.max_slabs = 1;
  std::vector<Ellipsoid3<double>> pair{make_ball<double, 3>(Vec3<double>(1, 1, 1), 0.1),
                                       make_ball<double, 3>(Vec3<double>(1, 4, 4), 0.1)};
  std::vector<RigidMotion<double, 3>> parallel(2);
  parallel[0].velocity = parallel[1].velocity = Vec3<double>(100, 0, 0);
  const auto p = earliest_contact<double, 3>(pair, parallel, 1.0, box, one);
  EXPECT_EQ(p.contact.status, ContactStatus::did_not_converge);
  EXPECT_GT(p.contact.time, 0.0);
  EXPECT_LT(p.contact.time, 1.0);
}

TEST(EarliestContact, BadInputIsNamed) {
  auto s = random_scene<double, 3>(4, 1, 6.0, 1.0);
  const PeriodicBox<3> box{{6.0, 6.0, 6.0}};
  s.motions[2].velocity.y() = std::numeric_limits<double>::infinity();
  testing::expect_field([&] { earliest_contact<double, 3>(s.bodies, s.motions, 1.0); }, "motions[2].velocity");
  s.motions[2].velocity.y() = 0.0;
  s.motions[3].angular_velocity.z() = std::nan("");
  testing::expect_field([&] { earliest_contact<double, 3>(s.bodies, s.motions, 1.0); }, "motions[3].angular_velocity");
  s.motions[3].angular_velocity.z() = 0.0;
  EXPECT_THROW((earliest_contact<double, 3>(s.bodies, std::span(s.motions).first(3), 1.0)), std::invalid_argument);
  testing::expect_field([&] { earliest_contact<double, 3>(s.bodies, s.motions, 1.0, PeriodicBox<3>{{6.0, 0.0, 6.0}}); },
                        "box.size");
  testing::expect_field([&] { earliest_contact<double, 3>(s.bodies, s.motions, 1.0, PeriodicBox<3>{{2.0, 6.0, 6.0}}); },
                        "box");
  testing::expect_field([&] { candidate_pairs<double, 3>(s.bodies, PeriodicBox<3>{{0.5, 0.5, 0.5}}); }, "box");
  s.bodies[0] = s.bodies[0].translated(Vec3<double>(1e12, 0, 0));
  testing::expect_field([&] { candidate_pairs<double, 3>(s.bodies, box); }, "bodies[0].center");
}

// Periodic overlapping pairs equal the loop over all pairs and images; centers outside the
// box are taken modulo it.
template <class T, int N>
void check_periodic_overlaps(unsigned seed) {
  const double side = N == 2 ? 7.0 : 4.0;
  PeriodicBox<N> box;
  box.size.fill(side);
  auto s = random_scene<T, N>(N == 2 ? 200 : 150, seed, side, 0.0, false);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> cell(-3, 3);
  for (auto& b : s.bodies) {
    std::array<std::int32_t, N> m;
    for (auto& x : m) x = cell(rng);
    b = moved(b, m, side);
  }
  std::vector<ImagePair<N>> all;
  for (std::uint32_t i = 0; i < s.bodies.size(); ++i)
    for (std::uint32_t j = i + 1; j < s.bodies.size(); ++j)
      for (int code = 0; code < (N == 2 ? 9 : 27); ++code) {
        // Around the image that brings j's center nearest to i's.
        std::array<std::int32_t, N> m;
        for (int k = 0, c = code; k < N; ++k, c /= 3)
          m[k] = std::int32_t(std::round(double(s.bodies[i].center()[k] - s.bodies[j].center()[k]) / side)) + c % 3 - 1;
        if (overlap(s.bodies[i], moved(s.bodies[j], m, side))) all.push_back({i, j, m});
      }
  std::sort(all.begin(), all.end());
  ASSERT_GT(all.size(), 10u);
  EXPECT_EQ((overlapping_pairs<T, N>(s.bodies, box)), all) << "seed " << seed;
  const auto candidates = candidate_pairs<T, N>(s.bodies, box);
  EXPECT_TRUE(std::includes(candidates.begin(), candidates.end(), all.begin(), all.end()));
}

TEST(PeriodicBox, OverlappingPairsEqualAllImagesLoop) {
  for (unsigned seed = 1; seed <= 2; ++seed) {
    check_periodic_overlaps<double, 2>(seed);
    check_periodic_overlaps<double, 3>(seed);
    check_periodic_overlaps<float, 3>(seed);
  }
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
}  // namespace ellipsect
