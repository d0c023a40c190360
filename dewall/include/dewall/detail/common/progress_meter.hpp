// Options::progress as the engines see it: work counted in units (points) out
// of a total, the caller's callback called now and then, and its refusal
// turned into dewall::Cancelled on every thread that polls next.
//
// The engines poll at a coarse grain (every few thousand insertions, every
// thousand wall simplices, each region), never per predicate: a poll is an
// atomic add and, when no other thread is in the callback, one call.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>

#include "dewall/error.hpp"

namespace dewall::detail {

class Progress_meter {
 public:
  /// `callback` (Options::progress, not empty) must outlive the meter.
  Progress_meter(const std::function<bool(double)>& callback, std::size_t total_units)
      : callback_(callback), total_(static_cast<double>(std::max<std::size_t>(total_units, 1))) {}
  Progress_meter(const Progress_meter&) = delete;
  Progress_meter& operator=(const Progress_meter&) = delete;

  /// `units` more done (0: only a poll). Calls the callback when this is a
  /// poll or the count passes a thousandth of the total (the walls finish
  /// many small subproblems: one call each would be thousands a second),
  /// unless another thread is in it, which keeps it from running concurrently.
  /// \throws Cancelled once the callback has returned false (on every thread
  /// that polls after that), what the callback throws.
  void advance(std::size_t units = 0) {
    const std::size_t done = done_.fetch_add(units, std::memory_order_relaxed) + units;
    const bool step = units == 0 || permille(done - units) != permille(done);
    if (step && !stopped_.load(std::memory_order_relaxed) && mutex_.try_lock()) {
      const std::lock_guard lock(mutex_, std::adopt_lock);
      // Never back: the walls may count a point twice, an engine that takes over counts anew.
      reported_ = std::max(reported_, std::min(1.0, static_cast<double>(done) / total_));
      try {
        if (!callback_(reported_)) stopped_.store(true, std::memory_order_relaxed);
      } catch (...) {
        stopped_.store(true, std::memory_order_relaxed);
        throw;
      }
    }
    if (stopped_.load(std::memory_order_relaxed)) throw Cancelled();
  }

  /// The last call, once the work is complete: the callback sees 1 (what it
  /// returns no longer matters).
  void complete() {
    const std::lock_guard lock(mutex_);
    callback_(1.0);
  }

 private:
  std::size_t permille(std::size_t done) const { return static_cast<std::size_t>(static_cast<double>(done) * 1000 / total_); }

  const std::function<bool(double)>& callback_;
  double total_;
  std::atomic<std::size_t> done_{0};
  std::atomic<bool> stopped_{false};
  std::mutex mutex_;
  double reported_ = 0;  // (under mutex_)
};

}  // namespace dewall::detail
