// The engines built on walls, for any kernel: DeWall (walls all the way down,
// the paper's algorithm) and the hybrid (walls down to regions, each built by
// an incremental construction: region.hpp). Both: the input checks, the point
// set, the recursion (wall.hpp), the simplices handed to the output in input
// indices. dewall.hpp calls triangulate_dewall for a user's kernel; the
// compiled library (dewall/src/engine_choice.hpp) runs both for
// Filtered_kernel_d with the project's flags.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "dewall/detail/walls/handover_rule.hpp"
#include "dewall/detail/common/input.hpp"
#include "dewall/detail/walls/point_set.hpp"
#include "dewall/detail/walls/region.hpp"
#include "dewall/detail/common/simplex_output.hpp"
#include "dewall/detail/walls/wall.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/options.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// What the hybrid adds to DeWall.
template <int D>
struct Hybrid {
  /// Triangulates the regions of region_points_for(options, n) points.
  const Region_triangulator<D>& regions;
  /// Engine::automatic: charged by every search (a copy per task,
  /// handover_rule.hpp); when it is spent nothing has been handed to the
  /// output.
  std::optional<Search_budget> budget = std::nullopt;
  /// distinct_points(points), when the caller computed it.
  const Distinct_points* distinct = nullptr;
  /// Engine::automatic: when the budget is spent after the output was told
  /// the input is no longer read (Point_set::reads_input), the input as the
  /// walls restored it for the engine that takes over (Point_set::restore_input).
  std::vector<kernel::Point_d<D>>* restored_input = nullptr;
};

/// Hands the Delaunay simplices of `points` (input indices, positively
/// oriented, in DeWall's depth-first order, with the recursion level of the
/// wall that built each one) to `output`: once complete, or as they are built
/// with Options::stream. `hybrid`, when given, adds the regions.
/// \throws Invalid_input (see dewall::triangulate_to); Search_budget_spent.
template <class K>
Statistics triangulate_walls(const K& k, std::span<const typename K::Point_d> points, const Options& options,
                             Simplex_output<K::dimension>& output, const Hybrid<K::dimension>* hybrid) {
  constexpr int D = K::dimension;
  const kernel::Fp_environment_guard guard;
  std::optional<const Point_set<K>> ps(
      std::in_place, k, points,
      hybrid && hybrid->distinct ? hybrid->distinct->indices() : distinct_points<K>(k, points).indices(),
      options.points_per_leaf);
  require_full_dimension<D>(ps->coords_for_checks());
  // The caller's points are read no more (Point_set::reads_input): when the
  // output's caller frees them, a hand-over takes them from the point set
  // (restore_input, below); else it reads the caller's, and nothing is copied.
  const bool input_released = !Point_set<K>::reads_input && output.frees_input() &&
                              (!hybrid || !hybrid->budget || hybrid->restored_input);
  if (input_released) output.input_no_longer_read();

  std::optional<Search_budget> budget = hybrid ? hybrid->budget : std::nullopt;
  // Streaming with a budget: held until the hand-over is decided (handover_rule.hpp).
  Handover_decision decision;
  Handover_decision* const streamed_decision = options.stream && budget ? &decision : nullptr;
  if (streamed_decision) budget->decide_with(streamed_decision);
  std::optional<Simplex_stream<D>> stream;
  if (options.stream) stream.emplace(output, streamed_decision != nullptr);
  Wall_stats stats;
  Search_stats search_stats;
  try {
    Wall_builder<K> builder(*ps, options.parallel_depth, budget, hybrid ? &hybrid->regions : nullptr,
                            region_points_for(options, ps->size()), streamed_decision);
    builder.progress = output.progress();
    std::vector<Index> all(ps->size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<Index>(i);
    Built_simplices<D> built(stream ? &*stream : nullptr);
    builder.run(all, built);
    if (stream) stream->release();  // (no region was kept: nothing can hand over now)
    else built.hand_to(output);
    stats = builder.stats();
    search_stats = builder.search_stats();
  } catch (const Search_budget_spent&) {
    // The walls are gone (their tasks' memory with them), then what the
    // stream held; the point set gives the input back and goes too, before
    // the engine that takes over builds anything.
    stream.reset();
    if constexpr (!Point_set<K>::reads_input) {
      if (input_released && hybrid && hybrid->restored_input) *hybrid->restored_input = ps->restore_input();
      ps.reset();
    }
    throw;
  }

  Statistics st;
  st.input_points = points.size();
  st.distinct_points = ps->size();
  st.simplices = stats.simplices;
  st.first_wall_simplices = stats.first_wall_simplices;
  st.recursion_depth = stats.max_depth;
  st.simplex_searches = search_stats.searches;
  st.nodes_visited = search_stats.nodes_visited;
  st.candidates_tested = search_stats.candidates;
  st.tree_leaves = ps->tree.leaf_count();
  st.region_simplices = stats.region_simplices;
  st.engine = hybrid ? Engine::hybrid : Engine::dewall;
  return st;
}

/// Engine::dewall: triangulate_walls without regions.
template <class K>
Statistics triangulate_dewall(const K& k, std::span<const typename K::Point_d> points, const Options& options,
                              Simplex_output<K::dimension>& output) {
  return triangulate_walls<K>(k, points, options, output, nullptr);
}

/// Engine::hybrid (and Engine::automatic, with a budget): triangulate_walls
/// with regions.
template <class K>
Statistics triangulate_hybrid(const K& k, std::span<const typename K::Point_d> points, const Options& options,
                              Simplex_output<K::dimension>& output, const Hybrid<K::dimension>& hybrid) {
  return triangulate_walls<K>(k, points, options, output, &hybrid);
}

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
