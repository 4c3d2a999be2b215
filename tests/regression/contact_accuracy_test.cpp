// first_contact far from the origin, on shallow approaches and at zero spin: the cases that
// broke its accuracy promises. The true contact times are the 50-digit reference's
// (tests/reference/rigid_contact_reference.hpp and reference.hpp, on the bodies as given).
#include <ellipsect/contact.hpp>

#include <gtest/gtest.h>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using E = Ellipse2<double>;

// axes given column-major, as printed by the failing test.
E ellipse(double cx, double cy, double a00, double a10, double a01, double a11, double r0, double r1) {
  Mat<double, 2> axes;
  axes << a00, a01, a10, a11;
  return E::from_axes(Vec<double, 2>(cx, cy), axes, Vec<double, 2>(r0, r1));
}

// 8e5 sizes from the origin, spinning: the advancement formed the bodies in world
// coordinates, whose rounding (eps times 8e5) entered the margin of every step, so it stopped
// 1e-9 of the size short of contact (2.3e-9 relative in time; the point off by 1.1e-9 of the
// size, the normal by 1.3e-9 rad), where the same pair at the origin was within 1.6e-14.
// Now the bodies are formed in a's frame (c_b - c_a moving at v_b - v_a).
TEST(ContactAccuracy, RigidContactFarFromOrigin) {
  const E a = ellipse(694432.71135187231, -404115.54172051756, -0.84666837106562742, -0.53212091618078405,
                      0.53212091618078405, -0.84666837106562742, 0.51460414984687119, 0.3076389583650429);
  const E b = ellipse(694433.11228499922, -404117.23532509618, 0.99417376273300162, 0.10778928283138955,
                      -0.10778928283138955, 0.99417376273300162, 0.95770253414531348, 0.35600172171238398);
  const RigidMotion<double, 2> ma{{0.50583346644738247, -0.2065838726399635}, 0.57348614070545845};
  const RigidMotion<double, 2> mb{{-0.61468485374133153, 3.0240622880386772}, -2.3695738174955565};
  const double lo = 0.24111291629151935;  // the double below the true contact
  const Contact<double, 2> c = first_contact(a, ma, b, mb, 1.0);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_LE(c.time, lo);
  EXPECT_LE(std::abs(c.time - lo), 1e-12 * lo);
}

// A shallow approach (sine about 1.2e-3) near the origin: the advancement stops where the
// gap is within its rounding margin (about 70 ulps of the size), which the slow approach
// turns into a time 1.2e-11..1.5e-11 early (the claim is 1e-12 from sine 1e-3). Now the last
// steps run in long double along the hit's normal, with margins 2^11 times narrower.
TEST(ContactAccuracy, RigidContactShallowApproach) {
  const E a = ellipse(-0.21102876711276844, 0.54986021145366604, 0.90721132224668577, 0.42067519155212851,
                      -0.42067519155212851, 0.90721132224668577, 1.1741828810404455, 0.4447635731292725);
  const E b = ellipse(1.4982885274338109, 2.7210284768955821, 0.32443284384828158, 0.94590873229530792,
                      -0.94590873229530792, 0.32443284384828158, 1.58172194003803, 0.41758310152681311);
  const RigidMotion<double, 2> ma{{0.027781245024358518, 0.96533199152560645}, 0.18000203977261509};
  const RigidMotion<double, 2> mb{{-0.16428924561336192, -0.0055141037071422495}, 0.13211530419858974};
  const double lo = 0.60161662196311549;  // the double below the true contact
  const Contact<double, 2> c = first_contact(a, ma, b, mb, 1.0);
  ASSERT_EQ(c.status, ContactStatus::hit);
  EXPECT_LE(c.time, lo);
  EXPECT_LE(std::abs(c.time - lo), 1e-12 * lo);
}

// Zero spin goes to the translational first_contact, which formed each body's position in
// world coordinates (4e5 from the origin), whose rounding (eps |c|) entered the distance: the
// time came 39 ulps after the true contact, where a point lies inside both bodies. Now the
// relative position is formed from the exact differences of the centers and velocities, and
// the time is the double just above the true contact; the rigid query, which promises never
// to be late, takes the root of the slab gap along the hit's normal (less its rounding)
// where it is earlier: at most the double below the true contact.
TEST(ContactAccuracy, ZeroSpinContactFarFromOrigin) {
  const E a = ellipse(-368909.31649992842, -389948.70389616612, 0.47382090800978149, -0.88062122795943676,
                      0.88062122795943676, 0.47382090800978149, 0.7533762601394306, 0.18281258881950987);
  const E b = ellipse(-368910.28164555581, -389952.12370434339, -0.71554680013067351, 0.69856479786971371,
                      -0.69856479786971371, -0.71554680013067351, 1.2205784346711845, 0.19550802090901165);
  const Vec<double, 2> va(-0.41891977339334452, -0.22367850245353596), vb(1.099085587439022, 6.0015056261348292);
  const double hi = 0.48062380029684953;  // the double above the true contact
  const Contact<double, 2> rigid = first_contact(a, RigidMotion<double, 2>{va, 0}, b, RigidMotion<double, 2>{vb, 0}, 1.0);
  const Contact<double, 2> linear = first_contact(a, va, b, vb, 1.0);
  ASSERT_EQ(linear.status, ContactStatus::hit);
  EXPECT_LE(linear.time, hi);
  EXPECT_LE(std::abs(linear.time - hi), 1e-12 * hi);
  ASSERT_EQ(rigid.status, ContactStatus::hit);
  EXPECT_LE(rigid.time, 0.48062380029684948);  // the double below the true contact
  EXPECT_LE(std::abs(rigid.time - hi), 1e-12 * hi);
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
