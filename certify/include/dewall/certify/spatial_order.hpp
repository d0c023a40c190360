// The certifier's own numbering of the points: along a Z-order (Morton) curve,
// so that the points of neighbouring simplices sit side by side in memory and
// the facets filed under neighbouring vertices lie in neighbouring buckets.
// Only the order of the work changes: every decision is an exact predicate on
// the same points, and every report is given in the input's numbers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace dewall::certify::detail {

/// The points' indices in Z order of a grid of 2^(32/D) cells per axis over the
/// bounding box of the points for which `finite(i)` holds (the others go
/// first); equal cells keep the input order. `coordinates(p)` gives D doubles.
/// Complexity: O(n), two passes of a 16-bit radix sort.
template <int D, class Point, class Coordinates, class Finite>
std::vector<std::uint32_t> z_order(std::span<const Point> points, Coordinates coordinates, Finite finite) {
  const std::size_t n = points.size();
  std::array<double, D> lo, hi;
  lo.fill(INFINITY);
  hi.fill(-INFINITY);
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite(i)) continue;
    const auto& x = coordinates(points[i]);
    for (int j = 0; j < D; ++j) {
      lo[j] = std::min(lo[j], double(x[j]));
      hi[j] = std::max(hi[j], double(x[j]));
    }
  }
  constexpr int bits = 32 / D;
  constexpr double cells = double(1u << bits);
  // Halved coordinates: their differences cannot overflow, so that t below is
  // in [0, 1] (rounding is monotone) and never NaN, for any finite points.
  std::array<double, D> extent;
  for (int j = 0; j < D; ++j) extent[j] = hi[j] * 0.5 - lo[j] * 0.5;
  // Key in the high 32 bits, index in the low ones.
  std::vector<std::uint64_t> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t key = 0;
    if (finite(i)) {
      const auto& x = coordinates(points[i]);
      std::array<std::uint32_t, D> q;
      for (int j = 0; j < D; ++j) {
        const double t = extent[j] > 0 ? (double(x[j]) * 0.5 - lo[j] * 0.5) / extent[j] : 0.0;
        q[j] = static_cast<std::uint32_t>(std::min(t * cells, cells - 1));
      }
      for (int bit = bits - 1; bit >= 0; --bit)
        for (int j = 0; j < D; ++j) key = (key << 1) | ((q[j] >> bit) & 1u);
    }
    a[i] = (std::uint64_t{key} << 32) | i;
  }
  for (int shift : {32, 48}) {
    std::vector<std::size_t> start(65537, 0);
    for (std::uint64_t x : a) ++start[((x >> shift) & 0xffff) + 1];
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    for (std::uint64_t x : a) b[start[(x >> shift) & 0xffff]++] = x;
    a.swap(b);
  }
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(a[i]);
  return order;
}

}  // namespace dewall::certify::detail
