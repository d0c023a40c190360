// The definition behind detail::triangulate_filtered (dewall.hpp), included only
// by this folder's files, each of which instantiates it for one dimension, so
// that the dimensions compile in parallel. Not installed: a user's file never
// compiles it (floating_point.hpp says why).
#pragma once

#include <stdexcept>
#include <string>

#include "cgal_engine.hpp"
#include "incremental_engine.hpp"
#include "dewall/detail/search_budget.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::detail {

/// The engine Options::engine names. The incremental engine's simplices get
/// wall level 0 (it builds no walls); a hybrid region's, its recursion level.
template <int D>
Statistics triangulate_filtered(std::span<const kernel::Point_d<D>> points, const Options& options,
                                Simplex_output<D>& output) {
  using K = kernel::Filtered_kernel_d<D>;
  const Engine chosen = options.incremental_engine;
  if (chosen != Engine::automatic && chosen != Engine::incremental && chosen != Engine::cgal)
    throw std::invalid_argument(std::string("dewall: Options::incremental_engine must be automatic, incremental or cgal, not ") +
                                engine_name(chosen));
  const bool own_engine = (chosen == Engine::automatic ? default_incremental_engine(D) : chosen) == Engine::incremental;
  const bool own_regions = (chosen == Engine::automatic ? default_region_engine(D) : chosen) == Engine::incremental;
  const Region_triangulator<D> regions = own_regions ? incremental_region_cells<D> : cgal_region_cells<D>;
  // The incremental construction where automatic leaves the input to one.
  auto incremental = [&](const std::vector<std::size_t>* distinct) {
    return own_engine ? triangulate_incremental<D>(points, output, distinct)
                      : triangulate_with_cgal<D>(points, output, distinct);
  };
  switch (options.engine) {
    case Engine::cgal:
      return triangulate_with_cgal<D>(points, output);
    case Engine::incremental:
      return triangulate_incremental<D>(points, output);
    case Engine::dewall:
      return triangulate_generic<K>({}, points, options, output);
    case Engine::hybrid:
      return triangulate_generic<K>({}, points, options, output, std::nullopt, &regions);
    case Engine::automatic:
      // In 4D and up the walls and the regions' filter only add to the
      // incremental construction (uniform points, one thread: the hybrid
      // 1.5–1.7× its time in 4D–6D, DeWall 1.8–2×).
      if constexpr (D >= 4) return incremental(nullptr);
      break;
  }
  // The input checks once, for both engines (on one circle they took a
  // fifth of CGAL's time).
  const std::vector<std::size_t> distinct = distinct_points<K>(K{}, points);
  // A problem that fits in one region is one region: a wall and two half
  // regions cost the kd-tree and the wall's searches, and gain nothing on one
  // thread (10^4 uniform points in 3D: 1.3x the incremental engine's time) and
  // little on two (1.1x).
  if (distinct.size() <= region_points_for(options, distinct.size())) return incremental(&distinct);
  const Search_budget budget(options.handover_candidates_per_search, points.size(), D);
  try {
    // (A spent budget has handed nothing to `output`: triangulate_generic.)
    return triangulate_generic<K>({}, points, options, output, budget, &regions, &distinct);
  } catch (const Search_budget_spent& spent) {
    Statistics st = incremental(&distinct);
    st.searches_before_handover = spent.searches;
    return st;
  }
}

}  // namespace dewall::detail
