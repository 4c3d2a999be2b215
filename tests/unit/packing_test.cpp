// jam_packing (packing.hpp): small fast compressions jam at the published densities within
// the spread of fast compression, isostatic (disks and spheres: mean contact number 2d
// without rattlers), with no pair overlapping by exact classification (tolerance 0, rational
// arithmetic: a certificate independent of the floating-point predictions); input errors.
#include <ellipsect/broad_phase.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/packing.hpp>

#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;

// No pair of the final packing overlaps: exact classification of every candidate pair
// through its image; returns the number of pairs checked.
template <int N>
std::size_t expect_no_overlap(const Packing<N>& p) {
  const auto pairs = candidate_pairs<double, N>(p.bodies, p.box);
  for (const ImagePair<N>& q : pairs) {
    Vec<double, N> offset;
    for (int k = 0; k < N; ++k) offset[k] = q.image[k] * p.box.size[k];
    const Relation r = classify(p.bodies[q.i], p.bodies[q.j].translated(offset), ellipsect::testing::exact_options);
    EXPECT_TRUE(r == Relation::separated || r == Relation::touching) << q.i << ' ' << q.j << ": " << to_string(r);
  }
  return pairs.size();
}

template <int N>
void expect_sound(const Packing<N>& p) {
  std::printf("  %zu bodies: density %.4f at pressure %.3g, %.3f contacts per body without %zu rattlers\n",
              p.bodies.size(), p.density, p.pressure, p.mean_contacts_without_rattlers, p.rattlers);
  EXPECT_EQ(p.status, PackingStatus::jammed);
  EXPECT_EQ(p.overlapping, 0u);
  EXPECT_EQ(p.predictions_overlapping, 0u);
  EXPECT_EQ(p.predictions_stopped, 0u);
  EXPECT_GT(expect_no_overlap(p), p.bodies.size());
  for (std::size_t k = 1; k < p.history.size(); ++k) EXPECT_GT(p.history[k][0], p.history[k - 1][0]);
}

// Bidisperse disks (radii 1 and 1.4, 50:50): random close packing at 0.842 (O'Hern, Silbert,
// Liu and Nagel, Phys. Rev. E 68, 011306 (2003)); fast growth jams a little lower.
// Fast growth to reduced pressure 100, then ten times slower: the contact network settles
// into an isostatic one (with the rate 0.1 throughout, 200 disks have 3.3 contacts per body
// within 1e-4 at pressure 1e6, and no rigid backbone once rattlers are removed).
TEST(Packing, BidisperseDisksJamIsostatic) {
  std::vector<Vec<double, 2>> radii;
  for (int i = 0; i < 200; ++i) radii.push_back(Vec<double, 2>::Constant(i % 2 ? 1.4 : 1.0));
  PackingOptions o;
  o.schedule = {{0.0, 0.1}, {1e2, 0.01}};
  o.pressure = 1e4;
  o.contact_gap = 2e-3;  // within the default 1e-2 (100 / pressure), near neighbors add about 0.2
  const Packing<2> p = jam_packing<2>(radii, o);
  expect_sound(p);
  EXPECT_GT(p.density, 0.83);
  EXPECT_LT(p.density, 0.85);
  EXPECT_NEAR(p.mean_contacts_without_rattlers, 4.0, 0.1);
}

// Spheres: maximally random jammed at about 0.64 (Torquato, Truskett and Debenedetti, Phys.
// Rev. Lett. 84, 2064 (2000)); 100 spheres at this growth jam a little lower.
TEST(Packing, SpheresJamIsostatic) {
  const std::vector<Vec<double, 3>> radii(100, Vec<double, 3>::Constant(1.0));
  PackingOptions o;
  o.schedule = {{0.0, 0.1}, {1e3, 0.01}};  // fast enough that 100 spheres do not crystallize
  o.pressure = 1e4;
  o.contact_gap = 3e-3;  // within 1e-2, the near neighbors of a random packing add 0.6
  const Packing<3> p = jam_packing<3>(radii, o);
  expect_sound(p);
  EXPECT_GT(p.density, 0.60);
  EXPECT_LT(p.density, 0.65);
  EXPECT_NEAR(p.mean_contacts_without_rattlers, 6.0, 0.25);
}

// The contacts are every pair, through every image, whose Perram-Wertheim scale factor mu is
// within the gap of 1: found here among all pairs and all 3^N images, not the broad phase's
// candidates. (They were the candidates of the bodies' own boxes, which miss a near-contact
// lined up with a box axis: its boxes are apart by up to the gap.) A wide gap makes such
// pairs common.
template <int N>
void expect_contacts_complete(const Packing<N>& p, double gap) {
  std::vector<ImagePair<N>> expected;
  const std::size_t n = p.bodies.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (int code = 0; code < (N == 2 ? 9 : 27); ++code) {
        ImagePair<N> q{std::uint32_t(i), std::uint32_t(j), {}};
        Vec<double, N> offset;
        for (int k = 0, c = code; k < N; ++k, c /= 3) {
          q.image[k] = c % 3 - 1;
          offset[k] = q.image[k] * p.box.size[k];
        }
        const Ellipsoid<double, N> b = p.bodies[j].translated(offset);
        if ((b.center() - p.bodies[i].center()).norm() >
            (1 + gap) * (p.bodies[i].radii().maxCoeff() + b.radii().maxCoeff()))
          continue;
        if (std::sqrt(perram_wertheim(p.bodies[i], b).f) - 1.0 < gap) expected.push_back(q);
      }
  std::vector<ImagePair<N>> got = p.contacts;
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, expected);
  EXPECT_DOUBLE_EQ(p.mean_contacts, 2.0 * double(expected.size()) / double(n));
}

TEST(Packing, ContactsAreEveryPairWithinTheGap) {
  std::vector<Vec<double, 2>> disks;
  for (int i = 0; i < 60; ++i) disks.push_back(Vec<double, 2>::Constant(i % 2 ? 1.4 : 1.0));
  PackingOptions o;
  o.schedule = {{0.0, 0.1}};
  o.pressure = 1e3;
  o.contact_gap = 0.05;
  expect_contacts_complete(jam_packing<2>(disks, o), o.contact_gap);
  const std::vector<Vec<double, 3>> spheroids(80, Vec<double, 3>(1.25, 1.0, 0.8));
  o.pressure = 1e2;
  expect_contacts_complete(jam_packing<3>(spheroids, o), o.contact_gap);
}

// The collision cap is a status: the packing stops short of jamming, not overlapping, its
// count at the cap.
TEST(Packing, CollisionCapIsAStatus) {
  const std::vector<Vec<double, 2>> radii(20, Vec<double, 2>(1.0, 0.5));
  PackingOptions o;
  o.max_collisions = 50;
  const Packing<2> p = jam_packing<2>(radii, o);
  EXPECT_EQ(p.status, PackingStatus::collision_limit);
  EXPECT_GE(p.collisions, 50u);
  EXPECT_LT(p.pressure, o.pressure);
  EXPECT_EQ(p.overlapping, 0u);
  EXPECT_EQ(to_string(p.status), "collision_limit");
}

// Bad radii name themselves where jam_packing is called; bad options where they are set, as
// Options' fields do.
TEST(Packing, BadInputIsNamed) {
  const std::vector<Vec<double, 2>> radii(10, Vec<double, 2>(1.0, 0.5));
  PackingOptions o;
  expect_field([&] { jam_packing<2>(std::span(radii).first(1), o); }, "radii");
  std::vector<Vec<double, 2>> bad = radii;
  bad[3][1] = -1;
  expect_field([&] { jam_packing<2>(bad, o); }, "radii[3]");
  for (const double density : {0.0, 0.5, 0.7, std::nan("")})
    expect_field([&] { o.initial_density = density; }, "initial_density");
  expect_field([&] { o.schedule = {{0.0, 0.1}, {0.0, 0.01}}; }, "schedule[1]");
  expect_field([&] { o.schedule = {{0.0, -0.1}}; }, "schedule[0]");
  expect_field([&] { o.schedule = GrowthSchedule(std::vector<GrowthStage>{}); }, "schedule");
  for (const double pressure : {0.5, 1.0, std::numeric_limits<double>::infinity()})
    expect_field([&] { o.pressure = pressure; }, "pressure");
  expect_field([&] { o.contact_gap = -1e-3; }, "contact_gap");
  for (const double skin : {-0.1, 0.0, std::nan("")}) expect_field([&] { o.skin = skin; }, "skin");
  expect_field([&] { o.max_collisions = 0; }, "max_collisions");
  expect_field([&] { o.collisions_per_update = 0; }, "collisions_per_update");
  expect_field([&] { (void)PackingOptions{.pressure = 0.9}; }, "pressure");
  // The options kept their defaults through the rejected assignments.
  EXPECT_EQ(double(o.initial_density), 0.2);
  EXPECT_EQ(o.schedule.stages().size(), 1u);
  EXPECT_EQ(double(o.pressure), 1e6);
  EXPECT_EQ(std::uint64_t(o.max_collisions), 1'000'000'000u);
  // The message states the range and the value.
  try {
    o.initial_density = 0.7;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("must be finite and in (0, 0.5) (got 0.7)"), std::string::npos) << e.what();
  }
}

// A start denser than random placement reaches is a status, not an exception: no bodies.
// (Random sequential placement of spheres jams at 0.38, Talbot et al., Colloids Surf. A 165
// (2000) 287, short of 0.45.)
TEST(Packing, NoRoomForTheStartIsAStatus) {
  const std::vector<Vec<double, 3>> spheres(60, Vec<double, 3>::Constant(1.0));
  PackingOptions o;
  o.initial_density = 0.45;
  const Packing<3> p = jam_packing<3>(spheres, o);
  EXPECT_EQ(p.status, PackingStatus::no_start);
  EXPECT_EQ(to_string(p.status), "no_start");
  EXPECT_TRUE(p.bodies.empty());
  EXPECT_EQ(p.collisions, 0u);
}

// Compression run in slices of any size is jam_packing: the same collisions, bodies and
// history bit for bit, since an update comes after the same collision however the run is cut;
// it is `compressing` until the end and advances no further after it.
template <int N>
void expect_same_packing(const Packing<N>& a, const Packing<N>& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.collisions, b.collisions);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.density, b.density);
  EXPECT_EQ(a.pressure, b.pressure);
  EXPECT_EQ(a.history, b.history);
  EXPECT_EQ(a.contacts, b.contacts);
  EXPECT_EQ(a.rattlers, b.rattlers);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].center(), b.bodies[i].center()) << i;
    EXPECT_EQ(a.bodies[i].radii(), b.bodies[i].radii()) << i;
  }
}

TEST(Packing, CompressionInSlicesIsJamPacking) {
  const std::vector<Vec<double, 2>> ellipses(40, Vec<double, 2>(1.0, 0.6));
  PackingOptions o;
  o.schedule = {{0.0, 0.2}, {1e2, 0.04}};
  o.pressure = 1e3;
  const Packing<2> whole = jam_packing<2>(ellipses, o);
  ASSERT_EQ(whole.status, PackingStatus::jammed);
  for (const std::uint64_t slice : {1u, 7u, 800u}) {
    Compression<2> c(ellipses, o);
    std::size_t updates = 0;
    while (c.status() == PackingStatus::compressing) {
      EXPECT_EQ(to_string(c.status()), "compressing");
      const std::uint64_t before = c.system().collisions();
      c.advance(slice);
      EXPECT_LE(c.system().collisions() - before, slice);
      EXPECT_GE(c.history().size(), updates);
      updates = c.history().size();
      EXPECT_EQ(c.density_at(c.system().now()) > 0.0, true);
    }
    expect_same_packing(c.packing(), whole);
    const std::uint64_t end = c.system().collisions();
    c.advance(100);
    EXPECT_EQ(c.system().collisions(), end);
  }
  // A cap inside a slice ends it there.
  o.max_collisions = 300;
  Compression<2> capped(ellipses, o);
  capped.advance(1'000'000);
  EXPECT_EQ(capped.status(), PackingStatus::collision_limit);
  EXPECT_EQ(capped.system().collisions(), 300u);
  expect_same_packing(capped.packing(), jam_packing<2>(ellipses, o));
}

// From the caller's start: the bodies' own box and volume; bodies at rest are refused, and a
// compression with no start has no system.
TEST(Packing, CompressionFromAGivenStart) {
  PeriodicBox<3> box;
  box.size = {16.0, 16.0, 16.0};  // jammed, each body's bounding box is about a third of its side
  std::vector<Ellipsoid<double, 3>> bodies;
  std::vector<RigidMotion<double, 3>> motions;
  for (int i = 0; i < 64; ++i) {
    const Vec<double, 3> c(2.0 + 4.0 * (i % 4), 2.0 + 4.0 * (i / 4 % 4), 2.0 + 4.0 * (i / 16));
    bodies.push_back(Ellipsoid<double, 3>::from_axes(c, Mat<double, 3>::Identity(), Vec<double, 3>(1.0, 0.8, 0.6)));
    RigidMotion<double, 3> m;
    m.velocity = Vec<double, 3>(std::sin(1.0 + i), std::cos(2.0 * i), std::sin(3.0 * i));
    motions.push_back(m);
  }
  PackingOptions o;
  o.schedule = {{0.0, 0.3}};
  o.pressure = 3e2;
  Compression<3> c(bodies, motions, box, o);
  EXPECT_NEAR(c.density_at(0.0), 64 * 4.0 / 3.0 * std::numbers::pi * 0.48 / 4096.0, 1e-15);
  EXPECT_NEAR(c.system().temperature(), 1.0, 1e-12);
  while (c.status() == PackingStatus::compressing) c.advance(500);
  const Packing<3> p = c.packing();
  EXPECT_EQ(p.status, PackingStatus::jammed);
  EXPECT_EQ(p.box.size, box.size);
  EXPECT_EQ(p.overlapping, 0u);
  expect_no_overlap(p);
  const std::vector<RigidMotion<double, 3>> still(bodies.size());
  expect_field([&] { Compression<3>(bodies, still, box, o); }, "motions");
  const std::vector<Vec<double, 3>> spheres(60, Vec<double, 3>::Constant(1.0));
  PackingOptions dense;
  dense.initial_density = 0.45;
  Compression<3> none(spheres, dense);
  EXPECT_EQ(none.status(), PackingStatus::no_start);
  EXPECT_THROW((void)none.system(), std::logic_error);
  none.advance(10);
  EXPECT_TRUE(none.packing().bodies.empty());
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
