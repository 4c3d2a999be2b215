// The bundled example: first contact of a 2D and a 3D swept pair, in the spirit of the
// figures of Eberly's "Intersection of Swept Ellipses and Swept Ellipsoids".
#include <ellipsect/ellipsect.hpp>

#include <cstdio>

using namespace ellipsect;

template <class T, int N>
void report(const char* title, const Ellipsoid<T, N>& a, const Vec<T, N>& va, const Ellipsoid<T, N>& b,
            const Vec<T, N>& vb, T t_max) {
  const Contact<T, N> c = first_contact(a, va, b, vb, t_max);
  std::printf("%s\n  relation at t = 0: %s\n  first contact: %s", title, to_string(classify(a, b)).data(),
              to_string(c.status).data());
  if (c.status == ContactStatus::hit || c.status == ContactStatus::touching_at_start) {
    std::printf(" at t = %.17g\n  point  =", double(c.time));
    for (int i = 0; i < N; ++i) std::printf(" %.17g", double(c.point[i]));
    std::printf("\n  normal =");
    for (int i = 0; i < N; ++i) std::printf(" %.17g", double(c.normal[i]));
  }
  std::printf("\n  Newton steps: %d\n", c.iterations);
}

int main() {
  // 2D: a tilted ellipse at rest and an ellipse moving in from the right.
  const auto e0 = make_ellipse<double>({0.0, 0.0}, 0.5, {3.0, 1.0});
  const auto e1 = make_ellipse<double>({8.0, 1.5}, -0.3, {1.5, 0.5});
  report<double, 2>("2D swept ellipses", e0, {0.0, 0.0}, e1, {-2.0, -0.25}, 10.0);

  // 3D: two ellipsoids flying past each other at an angle.
  const auto s0 = make_ellipsoid<double>({0.0, 0.0, 0.0}, Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized())),
                                         {2.0, 1.0, 0.5});
  const auto s1 = make_ellipsoid<double>({6.0, 4.0, 1.0}, Eigen::Quaterniond(Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitZ())),
                                         {1.0, 0.75, 0.5});
  report<double, 3>("3D swept ellipsoids", s0, {0.5, 0.0, 0.0}, s1, {-1.0, -1.0, -0.2}, 20.0);
  return 0;
}
