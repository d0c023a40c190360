// Per-stage counters: how often the filter, the permanent filter, the running-error stage, the interval stage, the exact stage
// and the symbolic perturbation decided. Compiled out unless the build defines
// DEWALL_PREDICATE_STATS (CMake option DEWALL_PREDICATE_STATS); the relaxed
// atomic increments cost a few percent on the hot path, so release builds skip them.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace dewall::kernel {

struct Predicate_stats {
  std::atomic<std::uint64_t> filter{0}, permanent{0}, running_error{0}, interval{0}, exact{0}, perturbed{0};

  std::uint64_t calls() const { return filter + permanent + running_error + interval + exact; }
  void reset() { filter = permanent = running_error = interval = exact = perturbed = 0; }
};

/// Counters indexed by dimension (0 and 1 unused).
struct All_predicate_stats {
  std::array<Predicate_stats, 8> orientation, side_of_sphere;
};

inline All_predicate_stats& predicate_stats() {
  static All_predicate_stats stats;
  return stats;
}

/// True when the counters are compiled in.
inline constexpr bool predicate_stats_enabled =
#ifdef DEWALL_PREDICATE_STATS
    true;
#else
    false;
#endif

/// The evaluations the filter left to the later stages on this thread, by the
/// last stage they reached. Always counted, unlike Predicate_stats: a
/// thread-local increment is nothing beside the 0.1–2 µs those stages take.
/// Engine::automatic reads them to charge a search for what it really cost
/// (dewall/detail/walls/handover_rule.hpp).
struct Slow_path_counts {
  /// second_stage: decided by the running-error or the interval stage.
  std::uint64_t second_stage = 0, exact = 0;
  /// Advanced by restart_interval_gates: a gate that last saw another epoch
  /// starts afresh (filtered_predicate.hpp, Stage_gate).
  std::uint32_t gate_epoch = 0;
};

inline Slow_path_counts& slow_path_counts() {
  thread_local Slow_path_counts counts;
  return counts;
}

/// Makes every stage gate of this thread start afresh. Which stage decides
/// a call, and so what it counts above, depends on its gate's state, which
/// depends on every call the thread made before; Engine::automatic's budget
/// restarts the gates at each search, so that a search's charge is a function
/// of the search alone, not of which tasks the thread ran before it: the
/// hand-over, and with it the output, stays the same for every number of
/// threads.
inline void restart_interval_gates() { ++slow_path_counts().gate_epoch; }

inline void count(std::atomic<std::uint64_t>& counter) {
  if constexpr (predicate_stats_enabled) counter.fetch_add(1, std::memory_order_relaxed);
  else (void)counter;
}

}  // namespace dewall::kernel
