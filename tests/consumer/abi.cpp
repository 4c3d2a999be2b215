// Built against the installed package once per compiler setting that changes Eigen's
// alignment (tests/consumer/CMakeLists.txt: -march=native, -mavx512f,
// EIGEN_MAX_STATIC_ALIGN_BYTES = 0 and 64, and the defaults), this program checks that
// every public struct the library fills, and every array of bodies it reads, means the
// same on both sides. Expected values are the inputs themselves or closed forms of balls.
#include <ellipsect/ellipsect.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#ifndef ABI_VARIANT
#define ABI_VARIANT "unnamed"
#endif

namespace {

using namespace ellipsect;
int failures = 0;

void check(bool ok, const char* what) {
  if (!ok) {
    std::printf("FAILED (%s): %s\n", ABI_VARIANT, what);
    ++failures;
  }
}

template <class A, class B>
bool near(const A& a, const B& b, double tol) {
  return (a.template cast<double>() - b.template cast<double>()).cwiseAbs().maxCoeff() <= tol;
}

void bodies() {
  const auto e = make_ellipse<double>({1, 2}, 0.3, {3, 4});
  check(e.center() == Vec2<double>(1, 2) && e.radii() == Vec2<double>(3, 4), "Ellipse2<double> center, radii");
  check(near(e.axes().col(0), Eigen::Vector2d(std::cos(0.3), std::sin(0.3)), 1e-15) &&
            near(e.axes().col(1), Eigen::Vector2d(-std::sin(0.3), std::cos(0.3)), 1e-15),
        "Ellipse2<double> axes");
  const auto f = make_ellipsoid<float>({1, 2, 3}, Mat3<float>::Identity(), {2, 3, 4});
  check(f.center() == Vec3<float>(1, 2, 3) && f.axes() == Mat3<float>::Identity() && f.radii() == Vec3<float>(2, 3, 4),
        "Ellipsoid3<float> fields");
  const auto q = make_ellipsoid<double>(Eigen::Vector3d(1, 2, 3),
                                        Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ())),
                                        Eigen::Vector3d(2, 3, 4));
  check(q.center() == Vec3<double>(1, 2, 3) && q.radii() == Vec3<double>(2, 3, 4) &&
            near(q.axes().col(0), Eigen::Vector3d(std::cos(0.5), std::sin(0.5), 0), 1e-15) &&
            near(q.axes().col(2), Eigen::Vector3d(0, 0, 1), 1e-15),
        "Ellipsoid3<double> from a quaternion");
  const Ellipsoid3<double> unit;
  check(unit.center() == Vec3<double>::Zero() && unit.axes() == Mat3<double>::Identity() &&
            unit.radii() == Vec3<double>::Ones(),
        "default Ellipsoid3<double>");
}

void contacts() {
  // Unit circles 10 apart closing at speed 2 first touch at t = 4, at (5, 0).
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({10, 0}, 1);
  const auto c = first_contact(a, Eigen::Vector2d(1, 0), b, Eigen::Vector2d(-1, 0), 100.0);
  check(c.status == ContactStatus::hit && std::abs(c.time - 4) <= 1e-13, "Contact<double, 2> status, time");
  check(near(c.point, Eigen::Vector2d(5, 0), 1e-12) && near(c.normal, Eigen::Vector2d(1, 0), 1e-12),
        "Contact<double, 2> point, normal");
  // Spheres of radii 1 and 2, 10 apart, the first moving at speed 1: t = 7, at (8, 0, 0).
  const auto s = first_contact(make_ball<float, 3>({0, 0, 0}, 1), Eigen::Vector3f(1, 0, 0),
                               make_ball<float, 3>({10, 0, 0}, 2), Eigen::Vector3f(0, 0, 0), 100.0f);
  check(s.status == ContactStatus::hit && std::abs(s.time - 7) <= 1e-5f, "Contact<float, 3> status, time");
  check(near(s.point, Eigen::Vector3f(8, 0, 0), 1e-5) && near(s.normal, Eigen::Vector3f(1, 0, 0), 1e-5),
        "Contact<float, 3> point, normal");
  // The batch function writes the same struct into an array the program owns.
  Pairs<double, 2> pairs;
  pairs.push_back(a, Eigen::Vector2d(1, 0), b, Eigen::Vector2d(-1, 0), 100);
  std::vector<Contact<double, 2>> out(1);
  first_contact(pairs, std::span<Contact<double, 2>>(out));
  check(out[0].status == ContactStatus::hit && out[0].time == c.time && out[0].point == c.point &&
            out[0].normal == c.normal && out[0].iterations == c.iterations,
        "batch Contact<double, 2>");
}

void distances() {
  // Balls of radii 1 and 2, centers 10 apart along y: 7 apart, witnesses (0, 1, 0), (0, 8, 0).
  const auto d = distance(make_ball<double, 3>({0, 0, 0}, 1), make_ball<double, 3>({0, 10, 0}, 2));
  check(d.status == DistanceStatus::separated && std::abs(d.distance - 7) <= 1e-13, "Distance<double, 3> distance");
  check(near(d.point_a, Eigen::Vector3d(0, 1, 0), 1e-12) && near(d.point_b, Eigen::Vector3d(0, 8, 0), 1e-12) &&
            near(d.normal, Eigen::Vector3d(0, 1, 0), 1e-12),
        "Distance<double, 3> points, normal");
  // Circles of radii 2 and 1, centers 2 apart: penetration 1, witnesses (2, 0) and (1, 0).
  const auto p = signed_distance(make_ball<float, 2>({0, 0}, 2), make_ball<float, 2>({2, 0}, 1));
  check(p.status == DistanceStatus::overlapping && std::abs(p.distance + 1) <= 1e-5f, "Distance<float, 2> depth");
  check(near(p.point_a, Eigen::Vector2f(2, 0), 1e-5) && near(p.point_b, Eigen::Vector2f(1, 0), 1e-5) &&
            near(p.normal, Eigen::Vector2f(1, 0), 1e-5),
        "Distance<float, 2> points, normal");
  // (0, 0, 7) is 4 from a sphere of radius 3 at the origin; its closest point is (0, 0, 3).
  const auto cp = closest_point(make_ball<double, 3>({0, 0, 0}, 3), Eigen::Vector3d(0, 0, 7));
  check(near(cp.point, Eigen::Vector3d(0, 0, 3), 1e-13) && std::abs(cp.signed_distance - 4) <= 1e-13,
        "ClosestPoint<double, 3>");
  const auto qp = closest_point_quartic(make_ellipse<double>({0, 0}, 0, {2, 1}), Eigen::Vector2d(5, 0));
  check(qp.status == QuarticStatus::outside && near(qp.point, Eigen::Vector2d(2, 0), 1e-13) &&
            std::abs(qp.distance - 3) <= 1e-13,
        "QuarticPoint<double>");
}

void contact_functions() {
  // Balls of radii 1 and 2, centers 6 apart along z: F = (6 / 3)^2 at lambda = 1 / 3; along x
  // they touch 3 apart, at (1, 0, 0) (float: (1, 0), normal (1, 0)).
  const auto f = perram_wertheim(make_ball<double, 3>({0, 0, 0}, 1), make_ball<double, 3>({0, 0, 6}, 2));
  check(f.status == ContactFunctionStatus::ok && std::abs(f.f - 4) <= 1e-14 && f.f_upper == f.f &&
            std::abs(f.lambda - 1.0 / 3) <= 1e-15 && f.iterations > 0,
        "ContactFunction<double>");
  const auto s = closest_approach(make_ball<float, 2>({0, 0}, 1), make_ball<float, 2>({0, 5}, 2), Eigen::Vector2f(2, 0));
  check(s.status == ContactFunctionStatus::ok && std::abs(s.distance - 3) <= 1e-6f && s.distance_lower == s.distance &&
            near(s.point, Eigen::Vector2f(1, 0), 1e-6) && near(s.normal, Eigen::Vector2f(1, 0), 1e-6) &&
            std::abs(s.lambda - 1.0f / 3) <= 1e-6f && s.iterations > 0,
        "ClosestApproach<float, 2>");
}

void plane() {
  // Unit circles with centers 1 apart cross at (1/2, -+sqrt(3)/2); the lens between them
  // has area 2 pi / 3 - sqrt(3) / 2.
  const auto a = make_ball<double, 2>({0, 0}, 1);
  const auto b = make_ball<double, 2>({1, 0}, 1);
  const auto x = intersect_boundaries(a, b);
  const double h = std::sqrt(3.0) / 2;
  check(x.status == BoundaryStatus::points && x.count == 2 && x.kinds[0] == CrossingKind::transverse &&
            x.kinds[1] == CrossingKind::transverse,
        "BoundaryIntersection<double> status, count, kinds");
  check(near(x.points[0], Eigen::Vector2d(0.5, -h), 1e-13) && near(x.points[1], Eigen::Vector2d(0.5, h), 1e-13),
        "BoundaryIntersection<double> points");
  const auto area = overlap_area(a, b);
  check(area.relation == Relation::overlapping && std::abs(area.area - (2 * std::numbers::pi / 3 - h)) <= 1e-13,
        "OverlapArea<double>");
  const auto circle = make_circle(Eigen::Vector2d(2, 1), 2.0);
  check(circle.center() == Eigen::Vector2d(2, 1) && circle.radius() == 2.0, "Circle<double>");
  const auto sc = segment_circle(Eigen::Vector2d(0, 0), Eigen::Vector2d(4, 0), circle);
  check(sc.verdict == Verdict::collision && sc.side == Side::left, "SegmentCircle");
  // The ellipse x^2/4 + y^2 <= 1 and the unit disk at (5, 0) are 2 apart along the x axis.
  const auto po = polygonal_overlap(make_ellipse<double>({0, 0}, 0, {2, 1}), make_circle(Eigen::Vector2d(5, 0), 1.0));
  check(po.verdict == Verdict::no_collision && po.gap_lo <= 2 && 2 <= po.gap_hi, "PolygonalOverlap<double>");
}

void arrays() {
  // The library reads arrays of bodies the program laid out: unit circles against unit
  // circles 1.5, 3 and 1 away (overlap, apart, overlap).
  std::vector<Ellipse2<double>> a(3), b;
  for (const double x : {1.5, 3.0, 1.0}) b.push_back(make_ball<double, 2>({x, 0}, 1));
  bool out[3];
  overlap<double, 2>(a, b, out);
  check(out[0] && !out[1] && out[2], "overlap over arrays of Ellipse2<double>");
}

// The bodies from points (geometry.hpp): a square's corners' enclosing circle (radius sqrt 2),
// the hull's four edges and the square's inscribed circle (radius 1), and the fit of points
// on the unit circle (its covariance a fixed-size matrix inside the result).
void geometry() {
  const std::vector<Vec2<double>> square{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0.5, 0.25}};
  const auto e = enclosing_ellipsoid<double, 2>(square);
  check(e.status == EnclosingStatus::optimal && e.volume_gap <= 1e-9 && near(e.body.center(), Eigen::Vector2d(0, 0), 1e-9) &&
            std::abs(e.body.radii()[0] - std::sqrt(2.0)) <= 1e-9 && e.support.size() == 4 && e.support_points.size() == 4,
        "EnclosingEllipsoid<double, 2>");
  const auto faces = hull_half_spaces<double, 2>(square);
  const auto in = inscribed_ellipsoid<double, 2>(faces);
  check(faces.size() == 4 && in.status == InscribedStatus::optimal && std::abs(in.body.radii()[1] - 1) <= 1e-8 &&
            in.active.size() == 4 && in.weights.size() == 4,
        "InscribedEllipsoid<double, 2>");
  std::vector<Vec3<float>> sphere;
  for (int i = 0; i < 40; ++i) {
    const double z = -1 + (i + 0.5) / 20, r = std::sqrt(1 - z * z), t = 2.4 * i;
    sphere.push_back(Vec3<float>(float(3 + r * std::cos(t)), float(r * std::sin(t)), float(z)));
  }
  const auto f = fit_ellipsoid<float, 3>(sphere);
  check(f.status == FitStatus::converged && near(f.body.center(), Eigen::Vector3f(3, 0, 0), 1e-4) &&
            f.rms_residual <= 1e-5 && f.covariance.allFinite() && f.covariance(0, 0) >= 0 && f.rank >= 6,
        "EllipsoidFit<float, 3>");
}

}  // namespace

int main() {
  bodies();
  contacts();
  distances();
  contact_functions();
  plane();
  arrays();
  geometry();
  std::printf("abi %s: %s (sizeof Ellipse2<double> %zu, Contact<double, 3> %zu)\n", ABI_VARIANT,
              failures ? "FAILED" : "ok", sizeof(Ellipse2<double>), sizeof(Contact<double, 3>));
  return failures ? 1 : 0;
}
