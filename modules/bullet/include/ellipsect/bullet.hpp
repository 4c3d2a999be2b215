// ellipsect as Bullet's (3.24) ellipsoid narrow phase: an exact ellipsoid collision shape and
// collision algorithms for it against ellipsoids, spheres, boxes, capsules, static planes and
// concave triangle shapes (docs/engines.md).
//
// Precision. Everything here is written on btScalar and compiles for both of Bullet's builds:
// float (libBulletCollision, the target ellipsect::bullet) and double (-DBT_USE_DOUBLE_PRECISION,
// libBulletCollision-float64, the target ellipsect::bullet_float64). The header must be
// compiled with the same BT_USE_DOUBLE_PRECISION setting as the library it links (the targets
// carry it). Whatever btScalar is, the queries run in double: poses, radii and the other
// shapes' dimensions are widened exactly, and the results are rounded to btScalar once.
//
// Contacts. The algorithms put into the pair's btPersistentManifold one contact per convex
// pair (the exact closest points or deepest-penetration witnesses of ellipsect's signed
// distance, distance.hpp, box.hpp, capsule.hpp, half_space.hpp) wherever the signed distance is
// below the manifold's contact breaking threshold plus the result's closest-point threshold, as
// Bullet's own convex algorithms do (their solver then takes a positive one as a speculative
// contact); pairs whose bounding balls are farther apart than that get no query. A concave
// shape gives one contact per triangle so near (triangle.hpp), reduced: deepest first, each
// dropped whose point on body 0 lies within the threshold of a kept one's (the manifold would
// merge the two, keeping the later one, not the deeper). The manifold is kept as Bullet keeps
// it (btSphereSphereCollisionAlgorithm's policy): a new point replaces the cached one it lands
// near (so warm starting carries its impulse over), refreshContactPoints drops points that moved
// apart, at most 4 are kept (its own reduction). A query that ends did_not_converge
// (distance.hpp: not seen on the tested pairs) adds no contact: the manifold keeps its
// refreshed points from the step before, and the event is counted by unconverged_queries().
//
// Accuracy (tests/engines/bullet_test.cpp, through btCollisionWorld's call path, both orders,
// against the 50-digit references of tests/reference/, with size = the largest radii of the
// pair summed plus |distance|): the contact's depth within 2e-6 size in the float build (the
// poses, radii and stored contact rounded to float; measured up to 1.5e-7 over the 10 scenario
// categories, aspect ratios to 1e4, scale 1e-6 to 1e6) and within 1e-10 size in the double
// build (measured 1e-15); its point on the ellipsoid on its surface to the same tolerance, its
// normal the ellipsoid's outward normal there to the angle that tolerance turns it by, the other
// point at point + depth * normal. Tested against ellipsoids, spheres, boxes, capsules of the
// three axes, static planes at any pose and a triangle mesh.
#pragma once

#include <ellipsect/distance.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/shapes.hpp>

#include <btBulletCollisionCommon.h>

#include <cstdint>

namespace ellipsect::bullet {

// The ellipsoid { R diag(r) u : |u| <= 1 } in its body frame (center at the origin, principal
// axes along the frame's axes), margin 0. Its support function is exact:
//     support(d) = diag(r)^2 d / |diag(r) d|      (in the body frame; world: c + R ... R^T d),
// so Bullet's own GJK/EPA (btConvexConvexAlgorithm), btConvexPlaneCollisionAlgorithm and
// btConvexConcaveCollisionAlgorithm run on the true ellipsoid wherever the algorithms of
// register_algorithms are not registered. Shape type CUSTOM_CONVEX_SHAPE_TYPE.
ATTRIBUTE_ALIGNED16(class) EllipsoidShape : public btConvexInternalShape {
public:
  BT_DECLARE_ALIGNED_ALLOCATOR();

  // radii: finite, > 0, aspect ratio at most Ellipsoid::max_aspect_ratio; throws InputError
  // naming "radii[i]" or "radii" (make_ellipsoid's checks) otherwise.
  explicit EllipsoidShape(const btVector3& radii);

  // The radii with the local scaling applied.
  btVector3 radii() const { return m_implicitShapeDimensions; }
  // The ellipsoid at the world pose `pose` (origin = center, basis columns = principal axes),
  // in double: the basis orthonormalized by orthonormal_basis. Throws InputError "axes" for a
  // basis farther than 1e-5 from orthonormal.
  Ellipsoid3<double> body(const btTransform& pose) const;

  btVector3 localGetSupportingVertexWithoutMargin(const btVector3& direction) const override;
  void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* directions, btVector3* out, int count)
      const override;
  // Solid ellipsoid: I_x = m (r_y^2 + r_z^2) / 5, and so on.
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override;
  // Exact box: half extent along world axis i = sqrt(sum_j (R_ij r_j)^2), rounded outwards.
  void getAabb(const btTransform& pose, btVector3& aabb_min, btVector3& aabb_max) const override;
  // Scaling by diag(s) in the body frame maps the ellipsoid to radii |s_i| r_i: exact. Throws
  // InputError "local_scaling[i]" for a zero or non-finite factor, "radii[i]" / "radii" where
  // the scaled radii leave the factory's range.
  void setLocalScaling(const btVector3& scaling) override;
  // The margin stays 0 (the shape is exact without one): throws InputError "margin" otherwise.
  void setMargin(btScalar margin) override;
  const char* getName() const override { return "ellipsect::EllipsoidShape"; }

private:
  btVector3 unscaled_radii_;
};

// The basis of a Bullet transform as a double matrix the factories accept as orthonormal: as
// given where it is within 1e-9 of orthonormal (max |R^T R - I|, the factories' tolerance); a
// float basis, orthonormal only to float rounding (about 1e-7), moved to its polar factor (the
// nearest orthonormal matrix) to about 1e-14 by one Newton step (R + R^-T) / 2, and that within
// normalize_tolerance (1e-5; shapes.hpp) to 1e-10. Farther: returned as given, for the
// factories to reject (InputError "axes").
Mat3<double> orthonormal_basis(const btMatrix3x3& basis);

// Registers the algorithms, for both orders of each pair and both of the dispatcher's tables
// (contacts: the world's step; closest points: btCollisionWorld::contactPairTest), for the
// ellipsoid against: EllipsoidShape; btSphereShape; btBoxShape (its full half extents with
// margin, getHalfExtentsWithMargin: the box the user asked for); btCapsuleShape and its X and
// Z variants; btStaticPlaneShape; and every btConcaveShape of the triangle-mesh, scaled-mesh,
// multimaterial-mesh and heightfield types (its triangles over the ellipsoid's box grown by the
// threshold, via processAllTriangles). A pair of those proxy types whose shapes are not these
// (another CUSTOM_CONVEX_SHAPE_TYPE shape) gets the collision configuration's own algorithm.
// No continuous collision: calculateTimeOfImpact returns 1, as Bullet's own convex algorithms
// do in a discrete world. An ellipsoid or box whose world basis is farther than 1e-5 from
// orthonormal (a shear or scale put into the transform) throws InputError "axes" out of the
// step (orthonormal_basis); other shapes take their transform as given, as Bullet does.
// `options` (options.hpp) go to every query: the tangency band and the iteration caps.
// Registering again replaces the dispatcher's earlier registration; the algorithms already
// created keep the options they were created with. Not to be called while the dispatcher is
// dispatching.
void register_algorithms(btCollisionDispatcher& dispatcher, const Options& options = {});
// Restores the collision configuration's algorithms for those pairs (Bullet's own answer for
// the same shapes) and frees the registration's create functions (else kept until the
// dispatcher is registered again, or the program ends).
void unregister_algorithms(btCollisionDispatcher& dispatcher);

// Queries that ended did_not_converge and so added no contact, since the program started
// (all dispatchers, all threads).
std::uint64_t unconverged_queries() noexcept;

}  // namespace ellipsect::bullet
