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
#include <utility>
#include <vector>

#include "dewall/kernel/serial_loop.hpp"

namespace dewall::certify::detail {

/// The points' indices in Z order of a grid of 2^(32/D) cells per axis over the
/// bounding box of the points for which `finite(i)` holds (the others go
/// first); equal cells keep the input order. `coordinates(p)` gives D doubles.
/// `loop(count, f)` calls f(i, worker) for i in [0, count), maybe at once: the
/// points are cut into `parts` ranges (a few per thread, so that a thread slowed
/// by other work holds up no other), each keyed and counted on its own. The
/// order is the same for any loop and any number of parts.
/// Complexity: O(n), two passes of a 16-bit radix sort.
template <int D, class Point, class Coordinates, class Finite, class Loop = kernel::Serial_loop>
std::vector<std::uint32_t> z_order(std::span<const Point> points, Coordinates coordinates, Finite finite, Loop loop = {},
                                   std::size_t parts = 1) {
  const std::size_t n = points.size();
  parts = std::clamp<std::size_t>(n / 65536, 1, std::max<std::size_t>(parts, 1));
  const auto range = [&](std::size_t k) { return std::pair{n * k / parts, n * (k + 1) / parts}; };
  std::vector<std::array<double, D>> part_lo(parts), part_hi(parts);
  loop(parts, [&](std::size_t k, unsigned) {
    std::array<double, D> lo, hi;
    lo.fill(INFINITY);
    hi.fill(-INFINITY);
    for (auto [i, end] = range(k); i < end; ++i) {
      if (!finite(i)) continue;
      const auto& x = coordinates(points[i]);
      for (int j = 0; j < D; ++j) {
        lo[j] = std::min(lo[j], double(x[j]));
        hi[j] = std::max(hi[j], double(x[j]));
      }
    }
    part_lo[k] = lo;
    part_hi[k] = hi;
  });
  std::array<double, D> lo = part_lo[0], hi = part_hi[0];
  for (std::size_t k = 1; k < parts; ++k)
    for (int j = 0; j < D; ++j) {
      lo[j] = std::min(lo[j], part_lo[k][j]);
      hi[j] = std::max(hi[j], part_hi[k][j]);
    }
  constexpr int bits = 32 / D;
  constexpr double cells = double(1u << bits);
  // Halved coordinates: their differences cannot overflow, so that t below is
  // in [0, 1] (rounding is monotone) and never NaN, for any finite points.
  std::array<double, D> extent;
  for (int j = 0; j < D; ++j) extent[j] = hi[j] * 0.5 - lo[j] * 0.5;
  // Key in the high 32 bits, index in the low ones.
  std::vector<std::uint64_t> a(n), b(n);
  loop(parts, [&](std::size_t k, unsigned) {
    for (auto [i, end] = range(k); i < end; ++i) {
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
  });
  // Each pass: every part counts its digits, then writes its keys where the
  // counts of the digits below and of the earlier parts end (stable).
  constexpr std::size_t digits = 65536;
  std::vector<std::vector<std::size_t>> next(parts, std::vector<std::size_t>(digits));
  for (int shift : {32, 48}) {
    loop(parts, [&](std::size_t k, unsigned) {
      std::fill(next[k].begin(), next[k].end(), 0);
      for (auto [i, end] = range(k); i < end; ++i) ++next[k][(a[i] >> shift) & 0xffff];
    });
    for (std::size_t d = 0, at = 0; d < digits; ++d)
      for (std::size_t k = 0; k < parts; ++k) {
        const std::size_t c = next[k][d];
        next[k][d] = at;
        at += c;
      }
    loop(parts, [&](std::size_t k, unsigned) {
      for (auto [i, end] = range(k); i < end; ++i) b[next[k][(a[i] >> shift) & 0xffff]++] = a[i];
    });
    a.swap(b);
  }
  std::vector<std::uint32_t> order(n);
  loop(parts, [&](std::size_t k, unsigned) {
    for (auto [i, end] = range(k); i < end; ++i) order[i] = static_cast<std::uint32_t>(a[i]);
  });
  return order;
}

}  // namespace dewall::certify::detail
