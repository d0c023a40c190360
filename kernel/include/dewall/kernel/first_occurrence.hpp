// Duplicate points: which input point stands for each point. Duplicates are one
// vertex, the first occurrence (CGAL's insert keeps the vertex already there),
// so dewall, the certifier and the Python bindings all ask the same question:
// for point i, the earliest point with the same coordinates.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "dewall/kernel/sign.hpp"

namespace dewall::kernel {

/// For each point i, the smallest index j with the same coordinates as point i
/// (i itself when no earlier point equals it), equality decided by `compare`, a
/// kernel's exact lexicographic order (Compare_lexicographically_d: −0 and +0
/// alike). A point for which `excluded(i)` is true (a non-finite one, say) is
/// compared with nothing and maps to itself.
/// \pre points.size() < 2^32 (indices are 32-bit, as everywhere in the project).
/// Complexity: O(n log n) comparisons.
template <class Point, class Compare, class Excluded>
std::vector<std::uint32_t> first_occurrences(std::span<const Point> points, Compare compare, Excluded excluded) {
  std::vector<std::uint32_t> first(points.size());
  std::iota(first.begin(), first.end(), std::uint32_t{0});
  std::vector<std::uint32_t> order;
  order.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!excluded(i)) order.push_back(static_cast<std::uint32_t>(i));
  // Stable: within a run of equal points the earliest input index comes first.
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return compare(points[a], points[b]) == SMALLER; });
  for (std::size_t i = 1; i < order.size(); ++i)
    if (compare(points[order[i - 1]], points[order[i]]) == EQUAL) first[order[i]] = first[order[i - 1]];
  return first;
}

/// As above, every point compared.
template <class Point, class Compare>
std::vector<std::uint32_t> first_occurrences(std::span<const Point> points, Compare compare) {
  return first_occurrences(points, compare, [](std::size_t) { return false; });
}

}  // namespace dewall::kernel
