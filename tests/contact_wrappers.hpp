// Non-template wrappers of first_contact, so braced velocities work inside test macros.
#pragma once

#include <ellipsect/contact.hpp>

namespace ellipsect {

inline Contact<double, 2> contact2(const Ellipse2<double>& a, const Vec2<double>& va, const Ellipse2<double>& b,
                                   const Vec2<double>& vb, double t_max, const Options& o = {}) {
  return first_contact(a, va, b, vb, t_max, o);
}
inline Contact<double, 3> contact3(const Ellipsoid3<double>& a, const Vec3<double>& va, const Ellipsoid3<double>& b,
                                   const Vec3<double>& vb, double t_max, const Options& o = {}) {
  return first_contact(a, va, b, vb, t_max, o);
}

}  // namespace ellipsect
