// Seeded test and benchmark cases, shared by tests/, bench/ and the tools.
//
// Every case is built from (category, seed) alone, so a failing case is reproduced by
// its seed. Geometric constructions (tangent pairs, contact at a chosen time, grazing
// paths) only steer the mix towards hard cases; the truth always comes from the
// high-precision reference, never from the construction.
#pragma once

#include <ellipsect/shapes.hpp>

#include <Eigen/QR>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string_view>

namespace ellipsect::scenarios {

enum class Category {
  random,         // moderate shapes and distances, about half of the pairs overlap
  high_aspect,    // aspect ratios up to 1e4 (needles and discs)
  near_tangent,   // gap of +-1e-9 .. 1e-6 relative to the size, any orientation
  containment,    // one body inside the other, some close to internal tangency
  spheres,        // balls, equal radii, identical bodies
  scaled_small,   // a random case scaled by 1e-6
  scaled_large,   // a random case scaled by 1e6
  far_apart,      // bodies 1e4 sizes apart, moving towards each other or not
  zero_velocity,  // no relative motion
  grazing,        // relative path tangent at contact (double root), miss of +-1e-9 .. 0
};

inline constexpr std::array<Category, 10> all_categories = {
    Category::random,     Category::high_aspect,  Category::near_tangent, Category::containment,
    Category::spheres,    Category::scaled_small, Category::scaled_large, Category::far_apart,
    Category::zero_velocity, Category::grazing};

inline std::string_view name(Category c) {
  constexpr std::array<std::string_view, 10> names = {"random",       "high_aspect",  "near_tangent", "containment",
                                                      "spheres",      "scaled_small", "scaled_large", "far_apart",
                                                      "zero_velocity", "grazing"};
  return names[static_cast<int>(c)];
}

template <int N>
struct Case {
  Category category;
  std::uint64_t seed;
  Ellipsoid<double, N> a, b;
  Vec<double, N> va, vb;
  double t_max;  // may be +infinity
};

namespace detail {

using Rng = std::mt19937_64;

inline double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
inline double log_uniform(Rng& rng, double lo, double hi) {
  return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

template <int N>
Vec<double, N> unit_vector(Rng& rng) {
  std::normal_distribution<double> g;
  Vec<double, N> v;
  do {
    for (int i = 0; i < N; ++i) v[i] = g(rng);
  } while (v.norm() < 1e-3);
  return v.normalized();
}

template <int N>
Mat<double, N> rotation(Rng& rng) {
  if constexpr (N == 2) {
    const double t = uniform(rng, -M_PI, M_PI);
    Mat<double, 2> r;
    r << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
    return r;
  } else {
    const Vec<double, 4> q = unit_vector<4>(rng);
    return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  }
}

// A uniformly random rotation or reflection: the orthogonal factor of a Gaussian matrix's QR
// (Householder), for the clouds of the enclosing ellipsoid's tests and benchmark.
template <int N>
Mat<double, N> orthogonal(Rng& rng) {
  std::normal_distribution<double> g;
  Mat<double, N> a;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) a(i, j) = g(rng);
  const Eigen::HouseholderQR<Eigen::Matrix<double, N, N>> qr(a);
  return qr.householderQ();
}

// Radii with the given largest aspect ratio, log-uniform, overall size `size`.
template <int N>
Vec<double, N> radii(Rng& rng, double size, double max_aspect) {
  Vec<double, N> r;
  for (int i = 0; i < N; ++i) r[i] = size * log_uniform(rng, 1.0 / std::sqrt(max_aspect), std::sqrt(max_aspect));
  return r;
}

template <int N>
Ellipsoid<double, N> body(const Vec<double, N>& c, const Mat<double, N>& axes, const Vec<double, N>& r) {
  return Ellipsoid<double, N>::from_axes(c, axes, r);
}

// Center for body b (axes, radii given) so that it touches a at the boundary point with
// parameter direction u, then moved by gap (times b's size) along a's outward normal.
template <int N>
Vec<double, N> tangent_center(const Ellipsoid<double, N>& a, const Vec<double, N>& u, const Mat<double, N>& axes_b,
                              const Vec<double, N>& radii_b, double gap, Vec<double, N>* normal = nullptr) {
  const Vec<double, N> p = a.center() + a.axes() * a.radii().asDiagonal() * u;
  const Vec<double, N> n = (a.quadric() * (p - a.center())).normalized();
  const Mat<double, N> minv = axes_b * radii_b.cwiseAbs2().asDiagonal() * axes_b.transpose();
  const Vec<double, N> support = minv * n / std::sqrt(n.dot(minv * n));  // b's point with normal n, from its center
  if (normal != nullptr) *normal = n;
  return p + gap * radii_b.maxCoeff() * n + support;
}

template <int N>
Case<N> scaled(Case<N> c, double s) {
  c.a = body<N>(c.a.center() * s, c.a.axes(), c.a.radii() * s);
  c.b = body<N>(c.b.center() * s, c.b.axes(), c.b.radii() * s);
  c.va *= s;
  c.vb *= s;
  return c;
}

// Velocities aimed roughly at a collision (or not), with a random window.
template <int N>
void random_motion(Rng& rng, Case<N>& c) {
  const Vec<double, N> d = c.a.center() - c.b.center();
  const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
  const double speed = log_uniform(rng, 0.1, 10.0) * size;
  c.va = unit_vector<N>(rng) * speed * uniform(rng, 0.0, 0.5);
  Vec<double, N> aim = d.norm() > 0 ? Vec<double, N>(d.normalized()) : unit_vector<N>(rng);
  aim = (aim + unit_vector<N>(rng) * uniform(rng, 0.0, 0.8)).normalized();
  c.vb = c.va + aim * speed;
  c.t_max = uniform(rng, 0, 1) < 0.3 ? std::numeric_limits<double>::infinity() : uniform(rng, 0.5, 4.0) * (d.norm() + size) / speed;
}

// A pair touching at time t0 under the relative velocity `v_rel` = approach * (-n) +
// tangential part; returns the case with positions moved back to t = 0.
template <int N>
Case<N> contact_at(Rng& rng, Case<N> c, double t0, double sin_angle, double miss) {
  const Vec<double, N> u = unit_vector<N>(rng);
  Vec<double, N> n;
  const Vec<double, N> cb = tangent_center<N>(c.a, u, c.b.axes(), c.b.radii(), miss, &n);
  Vec<double, N> tangent = unit_vector<N>(rng);
  tangent = (tangent - tangent.dot(n) * n).normalized();
  const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
  const double speed = log_uniform(rng, 0.1, 10.0) * size;
  const double cos_angle = std::sqrt(std::max(0.0, 1 - sin_angle * sin_angle));
  const Vec<double, N> v_rel = speed * (-sin_angle * n + cos_angle * tangent);
  c.va = unit_vector<N>(rng) * speed * uniform(rng, 0.0, 0.5);
  c.vb = c.va + v_rel;
  c.a = body<N>(c.a.center() - t0 * c.va, c.a.axes(), c.a.radii());
  c.b = body<N>(cb - t0 * c.vb, c.b.axes(), c.b.radii());
  c.t_max = uniform(rng, 0, 1) < 0.3 ? std::numeric_limits<double>::infinity() : t0 * uniform(rng, 1.2, 3.0);
  return c;
}

}  // namespace detail

template <int N>
Case<N> make_case(Category category, std::uint64_t seed) {
  using namespace detail;
  Rng rng(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(category));
  Case<N> c{category, seed, body<N>(Vec<double, N>::Zero(), Mat<double, N>::Identity(), Vec<double, N>::Ones()),
            body<N>(Vec<double, N>::Zero(), Mat<double, N>::Identity(), Vec<double, N>::Ones()),
            Vec<double, N>::Zero(), Vec<double, N>::Zero(), 1.0};
  auto random_pair = [&](double aspect, double distance_factor) {
    const Vec<double, N> ra = radii<N>(rng, log_uniform(rng, 0.3, 3.0), aspect);
    const Vec<double, N> rb = radii<N>(rng, log_uniform(rng, 0.3, 3.0), aspect);
    const Vec<double, N> ca = unit_vector<N>(rng) * uniform(rng, 0, 5);
    const double reach = ra.maxCoeff() + rb.maxCoeff();
    c.a = body<N>(ca, rotation<N>(rng), ra);
    c.b = body<N>(ca + unit_vector<N>(rng) * reach * uniform(rng, 0, distance_factor), rotation<N>(rng), rb);
    random_motion(rng, c);
  };
  switch (category) {
    case Category::random:
    case Category::scaled_small:
    case Category::scaled_large:
      random_pair(10.0, 1.3);
      if (category == Category::scaled_small) c = scaled(c, 1e-6);
      if (category == Category::scaled_large) c = scaled(c, 1e6);
      break;
    case Category::high_aspect: {
      random_pair(1e4, 1.0);
      if (uniform(rng, 0, 1) < 0.5) {  // touching pairs of needles and discs, then moved
        const double gap = (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-9, 1e-1);
        c.b = body<N>(tangent_center<N>(c.a, unit_vector<N>(rng), c.b.axes(), c.b.radii(), gap), c.b.axes(),
                      c.b.radii());
        random_motion(rng, c);
      }
      break;
    }
    case Category::near_tangent: {
      random_pair(uniform(rng, 0, 1) < 0.3 ? 1e3 : 10.0, 1.0);
      const double gap = (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-9, 1e-6);
      c.b = body<N>(tangent_center<N>(c.a, unit_vector<N>(rng), c.b.axes(), c.b.radii(), gap), c.b.axes(),
                    c.b.radii());
      random_motion(rng, c);
      break;
    }
    case Category::containment: {
      const Vec<double, N> ra = radii<N>(rng, log_uniform(rng, 0.3, 3.0), 100.0);
      const Vec<double, N> rb = radii<N>(rng, ra.minCoeff() * uniform(rng, 0.05, 0.9), 10.0);
      c.a = body<N>(unit_vector<N>(rng), rotation<N>(rng), ra);
      const Vec<double, N> inside = c.a.axes() * ra.asDiagonal() * unit_vector<N>(rng) * uniform(rng, 0, 0.6);
      c.b = body<N>(c.a.center() + inside, rotation<N>(rng), rb);
      if (uniform(rng, 0, 1) < 0.5) std::swap(c.a, c.b);
      random_motion(rng, c);
      break;
    }
    case Category::spheres: {
      const double r = log_uniform(rng, 0.3, 3.0);
      const int kind = static_cast<int>(uniform(rng, 0, 4));
      const Vec<double, N> ra = kind == 0 ? Vec<double, N>::Constant(r) : radii<N>(rng, r, 10.0);
      const Vec<double, N> rb = kind <= 1 ? Vec<double, N>::Constant(r * (kind == 0 ? 1.0 : uniform(rng, 0.5, 2))) : ra;
      c.a = body<N>(unit_vector<N>(rng), rotation<N>(rng), ra);
      const double reach = ra.maxCoeff() + rb.maxCoeff();
      const Vec<double, N> cb = kind == 3 ? c.a.center() : Vec<double, N>(c.a.center() + unit_vector<N>(rng) * reach * uniform(rng, 0, 1.2));
      c.b = body<N>(cb, kind == 3 ? c.a.axes() : rotation<N>(rng), rb);  // kind 3: identical bodies
      random_motion(rng, c);
      break;
    }
    case Category::far_apart: {
      random_pair(10.0, 1.0);
      const double size = c.a.radii().maxCoeff() + c.b.radii().maxCoeff();
      c.b = body<N>(c.a.center() + unit_vector<N>(rng) * size * log_uniform(rng, 1e3, 1e4), c.b.axes(), c.b.radii());
      random_motion(rng, c);
      c.vb = c.va + (c.vb - c.va).norm() * ((c.a.center() - c.b.center()).normalized() +
                                            unit_vector<N>(rng) * uniform(rng, 0, 2e-4)).normalized();
      c.t_max = std::numeric_limits<double>::infinity();
      break;
    }
    case Category::zero_velocity:
      random_pair(100.0, 1.3);
      c.vb = c.va;
      break;
    case Category::grazing: {
      random_pair(uniform(rng, 0, 1) < 0.3 ? 1e3 : 10.0, 1.0);
      const double miss = uniform(rng, 0, 1) < 0.2 ? 0.0 : (uniform(rng, 0, 1) < 0.5 ? -1 : 1) * log_uniform(rng, 1e-9, 1e-3);
      c = contact_at(rng, c, log_uniform(rng, 0.1, 10.0), 0.0, miss);
      break;
    }
  }
  return c;
}

// Pairs that touch at a known time t0 with a chosen approach angle (for contact tests):
// sin_angle = 1 is head-on, small values approach grazing.
template <int N>
Case<N> make_contact_case(Category category, std::uint64_t seed, double sin_angle_min) {
  Case<N> c = make_case<N>(category, seed);
  detail::Rng rng(seed ^ 0xC0FFEEull);
  const double t0 = detail::log_uniform(rng, 1e-3, 1e2);
  const double s = detail::log_uniform(rng, sin_angle_min, 1.0);
  return detail::contact_at(rng, c, t0, s, 0.0);
}

}  // namespace ellipsect::scenarios
