// Event-driven hard bodies (packing.hpp's HardBodies, started by examples/hard_bodies.hpp): after every collision the
// colliding pair touches and no pair of the box overlaps (classify through the periodic
// images), energy (without growth) and momentum are conserved to rounding, event times never
// decrease, and no prediction found an overlap or stopped; the same for growing bodies.
#include "examples/hard_bodies.hpp"

#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;

// classify of every pair whose boxes meet, through its image: none overlaps.
template <int N>
void expect_no_overlap(const HardBodies<N>& sim, long event) {
  const auto shapes = sim.shapes();
  for (const ImagePair<N>& p : overlapping_pairs<double, N>(shapes, sim.box())) {
    Vec<double, N> offset;
    for (int k = 0; k < N; ++k) offset[k] = p.image[k] * sim.box().size[k];
    const Relation r = classify(shapes[p.i], shapes[p.j].translated(offset), Options{1e-9});
    EXPECT_EQ(r, Relation::touching) << "pair " << p.i << ' ' << p.j << " after event " << event;
  }
}

// expansion > 0: the bodies grow (packing.hpp), which adds energy at each collision; the
// momentum is still conserved.
template <int N>
void run(int side, const Vec<double, N>& radii, double phi, long events, double expansion = 0.0) {
  HardBodies<N> sim = hard_bodies::lattice<N>(side, radii, phi, 3, expansion);
  const auto start = sim.totals();
  double last = 0.0;
  for (long k = 0; k < events; ++k) {
    const HardStep<N> step = sim.step();
    ASSERT_EQ(step.status, HardStatus::collided) << "event " << k;
    const HardEvent<N>& e = step.event;
    ASSERT_GE(e.time, last) << "event " << k;
    last = e.time;
    // The colliding pair touches, through the nearest image of j's center.
    const auto shapes = sim.shapes();
    Vec<double, N> offset;
    for (int d = 0; d < N; ++d) {
      const double L = sim.box().size[d];
      offset[d] = -std::round((shapes[e.j].center()[d] - shapes[e.i].center()[d]) / L) * L;
    }
    ASSERT_NE(e.i, e.j);
    EXPECT_EQ(classify(shapes[e.i], shapes[e.j].translated(offset), Options{1e-9}), Relation::touching)
        << "event " << k;
    if (k % (events / 20) == 0) expect_no_overlap(sim, k);
    const auto now = sim.totals();
    if (expansion == 0.0) {
      EXPECT_NEAR(now.energy / start.energy, 1.0, 1e-11) << "event " << k;
    } else {
      EXPECT_GE(now.energy, start.energy * (1 - 1e-11)) << "event " << k;
    }
  }
  const auto end = sim.totals();
  EXPECT_LT((end.momentum - start.momentum).norm(), 1e-12 * end.momentum_scale);
  EXPECT_EQ(sim.overlaps(), 0u);
  EXPECT_EQ(sim.stopped(), 0u);
  EXPECT_GT(sim.rebuilds(), 1u);
  expect_no_overlap(sim, events);
}

TEST(HardBodies, Ellipses) { run<2>(8, Vec<double, 2>(1.0, 0.5), 0.5, ellipsect::testing::cases(3000)); }

TEST(HardBodies, Ellipsoids) { run<3>(6, Vec<double, 3>(1.0, 0.6, 0.4), 0.3, ellipsect::testing::cases(3000)); }

// Growing from 0.5 (2D) and 0.3 (3D) at a rate that adds about 0.1 to the packing fraction
// over the run.
TEST(HardBodies, GrowingEllipses) {
  run<2>(8, Vec<double, 2>(1.0, 0.5), 0.5, ellipsect::testing::cases(3000), 0.02);
}
TEST(HardBodies, GrowingEllipsoids) {
  run<3>(6, Vec<double, 3>(1.0, 0.6, 0.4), 0.3, ellipsect::testing::cases(3000), 0.02);
}

// Bodies at rest that do not grow never meet: step() says so and leaves the system as it was.
TEST(HardBodies, NothingMovingIsNoEvent) {
  const std::vector<Ellipsoid<double, 2>> bodies = {make_ellipse<double>({1, 1}, 0.0, {0.5, 0.25}),
                                                    make_ellipse<double>({3, 3}, 0.5, {0.5, 0.25})};
  const std::vector<RigidMotion<double, 2>> rest(2);
  HardBodies<2> sim(bodies, rest, PeriodicBox<2>{{4.0, 4.0}});
  const HardStep<2> step = sim.step();
  EXPECT_EQ(step.status, HardStatus::no_event);
  EXPECT_EQ(to_string(step.status), "no_event");
  EXPECT_EQ(sim.collisions(), 0u);
  EXPECT_EQ(sim.now(), 0.0);
  EXPECT_EQ(sim.next_event(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(sim.shapes()[1].center(), bodies[1].center());
}

// Bad input names its argument.
TEST(HardBodies, BadInputIsNamed) {
  const std::vector<Ellipsoid<double, 2>> bodies = {make_ellipse<double>({1, 1}, 0.0, {0.5, 0.25}),
                                                    make_ellipse<double>({3, 3}, 0.5, {0.5, 0.25})};
  std::vector<RigidMotion<double, 2>> motions(2);
  const PeriodicBox<2> box{{4.0, 4.0}};
  expect_field([&] { HardBodies<2>(bodies, std::span(motions).first(1), box); }, "motions");
  expect_field([&] { HardBodies<2>(bodies, motions, PeriodicBox<2>{{4.0, -1.0}}); }, "box.size");
  expect_field([&] { HardBodies<2>(bodies, motions, box, 0.0); }, "skin");
  expect_field([&] { HardBodies<2>(bodies, motions, box, 0.5, -1.0); }, "expansion");
  motions[1].angular_velocity = std::nan("");
  expect_field([&] { HardBodies<2>(bodies, motions, box); }, "motions[1].angular_velocity");
  motions[1] = {};
  HardBodies<2> sim(bodies, motions, box);
  expect_field([&] { sim.rescale(0.0, 0.0); }, "factor");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
