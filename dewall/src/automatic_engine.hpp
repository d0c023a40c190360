// Engine::automatic: which engine builds an input, and when the walls hand
// over to an incremental construction. Private to dewall/src.
//
// The rule, in the order it is applied (docs/engines.md has the measurements
// behind each step):
//  1. In 4D and up: the incremental construction alone (the walls and the
//     regions' filter only add to it there).
//  2. At most automatic_whole_limit distinct points (options.hpp: 2^25
//     collected with the default regions, else one region's worth): the
//     incremental construction alone (below that the walls and regions cost
//     more than they gain on one thread and on two).
//  3. Otherwise the hybrid (dewall_engine.hpp) with a Search_budget charged by
//     every search; when the walls' searches prove too costly, or a region
//     saves no search (handover_rule.hpp, the whole rule of a spent budget),
//     the incremental construction builds the whole triangulation from
//     scratch, reusing the input checks. Nothing was handed to the output
//     before: the hybrid holds its simplices until the budget can no longer
//     be spent.
#pragma once

#include <span>
#include <vector>

#ifdef __GLIBC__
#include <malloc.h>  // malloc_trim
#endif

#include "incremental_choice.hpp"
#include "dewall/detail/walls/handover_rule.hpp"
#include "dewall/detail/common/input.hpp"
#include "dewall/detail/walls/dewall_engine.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/options.hpp"

namespace dewall::detail {

/// The output of the engine that takes over from the walls, when it reads
/// the input the walls restored: that copy goes as soon as the engine has
/// read it (as the caller's own points would), the rest is `output`'s.
template <int D>
class Restored_input_output final : public Simplex_output<D> {
 public:
  Restored_input_output(Simplex_output<D>& output, std::vector<kernel::Point_d<D>>& restored)
      : output_(output), restored_(restored) {}
  Cell_graph_output<D>* cell_graph() override { return output_.cell_graph(); }
  void expect(std::size_t count) override { output_.expect(count); }
  void put(std::span<const Built_simplex<D>> block) override { output_.put(block); }
  bool frees_input() const override { return true; }
  Progress_meter* progress() override { return output_.progress(); }
  void input_no_longer_read() override {
    std::vector<kernel::Point_d<D>>().swap(restored_);
#ifdef __GLIBC__
    // The copy usually lies inside the heap, not in a mapping of its own:
    // glibc maps only blocks above a threshold that it raised to the size of
    // the caller's points when they were freed. Its pages go back now, as
    // the caller's would have (measured: 10^6 points on a sphere, streamed:
    // 24 MB more peak without this).
    malloc_trim(0);
#endif
  }

 private:
  Simplex_output<D>& output_;
  std::vector<kernel::Point_d<D>>& restored_;
};

template <int D>
Statistics triangulate_automatic(std::span<const kernel::Point_d<D>> points, const Options& options,
                                 Simplex_output<D>& output, const Incremental_choice<D>& incremental) {
  using K = kernel::Filtered_kernel_d<D>;
  if constexpr (D >= 4) return incremental.whole(points, output);
  // An input of at most as many points as the limit (then its distinct
  // points are within their own limit too: automatic_whole_limit is constant
  // up to there) goes to the incremental construction, which finds the
  // repeats itself on the way (triangulate_incremental).
  if (points.size() <= automatic_whole_limit(options, points.size())) return incremental.whole(points, output);
  // The input checks once, for both engines.
  const Distinct_points distinct = distinct_points<K>(K{}, points);
  if (distinct.size() <= automatic_whole_limit(options, distinct.size())) return incremental.whole(points, output, &distinct);
  // The walls tell the output the points are no longer read (the caller may
  // free them): a hand-over then builds from the copy the walls restore.
  std::vector<kernel::Point_d<D>> restored;
  const Hybrid<D> hybrid{incremental.regions(),
                         Search_budget(options.handover_candidates_per_search, points.size(), D), &distinct,
                         &restored};
  try {
    return triangulate_hybrid<K>({}, points, options, output, hybrid);
  } catch (const Search_budget_spent& spent) {
    Restored_input_output<D> from_restored(output, restored);
    Statistics st = restored.empty() ? incremental.whole(points, output, &distinct)
                                     : incremental.whole(restored, from_restored, &distinct);
    st.searches_before_handover = spent.searches;
    return st;
  }
}

}  // namespace dewall::detail
