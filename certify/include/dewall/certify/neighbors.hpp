// The simplex across each facet of a triangulation (scipy's `neighbors`), from
// the facet grouping the certifier matches facets with (face_grouping.hpp).
// Topology only: nothing here knows the kernel.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include "dewall/certify/face_grouping.hpp"

namespace dewall::certify {

/// Fills out[r][j] with the row of the simplex that shares the facet of
/// simplex r opposite its vertex j, or −1 when no other simplex has that facet
/// (a facet of the convex hull, for a triangulation of the points).
/// \pre every index < vertex_count; no row repeats a vertex;
/// out.size() == simplices.size(); Index is a signed integer type that holds
/// every row number.
/// \throws std::invalid_argument when a facet belongs to more than two
/// simplices (not a triangulation; certify() says what else is wrong).
/// Complexity: O(m·(D + 1) + vertex_count) plus small sorts, m simplices.
/// `progress(fraction)`, when given, is told the share done every few
/// thousand vertices; what it throws stops the work (and is passed on).
template <int D, class Index, class Progress = void (*)(double)>
void neighbors(std::size_t vertex_count, std::span<const std::array<std::uint32_t, D + 1>> simplices,
               std::span<std::array<Index, D + 1>> out, Progress&& progress = [](double) {}) {
  static_assert(std::numeric_limits<Index>::is_signed, "−1 marks a hull facet");
  for (auto& row : out) row.fill(-1);
  detail::group_faces<D + 1>(vertex_count, simplices, [&](std::span<const detail::Face_ref> g) {
    if (g.size() > 2)
      throw std::invalid_argument("not a triangulation: simplices " + std::to_string(g[0].row) + ", " +
                                  std::to_string(g[1].row) + " and " + std::to_string(g[2].row) +
                                  " share a facet");
    if (g.size() == 2) {
      out[g[0].row][static_cast<std::size_t>(g[0].position)] = static_cast<Index>(g[1].row);
      out[g[1].row][static_cast<std::size_t>(g[1].position)] = static_cast<Index>(g[0].row);
    }
  }, progress);
}

}  // namespace dewall::certify
