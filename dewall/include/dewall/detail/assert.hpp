// Assertion tiers (STYLE.md): DEWALL_ASSERT is always on (cheap invariants);
// DEWALL_DEBUG_ASSERT only without NDEBUG; DEWALL_EXPENSIVE_ASSERT (O(n) checks)
// only when DEWALL_EXPENSIVE_CHECKS is defined (tests and fuzzing).
#pragma once

#include <cstdio>
#include <cstdlib>

namespace dewall::detail {
[[noreturn]] inline void assertion_failed(const char* expr, const char* file, int line) {
  std::fprintf(stderr, "dewall: internal error: %s (%s:%d)\n", expr, file, line);
  std::abort();
}
}  // namespace dewall::detail

#define DEWALL_ASSERT(expr) \
  ((expr) ? static_cast<void>(0) : ::dewall::detail::assertion_failed(#expr, __FILE__, __LINE__))
#ifdef NDEBUG
#define DEWALL_DEBUG_ASSERT(expr) static_cast<void>(0)
#else
#define DEWALL_DEBUG_ASSERT(expr) DEWALL_ASSERT(expr)
#endif
#ifdef DEWALL_EXPENSIVE_CHECKS
#define DEWALL_EXPENSIVE_ASSERT(expr) DEWALL_ASSERT(expr)
#else
#define DEWALL_EXPENSIVE_ASSERT(expr) static_cast<void>(0)
#endif
