// Assertion tiers, as CGAL's and Geogram's: DEWALL_ASSERT is always on (cheap invariants);
// DEWALL_EXPENSIVE_ASSERT (O(n) checks: every search's answer against all
// points, make_simplex.hpp) only when DEWALL_EXPENSIVE_CHECKS is defined, as the
// fuzz harnesses define it (fuzz/CMakeLists.txt).
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
#ifdef DEWALL_EXPENSIVE_CHECKS
#define DEWALL_EXPENSIVE_ASSERT(expr) DEWALL_ASSERT(expr)
#else
#define DEWALL_EXPENSIVE_ASSERT(expr) static_cast<void>(0)
#endif
