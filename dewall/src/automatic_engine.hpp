// Engine::automatic: which engine builds an input, and when the walls hand
// over to an incremental construction. Private to dewall/src.
//
// The rule, in the order it is applied (docs/engines.md has the measurements
// behind each step):
//  1. In 4D and up: the incremental construction alone (the walls and the
//     regions' filter only add to it there).
//  2. At most automatic_whole_limit distinct points (options.hpp: 1048576
//     collected with the default regions, else one region's worth): the
//     incremental construction alone (below that the walls and regions cost
//     more than they gain on one thread and on two).
//  3. Otherwise the hybrid (wall_engines.hpp) with a Search_budget charged by
//     every search; when the walls' searches prove too costly, or a region
//     saves no search (handover_rule.hpp, the whole rule of a spent budget),
//     the incremental construction builds the whole triangulation from
//     scratch, reusing the input checks. Nothing was handed to the output
//     before: the hybrid holds its simplices until the budget can no longer
//     be spent.
#pragma once

#include <span>
#include <vector>

#include "incremental_choice.hpp"
#include "dewall/detail/handover_rule.hpp"
#include "dewall/detail/input.hpp"
#include "dewall/detail/wall_engines.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/options.hpp"

namespace dewall::detail {

template <int D>
Statistics triangulate_automatic(std::span<const kernel::Point_d<D>> points, const Options& options,
                                 Simplex_output<D>& output, const Incremental_choice<D>& incremental) {
  using K = kernel::Filtered_kernel_d<D>;
  if constexpr (D >= 4) return incremental.whole(points, output);
  // The input checks once, for both engines.
  const Distinct_points distinct = distinct_points<K>(K{}, points);
  if (distinct.size() <= automatic_whole_limit(options, distinct.size())) return incremental.whole(points, output, &distinct);
  const Hybrid<D> hybrid{incremental.regions(),
                         Search_budget(options.handover_candidates_per_search, points.size(), D), &distinct};
  try {
    return triangulate_hybrid<K>({}, points, options, output, hybrid);
  } catch (const Search_budget_spent& spent) {
    Statistics st = incremental.whole(points, output, &distinct);
    st.searches_before_handover = spent.searches;
    return st;
  }
}

}  // namespace dewall::detail
