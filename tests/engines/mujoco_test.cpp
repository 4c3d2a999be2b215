// The MuJoCo integration (modules/mujoco, ellipsect/mujoco.hpp) through MuJoCo's own call
// path: models loaded from MJCF, poses set through qpos, contacts found by mj_collision, bodies
// moved by mj_step.
//
// Claims under test:
//   install() and uninstall() change exactly the ellipsoid's entries of mjCOLLISIONFUNC and
//   restore MuJoCo's;
//   every contact MuJoCo's solver receives for an ellipsoid against an ellipsoid or sphere
//   (all scenario categories), a plane, a capsule or a box has dist within 1e-12 of the size of
//   the 50-digit reference's signed distance of the geoms MuJoCo holds (tests/reference: the
//   support gap searched over directions, a route of its own), a normal from geom1 to geom2
//   along the reference's and pos halfway between the reference's witness points where they are
//   unique; a contact exactly when that distance is at most the margin;
//   at rest on a plane or a box face an ellipsoid sinks by the penetration MuJoCo's soft contact
//   gives a sphere of the same mass (MuJoCo's exact sphere functions), to 1e-9 of its size; a
//   rocking spheroid's centre stays at its support height less that penetration; a pile of
//   ellipsoids in a box settles with no pair deeper than the solver's soft penetration;
//   geoms with sizes ellipsect refuses reach mju_error naming the geom and the field.
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/mujoco.hpp>

#include "scenarios/mujoco_scenes.hpp"
#include "scenarios/scenarios.hpp"
#include "tests/property/common.hpp"
#include "tests/reference/distance_reference.hpp"
#include "tests/reference/half_space_reference.hpp"
#include "tests/reference/support_gap_reference.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using namespace ellipsect::testing;
using Vec3d = Vec3<double>;
using Mat3d = Mat3<double>;

// A scene (scenarios/mujoco_scenes.hpp) with the accessors the tests read.
struct Sim : scenarios::MujocoScene {
  explicit Sim(const std::string& xml) : MujocoScene(xml, ::testing::TempDir() + "ellipsect_mujoco_test.xml") {}
  Vec3d xpos(int g) const { return Eigen::Map<const Vec3d>(d->geom_xpos + 3 * g); }
  Mat3d xmat(int g) const { return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->geom_xmat + 9 * g); }
  Vec3d size(int g) const { return Eigen::Map<const Vec3d>(m->geom_size + 3 * g); }
  // The reference's body for an ellipsoid or sphere geom, as MuJoCo holds it.
  reference::Body<3> ref_body(int g) const {
    const Vec3d s = size(g);
    const Vec3d r = m->geom_type[g] == mjGEOM_SPHERE ? Vec3d::Constant(s[0]) : s;
    return {xpos(g), xmat(g), r};
  }
  // Sets a free body's pose (its joint's qpos).
  void set_pose(int b, const Vec3d& p, const Mat3d& r) {
    const int q = m->jnt_qposadr[m->body_jntadr[b]];
    const Eigen::Quaterniond quat(r);
    for (int i = 0; i < 3; ++i) d->qpos[q + i] = p[i];
    d->qpos[q + 3] = quat.w(), d->qpos[q + 4] = quat.x(), d->qpos[q + 5] = quat.y(), d->qpos[q + 6] = quat.z();
  }
  // Sets a world geom's pose and size, and its bounding radius.
  void set_static(int g, const Vec3d& p, const Mat3d& r, const Vec3d& s, double rbound) {
    const Eigen::Quaterniond quat(r);
    for (int i = 0; i < 3; ++i) m->geom_pos[3 * g + i] = p[i], m->geom_size[3 * g + i] = s[i];
    m->geom_quat[4 * g] = quat.w(), m->geom_quat[4 * g + 1] = quat.x(), m->geom_quat[4 * g + 2] = quat.y(),
                 m->geom_quat[4 * g + 3] = quat.z();
    m->geom_sameframe[g] = 0;
    m->geom_rbound[g] = rbound;
  }
  void set_size(int g, const Vec3d& s) {
    for (int i = 0; i < 3; ++i) m->geom_size[3 * g + i] = s[i];
    m->geom_rbound[g] = s.maxCoeff();
  }
  // The contacts between geoms g1 and g2 after mj_collision.
  std::vector<mjContact> contacts(int g1, int g2) const {
    std::vector<mjContact> out;
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& c = d->contact[i];
      if ((c.geom1 == g1 && c.geom2 == g2) || (c.geom1 == g2 && c.geom2 == g1)) out.push_back(c);
    }
    return out;
  }
  void collide() {
    mj_kinematics(m.get(), d.get());
    mj_collision(m.get(), d.get());
  }
};

// install() for the scope of a test, uninstall() after it, whatever happens.
struct Installed {
  Installed() { mujoco::install(); }
  ~Installed() { mujoco::uninstall(); }
  Installed(const Installed&) = delete;
  Installed& operator=(const Installed&) = delete;
};

TEST(MujocoInstall, ReplacesTheEllipsoidEntriesAndRestoresMuJoCos) {
  ASSERT_FALSE(mujoco::installed());
  std::array<std::array<mjfCollision, mjNGEOMTYPES>, mjNGEOMTYPES> before{};
  for (int i = 0; i < mjNGEOMTYPES; ++i)
    for (int j = 0; j < mjNGEOMTYPES; ++j) before[i][j] = mjCOLLISIONFUNC[i][j];
  mujoco::install();
  mujoco::install();  // a second call changes nothing
  ASSERT_TRUE(mujoco::installed());
  const std::array<int, 5> ours = {mjGEOM_ELLIPSOID, mjGEOM_SPHERE, mjGEOM_PLANE, mjGEOM_CAPSULE, mjGEOM_BOX};
  for (int i = 0; i < mjNGEOMTYPES; ++i)
    for (int j = 0; j < mjNGEOMTYPES; ++j) {
      const bool replaced = (i == mjGEOM_ELLIPSOID && std::find(ours.begin(), ours.end(), j) != ours.end()) ||
                            (j == mjGEOM_ELLIPSOID && std::find(ours.begin(), ours.end(), i) != ours.end());
      EXPECT_EQ(mjCOLLISIONFUNC[i][j], replaced ? &mujoco::collide : before[i][j]) << i << " " << j;
    }
  mujoco::uninstall();
  mujoco::uninstall();
  ASSERT_FALSE(mujoco::installed());
  for (int i = 0; i < mjNGEOMTYPES; ++i)
    for (int j = 0; j < mjNGEOMTYPES; ++j) EXPECT_EQ(mjCOLLISIONFUNC[i][j], before[i][j]) << i << " " << j;
}

// Checks one contact against the reference's signed distance `want` (normal and witness
// points where given: want_normal from geom1 towards geom2).
void expect_contact(const std::vector<mjContact>& got, double want, double margin, double scale,
                    const reference::RVec<3>* want_normal, const reference::RVec<3>* want_mid, const std::string& what) {
  const double tol = 1e-12 * scale;
  if (want > margin + tol) {
    EXPECT_TRUE(got.empty()) << what << " dist " << got[0].dist << " want " << want;
    return;
  }
  if (want < margin - tol) {
    ASSERT_EQ(got.size(), 1u) << what << " want " << want;
  }
  if (got.empty()) return;
  ASSERT_EQ(got.size(), 1u) << what;
  const mjContact& c = got[0];
  EXPECT_NEAR(c.dist, want, tol) << what;
  const Vec3d n(c.frame[0], c.frame[1], c.frame[2]);
  EXPECT_NEAR(n.norm(), 1.0, 1e-14) << what;
  // mj_collision completed the frame: orthonormal rows, the first the normal.
  const Mat3d frame = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(c.frame);
  EXPECT_LE((frame * frame.transpose() - Mat3d::Identity()).cwiseAbs().maxCoeff(), 1e-12) << what;
  if (want_normal != nullptr) {
    EXPECT_LE(reference::to_double((want_normal->cast<reference::Real>() - n.cast<reference::Real>()).norm()), 1e-7)
        << what;
  }
  if (want_mid != nullptr) {
    const Vec3d pos(c.pos[0], c.pos[1], c.pos[2]);
    EXPECT_LE(reference::to_double((*want_mid - pos.cast<reference::Real>()).norm()), 1e-9 * scale) << what;
  }
}

// Ellipsoid pairs of every category, through mj_collision: ellipsect's contacts against the
// reference, at margin 0 and at a margin beyond the pair's distance; MuJoCo's own (libccd's
// MPR) at margin 0 beside them, its misses and errors counted and printed.
TEST(MujocoCollide, EllipsoidPairsOfEveryCategoryMatchTheReference) {
  Sim sim(R"(<mujoco><option gravity="0 0 0"/><worldbody>
      <body name="a"><freejoint/><geom name="a" type="ellipsoid" size="1 1 1"/></body>
      <body name="b"><freejoint/><geom name="b" type="ellipsoid" size="1 1 1"/></body>
      </worldbody></mujoco>)");
  const int ga = sim.geom("a"), gb = sim.geom("b");
  Tally theirs;
  for (const auto category : scenarios::all_categories) {
    for (int seed = 0; seed < cases(40); ++seed) {
      const auto c = scenarios::make_case<3>(category, static_cast<std::uint64_t>(seed));
      sim.set_size(ga, c.a.radii());
      sim.set_size(gb, c.b.radii());
      sim.set_pose(sim.body("a"), c.a.center(), c.a.axes());
      sim.set_pose(sim.body("b"), c.b.center(), c.b.axes());
      sim.m->geom_margin[ga] = sim.m->geom_margin[gb] = 0;
      mj_kinematics(sim.m.get(), sim.d.get());
      const auto r = reference::signed_distance<3>(sim.ref_body(ga), sim.ref_body(gb));
      const double want = reference::to_double(r.distance);
      const double scale = c.a.radii().maxCoeff() + c.b.radii().maxCoeff() + std::abs(want);
      const bool unique = reference::to_double(r.distance - r.runner_up) > 1e-6 * scale;
      const reference::RVec<3> mid = (r.point_a + r.point_b) / 2;
      const std::string what = describe(c);
      for (const double margin : {0.0, 2 * std::abs(want)}) {
        sim.m->geom_margin[ga] = sim.m->geom_margin[gb] = margin;
        {
          Installed on;
          sim.collide();
        }
        expect_contact(sim.contacts(ga, gb), want, margin, scale, unique ? &r.normal : nullptr, unique ? &mid : nullptr,
                       what + " margin " + std::to_string(margin));
      }
      // MuJoCo's own at margin 0.
      sim.m->geom_margin[ga] = sim.m->geom_margin[gb] = 0;
      sim.collide();
      const auto own = sim.contacts(ga, gb);
      const char* outcome = want < -1e-12 * scale ? (own.empty()                                          ? "missed"
                                                     : std::abs(own[0].dist - want) > 1e-6 * scale ? "depth_off_1e-6"
                                                                                                    : "right")
                                                  : (own.empty() ? "right" : "false_contact");
      theirs.add(scenarios::name(category), outcome);
    }
  }
  theirs.print("MuJoCo's own ellipsoid-ellipsoid (libccd MPR), margin 0, against the reference:");
}

// The ellipsoid against a sphere, capsule, box and plane placed from each category's second
// body (center, axes, radii): the sphere of its first radius, the capsule along its third axis
// (half-length the third radius, radius the first), the box of half-sizes its radii, the plane
// through its center normal to its third axis. References: the sphere as a body; the plane's
// closed form (half_space_reference); the box's corners and the capsule's segment by the support
// gap (the capsule's signed distance is its segment's less its radius).
TEST(MujocoCollide, EllipsoidAgainstSphereCapsuleBoxAndPlaneMatchesTheReference) {
  Sim sim(R"(<mujoco><option gravity="0 0 0"/><worldbody>
      <geom name="sphere" type="sphere" size="1"/>
      <geom name="capsule" type="capsule" size="1 1"/>
      <geom name="box" type="box" size="1 1 1"/>
      <geom name="plane" type="plane" size="0 0 1"/>
      <body name="e"><freejoint/><geom name="e" type="ellipsoid" size="1 1 1"/></body>
      </worldbody></mujoco>)");
  const int ge = sim.geom("e");
  const std::array<const char*, 4> shapes = {"sphere", "capsule", "box", "plane"};
  for (const auto category : scenarios::all_categories) {
    // The polytope reference searches the sphere per vertex: a few cases per category.
    for (int seed = 0; seed < std::max(2, cases(40) / 8); ++seed) {
      const auto c = scenarios::make_case<3>(category, static_cast<std::uint64_t>(seed));
      const Vec3d rb = c.b.radii();
      const Vec3d center = c.b.center();
      const Mat3d axes = c.b.axes();
      for (const char* shape : shapes) {
        const int g = sim.geom(shape);
        const std::string name = shape;
        Vec3d s = rb;
        double rbound = rb.norm();
        if (name == "sphere") s = Vec3d(rb[0], 0, 0), rbound = rb[0];
        if (name == "capsule") s = Vec3d(rb[0], rb[2], 0), rbound = rb[0] + rb[2];
        if (name == "plane") s = Vec3d(0, 0, 1), rbound = 0;
        // Every other static geom far away, out of the test.
        for (const char* other : shapes) {
          sim.m->geom_margin[sim.geom(other)] = 0;
          if (other != shape)
            sim.set_static(sim.geom(other), Vec3d::Constant(1e12), Mat3d::Identity(), Vec3d::Constant(1), 1);
        }
        sim.set_static(g, center, axes, s, rbound);
        sim.set_size(ge, c.a.radii());
        sim.set_pose(sim.body("e"), c.a.center(), c.a.axes());
        sim.m->geom_margin[ge] = sim.m->geom_margin[g] = 0;
        mj_kinematics(sim.m.get(), sim.d.get());
        const auto body = sim.ref_body(ge);
        const Vec3d p = sim.xpos(g);
        const Mat3d r = sim.xmat(g);
        double want = 0;
        if (name == "sphere") {
          want = reference::to_double(reference::signed_distance<3>(sim.ref_body(g), body).distance);
        } else if (name == "plane") {
          want = reference::to_double(reference::half_space_gaps<3>(body, p, r.col(2)).lower);
        } else if (name == "box") {
          std::vector<reference::DVec<3>> corners;
          for (int k = 0; k < 8; ++k)
            corners.push_back(p + r * Vec3d((k & 1 ? 1 : -1) * s[0], (k & 2 ? 1 : -1) * s[1], (k & 4 ? 1 : -1) * s[2]));
          want = reference::to_double(reference::max_support_gap<3>(body, corners).gap);
        } else {
          const std::vector<reference::DVec<3>> ends = {p - s[1] * r.col(2), p + s[1] * r.col(2)};
          want = reference::to_double(reference::max_support_gap<3>(body, ends).gap) - s[0];
        }
        const double scale = c.a.radii().maxCoeff() + rb.maxCoeff() + std::abs(want);
        for (const double margin : {0.0, 2 * std::abs(want)}) {
          sim.m->geom_margin[ge] = sim.m->geom_margin[g] = margin;
          Installed on;
          sim.collide();
          const auto got = sim.contacts(ge, g);
          expect_contact(got, want, margin, scale, nullptr, nullptr, name + " " + describe(c));
          // The normal runs from geom1 (the lower type: the plane, sphere or capsule; the
          // ellipsoid before the box) to geom2: pushing geom2 along it by -dist makes them touch.
          if (got.size() == 1) {
            const Vec3d n(got[0].frame[0], got[0].frame[1], got[0].frame[2]);
            const Vec3d to_second = got[0].geom2 == ge ? Vec3d(sim.xpos(ge) - p) : Vec3d(p - sim.xpos(ge));
            if (name == "plane") {
              EXPECT_LE((n - r.col(2)).norm(), 1e-12) << describe(c);
            } else if (to_second.norm() > 1e-6 * scale && want > 0) {
              EXPECT_GT(n.dot(to_second), 0) << name << " " << describe(c);
            }
          }
        }
      }
    }
  }
}

// A scene in which one ellipsoid and one sphere of the same mass rest on `floor` (a plane or
// a static box's top face at height 0), far apart; the ellipsoid on its radius c.
std::string resting_scene(const std::string& floor, double c, double tilt) {
  char xml[2000];
  std::snprintf(xml, sizeof xml, R"(<mujoco><option timestep="0.002"/><worldbody>
      %s
      <body name="e" pos="0 0 %.17g" euler="%.17g 0 0"><freejoint/>
        <geom name="e" type="ellipsoid" size="0.3 0.2 %.17g" mass="1"/></body>
      <body name="s" pos="3 0 %.17g"><freejoint/><geom name="s" type="sphere" size="%.17g" mass="1"/></body>
      </worldbody></mujoco>)",
                floor.c_str(), c, tilt, c, c, c);
  return xml;
}

// The height of a body's centre after `seconds` of simulation.
double settle(Sim& sim, const char* body, double seconds) {
  sim.step(static_cast<int>(seconds / sim.m->opt.timestep));
  return sim.d->xpos[3 * sim.body(body) + 2];
}

TEST(MujocoSimulation, AnEllipsoidAtRestSinksAsASphereOfItsMass) {
  Installed on;
  for (const std::string floor : {R"(<geom name="floor" type="plane" size="0 0 1"/>)",
                                  R"(<geom name="floor" type="box" pos="0 0 -0.5" size="5 5 0.5"/>)"}) {
    const double c = 0.1;
    Sim sim(resting_scene(floor, c, 0));
    mujoco::reset_counters();
    const double ze = settle(sim, "e", 2.0), zs = settle(sim, "s", 0.0);
    const double sink = c - zs;  // MuJoCo's soft contact: the sphere's (exact) penetration at rest
    EXPECT_GT(sink, 0) << floor;
    EXPECT_LT(sink, 0.05 * c) << floor;
    EXPECT_NEAR(ze, c - sink, 1e-9 * 0.3) << floor;
    // It stays upright: its third axis vertical.
    const Mat3d r = sim.xmat(sim.geom("e"));
    EXPECT_NEAR(r(2, 2), 1.0, 1e-9) << floor;
    const auto k = mujoco::counters();
    EXPECT_GT(k.contacts, 0u);
    EXPECT_EQ(k.not_converged, 0u);
  }
}

// A prolate spheroid (radii 0.1, 0.1, 0.3) let go at 40 degrees on a plane rocks down and rolls
// over. MuJoCo's own plane-ellipsoid function is exact too (the support point along the plane's
// normal), so the two runs agree step for step to the rounding that the rocking amplifies; the
// centre is never above the exact support height h = sqrt(a^2 (1 - u_z^2) + c^2 u_z^2) (u the
// long axis), and below it by the soft contact's penetration alone (up to 13% of a while it
// rolls over at speed, with MuJoCo's default solref).
TEST(MujocoSimulation, ARockingSpheroidFollowsMuJoCosExactPlaneContact) {
  const double a = 0.1, c = 0.3;
  Sim ours(scenarios::spheroid_mjcf(a, c, 0.7)), theirs(scenarios::spheroid_mjcf(a, c, 0.7));
  const int g = ours.geom("spheroid");
  double apart = 0, above = -1, below = 0;
  for (int i = 0; i < 2000; ++i) {
    {
      Installed on;
      ours.step(1);
    }
    theirs.step(1);
    apart = std::max({apart, (ours.xpos(g) - theirs.xpos(g)).norm(), (ours.xmat(g) - theirs.xmat(g)).norm()});
    const Vec3d u = ours.xmat(g).col(2);
    const double h = std::sqrt(a * a * (1 - u[2] * u[2]) + c * c * u[2] * u[2]);
    above = std::max(above, ours.xpos(g)[2] - h);
    below = std::max(below, h - ours.xpos(g)[2]);
  }
  std::printf("spheroid: runs apart by %.3g, centre above its support height by %.3g, below by %.3g\n", apart, above,
              below);
  EXPECT_LE(apart, 1e-9);
  EXPECT_LE(above, 1e-4 * a);  // a rebound of the soft contact at the start, in both runs
  EXPECT_LE(below, 0.2 * a);
  EXPECT_GT(below, 0);
}

// 100 ellipsoids (radii 0.1, 0.075, 0.05) poured into a box of four static walls on a plane:
// after 1.5 s every pair, and every body against the floor and walls, is no deeper than a fifth
// of the smallest radius (the soft contact's penetration under the pile's weight), by
// ellipsect's signed distance of the final poses; MuJoCo's own functions, on the same scene,
// printed beside it.
TEST(MujocoSimulation, APileOfEllipsoidsSettlesWithoutDeepOverlaps) {
  const std::string xml = scenarios::pile_mjcf(5, 4);
  auto ellipsoids = [](const Sim& sim) {
    std::vector<int> out;
    for (int g = 0; g < sim.m->ngeom; ++g)
      if (sim.m->geom_type[g] == mjGEOM_ELLIPSOID) out.push_back(g);
    return out;
  };
  auto deepest = [&](Sim& sim) {
    std::vector<Ellipsoid3<double>> e;
    for (const int g : ellipsoids(sim)) e.push_back(make_ellipsoid(sim.xpos(g), sim.xmat(g), sim.size(g)));
    const int n = static_cast<int>(e.size());
    double depth = 0;
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) depth = std::max(depth, -signed_distance(e[i], e[j]).distance);
      depth = std::max(depth, -signed_distance(e[i], make_half_space<double, 3>(Vec3d::Zero(), Vec3d::UnitZ())).distance);
      for (const char* w : {"w0", "w1", "w2", "w3"}) {
        const int g = sim.geom(w);
        depth = std::max(depth, -signed_distance(e[i], make_box(sim.xpos(g), sim.xmat(g), sim.size(g))).distance);
      }
    }
    return depth;
  };
  double ours = 0, theirs = 0;
  {
    Installed on;
    Sim sim(xml);
    sim.step(750);
    ours = deepest(sim);
    ASSERT_EQ(ellipsoids(sim).size(), 100u);
    for (const int g : ellipsoids(sim)) {  // all inside the walls, above the floor
      EXPECT_LT(sim.xpos(g).head<2>().cwiseAbs().maxCoeff(), scenarios::pile_half_width) << g;
      EXPECT_GT(sim.xpos(g)[2], 0.0) << g;
    }
  }
  {
    Sim sim(xml);
    sim.step(750);
    theirs = deepest(sim);
  }
  std::printf("pile of 100: deepest overlap %.3g (ellipsect), %.3g (MuJoCo's own functions)\n", ours, theirs);
  EXPECT_LE(ours, 0.2 * 0.05);
}

std::string last_error;
void record_error(const char* message) { last_error = message; }

TEST(MujocoCollide, SizesEllipsectRefusesReachMjuErrorNamingTheGeomAndField) {
  Sim sim(R"(<mujoco><worldbody>
      <body name="a"><freejoint/><geom name="first" type="ellipsoid" size="1 1 1"/></body>
      <body name="b" pos="0.5 0 0"><freejoint/><geom name="second" type="ellipsoid" size="1 1 1"/></body>
      </worldbody></mujoco>)");
  mj_kinematics(sim.m.get(), sim.d.get());
  const int g1 = sim.geom("first"), g2 = sim.geom("second");
  void (*previous)(const char*) = mju_user_error;
  mju_user_error = record_error;
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    sim.m->geom_size[3 * g2 + 1] = bad;
    last_error.clear();
    mjContact con{};
    EXPECT_EQ(mujoco::collide(sim.m.get(), sim.d.get(), &con, g1, g2, 0), 0);
    EXPECT_NE(last_error.find("'second'"), std::string::npos) << last_error;
    EXPECT_NE(last_error.find("radii[1]"), std::string::npos) << last_error;
  }
  mju_user_error = previous;
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
