// The starting state of the hard-body examples: identical bodies on a lattice in a periodic
// box, for the library's event-driven HardBodies (packing.hpp).
#pragma once

#include <ellipsect/packing.hpp>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace hard_bodies {

using namespace ellipsect;

// Identical bodies of radii `radii` on a lattice of n^N sites, spaced so that the packing
// fraction is phi, aligned, with random velocities (zero total momentum) and spins; masses 1.
// `expansion`: the rate of the scale of the radii (0: rigid bodies).
template <int N>
HardBodies<N> lattice(int n, const Vec<double, N>& radii, double phi, unsigned seed, double expansion = 0.0) {
  const double volume = N == 2 ? M_PI * radii.prod() : 4.0 / 3.0 * M_PI * radii.prod();
  const double cell = std::pow(volume / phi / (std::pow(2.0, N) * radii.prod()), 1.0 / N);  // spacing / diameter
  if (!(cell > 1.0)) throw std::invalid_argument("packing fraction too high for an aligned lattice");
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  PeriodicBox<N> box;
  for (int k = 0; k < N; ++k) box.size[k] = n * 2.0 * radii[k] * cell;
  int sites = 1;
  for (int k = 0; k < N; ++k) sites *= n;
  std::vector<Ellipsoid<double, N>> bodies;
  std::vector<RigidMotion<double, N>> motions(sites);
  Vec<double, N> total = Vec<double, N>::Zero();
  for (int s = 0; s < sites; ++s) {
    Vec<double, N> c;
    for (int k = 0, code = s; k < N; ++k, code /= n) c[k] = (code % n + 0.5) * 2.0 * radii[k] * cell;
    bodies.push_back(Ellipsoid<double, N>::from_axes(c, Mat<double, N>::Identity(), radii));
    for (int k = 0; k < N; ++k) motions[s].velocity[k] = normal(rng);
    if constexpr (N == 2)
      motions[s].angular_velocity = normal(rng);
    else
      motions[s].angular_velocity = Vec<double, 3>(normal(rng), normal(rng), normal(rng));
    total += motions[s].velocity;
  }
  for (auto& m : motions) m.velocity -= total / double(sites);
  return HardBodies<N>(bodies, motions, box, 0.5, expansion);
}

}  // namespace hard_bodies
