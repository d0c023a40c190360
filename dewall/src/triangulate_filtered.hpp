// The definition behind detail::triangulate_filtered (dewall.hpp), included only
// by this folder's files, each of which instantiates it for one dimension, so
// that the dimensions compile in parallel. Not installed: a user's file never
// compiles it (floating_point.hpp says why).
#pragma once

#include "cgal_engine.hpp"
#include "dewall/detail/search_budget.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::detail {

/// The engine Options::engine names. The incremental engine's simplices get
/// wall level 0 (it builds no walls); a hybrid region's, its recursion level.
template <int D>
Statistics triangulate_filtered(std::span<const kernel::Point_d<D>> points, const Options& options,
                                std::vector<Simplex<D>>& simplices, std::vector<std::uint8_t>* wall_levels) {
  using K = kernel::Filtered_kernel_d<D>;
  const std::size_t simplices_before = simplices.size(), levels_before = wall_levels ? wall_levels->size() : 0;
  const auto incremental = [&] {
    simplices.resize(simplices_before);
    const Statistics st = triangulate_with_cgal<D>(points, simplices);
    if (wall_levels) wall_levels->resize(levels_before + st.simplices, 0);
    return st;
  };
  const Region_triangulator<D> regions = cgal_region_cells<D>;
  switch (options.engine) {
    case Engine::cgal:
      return incremental();
    case Engine::dewall:
      return triangulate_generic<K>({}, points, options, simplices, wall_levels);
    case Engine::hybrid:
      return triangulate_generic<K>({}, points, options, simplices, wall_levels, nullptr, &regions);
    case Engine::automatic:
      break;
  }
  Search_budget budget(options.handover_candidates_per_search, points.size());
  try {
    Statistics st = triangulate_generic<K>({}, points, options, simplices, wall_levels, &budget, &regions);
    return st;
  } catch (const Search_budget_spent&) {
    if (wall_levels) wall_levels->resize(levels_before);
    Statistics st = incremental();
    st.searches_before_handover = budget.searches();
    return st;
  }
}

}  // namespace dewall::detail
