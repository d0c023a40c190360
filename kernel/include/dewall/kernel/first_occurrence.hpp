// Duplicate points: which input point stands for each point. Duplicates are one
// vertex, the first occurrence (CGAL's insert keeps the vertex already there),
// so dewall, the certifier and the Python bindings all ask the same question:
// for point i, the earliest point with the same coordinates.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "dewall/kernel/sign.hpp"
#include "dewall/kernel/serial_loop.hpp"

namespace dewall::kernel {

/// A 64-bit hash of a point's coordinates (a range of doubles), equal for
/// equal points: −0 hashes as +0 (they compare equal); on the bits, so that
/// neither the rounding mode nor a user's -ffast-math can change it. Used by
/// first_occurrences' table and by the BRIO order's rounds, which must put
/// equal points in one round (dewall/detail/incremental/brio_order.hpp).
template <class Coordinates>
constexpr std::uint64_t coordinate_hash(const Coordinates& coordinates) {
  std::uint64_t h = 0x9e3779b97f4a7c15u;
  for (double c : coordinates) {
    std::uint64_t bits = std::bit_cast<std::uint64_t>(c);
    if ((bits << 1) == 0) bits = 0;
    h ^= bits;
    h *= 0xbf58476d1ce4e5b9u;
    h ^= h >> 31;
  }
  // A full 64-bit finalizer (MurmurHash3's fmix64 constants): every bit of
  // every coordinate reaches the slot bits, so lattices and dyadic
  // coordinates do not pile up in a few slots.
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdu;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53u;
  h ^= h >> 33;
  return h;
}

/// For each point i, the smallest index j with the same coordinates as point i
/// (i itself when no earlier point equals it), equality decided by `compare`, a
/// kernel's exact lexicographic order (Compare_lexicographically_d: −0 and +0
/// alike). `coordinates(p)`: the point's approximate coordinates (a kernel's
/// Approximate_coordinates_d), which must be equal for equal points (true of
/// doubles; a lazy exact kernel's approximations need not be); they only place
/// points in a hash table, `compare` decides. A point for which `excluded(i)` is true
/// (a non-finite one, say) is compared with nothing and maps to itself.
/// `max_table_bytes` (0: no limit) bounds the hash tables: above it the points
/// are taken in passes, each the points whose hash starts with the pass's bits
/// (equal points have equal hashes, so they meet in one pass), at the cost of
/// hashing every point once more per pass. At most 2^16 passes: a bound below
/// 16 bytes per 2^16 points is exceeded.
/// `loop(count, f)` calls f(i, worker) for i in [0, count), on up to `workers`
/// threads (worker < workers): without a bound, the points are taken in as
/// many passes as workers, at once, each with its worker's table (together the
/// size of one). The answer is the same for any loop.
/// \pre points.size() < 2^32 (indices are 32-bit, as everywhere in the project).
/// Complexity: O(n) expected comparisons, one table of 2n–4n 8-byte slots (a sort
/// of indices cost far more: docs/engines.md), or of max_table_bytes and
/// O(n · 16n / max_table_bytes) hashes.
template <class Point, class Compare, class Coordinates, class Excluded, class Loop = Serial_loop>
std::vector<std::uint32_t> first_occurrences(std::span<const Point> points, Compare compare, Coordinates coordinates,
                                             Excluded excluded, std::size_t max_table_bytes = 0, Loop loop = {},
                                             unsigned workers = 1) {
  const std::size_t n = points.size();
  // Threads only for enough points to pay for them and without a bound on the
  // tables (under one, the passes are many and each reads every point: they
  // are bound by the memory's bandwidth, not by a core); then every part of
  // the work goes through `loop`, else through a serial one.
  const std::size_t concurrent = n >= 8192 && max_table_bytes == 0 ? std::max(1u, workers) : 1;
  const auto run = [&](std::size_t count, auto&& f) {
    if (concurrent > 1) loop(count, f);
    else Serial_loop{}(count, f);
  };
  std::vector<std::uint32_t> first(n);
  const std::size_t parts = concurrent;
  const auto part = [&](std::size_t k) { return std::pair{n * k / parts, n * (k + 1) / parts}; };
  run(parts, [&](std::size_t k, unsigned) {
    for (auto [i, end] = part(k); i < end; ++i) first[i] = static_cast<std::uint32_t>(i);
  });
  const auto hash_of = [&](std::size_t i) { return coordinate_hash(coordinates(points[i])); };
  // Passes: a power of two, the pass of a hash its top bits. The table of a
  // pass is sized for the points the pass really has (counted first), so
  // that a skewed split cannot fill it.
  constexpr std::size_t slot_bytes = sizeof(std::uint64_t);
  int pass_bits = 0;
  while ((std::size_t{1} << pass_bits) < concurrent) ++pass_bits;
  while (max_table_bytes != 0 && pass_bits < 16 && std::bit_ceil(2 * (n >> pass_bits) + 2) * slot_bytes > max_table_bytes)
    ++pass_bits;
  const std::size_t passes = std::size_t{1} << pass_bits;
  const auto pass_of = [&](std::uint64_t hash) {
    return pass_bits == 0 ? std::size_t{0} : static_cast<std::size_t>(hash >> (64 - pass_bits));
  };
  std::vector<std::size_t> in_pass(passes, 0);
  if (passes == 1) {
    in_pass[0] = n;
  } else {
    std::vector<std::vector<std::size_t>> counted(parts, std::vector<std::size_t>(passes, 0));
    run(parts, [&](std::size_t k, unsigned) {
      for (auto [i, end] = part(k); i < end; ++i)
        if (!excluded(i)) ++counted[k][pass_of(hash_of(i))];
    });
    for (const auto& c : counted)
      for (std::size_t p = 0; p < passes; ++p) in_pass[p] += c[p];
  }
  // Open addressing with linear probing. A slot holds, in its low 32 bits, 1 +
  // the index of the first occurrence of its point (0: empty), and in its
  // high 32 bits the high half of that point's hash: a probe compares points
  // only when those agree, because each comparison reads an earlier point at
  // random, a cache miss. Points are entered in input order, so the first
  // equal point a probe meets is the earliest.
  const std::size_t slots = std::bit_ceil(2 * *std::max_element(in_pass.begin(), in_pass.end()) + 2), mask = slots - 1;
  constexpr std::uint64_t index_bits = 0xffffffffu, tag_bits = ~index_bits;
  std::vector<std::vector<std::uint64_t>> tables(concurrent);
  run(passes, [&](std::size_t pass, unsigned worker) {
    if (in_pass[pass] == 0) return;
    std::vector<std::uint64_t>& table = tables[worker];
    if (table.empty()) table.resize(slots);
    else std::fill(table.begin(), table.end(), 0);
    // The slots are random, each a cache miss: they are hashed and asked for
    // `ahead` points in advance (measured: the probes were most of the time).
    constexpr std::size_t ahead = 16;
    std::array<std::uint64_t, ahead> upcoming{};
    for (std::size_t i = 0; i < std::min(n, ahead); ++i) {
      upcoming[i] = hash_of(i);
      __builtin_prefetch(&table[upcoming[i] & mask]);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t hash = upcoming[i % ahead];
      if (i + ahead < n) {
        upcoming[i % ahead] = hash_of(i + ahead);
        if (pass_of(upcoming[i % ahead]) == pass) __builtin_prefetch(&table[upcoming[i % ahead] & mask]);
      }
      if (pass_of(hash) != pass || excluded(i)) continue;
      const std::uint64_t tag = hash & tag_bits;
      for (std::size_t s = hash & mask;; s = (s + 1) & mask) {
        if (table[s] == 0) {
          table[s] = tag | (i + 1);
          break;
        }
        if ((table[s] & tag_bits) != tag) continue;  // a different point: its hash differs
        const auto j = static_cast<std::uint32_t>((table[s] & index_bits) - 1);
        if (compare(points[j], points[i]) == EQUAL) {
          first[i] = j;
          break;
        }
      }
    }
  });
  return first;
}

/// As above, every point compared.
template <class Point, class Compare, class Coordinates>
std::vector<std::uint32_t> first_occurrences(std::span<const Point> points, Compare compare, Coordinates coordinates) {
  return first_occurrences(points, compare, coordinates, [](std::size_t) { return false; });
}

}  // namespace dewall::kernel
