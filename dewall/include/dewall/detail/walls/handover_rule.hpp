// The hand-over rule of Engine::automatic: when the walls give up for an
// incremental construction (dewall/src/automatic_engine.hpp applies it).
//  * Search_budget: what DeWall's searches cost, charged by every search
//    (make_simplex.hpp: begin_search, charge) in candidates and slow-path
//    predicate evaluations (kernel/predicate_stats.hpp, slow_path_counts);
//    spent when the cost per search passes Options::handover_candidates_per_search.
//  * Region_handover: a region of the hybrid that saves no search (wall.hpp).
//  * Handover_decision: streaming decides once, for all tasks.
// Integer bookkeeping only: it never touches the triangulation, it only stops
// DeWall. The figures behind the constants: docs/engines.md.
//
// One budget per Simplex_search, and so per task of the recursion: the tasks
// are fixed by the points (Options::parallel_depth), not by the threads, and
// each task's searches run in one order, so whether a budget is spent, and so
// the output, is the same for every number of threads. (One budget shared by
// all tasks would see their charges interleaved differently on each run.)
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "dewall/kernel/predicate_stats.hpp"

namespace dewall::detail {

/// Thrown out of the DeWall recursion when a budget is spent.
struct Search_budget_spent {
  std::size_t searches;  // of the task whose budget it was
};

/// Streaming (Options::stream) cannot take back simplices it has passed on,
/// so there the hand-over is decided once, for all tasks: open until the first
/// region's simplices are kept, then settled (no hand-over afterwards: the
/// budgets stop counting) or abandoned (a budget was spent first: the
/// triangulation hands over, and the held stream is dropped). The first of
/// the two wins, whichever thread gets there first.
class Handover_decision {
 public:
  /// True when the run goes on without handing over.
  bool settle() { return decide(settled); }
  /// True when the run hands over.
  bool abandon() { return decide(abandoned); }

 private:
  enum State { open, settled, abandoned };
  bool decide(State wanted) {
    State s = open;
    return state_.compare_exchange_strong(s, wanted) || s == wanted;
  }
  std::atomic<State> state_{open};
};

/// The automatic engine's rule for one region (wall.hpp, triangulate_region):
/// hand over when a region saves no search. A region's gain is that most of
/// its cells are kept without the exact emptiness search; when more than a
/// quarter of them need it (their spheres leave the region: two parallel
/// layers), the region costs the incremental construction's work plus
/// DeWall's. Decided as soon as the share passes a quarter (the count only
/// grows, so the decision is the same). Regions of fewer than
/// `min_cells` cells never hand over: a few hull cells are a large share of a
/// small region. docs/engines.md has the measured shares.
class Region_handover {
 public:
  static constexpr std::size_t min_cells = 4096;

  Region_handover() = default;
  /// A region of `cells` cells; `charged`: its searches are charged to a
  /// budget (Engine::automatic).
  Region_handover(bool charged, std::size_t cells) : applies_(charged && cells >= min_cells), cells_(cells) {}

  /// One more of the region's cells needed the emptiness search; true when
  /// the region saves no search.
  bool searched_one() { return applies_ && 4 * ++searched_ > cells_; }

 private:
  bool applies_ = false;
  std::size_t cells_ = 0, searched_ = 0;
};

class Search_budget {
 public:
  /// The cost of a predicate evaluation the filters left to a second stage
  /// (running error or intervals) or the exact stage, in candidates (one candidate is examined with the
  /// filters deciding): the stages' measured cost ratios (docs/engines.md). On
  /// points on one circle or sphere nearly every test goes to the exact stage,
  /// so counting candidates alone would let DeWall run far too long.
  static constexpr std::size_t second_stage_cost = 10, exact_cost = 100;

  /// per_search: Options::handover_candidates_per_search; n: the number of
  /// points; d: their dimension.
  Search_budget(double per_search, std::size_t n, int d)
      : per_search_(per_search), allowance_(64 * per_search + static_cast<double>(n << (2 * (d - 2)))) {}

  /// From now on (and in every copy made from now on) a spent budget hands
  /// over only if `decision` is not settled.
  void decide_with(Handover_decision* decision) { decision_ = decision; }

  /// A search (or an emptiness test) begins: the slow-path evaluations of this
  /// thread are charged from here.
  void begin_search() {
    ++searches_;
    kernel::restart_interval_gates();  // (the charge then depends on this search alone)
    mark_ = kernel::slow_path_counts();
  }

  /// Charges the search in progress: `candidates`, the candidates of all
  /// searches so far, and the slow-path evaluations since the last call.
  /// \throws Search_budget_spent once the cost exceeds per_search × searches +
  /// 64 × per_search + 4^(d−2) × n: an allowance for a few costly searches
  /// (near the hull, and the first simplex's, whose attempts on faces that are
  /// not Delaunay have large spheres) and a few looks at every point, small
  /// beside the incremental construction's time (docs/engines.md). Called
  /// during long searches too, so one search of a sphere's points does not run
  /// to its end.
  void charge(std::size_t candidates) {
    if (settled_) return;
    const kernel::Slow_path_counts& now = kernel::slow_path_counts();
    slow_cost_ += second_stage_cost * (now.second_stage - mark_.second_stage) + exact_cost * (now.exact - mark_.exact);
    mark_ = now;
    if (static_cast<double>(candidates + slow_cost_) > per_search_ * static_cast<double>(searches_) + allowance_)
      spend();
  }

  /// Hands over now, whatever is left (a region that saves no search, wall.hpp),
  /// unless the decision is settled: then it returns.
  /// \throws Search_budget_spent
  void spend() {
    if (settled_) return;
    if (!decision_ || decision_->abandon()) throw Search_budget_spent{searches_};
    settled_ = true;  // (not asking the shared decision again on every charge)
  }

 private:
  double per_search_, allowance_;
  Handover_decision* decision_ = nullptr;
  bool settled_ = false;
  std::size_t searches_ = 0;
  std::uint64_t slow_cost_ = 0;
  kernel::Slow_path_counts mark_;
};

}  // namespace dewall::detail
