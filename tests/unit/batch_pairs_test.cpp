// The batch forms of the other pair queries (batch.hpp, "Every other pair query") equal the
// scalar functions bit for bit on every scenario category, at one thread and on the pool;
// spans of unequal sizes and a bad direction are rejected before any pair is computed.
#include <ellipsect/batch.hpp>

#include "scenarios/scenarios.hpp"
#include "tests/support.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace {
namespace ELLIPSECT_UNITY_ID {

using namespace ellipsect;
using ellipsect::testing::expect_field;

// The bytes of each field (no padding): equal bytes are equal answers, NaNs included.
using Bytes = std::vector<unsigned char>;
template <class X>
  requires(std::is_arithmetic_v<X> || std::is_enum_v<X>)
void put(Bytes& out, const X& x) {
  const auto* p = reinterpret_cast<const unsigned char*>(&x);
  out.insert(out.end(), p, p + sizeof x);
}
template <class Derived>
void put(Bytes& out, const Eigen::MatrixBase<Derived>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i) put(out, m(i, j));
}
template <class T, int N>
void put(Bytes& out, const Distance<T, N>& d) {
  put(out, d.status), put(out, d.distance), put(out, d.point_a), put(out, d.point_b), put(out, d.normal);
  put(out, d.iterations);
}
template <class T, int N>
void put(Bytes& out, const Contact<T, N>& c) {
  put(out, c.status), put(out, c.time), put(out, c.point), put(out, c.normal), put(out, c.iterations);
}
template <class T>
void put(Bytes& out, const ContactFunction<T>& f) {
  put(out, f.status), put(out, f.f), put(out, f.f_upper), put(out, f.lambda), put(out, f.iterations);
}
template <class T, int N>
void put(Bytes& out, const ClosestApproach<T, N>& c) {
  put(out, c.status), put(out, c.distance), put(out, c.distance_lower), put(out, c.point), put(out, c.normal);
  put(out, c.lambda), put(out, c.iterations);
}
template <class T>
void put(Bytes& out, const OverlapArea<T>& a) {
  put(out, a.area), put(out, a.relation);
}
template <class T, int N>
void put(Bytes& out, const BodyGradient<T, N>& g) {
  put(out, g.center), put(out, g.orientation), put(out, g.radii);
}
template <class T, int N>
void put(Bytes& out, const BodyJacobian<T, N>& j) {
  put(out, j.center), put(out, j.orientation), put(out, j.radii);
}
template <class G>
  requires requires(const G& g) { g.value; g.a; g.b; }
void put(Bytes& out, const G& g) {
  put(out, g.value), put(out, g.a), put(out, g.b);
  if constexpr (requires { g.relation; }) put(out, g.relation);
  if constexpr (requires { g.direction; }) put(out, g.direction);
  if constexpr (requires { g.velocity_a; }) {
    put(out, g.velocity_a), put(out, g.velocity_b), put(out, g.angular_velocity_a), put(out, g.angular_velocity_b);
    put(out, g.point.a), put(out, g.point.b), put(out, g.point.velocity_a), put(out, g.point.velocity_b);
    put(out, g.point.angular_velocity_a), put(out, g.point.angular_velocity_b);
  }
}
template <class X>
Bytes bytes(const X& x) {
  Bytes out;
  put(out, x);
  return out;
}

// Every category's cases, with their motions and a direction from a's center to b's.
template <int N>
struct Cases {
  std::vector<Ellipsoid<double, N>> a, b;
  std::vector<Vec<double, N>> va, vb, direction;
  std::vector<RigidMotion<double, N>> ma, mb;
  std::vector<double> t_max;

  explicit Cases(int per_category) {
    for (const auto category : scenarios::all_categories)
      for (int i = 0; i < per_category; ++i) {
        const auto c = scenarios::make_case<N>(category, 4100 + std::uint64_t(i));
        a.push_back(c.a), b.push_back(c.b), va.push_back(c.va), vb.push_back(c.vb), t_max.push_back(c.t_max);
        const Vec<double, N> d = c.b.center() - c.a.center();
        direction.push_back(d.isZero(0) ? Vec<double, N>::UnitX() : d);
        RigidMotion<double, N> m{c.va, {}, 0.0}, n{c.vb, {}, 0.0};
        if constexpr (N == 2) m.angular_velocity = 0.5 * (i % 3), n.angular_velocity = -0.25;
        else m.angular_velocity = Vec<double, 3>(0.5 * (i % 3), 0.1, 0.0), n.angular_velocity = Vec<double, 3>(0, 0, -0.25);
        ma.push_back(m), mb.push_back(n);
      }
  }
  std::size_t size() const { return a.size(); }
};

// batch(out, options) fills out; scalar(i) is pair i's answer: equal bytes at 1 thread and all.
template <class R, class Batch, class Scalar>
void expect_scalar(std::size_t n, const Batch& batch, const Scalar& scalar, const char* what) {
  for (const int threads : {1, 0}) {
    std::vector<R> out(n);
    batch(std::span<R>(out), BatchOptions{Options{}, threads});
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(bytes(out[i]), bytes(scalar(i))) << what << " pair " << i;
  }
}

template <int N>
void every_query() {
  const Cases<N> c(ellipsect::testing::cases(12));
  const std::size_t n = c.size();
  using E = std::span<const Ellipsoid<double, N>>;
  const E a(c.a), b(c.b);
  expect_scalar<Distance<double, N>>(
      n, [&](auto out, const auto& o) { distance<double, N>(a, b, out, o); },
      [&](std::size_t i) { return distance(c.a[i], c.b[i]); }, "distance");
  expect_scalar<Distance<double, N>>(
      n, [&](auto out, const auto& o) { signed_distance<double, N>(a, b, out, o); },
      [&](std::size_t i) { return signed_distance(c.a[i], c.b[i]); }, "signed_distance");
  expect_scalar<DistanceGradient<double, N>>(
      n, [&](auto out, const auto& o) { signed_distance_gradient<double, N>(a, b, out, o); },
      [&](std::size_t i) { return signed_distance_gradient(c.a[i], c.b[i]); }, "signed_distance_gradient");
  expect_scalar<ContactFunction<double>>(
      n, [&](auto out, const auto& o) { perram_wertheim<double, N>(a, b, out, o); },
      [&](std::size_t i) { return perram_wertheim(c.a[i], c.b[i]); }, "perram_wertheim");
  expect_scalar<ContactFunctionGradient<double, N>>(
      n, [&](auto out, const auto& o) { perram_wertheim_gradient<double, N>(a, b, out, o); },
      [&](std::size_t i) { return perram_wertheim_gradient(c.a[i], c.b[i]); }, "perram_wertheim_gradient");
  expect_scalar<ClosestApproachGradient<double, N>>(
      n,
      [&](auto out, const auto& o) {
        closest_approach_gradient<double, N>(a, b, std::span<const Vec<double, N>>(c.direction), out, o);
      },
      [&](std::size_t i) { return closest_approach_gradient<double, N>(c.a[i], c.b[i], c.direction[i]); },
      "closest_approach_gradient");
  const std::span<const double> t_max(c.t_max);
  expect_scalar<ContactGradient<double, N>>(
      n,
      [&](auto out, const auto& o) {
        first_contact_gradient<double, N>(a, std::span<const Vec<double, N>>(c.va), b,
                                          std::span<const Vec<double, N>>(c.vb), t_max, out, o);
      },
      [&](std::size_t i) { return first_contact_gradient<double, N>(c.a[i], c.va[i], c.b[i], c.vb[i], c.t_max[i]); },
      "first_contact_gradient (linear)");
  expect_scalar<ContactGradient<double, N>>(
      n,
      [&](auto out, const auto& o) {
        first_contact_gradient<double, N>(a, std::span<const RigidMotion<double, N>>(c.ma), b,
                                          std::span<const RigidMotion<double, N>>(c.mb), t_max, out, o);
      },
      [&](std::size_t i) { return first_contact_gradient<double, N>(c.a[i], c.ma[i], c.b[i], c.mb[i], c.t_max[i]); },
      "first_contact_gradient (rigid)");
}

TEST(BatchPairs, EqualScalar2D) { every_query<2>(); }
TEST(BatchPairs, EqualScalar3D) { every_query<3>(); }

TEST(BatchPairs, EllipsesEqualScalar) {
  const Cases<2> c(ellipsect::testing::cases(12));
  const std::size_t n = c.size();
  const std::span<const Ellipse2<double>> a(c.a), b(c.b);
  expect_scalar<OverlapArea<double>>(
      n, [&](auto out, const auto& o) { overlap_area<double>(a, b, out, o); },
      [&](std::size_t i) { return overlap_area(c.a[i], c.b[i]); }, "overlap_area");
  expect_scalar<double>(
      n, [&](auto out, const auto& o) { intersection_over_union<double>(a, b, out, o); },
      [&](std::size_t i) { return intersection_over_union(c.a[i], c.b[i]); }, "intersection_over_union");
  expect_scalar<OverlapAreaGradient<double>>(
      n, [&](auto out, const auto& o) { overlap_area_gradient<double>(a, b, out, o); },
      [&](std::size_t i) { return overlap_area_gradient(c.a[i], c.b[i]); }, "overlap_area_gradient");
  expect_scalar<IouGradient<double>>(
      n, [&](auto out, const auto& o) { intersection_over_union_gradient<double>(a, b, out, o); },
      [&](std::size_t i) { return intersection_over_union_gradient(c.a[i], c.b[i]); },
      "intersection_over_union_gradient");
}

// The options reach every pair: a cap of one iteration is the scalar's status at that cap.
TEST(BatchPairs, OptionsReachThePairs) {
  const Cases<3> c(2);
  std::vector<Distance<double, 3>> out(c.size());
  const Options capped{.max_distance_iterations = 1};
  signed_distance<double, 3>(c.a, c.b, out, BatchOptions{capped, 0});
  std::size_t capped_answers = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(bytes(out[i]), bytes(signed_distance(c.a[i], c.b[i], capped)));
    capped_answers += bytes(out[i]) != bytes(signed_distance(c.a[i], c.b[i]));
  }
  EXPECT_GT(capped_answers, 0u);  // the cap changed some answers: it was passed
}

TEST(BatchPairs, BadSizesAndDirectionsAreRejected) {
  const Cases<2> c(1);
  std::vector<Distance<double, 2>> short_out(c.size() - 1);
  EXPECT_THROW((distance<double, 2>(c.a, c.b, short_out)), std::invalid_argument);
  std::vector<ContactGradient<double, 2>> out(c.size());
  const std::vector<double> t_max(c.size() - 1, 1.0);
  EXPECT_THROW((first_contact_gradient<double, 2>(c.a, std::span<const Vec<double, 2>>(c.va), c.b,
                                                  std::span<const Vec<double, 2>>(c.vb), t_max, out)),
               std::invalid_argument);
  std::vector<Vec<double, 2>> direction = c.direction;
  direction[2] = Vec<double, 2>::Zero();
  std::vector<ClosestApproachGradient<double, 2>> approach(c.size());
  expect_field([&] { closest_approach_gradient<double, 2>(c.a, c.b, direction, approach); }, "direction[2]");
  direction[2] = {1.0, std::nan("")};
  expect_field([&] { closest_approach_gradient<double, 2>(c.a, c.b, direction, approach); }, "direction[2]");
}

}  // namespace ELLIPSECT_UNITY_ID
}  // namespace
