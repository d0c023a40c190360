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
#include "dewall/detail/simplex_output.hpp"
#include "dewall/detail/wall.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/options.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// Hands the Delaunay simplices of `points` (input indices, positively
/// oriented, in DeWall's depth-first order, with the recursion level of the
/// wall that built each one) to `output`: once complete, or as they are built
/// with Options::stream. `budget`, when given, is charged by every search (a
/// copy per task); when it is spent nothing has been handed to `output`.
/// `regions`, when given, triangulates the regions of Options::region_points
/// points (Engine::hybrid). `distinct`, when given, is distinct_points(points),
/// computed by the caller.
/// \throws Invalid_input (see dewall::triangulate_to); Search_budget_spent.
template <class K>
Statistics triangulate_generic(const K& k, std::span<const typename K::Point_d> points, const Options& options,
                               Simplex_output<K::dimension>& output,
                               std::optional<Search_budget> budget = std::nullopt,
                               const Region_triangulator<K::dimension>* regions = nullptr,
                               const std::vector<std::size_t>* distinct = nullptr) {
  constexpr int D = K::dimension;
  const kernel::Fp_environment_guard guard;
  std::vector<std::size_t> input = distinct ? *distinct : distinct_points<K>(k, points);
  std::vector<const typename K::Point_d*> refs(input.size());
  for (std::size_t i = 0; i < input.size(); ++i) refs[i] = &points[input[i]];
  const Point_set<K> ps(k, std::move(refs), std::move(input), options.points_per_leaf);
  require_full_dimension<D>(ps.coords_for_checks());

  // Streaming with a budget: held until the hand-over is decided (search_budget.hpp).
  Handover_decision decision;
  Handover_decision* const streamed_decision = options.stream && budget ? &decision : nullptr;
  if (streamed_decision) budget->decide_with(streamed_decision);
  std::optional<Simplex_stream<D>> stream;
  if (options.stream) stream.emplace(output, streamed_decision != nullptr);
  Wall_builder<K> builder(ps, options.parallel_depth, budget, regions, region_points_for(options, ps.size()),
                          streamed_decision);
  std::vector<Index> all(ps.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
  Built_simplices<D> built(stream ? &*stream : nullptr);
  builder.run(all, built);
  if (stream) stream->release();  // (no region was kept: nothing can hand over now)
  else built.hand_to(output);

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
