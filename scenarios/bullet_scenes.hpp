// Bullet scenes shared by tests/engines, bench/bench_bullet.cpp and examples/bullet_scenes.cpp: a
// dynamics world with ellipsect's algorithms registered (or Bullet's own), the pile and the
// rocking spheroid.
#pragma once

#include <ellipsect/bullet.hpp>

#include "scenarios/scenarios.hpp"

#include <Eigen/Geometry>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>
#include <random>
#include <utility>
#include <vector>

namespace ellipsect::scenarios {

inline btVector3 to_bt(const Vec3<double>& v) { return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2])); }

// The transform of a body with principal axes `axes` (columns) centered at `center`.
inline btTransform bullet_pose(const Mat3<double>& axes, const Vec3<double>& center) {
  btMatrix3x3 basis;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) basis[i][j] = btScalar(axes(i, j));
  return btTransform(basis, to_bt(center));
}

// A btDiscreteDynamicsWorld (sequential impulse solver, gravity -9.81 along z) owning its
// shapes and bodies, with ellipsect's algorithms registered on its dispatcher or not.
class BulletWorld {
public:
  explicit BulletWorld(bool ellipsect) {
    if (ellipsect) bullet::register_algorithms(dispatcher_);
    world_.setGravity(btVector3(0, 0, btScalar(-9.81)));
  }
  ~BulletWorld() {
    for (auto& b : bodies_) world_.removeRigidBody(b.get());
  }
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  // A rigid body of the shape at t; static where mass is 0.
  btRigidBody* add(std::unique_ptr<btCollisionShape> shape, const btTransform& t, double mass) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, shape.get(), inertia);
    info.m_startWorldTransform = t;
    bodies_.push_back(std::make_unique<btRigidBody>(info));
    world_.addRigidBody(bodies_.back().get());
    shapes_.push_back(std::move(shape));
    return bodies_.back().get();
  }
  // The static half-space normal . x <= constant.
  btRigidBody* add_plane(const Vec3<double>& normal, double constant) {
    return add(std::make_unique<btStaticPlaneShape>(to_bt(normal), btScalar(constant)), btTransform::getIdentity(), 0);
  }
  void run(double seconds, double dt) {
    const int steps = static_cast<int>(std::lround(seconds / dt));
    for (int i = 0; i < steps; ++i) world_.stepSimulation(btScalar(dt), 0, btScalar(dt));
  }
  // The contact points in the world's manifolds.
  int contacts() {
    int n = 0;
    for (int i = 0; i < dispatcher_.getNumManifolds(); ++i) n += dispatcher_.getManifoldByIndexInternal(i)->getNumContacts();
    return n;
  }
  btDiscreteDynamicsWorld& world() { return world_; }
  btCollisionDispatcher& dispatcher() { return dispatcher_; }

private:
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &config_};
};

// The pile's box: the floor z >= 0 and walls |x|, |y| <= 1, as (outward normal n, constant k)
// of the solid half-spaces n . x <= k.
inline const std::vector<std::pair<Vec3<double>, double>> pile_walls = {
    {Vec3<double>(0, 0, 1), 0}, {Vec3<double>(1, 0, 0), -1}, {Vec3<double>(-1, 0, 0), -1},
    {Vec3<double>(0, 1, 0), -1}, {Vec3<double>(0, -1, 0), -1}};

// The pile: the box's walls as static planes, and n ellipsoids of mass 1 (radii drawn from
// [0.15, 0.3] x [0.12, 0.25] x [0.1, 0.2], random orientations, seed 9) in 3 x 3 columns,
// 0.6 apart, layers 0.7 apart from z = 0.4, to be dropped. Returns the ellipsoids' bodies.
inline std::vector<btRigidBody*> add_pile(BulletWorld& world, int n) {
  for (const auto& [normal, constant] : pile_walls) world.add_plane(normal, constant);
  std::mt19937_64 rng(9);
  std::vector<btRigidBody*> bodies;
  for (int i = 0; i < n; ++i) {
    const Vec3<double> radii(detail::uniform(rng, 0.15, 0.3), detail::uniform(rng, 0.12, 0.25),
                             detail::uniform(rng, 0.1, 0.2));
    const Vec3<double> c(-0.6 + 0.6 * (i % 3), -0.6 + 0.6 * ((i / 3) % 3), 0.4 + 0.7 * (i / 9));
    bodies.push_back(world.add(std::make_unique<bullet::EllipsoidShape>(to_bt(radii)),
                               bullet_pose(detail::rotation<3>(rng), c), 1.0));
  }
  return bodies;
}

// A prolate spheroid (radii a, b, b; mass 1, friction 0.8, never deactivated) on the floor
// plane z >= 0, its long axis tilted down by `tilt` radians about y from the horizontal, its
// lowest point on the floor, at rest, to rock down. Returns its body; its support height along
// the floor's normal is sqrt(a^2 u_z^2 + b^2 (1 - u_z^2)), u its long axis.
inline btRigidBody* add_spheroid(BulletWorld& world, double a, double b, double tilt) {
  world.add_plane(Vec3<double>(0, 0, 1), 0);
  const Mat3<double> r = Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double uz = r(2, 0);
  btRigidBody* e = world.add(std::make_unique<bullet::EllipsoidShape>(btVector3(btScalar(a), btScalar(b), btScalar(b))),
                             bullet_pose(r, Vec3<double>(0, 0, std::sqrt(a * a * uz * uz + b * b * (1 - uz * uz)))), 1.0);
  e->setFriction(btScalar(0.8));
  e->setActivationState(DISABLE_DEACTIVATION);
  return e;
}

}  // namespace ellipsect::scenarios
