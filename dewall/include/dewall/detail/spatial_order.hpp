// The insertion order of the incremental engine (incremental_delaunay.hpp):
// biased randomized insertion order (BRIO; Amenta, Choi, Rote, "Incremental
// constructions con BRIO", SoCG 2003) with each round along a Hilbert curve.
//
// Why: an incremental Delaunay construction spends its time locating each new
// point (a walk from the last cell created) and in cache misses on the cells it
// touches. Consecutive points close in space make both short; the random rounds
// keep the cavities small in expectation (a pure curve order can build long
// thin cells first, on a lattice for example).
//
// 1. A seeded random permutation (our own generator: the order, hence the
//    output's cell order, is the same on every platform and standard library).
// 2. Rounds: the last three quarters of the permutation are the last round, the
//    rest is split again the same way, down to rounds of `smallest_round` points
//    (CGAL's multiscale sort uses the same ratio).
// 3. Each round sorted by the Hilbert index of its points (J. Skilling,
//    "Programming the Hilbert curve", AIP Conf. Proc. 707, 2004: the transposed
//    index from the axes, then the bits interleaved), computed on a grid of
//    2^(63/D) cells per axis over the points' bounding box; every other round
//    runs the curve backwards, so that each round starts near where the last
//    one ended.
// Floating point only ranks here: the order changes the time, never the
// triangulation (which is a function of the point set).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace dewall::detail {

/// Skilling's transform: the D coordinates of a grid cell (each `bits` bits)
/// become the Hilbert index of the cell, interleaved into one integer
/// (D·bits ≤ 64).
template <int D>
std::uint64_t hilbert_index(std::array<std::uint32_t, D> x, int bits) {
  // Axes to transposed index: undo the excess work of the Gray code.
  for (std::uint32_t q = std::uint32_t{1} << (bits - 1); q > 1; q >>= 1) {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < D; ++i) {
      if (x[i] & q) {
        x[0] ^= p;  // invert the low bits of the first axis
      } else {
        const std::uint32_t t = (x[0] ^ x[i]) & p;  // exchange the low bits
        x[0] ^= t;
        x[i] ^= t;
      }
    }
  }
  // Gray encode.
  for (int i = 1; i < D; ++i) x[i] ^= x[i - 1];
  std::uint32_t t = 0;
  for (std::uint32_t q = std::uint32_t{1} << (bits - 1); q > 1; q >>= 1)
    if (x[D - 1] & q) t ^= q - 1;
  for (int i = 0; i < D; ++i) x[i] ^= t;
  // Interleave: bit b of axis i is bit b·D + (D − 1 − i) of the index.
  std::uint64_t index = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int i = 0; i < D; ++i) index = index << 1 | ((x[i] >> b) & 1u);
  return index;
}

/// A small, fast, seeded generator (splitmix64): the same sequence everywhere.
struct Splitmix64 {
  std::uint64_t state;
  std::uint64_t operator()() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, n), n > 0 (Lemire's multiply-shift; its bias below 2^-32 only shapes the order).
  std::uint32_t below(std::uint32_t n) {
    return static_cast<std::uint32_t>(((*this)() >> 32) * n >> 32);
  }
};

/// The BRIO order of `count` points: a permutation of 0 … count − 1.
/// `coords(i)` gives point i's coordinates (an array of D doubles, finite).
/// Deterministic: a function of the coordinates and `seed`.
template <int D, class Coords>
std::vector<std::uint32_t> brio_order(std::size_t count, Coords&& coords, std::size_t smallest_round = 1000,
                                      std::uint64_t seed = 0x5eed) {
  std::vector<std::uint32_t> order(count);
  for (std::size_t i = 0; i < count; ++i) order[i] = static_cast<std::uint32_t>(i);
  if (count < 2) return order;
  Splitmix64 random{seed};
  for (std::size_t i = count - 1; i > 0; --i)
    std::swap(order[i], order[random.below(static_cast<std::uint32_t>(i + 1))]);

  std::array<double, D> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < count; ++i) {
    const auto& x = coords(i);
    for (int j = 0; j < D; ++j) {
      lo[j] = std::min(lo[j], x[j]);
      hi[j] = std::max(hi[j], x[j]);
    }
  }
  constexpr int bits = 63 / D > 31 ? 31 : 63 / D;
  const double cells = static_cast<double>((std::uint32_t{1} << bits) - 1);
  std::array<double, D> scale;
  for (int j = 0; j < D; ++j) {
    // (x − lo)·scale ≤ cells even after rounding: hi − lo rounds up at most
    // relatively 2^-53 and the product is then clamped.
    const double extent = hi[j] - lo[j];
    scale[j] = extent > 0 && extent < std::numeric_limits<double>::infinity() ? cells / extent : 0;
  }
  auto key = [&](std::uint32_t i) {
    const auto& x = coords(i);
    std::array<std::uint32_t, D> cell;
    for (int j = 0; j < D; ++j) {
      double t = (x[j] - lo[j]) * scale[j];
      t = t < 0 || !(t == t) ? 0 : t > cells ? cells : t;  // overflowing differences (|x| near 2^1023)
      cell[j] = static_cast<std::uint32_t>(t);
    }
    return hilbert_index<D>(cell, bits);
  };

  // Round boundaries, from the end: [first, end) is the last round not yet sorted.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  std::size_t end = count;
  bool backwards = false;
  std::vector<std::pair<std::size_t, std::size_t>> rounds;
  while (end > 0) {
    const std::size_t first = end <= smallest_round ? 0 : end / 4;
    rounds.emplace_back(first, end);
    end = first;
  }
  // Sorted from the first round on, so that the direction alternates in insertion order.
  for (auto r = rounds.rbegin(); r != rounds.rend(); ++r) {
    const auto [first, last] = *r;
    keyed.resize(last - first);
    for (std::size_t k = first; k < last; ++k) keyed[k - first] = {key(order[k]), order[k]};
    std::sort(keyed.begin(), keyed.end());
    if (backwards) std::reverse(keyed.begin(), keyed.end());
    for (std::size_t k = first; k < last; ++k) order[k] = keyed[k - first].second;
    backwards = !backwards;
  }
  return order;
}

}  // namespace dewall::detail
