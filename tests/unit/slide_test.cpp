// collide_and_slide (slide.hpp): sliding on a floor, stopping in a 2D corner, along a 3D
// crease and in a 3D corner, the start states, and on random worlds: the body never ends
// inside a half-space, never moves farther than asked, and ends touching what stopped it.
#include <ellipsect/slide.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using V2 = Vec2<double>;
using V3 = Vec3<double>;

template <int N>
using World = std::vector<HalfSpace<double, N>>;

TEST(CollideAndSlide, SlidesAlongAFloor) {
  const auto ball = make_ball<double, 3>(V3(0, 0, 2), 1);
  const World<3> floor{make_half_space<double, 3>(V3(0, 0, 0), V3(0, 0, 1))};
  // Down by 3 and along x by 4: 1 down to the floor (a third of the way, x += 4/3), then the
  // rest along x.
  const auto s = collide_and_slide(ball, V3(4, 0, -3), std::span(floor));
  EXPECT_EQ(s.status, SlideStatus::slid);
  EXPECT_EQ(s.contacts, 1);
  EXPECT_EQ(s.last_contact, 0);
  EXPECT_NEAR(s.body.center()[0], 4, 1e-14);
  EXPECT_NEAR(s.body.center()[2], 1, 1e-14);
  EXPECT_EQ(classify(s.body, floor[0]), Relation::touching);
  EXPECT_NEAR((s.moved - V3(4, 0, -1)).norm(), 0, 1e-14);
  // Nothing in the way: the whole displacement.
  const auto free = collide_and_slide(ball, V3(1, 2, 0.5), std::span(floor));
  EXPECT_EQ(free.status, SlideStatus::moved);
  EXPECT_EQ(free.body.center(), V3(1, 2, 2.5));
  EXPECT_EQ(free.contacts, 0);
  EXPECT_EQ(free.last_contact, -1);
  // Starting on the floor and moving along it, or up and away: no contact.
  const auto resting = make_ball<double, 3>(V3(0, 0, 1), 1);
  EXPECT_EQ(collide_and_slide(resting, V3(3, 0, 0), std::span(floor)).status, SlideStatus::moved);
  EXPECT_EQ(collide_and_slide(resting, V3(0, 0, 1), std::span(floor)).body.center(), V3(0, 0, 2));
  // Pressed straight down while resting: it stays.
  const auto pressed = collide_and_slide(resting, V3(0, 0, -5), std::span(floor));
  EXPECT_EQ(pressed.body.center(), V3(0, 0, 1));
  EXPECT_EQ(pressed.status, SlideStatus::slid);
}

TEST(CollideAndSlide, StopsInACornerIn2D) {
  // The quadrant x >= 0, y >= 0 is free; an ellipse with radii 2 and 1 (unrotated).
  const World<2> walls{make_half_space<double, 2>(V2(0, 0), V2(1, 0)), make_half_space<double, 2>(V2(0, 0), V2(0, 1))};
  const auto e = make_ellipse<double>(V2(5, 5), 0, V2(2, 1));
  const auto s = collide_and_slide(e, V2(-10, -6), std::span(walls));
  EXPECT_EQ(s.status, SlideStatus::slid);
  EXPECT_EQ(s.contacts, 2);
  EXPECT_NEAR(s.body.center()[0], 2, 1e-14);
  EXPECT_NEAR(s.body.center()[1], 1, 1e-14);
  for (const auto& w : walls) EXPECT_EQ(classify(s.body, w), Relation::touching);
}

TEST(CollideAndSlide, FollowsACreaseAndStopsInACornerIn3D) {
  // Floor z >= 0 and wall x >= 0 (free side); a crease along y.
  const World<3> crease{make_half_space<double, 3>(V3(0, 0, 0), V3(0, 0, 1)),
                        make_half_space<double, 3>(V3(0, 0, 0), V3(1, 0, 0))};
  const auto ball = make_ball<double, 3>(V3(3, 0, 3), 1);
  const auto s = collide_and_slide(ball, V3(-4, 5, -4), std::span(crease));
  EXPECT_EQ(s.status, SlideStatus::slid);
  EXPECT_NEAR(s.body.center()[0], 1, 1e-14);
  EXPECT_NEAR(s.body.center()[1], 5, 1e-14);
  EXPECT_NEAR(s.body.center()[2], 1, 1e-14);
  // A third wall y <= 3: the corner.
  World<3> corner = crease;
  corner.push_back(make_half_space<double, 3>(V3(0, 3, 0), V3(0, -1, 0)));
  const auto c = collide_and_slide(ball, V3(-4, 5, -4), std::span(corner));
  EXPECT_EQ(c.status, SlideStatus::slid);
  EXPECT_NEAR((c.body.center() - V3(1, 2, 1)).norm(), 0, 1e-14);
  for (const auto& w : corner) EXPECT_EQ(classify(c.body, w), Relation::touching);
}

TEST(CollideAndSlide, StartStatesAndBadInput) {
  const World<3> floor{make_half_space<double, 3>(V3(0, 0, 0), V3(0, 0, 1))};
  const auto sunk = make_ball<double, 3>(V3(0, 0, 0.5), 1);
  const auto s = collide_and_slide(sunk, V3(1, 0, 0), std::span(floor));
  EXPECT_EQ(s.status, SlideStatus::overlapping_at_start);
  EXPECT_EQ(s.body.center(), sunk.center());
  const auto ball = make_ball<double, 3>(V3(0, 0, 2), 1);
  EXPECT_EQ(collide_and_slide(ball, V3(std::nan(""), 0, 0), std::span(floor)).status, SlideStatus::invalid_input);
  EXPECT_EQ(collide_and_slide(make_ball<double, 3>(V3(1e308, 0, 2), 1), V3(1e308, 0, 0), std::span(floor)).status,
            SlideStatus::invalid_input);
  // No world: the whole displacement.
  EXPECT_EQ(collide_and_slide(ball, V3(1, 1, 1), std::span<const HalfSpace<double, 3>>()).status, SlideStatus::moved);
  // A round cap of 1: stopped at the floor with displacement left.
  Options one;
  one.max_slide_rounds = 1;
  EXPECT_EQ(collide_and_slide(ball, V3(4, 0, -3), std::span(floor), one).status, SlideStatus::blocked);
}

// Random boxes of walls around a body, random long displacements: never inside, never
// farther than asked, and when stopped, touching.
template <int N>
void random_worlds() {
  scenarios::detail::Rng rng(11);
  using namespace scenarios::detail;
  std::map<std::string, int> tally;
  for (int i = 0; i < ellipsect::testing::cases(300); ++i) {
    const auto body = Ellipsoid<double, N>::from_axes(Vec<double, N>::Zero(), rotation<N>(rng), radii<N>(rng, 1.0, 20));
    World<N> world;
    for (int k = 0; k < 2 * N + 2; ++k) {
      const Vec<double, N> n = unit_vector<N>(rng);
      // A plane the body is above: its point beyond the body's support along -n.
      const double rho = (body.radii().asDiagonal() * body.axes().transpose() * n).norm();
      world.push_back(make_half_space<double, N>(Vec<double, N>(-n * (rho + uniform(rng, 0, 3))), n));
    }
    const Vec<double, N> d = unit_vector<N>(rng) * log_uniform(rng, 0.1, 100);
    const auto s = collide_and_slide(body, d, std::span(world));
    tally[std::string(to_string(s.status))]++;
    tally["contacts " + std::to_string(std::min(s.contacts, 3))]++;
    ASSERT_NE(s.status, SlideStatus::invalid_input);
    ASSERT_NE(s.status, SlideStatus::overlapping_at_start);
    for (const auto& h : world) {
      const Relation r = classify(s.body, h);
      ASSERT_TRUE(r == Relation::separated || r == Relation::touching) << "case " << i;
    }
    ASSERT_LE(s.moved.norm(), d.norm() * (1 + 1e-12)) << "case " << i;
    ASSERT_LE((s.body.center() - s.moved).norm(), 1e-12 * (1 + d.norm())) << "case " << i;
    if (s.status == SlideStatus::slid) {
      ASSERT_GE(s.last_contact, 0);
      bool touching = false;
      for (const auto& h : world) touching |= classify(s.body, h, Options{1e-9}) == Relation::touching;
      ASSERT_TRUE(touching) << "case " << i;
    }
  }
  std::printf("%dD:", N);
  for (const auto& [outcome, count] : tally) std::printf(" %s=%d", outcome.c_str(), count);
  std::printf("\n");
  if (!ellipsect::testing::full_case_counts()) return;
  EXPECT_GT(tally["moved"], 0);
  EXPECT_GT(tally["slid"], 0);
  EXPECT_GT(tally["contacts 2"] + tally["contacts 3"], 0);
}

TEST(CollideAndSlide, RandomWorlds2D) { random_worlds<2>(); }
TEST(CollideAndSlide, RandomWorlds3D) { random_worlds<3>(); }

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
