// The installed engine modules, where they were built: MuJoCo's table takes ellipsect's function
// and gives its own back; Bullet's exact shape gives the ellipsoid's box.
#include <cstdio>

#ifdef CONSUMER_MUJOCO
#include <ellipsect/mujoco.hpp>
#endif
#ifdef CONSUMER_BULLET
#include <ellipsect/bullet.hpp>
#endif

int main() {
  bool ok = true;
#ifdef CONSUMER_MUJOCO
  const mjfCollision own = mjCOLLISIONFUNC[mjGEOM_ELLIPSOID][mjGEOM_ELLIPSOID];
  ellipsect::mujoco::install();
  ok = ok && mjCOLLISIONFUNC[mjGEOM_ELLIPSOID][mjGEOM_ELLIPSOID] == &ellipsect::mujoco::collide;
  ellipsect::mujoco::uninstall();
  ok = ok && mjCOLLISIONFUNC[mjGEOM_ELLIPSOID][mjGEOM_ELLIPSOID] == own;
  std::printf("mujoco: %s\n", ok ? "ok" : "failed");
#endif
#ifdef CONSUMER_BULLET
  const ellipsect::bullet::EllipsoidShape shape(btVector3(3, 2, 1));
  btVector3 lo, hi;
  shape.getAabb(btTransform::getIdentity(), lo, hi);
  ok = ok && hi.x() >= 3 && hi.x() < 3.001 && lo.z() <= -1 && lo.z() > -1.001;
  std::printf("bullet: %s\n", ok ? "ok" : "failed");
#endif
  return ok ? 0 : 1;
}
