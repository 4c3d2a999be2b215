// The ellipsoid shape and its collision algorithms (include/ellipsect/bullet.hpp).
#include <ellipsect/box.hpp>
#include <ellipsect/bullet.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/margin.hpp>
#include <ellipsect/triangle.hpp>

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <vector>

namespace ellipsect::bullet {
namespace {

using V3 = Vec3<double>;

std::atomic<std::uint64_t> unconverged{0};

V3 to_double(const btVector3& v) { return V3(double(v.x()), double(v.y()), double(v.z())); }
btVector3 to_bt(const V3& v) { return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2])); }

// btScalar bounds of [lo, hi] computed in double: rounded outwards.
void outward(const V3& lo, const V3& hi, btVector3& out_lo, btVector3& out_hi) {
  constexpr btScalar inf = std::numeric_limits<btScalar>::infinity();
  for (int i = 0; i < 3; ++i) {
    out_lo[i] = std::nextafter(btScalar(lo[i]), -inf);
    out_hi[i] = std::nextafter(btScalar(hi[i]), inf);
  }
}

// Half extents along the frame's axes of the ellipsoid with axes R and radii r:
// h_i = sqrt(sum_j (R_ij r_j)^2) (the support radius along axis i).
V3 half_extents(const Mat3<double>& R, const V3& r) { return (R * r.asDiagonal()).rowwise().norm(); }

const EllipsoidShape* as_ellipsoid(const btCollisionShape* s) {
  return s->getShapeType() == CUSTOM_CONVEX_SHAPE_TYPE ? dynamic_cast<const EllipsoidShape*>(s) : nullptr;
}

// The other shape's kinds handled here (register_algorithms).
bool supported_other(const btCollisionShape* s) {
  switch (s->getShapeType()) {
    case CUSTOM_CONVEX_SHAPE_TYPE:
      return as_ellipsoid(s) != nullptr;
    case SPHERE_SHAPE_PROXYTYPE:
    case BOX_SHAPE_PROXYTYPE:
    case CAPSULE_SHAPE_PROXYTYPE:
    case STATIC_PLANE_PROXYTYPE:
      return true;
    default:
      return dynamic_cast<const btConcaveShape*>(s) != nullptr;
  }
}

// The types of the other shape registered with the ellipsoid.
constexpr std::array<int, 9> other_types = {CUSTOM_CONVEX_SHAPE_TYPE,
                                            SPHERE_SHAPE_PROXYTYPE,
                                            BOX_SHAPE_PROXYTYPE,
                                            CAPSULE_SHAPE_PROXYTYPE,
                                            STATIC_PLANE_PROXYTYPE,
                                            TRIANGLE_MESH_SHAPE_PROXYTYPE,
                                            SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE,
                                            TERRAIN_SHAPE_PROXYTYPE,
                                            MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE};

// The radius about its origin of a ball holding a convex shape handled here (its center at
// the origin of its frame); -1 for static planes and concave shapes.
double bounding_radius(const btCollisionShape* s) {
  switch (s->getShapeType()) {
    case CUSTOM_CONVEX_SHAPE_TYPE: {
      const btVector3 r = as_ellipsoid(s)->radii();
      return double(r[r.maxAxis()]);
    }
    case SPHERE_SHAPE_PROXYTYPE:
      return double(static_cast<const btSphereShape*>(s)->getRadius());
    case BOX_SHAPE_PROXYTYPE:
      return to_double(static_cast<const btBoxShape*>(s)->getHalfExtentsWithMargin()).norm();
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto* capsule = static_cast<const btCapsuleShape*>(s);
      return double(capsule->getHalfHeight()) + double(capsule->getRadius());
    }
    default:
      return -1;
  }
}

// Adds the contact of a signed-distance answer (a: the ellipsoid, b: the other shape; normal
// from a to b) to the result in Bullet's convention: the normal on body 1 pointing towards
// body 0, the point on body 1, the depth negative when penetrating. Returns whether a point
// was added; a pair proved beyond the threshold (nullopt: signed_distance_within, margin.hpp)
// adds none, and a did_not_converge answer adds none and is counted.
bool add_contact(const std::optional<Distance<double, 3>>& found, bool ellipsoid_is_body0, double threshold,
                 btManifoldResult& out) {
  if (!found) return false;
  const Distance<double, 3>& d = *found;
  if (d.status == DistanceStatus::did_not_converge) {
    unconverged.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  if (!(d.distance < threshold)) return false;
  if (ellipsoid_is_body0)
    out.addContactPoint(to_bt(-d.normal), to_bt(d.point_b), btScalar(d.distance));
  else
    out.addContactPoint(to_bt(d.normal), to_bt(d.point_a), btScalar(d.distance));
  return true;
}

// The triangles of a concave shape (vertices in that shape's frame) against the ellipsoid:
// each one's signed distance, kept where below the threshold.
class TriangleContacts : public btTriangleCallback {
public:
  struct Hit {
    Distance<double, 3> distance;
    int part, index;
  };

  TriangleContacts(const Ellipsoid3<double>& body, const btTransform& mesh_pose, double threshold,
                   const Options& options)
      : body_(body),
        rotation_(orthonormal_basis(mesh_pose.getBasis())),
        origin_(to_double(mesh_pose.getOrigin())),
        threshold_(threshold),
        options_(options) {}

  void processTriangle(btVector3* vertices, int part, int index) override {
    std::array<V3, 3> w;
    for (int k = 0; k < 3; ++k) w[k] = origin_ + rotation_ * to_double(vertices[k]);
    const auto d = signed_distance_within(body_, make_triangle<double, 3>(w[0], w[1], w[2]), threshold_, options_);
    if (d && (d->status == DistanceStatus::did_not_converge || d->distance < threshold_)) hits.push_back({*d, part, index});
  }

  std::vector<Hit> hits;

private:
  const Ellipsoid3<double>& body_;
  Mat3<double> rotation_;
  V3 origin_;
  double threshold_;
  const Options& options_;
};

// The contacts of a concave shape's triangles, reduced: deepest first, each dropped whose
// point on body 0 lies within the threshold of a kept one's (btPersistentManifold would merge
// the two, keeping whichever came last, not the deeper).
void add_triangle_contacts(std::vector<TriangleContacts::Hit>& hits, bool ellipsoid_is_body0, double threshold,
                           btManifoldResult& out) {
  std::sort(hits.begin(), hits.end(),
            [](const auto& x, const auto& y) { return x.distance.distance < y.distance.distance; });
  std::vector<V3> kept;
  for (const auto& h : hits) {
    const V3& p = ellipsoid_is_body0 ? h.distance.point_a : h.distance.point_b;
    if (h.distance.status != DistanceStatus::did_not_converge &&
        std::any_of(kept.begin(), kept.end(), [&](const V3& q) { return (p - q).norm() <= threshold; }))
      continue;
    if (ellipsoid_is_body0)
      out.setShapeIdentifiersB(h.part, h.index);
    else
      out.setShapeIdentifiersA(h.part, h.index);
    if (add_contact(h.distance, ellipsoid_is_body0, threshold, out)) kept.push_back(p);
  }
}

// The ellipsoid against one of the supported shapes (either order), one manifold per pair.
class EllipsoidAlgorithm : public btActivatingCollisionAlgorithm {
public:
  EllipsoidAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* w0,
                     const btCollisionObjectWrapper* w1, const Options& options)
      : btActivatingCollisionAlgorithm(ci, w0, w1), manifold_(ci.m_manifold), own_manifold_(false), options_(options) {}

  ~EllipsoidAlgorithm() override {
    if (own_manifold_ && manifold_ != nullptr) m_dispatcher->releaseManifold(manifold_);
  }

  void processCollision(const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1, const btDispatcherInfo&,
                        btManifoldResult* out) override {
    if (manifold_ == nullptr) {
      manifold_ = m_dispatcher->getNewManifold(w0->getCollisionObject(), w1->getCollisionObject());
      own_manifold_ = true;
    }
    out->setPersistentManifold(manifold_);
    const EllipsoidShape* e0 = as_ellipsoid(w0->getCollisionShape());
    const bool first = e0 != nullptr;  // the ellipsoid is body 0 (for two ellipsoids, a = body 0)
    const EllipsoidShape* ellipsoid = first ? e0 : as_ellipsoid(w1->getCollisionShape());
    const btCollisionObjectWrapper* ew = first ? w0 : w1;
    const btCollisionObjectWrapper* ow = first ? w1 : w0;
    const double threshold =
        double(manifold_->getContactBreakingThreshold()) + double(out->m_closestPointDistanceThreshold);
    const btCollisionShape* other = ow->getCollisionShape();
    const btTransform& pose = ow->getWorldTransform();
    const V3 origin = to_double(pose.getOrigin());
    // Convex shapes whose bounding balls are apart by more than the threshold: no contact, and
    // no query (the signed distance is at least the balls' gap).
    const double ball = bounding_radius(other);
    const double ball_gap =
        (origin - to_double(ew->getWorldTransform().getOrigin())).norm() - bounding_radius(ellipsoid) - ball;
    if (ball >= 0 && ball_gap > threshold) {
      if (own_manifold_) out->refreshContactPoints();
      return;
    }
    const Ellipsoid3<double> a = ellipsoid->body(ew->getWorldTransform());
    switch (other->getShapeType()) {
      case CUSTOM_CONVEX_SHAPE_TYPE:
        add_contact(signed_distance_within(a, as_ellipsoid(other)->body(pose), threshold, options_), first, threshold, *out);
        break;
      case SPHERE_SHAPE_PROXYTYPE:
        add_contact(signed_distance_within(
                        a, make_ball<double, 3>(origin, double(static_cast<const btSphereShape*>(other)->getRadius())),
                        threshold, options_),
                    first, threshold, *out);
        break;
      case BOX_SHAPE_PROXYTYPE: {
        const V3 half = to_double(static_cast<const btBoxShape*>(other)->getHalfExtentsWithMargin());
        add_contact(signed_distance_within(a, make_box<double, 3>(origin, orthonormal_basis(pose.getBasis()), half),
                                           threshold, options_),
                    first, threshold, *out);
        break;
      }
      case CAPSULE_SHAPE_PROXYTYPE: {
        const auto* capsule = static_cast<const btCapsuleShape*>(other);
        const V3 axis = orthonormal_basis(pose.getBasis()).col(capsule->getUpAxis()) * double(capsule->getHalfHeight());
        add_contact(
            signed_distance_within(a, make_capsule<double, 3>(origin - axis, origin + axis, double(capsule->getRadius())),
                                   threshold, options_),
            first, threshold, *out);
        break;
      }
      case STATIC_PLANE_PROXYTYPE: {
        // Local plane n . x = constant, solid below; world normal R n through origin + R n constant.
        const auto* plane = static_cast<const btStaticPlaneShape*>(other);
        const Mat3<double> R = orthonormal_basis(pose.getBasis());
        const V3 n = R * to_double(plane->getPlaneNormal());
        add_contact(
            signed_distance_within(a, make_half_space<double, 3>(origin + n * double(plane->getPlaneConstant()), n),
                                   threshold, options_),
            first, threshold, *out);
        break;
      }
      default: {
        // A concave shape: its triangles within the ellipsoid's box in the shape's frame, grown
        // by the threshold.
        const Mat3<double> R = orthonormal_basis(pose.getBasis());
        const Mat3<double> local_axes = R.transpose() * a.axes();
        const V3 local_center = R.transpose() * (a.center() - origin);
        const V3 reach = half_extents(local_axes, a.radii()).array() + threshold;
        btVector3 lo, hi;
        outward(local_center - reach, local_center + reach, lo, hi);
        TriangleContacts contacts(a, pose, threshold, options_);
        static_cast<const btConcaveShape*>(other)->processAllTriangles(&contacts, lo, hi);
        add_triangle_contacts(contacts.hits, first, threshold, *out);
        break;
      }
    }
    if (own_manifold_) out->refreshContactPoints();
  }

  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return btScalar(1);
  }

  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (manifold_ != nullptr && own_manifold_) manifolds.push_back(manifold_);
  }

private:
  btPersistentManifold* manifold_;
  bool own_manifold_;
  Options options_;
};

// Creates EllipsoidAlgorithm (with the registration's options) for the pairs it handles, and
// the configuration's own algorithm (of the contact table or the closest-points table) for any
// other pair of the same types.
class CreateFunc : public btCollisionAlgorithmCreateFunc {
public:
  CreateFunc(bool closest_points, const Options& options) : closest_points_(closest_points), options_(options) {}

  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* w0,
                                                 const btCollisionObjectWrapper* w1) override {
    const btCollisionShape* s0 = w0->getCollisionShape();
    const btCollisionShape* s1 = w1->getCollisionShape();
    const bool ours =
        (as_ellipsoid(s0) != nullptr && supported_other(s1)) || (as_ellipsoid(s1) != nullptr && supported_other(s0));
    if (!ours) {
      btCollisionConfiguration* config =
          static_cast<btCollisionDispatcher*>(ci.m_dispatcher1)->getCollisionConfiguration();
      const int t0 = s0->getShapeType(), t1 = s1->getShapeType();
      btCollisionAlgorithmCreateFunc* f = closest_points_ ? config->getClosestPointsAlgorithmCreateFunc(t0, t1)
                                                          : config->getCollisionAlgorithmCreateFunc(t0, t1);
      return f->CreateCollisionAlgorithm(ci, w0, w1);
    }
    void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(EllipsoidAlgorithm));
    return new (memory) EllipsoidAlgorithm(ci, w0, w1, options_);
  }

private:
  bool closest_points_;
  Options options_;
};

// The create functions registered with each dispatcher (its contact and closest-points
// tables), kept until unregister_algorithms or the program's end.
struct Registered {
  CreateFunc contact_points, closest_points;
};
std::mutex registry_mutex;
std::map<const btCollisionDispatcher*, std::unique_ptr<Registered>> registry;

}  // namespace

EllipsoidShape::EllipsoidShape(const btVector3& radii) : unscaled_radii_(radii) {
  m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE;
  m_collisionMargin = btScalar(0);
  (void)make_ellipsoid<double>(V3::Zero(), Mat3<double>::Identity(), to_double(radii));  // the factory's checks
  m_implicitShapeDimensions = radii;
}

Ellipsoid3<double> EllipsoidShape::body(const btTransform& pose) const {
  return make_ellipsoid<double>(to_double(pose.getOrigin()), orthonormal_basis(pose.getBasis()),
                                to_double(m_implicitShapeDimensions));
}

btVector3 EllipsoidShape::localGetSupportingVertexWithoutMargin(const btVector3& direction) const {
  const V3 r = to_double(m_implicitShapeDimensions);
  const V3 w = r.cwiseProduct(to_double(direction));
  const double length = w.norm();
  if (length == 0) return btVector3(m_implicitShapeDimensions.x(), btScalar(0), btScalar(0));  // any boundary point
  return to_bt(r.cwiseProduct(w) / length);
}

void EllipsoidShape::batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* directions, btVector3* out,
                                                                       int count) const {
  for (int i = 0; i < count; ++i) out[i] = localGetSupportingVertexWithoutMargin(directions[i]);
}

void EllipsoidShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const {
  const V3 r2 = to_double(m_implicitShapeDimensions).cwiseAbs2();
  const double m5 = double(mass) / 5;
  inertia = to_bt(V3(m5 * (r2[1] + r2[2]), m5 * (r2[0] + r2[2]), m5 * (r2[0] + r2[1])));
}

void EllipsoidShape::getAabb(const btTransform& pose, btVector3& aabb_min, btVector3& aabb_max) const {
  const V3 c = to_double(pose.getOrigin());
  Mat3<double> R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = double(pose.getBasis()[i][j]);
  const V3 h = half_extents(R, to_double(m_implicitShapeDimensions));
  outward(c - h, c + h, aabb_min, aabb_max);
}

void EllipsoidShape::setLocalScaling(const btVector3& scaling) {
  const V3 s = to_double(scaling);
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(s[i]) || s[i] == 0)
      throw InputError("local_scaling[" + std::to_string(i) + "]",
                       "must be finite and nonzero (got " + std::to_string(s[i]) + ")");
  const V3 r = to_double(unscaled_radii_).cwiseProduct(s.cwiseAbs());
  (void)make_ellipsoid<double>(V3::Zero(), Mat3<double>::Identity(), r);
  m_localScaling = scaling.absolute();
  m_implicitShapeDimensions = to_bt(r);
}

void EllipsoidShape::setMargin(btScalar margin) {
  if (margin != btScalar(0))
    throw InputError("margin",
                     "must be 0: the ellipsoid's support is exact (got " + std::to_string(double(margin)) + ")");
}

Mat3<double> orthonormal_basis(const btMatrix3x3& basis) {
  Mat3<double> R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = double(basis[i][j]);
  const double deviation = (R.transpose() * R - Mat3<double>::Identity()).cwiseAbs().maxCoeff();
  if (deviation <= Ellipsoid3<double>::axes_tolerance || !(deviation <= normalize_tolerance)) return R;
  // One Newton step of the polar iteration, (R + R^-T) / 2: for R = Q (I + E) with E symmetric
  // it gives Q (I + O(E^2)), a float basis's 1e-7 becoming about 1e-14 (1e-5: 1e-10), within
  // the factories' tolerance (they finish the orthonormalization); a tenth of the cost of
  // normalized_rotation's SVD.
  const Mat3<double> step = (R + Mat3<double>(R.inverse().transpose())) / 2;
  return step;
}

void register_algorithms(btCollisionDispatcher& dispatcher, const Options& options) {
  auto funcs = std::make_unique<Registered>(Registered{CreateFunc(false, options), CreateFunc(true, options)});
  for (const int t : other_types) {
    dispatcher.registerCollisionCreateFunc(CUSTOM_CONVEX_SHAPE_TYPE, t, &funcs->contact_points);
    dispatcher.registerCollisionCreateFunc(t, CUSTOM_CONVEX_SHAPE_TYPE, &funcs->contact_points);
    dispatcher.registerClosestPointsCreateFunc(CUSTOM_CONVEX_SHAPE_TYPE, t, &funcs->closest_points);
    dispatcher.registerClosestPointsCreateFunc(t, CUSTOM_CONVEX_SHAPE_TYPE, &funcs->closest_points);
  }
  const std::lock_guard<std::mutex> lock(registry_mutex);
  registry[&dispatcher] = std::move(funcs);  // the previous registration's functions, if any, freed
}

void unregister_algorithms(btCollisionDispatcher& dispatcher) {
  btCollisionConfiguration* config = dispatcher.getCollisionConfiguration();
  for (const int t : other_types) {
    const int c = CUSTOM_CONVEX_SHAPE_TYPE;
    dispatcher.registerCollisionCreateFunc(c, t, config->getCollisionAlgorithmCreateFunc(c, t));
    dispatcher.registerCollisionCreateFunc(t, c, config->getCollisionAlgorithmCreateFunc(t, c));
    dispatcher.registerClosestPointsCreateFunc(c, t, config->getClosestPointsAlgorithmCreateFunc(c, t));
    dispatcher.registerClosestPointsCreateFunc(t, c, config->getClosestPointsAlgorithmCreateFunc(t, c));
  }
  const std::lock_guard<std::mutex> lock(registry_mutex);
  registry.erase(&dispatcher);
}

std::uint64_t unconverged_queries() noexcept { return unconverged.load(std::memory_order_relaxed); }

}  // namespace ellipsect::bullet
