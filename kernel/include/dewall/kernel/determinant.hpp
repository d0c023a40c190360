// The K×K determinant by Laplace expansion with shared minors, over any ring.
//
// One routine serves every stage of every predicate: double (the filter),
// Interval (the second stage) and GMP integers (the exact stage). Sharing one
// routine is what makes the filter's error bound (error_bounds.hpp) a statement
// about the very operations the exact stage repeats without rounding.
//
// Evaluation order. Rows are expanded from the bottom: the minors of the last
// r rows are indexed by their column set (a bit mask of popcount r), and
//   minor(row K-r, mask) = Σ_{j ∈ mask, ascending} (-1)^{#(mask below j)} a[K-r][j] · minor(mask \ j)
// summed left to right. There are C(K,r) minors of size r, so the whole
// determinant costs K·2^(K-1) products (448 for K = 7) instead of K!.
#pragma once

#include <array>
#include <bit>
#include <cstddef>

namespace dewall::kernel {

template <class T, int K>
using Matrix = std::array<std::array<T, K>, K>;

namespace detail {

/// The column masks of popcount r, r = 1..K, in increasing order; computed at
/// compile time so that the loops below have constant trip counts.
template <int K>
struct Minor_masks {
  static constexpr int count = 1 << K;
  std::array<unsigned, count> masks{};
  std::array<int, K + 2> level_begin{};  // masks of popcount r: [level_begin[r], level_begin[r+1])
  constexpr Minor_masks() {
    int n = 0;
    for (int r = 0; r <= K; ++r) {
      level_begin[static_cast<std::size_t>(r)] = n;
      for (unsigned m = 0; m < static_cast<unsigned>(count); ++m)
        if (std::popcount(m) == r) masks[static_cast<std::size_t>(n++)] = m;
    }
    level_begin[static_cast<std::size_t>(K + 1)] = n;
  }
};

}  // namespace detail

/// The determinant of `a`, computed by the shared-minor Laplace expansion above.
/// T must support copy, +, -, * (a commutative ring). Complexity: K·2^(K-1)
/// products and as many additions.
template <class T, int K>
[[gnu::always_inline]] inline T determinant(const Matrix<T, K>& a) {
  static_assert(K >= 1 && K <= 8);
  if constexpr (K == 1) {
    return a[0][0];
  } else {
    static constexpr detail::Minor_masks<K> table{};
    std::array<T, (1 << K)> minor{};
    // Level 1: the minors of the last row are its entries.
    for (int j = 0; j < K; ++j) minor[std::size_t{1} << j] = a[K - 1][static_cast<std::size_t>(j)];
    for (int r = 2; r <= K; ++r) {
      const auto& row = a[static_cast<std::size_t>(K - r)];
      for (int t = table.level_begin[static_cast<std::size_t>(r)];
           t < table.level_begin[static_cast<std::size_t>(r + 1)]; ++t) {
        const unsigned mask = table.masks[static_cast<std::size_t>(t)];
        bool first = true;
        bool negate = false;
        T sum{};
        for (int j = 0; j < K; ++j) {
          if (!(mask & (1u << j))) continue;
          T term = row[static_cast<std::size_t>(j)] * minor[mask & ~(1u << j)];
          if (first) {
            sum = term;
            first = false;
          } else if (negate) {
            sum -= term;
          } else {
            sum += term;
          }
          negate = !negate;
        }
        minor[mask] = sum;
      }
    }
    return minor[(1u << K) - 1];
  }
}

}  // namespace dewall::kernel
