// The whole triangulation for any kernel: input checks, the point set, the
// DeWall recursion, the simplices mapped back to input indices. dewall.hpp
// calls it for a user's kernel; the compiled library (dewall/src/) instantiates
// it for Filtered_kernel_d with the project's flags.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dewall/detail/input.hpp"
#include "dewall/detail/point_set.hpp"
#include "dewall/detail/region.hpp"
#include "dewall/detail/wall.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/options.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// Appends the Delaunay simplices of `points` (input indices, positively
/// oriented, in DeWall's depth-first order) to `simplices`, and the recursion
/// level of the wall that built each one to `wall_levels` when it is given.
/// `budget`, when given, is charged by every search (a copy per task).
/// `regions`, when given, triangulates the regions of Options::region_points
/// points (Engine::hybrid). `distinct`, when given, is distinct_points(points),
/// computed by the caller.
/// \throws Invalid_input (see dewall::triangulate_to); Search_budget_spent.
template <class K>
Statistics triangulate_generic(const K& k, std::span<const typename K::Point_d> points, const Options& options,
                               std::vector<std::array<std::uint32_t, K::dimension + 1>>& simplices,
                               std::vector<std::uint8_t>* wall_levels,
                               const std::optional<Search_budget>& budget = std::nullopt,
                               const Region_triangulator<K::dimension>* regions = nullptr,
                               const std::vector<std::size_t>* distinct = nullptr) {
  constexpr int D = K::dimension;
  const kernel::Fp_environment_guard guard;
  const std::vector<std::size_t> input = distinct ? *distinct : distinct_points<K>(k, points);
  std::vector<const typename K::Point_d*> refs(input.size());
  for (std::size_t i = 0; i < input.size(); ++i) refs[i] = &points[input[i]];
  const Point_set<K> ps(k, std::move(refs), input, options.points_per_leaf);
  require_full_dimension<D>(ps.coords_for_checks());

  Wall_builder<K> builder(ps, options.parallel_depth, budget, regions, region_points_for(options, ps.size()));
  std::vector<Index> all(ps.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
  Built_simplices<D> built;
  builder.run(all, built);
  simplices.reserve(simplices.size() + built.size());
  if (wall_levels) wall_levels->reserve(wall_levels->size() + built.size());
  built.for_each([&](const Built_simplex<D>& s) {
    simplices.push_back(s.vertices);
    if (wall_levels) wall_levels->push_back(s.wall_level);
  });

  Statistics st;
  st.input_points = points.size();
  st.distinct_points = ps.size();
  st.simplices = builder.stats().simplices;
  st.first_wall_simplices = builder.stats().first_wall_simplices;
  st.recursion_depth = builder.stats().max_depth;
  st.simplex_searches = builder.search_stats().searches;
  st.nodes_visited = builder.search_stats().nodes_visited;
  st.candidates_tested = builder.search_stats().candidates;
  st.tree_leaves = ps.tree.leaf_count();
  st.region_simplices = builder.stats().region_simplices;
  st.engine = regions ? Engine::hybrid : Engine::dewall;
  return st;
}

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
