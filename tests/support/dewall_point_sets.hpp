// Point families for the triangulator tests: random, lattices, cospherical
// integer points, parallel planes, and rescaled copies. Randomness comes from
// an explicit, seeded engine (the caller logs the seed).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/point_array.hpp"

namespace dewall::test {

template <int D>
std::vector<kernel::Point_d<D>> uniform(std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<kernel::Point_d<D>> p(n);
  for (auto& q : p)
    for (int j = 0; j < D; ++j) q[j] = u(rng);
  return p;
}

/// The integer lattice {0 … k−1}^D with k^D ≈ n (every point ties with many):
/// the library's `grid` generator (`dewall generate grid N`), first coordinate
/// fastest.
template <int D>
std::vector<kernel::Point_d<D>> lattice(std::size_t n) {
  return kernel::points_from_coordinates<D>(io::generate_points(io::Point_kind::grid, n, D, 0).coordinates);
}

/// n random points of the lattice {0 … k−1}^D: duplicates and ties, random order.
template <int D>
std::vector<kernel::Point_d<D>> lattice_samples(std::size_t n, int k, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> u(0, k - 1);
  std::vector<kernel::Point_d<D>> p(n);
  for (auto& q : p)
    for (int j = 0; j < D; ++j) q[j] = u(rng);
  return p;
}

/// All integer points on the sphere of squared radius r² about the origin
/// (r² = 25 in 2D, 9 in 3D, 5 in 4D, 2 above), optionally with the centre.
template <int D>
std::vector<kernel::Point_d<D>> cospherical(bool with_centre) {
  const int r2 = D == 2 ? 25 : D == 3 ? 9 : D == 4 ? 5 : 2;
  const int r = static_cast<int>(std::sqrt(static_cast<double>(r2)));
  std::vector<kernel::Point_d<D>> p;
  std::array<int, D> c;
  c.fill(-r);
  for (;;) {
    int s = 0;
    for (int v : c) s += v * v;
    if (s == r2) {
      kernel::Point_d<D> q;
      for (int j = 0; j < D; ++j) q[j] = c[j];
      p.push_back(q);
    }
    int j = 0;
    while (j < D && ++c[j] > r) c[j++] = -r;
    if (j == D) break;
  }
  if (with_centre) p.push_back(kernel::Point_d<D>{});
  return p;
}

/// n points on `count` parallel hyperplanes x_{D−1} = 0, 1, …, with
/// coordinates on a coarse lattice within each plane (coplanar and cocircular).
template <int D>
std::vector<kernel::Point_d<D>> planes(std::size_t n, int count, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> plane(0, count - 1), coord(0, 6);
  std::vector<kernel::Point_d<D>> p(n);
  for (auto& q : p) {
    for (int j = 0; j + 1 < D; ++j) q[j] = coord(rng);
    q[D - 1] = 3 * plane(rng);
  }
  return p;
}

template <int D>
std::vector<kernel::Point_d<D>> scaled(std::vector<kernel::Point_d<D>> p, double scale, double offset) {
  for (auto& q : p)
    for (int j = 0; j < D; ++j) q[j] = offset + q[j] * scale;
  return p;
}

}  // namespace dewall::test
