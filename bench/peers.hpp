// An ellipsoid as the peer libraries see it (FCL 0.7, libccd 2.1), shared by the benchmark
// programs. Each part is compiled only when its library was found (bench/CMakeLists.txt).
#pragma once

#include <ellipsect/shapes.hpp>

#include "bench/bench_support.hpp"

#ifdef ELLIPSECT_HAVE_FCL
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/continuous_collision.h>
#endif
#ifdef ELLIPSECT_HAVE_CCD
#include <ccd/ccd.h>
#endif

#include <memory>

namespace ellipsect::bench {

#ifdef ELLIPSECT_HAVE_FCL
// fcl::Ellipsoidd has its radii along its local x, y, z axes: the pose's rotation is e's
// axes (a reflection gives the same set), its translation e's center moved by `offset`.
inline std::shared_ptr<fcl::Ellipsoidd> fcl_shape(const Ellipsoid3<double>& e) {
  return std::make_shared<fcl::Ellipsoidd>(e.radii()[0], e.radii()[1], e.radii()[2]);
}

inline fcl::Transform3d fcl_pose(const Ellipsoid3<double>& e, const Vec3<double>& offset = Vec3<double>::Zero()) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = e.axes();
  tf.translation() = e.center() + offset;
  return tf;
}

inline std::shared_ptr<fcl::CollisionObjectd> fcl_object(const Ellipsoid3<double>& e) {
  return std::make_shared<fcl::CollisionObjectd>(fcl_shape(e), fcl_pose(e));
}

// From a pose, as a simulation step would: the shape on the stack, the transform from the
// quaternion (for fcl::collide and fcl::distance on geometries and transforms).
inline fcl::Ellipsoidd fcl_shape(const Pose3& p) { return fcl::Ellipsoidd(p.radii[0], p.radii[1], p.radii[2]); }

// Two shapes (bodies, or a body and a box, capsule or triangle model) moving from their
// poses at t = 0 (a0, b0) to those at t = window (a1, b1).
struct FclMotion {
  std::shared_ptr<fcl::CollisionGeometryd> a, b;
  fcl::Transform3d a0, a1, b0, b1;
  double window;
};

// fcl::continuousCollide on the motion: the time of contact in the motion's units (0 when
// in contact at the start), or -1 for no contact.
inline double fcl_contact_time(const FclMotion& m, const fcl::ContinuousCollisionRequestd& request) {
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(m.a.get(), m.a0, m.a1, m.b.get(), m.b0, m.b1, request, result);
  return result.is_collide ? result.time_of_contact * m.window : -1.0;
}

inline fcl::Transform3d fcl_pose(const Pose3& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = p.rotation.toRotationMatrix();
  tf.translation() = p.center;
  return tf;
}
#endif

#ifdef ELLIPSECT_HAVE_CCD
struct CcdBody {
  Mat3<double> axes;
  Vec3<double> radii, center;
};

inline CcdBody ccd_body(const Ellipsoid3<double>& e) { return {e.axes(), e.radii(), e.center()}; }
inline CcdBody ccd_body(const Pose3& p) { return {p.rotation.toRotationMatrix(), p.radii, p.center}; }

// Support point in direction d: c + A diag(r^2) A^T d / |diag(r) A^T d|.
inline void ccd_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto& b = *static_cast<const CcdBody*>(obj);
  const Vec3<double> w = b.radii.cwiseProduct(b.axes.transpose() * Vec3<double>(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir)));
  const Vec3<double> p = b.center + b.axes * (b.radii.cwiseProduct(w) / w.norm());
  ccdVec3Set(out, p.x(), p.y(), p.z());
}

inline void ccd_center(const void* obj, ccd_vec3_t* out) {
  const auto& b = *static_cast<const CcdBody*>(obj);
  ccdVec3Set(out, b.center.x(), b.center.y(), b.center.z());
}
#endif

}  // namespace ellipsect::bench
