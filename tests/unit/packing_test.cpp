// jam_packing (packing.hpp): small fast compressions jam at the published densities within
// the spread of fast compression, isostatic (disks and spheres: mean contact number 2d
// without rattlers), with no pair overlapping by exact classification (tolerance 0, rational
// arithmetic: a certificate independent of the floating-point predictions); input errors.
#include <ellipsect/broad_phase.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/packing.hpp>

#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cstdio>
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

TEST(Packing, BadInputIsNamed) {
  const std::vector<Vec<double, 2>> radii(10, Vec<double, 2>(1.0, 0.5));
  PackingOptions o;
  expect_field([&] { jam_packing<2>(std::span(radii).first(1), o); }, "radii");
  std::vector<Vec<double, 2>> bad = radii;
  bad[3][1] = -1;
  expect_field([&] { jam_packing<2>(bad, o); }, "radii[3]");
  o.initial_density = 0.7;
  expect_field([&] { jam_packing<2>(radii, o); }, "options.initial_density");
  o = {};
  o.schedule = {{0.0, 0.1}, {0.0, 0.01}};
  expect_field([&] { jam_packing<2>(radii, o); }, "options.schedule[1]");
  o = {};
  o.pressure = 0.5;
  expect_field([&] { jam_packing<2>(radii, o); }, "options.pressure");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
