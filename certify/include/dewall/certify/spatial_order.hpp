// The certifier's own numbering of the points: along a Z-order (Morton) curve,
// so that the points of neighbouring simplices sit side by side in memory and
// the facets filed under neighbouring vertices lie in neighbouring buckets.
// Only the order of the work changes: every decision is an exact predicate on
// the same points, and every report is given in the input's numbers. The same
// order finds the duplicate points: equal points share a cell, and only the
// points of a cell are compared (exactly).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "dewall/certify/uninitialized.hpp"
#include "dewall/kernel/serial_loop.hpp"
#include "dewall/kernel/sign.hpp"

namespace dewall::certify::detail {

/// Bit b of a byte at bit b·D.
template <int D>
inline constexpr std::array<std::uint64_t, 256> spread_byte = [] {
  std::array<std::uint64_t, 256> t{};
  for (std::size_t i = 0; i < 256; ++i)
    for (int b = 0; b < 8; ++b)
      if ((i >> b) & 1) t[i] |= std::uint64_t{1} << (b * D);
  return t;
}();

/// Spreads the low 16 bits of x: bit b to bit b·D.
template <int D>
constexpr std::uint64_t spread_bits(std::uint32_t x) {
  return spread_byte<D>[x & 255] | (spread_byte<D>[(x >> 8) & 255] << (8 * D));
}

/// The points in Z order of a grid of 2^(32/D) cells per axis over the
/// bounding box of the points for which `finite(i)` holds (the others go
/// first): each as its cell's key in the high 32 bits and its index in the
/// low ones, sorted (equal cells keep the input order). `coordinates(p)`
/// gives D doubles. `loop(count, f)` calls f(i, worker) for i in [0, count),
/// maybe at once: the points are cut into `parts` ranges (a few per thread, so
/// that a thread slowed by other work holds up no other), each keyed and
/// counted on its own. The order is the same for any loop and any number of parts.
/// Complexity: O(n), three passes of an 11-bit radix sort.
template <int D, class Point, class Coordinates, class Finite, class Loop = kernel::Serial_loop>
Uninitialized_vector<std::uint64_t> z_order_keys(std::span<const Point> points, Coordinates coordinates, Finite finite, Loop loop = {},
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
  Uninitialized_vector<std::uint64_t> a(n), b(n);
  loop(parts, [&](std::size_t k, unsigned) {
    for (auto [i, end] = range(k); i < end; ++i) {
      std::uint64_t key = 0;
      if (finite(i)) {
        const auto& x = coordinates(points[i]);
        // The bits of the cell's coordinates interleaved, the first axis's highest.
        for (int j = 0; j < D; ++j) {
          const double t = extent[j] > 0 ? (double(x[j]) * 0.5 - lo[j] * 0.5) / extent[j] : 0.0;
          key |= spread_bits<D>(static_cast<std::uint32_t>(std::min(t * cells, cells - 1))) << (D - 1 - j);
        }
      }
      a[i] = (key << 32) | i;
    }
  });
  // Three passes of 11 bits: the places a pass writes to stay in cache. Each
  // pass: every part counts its digits, then writes its keys where the counts
  // of the digits below and of the earlier parts end (stable).
  constexpr std::size_t digits = 2048;
  std::vector<std::array<std::size_t, digits>> next(parts);
  for (int shift : {32, 43, 54}) {
    loop(parts, [&](std::size_t k, unsigned) {
      next[k].fill(0);
      for (auto [i, end] = range(k); i < end; ++i) ++next[k][(a[i] >> shift) & (digits - 1)];
    });
    for (std::size_t d = 0, at = 0; d < digits; ++d)
      for (std::size_t k = 0; k < parts; ++k) {
        const std::size_t c = next[k][d];
        next[k][d] = at;
        at += c;
      }
    loop(parts, [&](std::size_t k, unsigned) {
      for (auto [i, end] = range(k); i < end; ++i) b[next[k][(a[i] >> shift) & (digits - 1)]++] = a[i];
    });
    a.swap(b);
  }
  return a;
}

/// The points' indices in Z order (z_order_keys without the keys).
template <int D, class Point, class Coordinates, class Finite, class Loop = kernel::Serial_loop>
std::vector<std::uint32_t> z_order(std::span<const Point> points, Coordinates coordinates, Finite finite, Loop loop = {},
                                   std::size_t parts = 1) {
  const auto a = z_order_keys<D>(points, coordinates, finite, loop, parts);
  std::vector<std::uint32_t> order(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) order[i] = static_cast<std::uint32_t>(a[i]);
  return order;
}

/// kernel::first_occurrences from the points' Z order (z_order_keys, with
/// `excluded(i)` for !finite(i)): for each point i, the smallest index with
/// the same coordinates (i itself when none is earlier; an excluded point
/// maps to itself). Equal points have equal coordinates, so one cell: only
/// the points of a cell are compared, by `compare` (a kernel's exact
/// lexicographic order), a few at a time, a crowded cell sorted.
/// Complexity: O(n) expected for spread points; O(s log s) comparisons for a cell of s points.
template <class Point, class Compare, class Excluded>
std::vector<std::uint32_t> first_occurrences_in_z_order(std::span<const Point> points, std::span<const std::uint64_t> sorted,
                                                        Compare compare, Excluded excluded) {
  const std::size_t n = points.size();
  std::vector<std::uint32_t> first(n);
  for (std::size_t i = 0; i < n; ++i) first[i] = static_cast<std::uint32_t>(i);
  std::vector<std::uint32_t> cell;
  for (std::size_t a = 0, b; a < sorted.size(); a = b) {
    for (b = a + 1; b < sorted.size() && (sorted[b] >> 32) == (sorted[a] >> 32);) ++b;
    if (b - a == 1) continue;
    cell.clear();
    for (std::size_t k = a; k < b; ++k)  // in increasing index
      if (const auto i = static_cast<std::uint32_t>(sorted[k]); !excluded(i)) cell.push_back(i);
    if (cell.size() <= 8) {
      // Each point against the earlier first occurrences: the earliest equal
      // point is one (nothing equal comes before it).
      for (std::size_t x = 1; x < cell.size(); ++x)
        for (std::size_t y = 0; y < x; ++y)
          if (first[cell[y]] == cell[y] && compare(points[cell[y]], points[cell[x]]) == kernel::EQUAL) {
            first[cell[x]] = cell[y];
            break;
          }
    } else {
      std::sort(cell.begin(), cell.end(), [&](std::uint32_t u, std::uint32_t v) {
        const auto c = compare(points[u], points[v]);
        return c != kernel::EQUAL ? c == kernel::SMALLER : u < v;
      });
      for (std::size_t x = 1; x < cell.size(); ++x)
        if (compare(points[cell[x - 1]], points[cell[x]]) == kernel::EQUAL) first[cell[x]] = first[cell[x - 1]];
    }
  }
  return first;
}

}  // namespace dewall::certify::detail
