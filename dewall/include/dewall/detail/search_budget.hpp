// Search_budget: what Engine::automatic measures of DeWall's cost (options.hpp),
// shared by every task of one triangulation. Integer bookkeeping only: it never
// touches the triangulation, it only stops DeWall.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>

namespace dewall::detail {

/// Thrown out of the DeWall recursion when the budget is spent.
struct Search_budget_spent {};

class Search_budget {
 public:
  /// per_search: Options::handover_candidates_per_search; n: the number of points.
  Search_budget(double per_search, std::size_t n)
      : per_search_(per_search), allowance_(std::min(64 * per_search, static_cast<double>(n))) {}

  /// Records one search that examined `candidates` points.
  /// \throws Search_budget_spent once all searches so far examined more than
  /// per_search × searches + min(64 × per_search, n) candidates: an allowance
  /// for a few costly searches near the hull, but never more than one look at
  /// every point (on small inputs the incremental construction takes less time
  /// than 64 searches of a sphere's points).
  void charge(std::size_t candidates) {
    const std::size_t s = searches_.fetch_add(1, std::memory_order_relaxed) + 1;
    const std::size_t c = candidates_.fetch_add(candidates, std::memory_order_relaxed) + candidates;
    if (static_cast<double>(c) > per_search_ * static_cast<double>(s) + allowance_) throw Search_budget_spent{};
  }
  std::size_t searches() const { return searches_.load(std::memory_order_relaxed); }

 private:
  double per_search_, allowance_;
  std::atomic<std::size_t> searches_{0}, candidates_{0};
};

}  // namespace dewall::detail
