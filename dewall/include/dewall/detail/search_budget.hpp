// Search_budget: what Engine::automatic measures of DeWall's cost (options.hpp),
// shared by every task of one triangulation. Integer bookkeeping only: it never
// touches the triangulation, it only stops DeWall.
#pragma once

#include <atomic>
#include <cstddef>

namespace dewall::detail {

/// Thrown out of the DeWall recursion when the budget is spent.
struct Search_budget_spent {};

class Search_budget {
 public:
  explicit Search_budget(double candidates_per_search) : per_search_(candidates_per_search) {}

  /// Records one search that examined `candidates` points.
  /// \throws Search_budget_spent once all searches so far examined more than
  /// per_search × (searches + 64) candidates.
  void charge(std::size_t candidates) {
    const std::size_t s = searches_.fetch_add(1, std::memory_order_relaxed) + 1;
    const std::size_t c = candidates_.fetch_add(candidates, std::memory_order_relaxed) + candidates;
    if (static_cast<double>(c) > per_search_ * static_cast<double>(s + allowance)) throw Search_budget_spent{};
  }
  std::size_t searches() const { return searches_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::size_t allowance = 64;
  double per_search_;
  std::atomic<std::size_t> searches_{0}, candidates_{0};
};

}  // namespace dewall::detail
