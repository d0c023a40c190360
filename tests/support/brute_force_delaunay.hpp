// The one brute-force Delaunay check of the tests and the triangulate fuzzer:
// every simplex against every distinct point with the kernel's exact perturbed
// predicate alone — no search structure, no filter of the algorithm, nothing
// of the certifier — so it stays independent of both. O(m·n): small inputs.
// Everything else (a triangulation of the hull, canonical) is the certifier's.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/side_of_sphere.hpp"

namespace dewall::test {

/// The first occurrence of each distinct point (by exact coordinates).
template <int D>
std::vector<std::size_t> first_occurrences_by_brute_force(const std::vector<kernel::Point_d<D>>& points) {
  std::map<std::array<double, D>, std::size_t> first;
  for (std::size_t i = points.size(); i-- > 0;) first[points[i].x] = i;
  std::vector<std::size_t> indices;
  for (const auto& entry : first) indices.push_back(entry.second);
  std::sort(indices.begin(), indices.end());
  return indices;
}

/// The first (simplex, point) pair that breaks the Delaunay property: a
/// simplex that is not positively oriented (point = its first vertex), or a
/// distinct point, not a vertex, inside the simplex's perturbed sphere.
/// Nothing when every simplex passes.
template <int D, class Simplices>
std::optional<std::pair<std::size_t, std::size_t>> brute_force_violation(const std::vector<kernel::Point_d<D>>& points,
                                                                         const Simplices& simplices) {
  const auto distinct = first_occurrences_by_brute_force<D>(points);
  for (std::size_t r = 0; r < simplices.size(); ++r) {
    const auto& s = simplices[r];
    std::array<const kernel::Point_d<D>*, D + 2> refs;
    std::array<const kernel::Point_d<D>*, D + 1> simplex;
    for (int i = 0; i <= D; ++i) refs[static_cast<std::size_t>(i)] = simplex[static_cast<std::size_t>(i)] = &points[s[i]];
    if (kernel::orientation_d<D>(simplex) != kernel::POSITIVE) return std::pair{r, std::size_t{s[0]}};
    for (std::size_t q : distinct) {
      if (std::find(s.begin(), s.end(), q) != s.end()) continue;
      refs[D + 1] = &points[q];
      if (kernel::side_of_oriented_sphere_d_sos<D>(refs) != kernel::ON_NEGATIVE_SIDE) return std::pair{r, q};
    }
  }
  return std::nullopt;
}

}  // namespace dewall::test
