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
#include <type_traits>
#include <gmp.h>

#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
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

namespace detail {
template <int K>
inline constexpr Minor_masks<K> minor_masks{};

/// Marks a lambda's body for inlining like the function around it: the
/// expansion's lambdas are its whole body, and GCC's heuristics left them out
/// of line in some callers (measured: the walk's orientation in the
/// incremental construction, 5 % of its samples, as calls).
#if defined(__GNUC__)
#define DEWALL_INLINE_LAMBDA __attribute__((always_inline))
#else
#define DEWALL_INLINE_LAMBDA
#endif

/// f(integral_constant<int, i>) for i = Begin … End−1, unrolled at compile time.
template <int Begin, int End, class F>
[[gnu::always_inline]] inline void static_for(F&& f) {
  if constexpr (Begin < End) {
    f(std::integral_constant<int, Begin>{});
    static_for<Begin + 1, End>(f);
  }
}
}  // namespace detail

/// The minors of the last `Top` rows of `a` (Top ≤ K), each stored at its column mask, by the
/// shared-minor expansion above; determinant() is the case Top = K. Every loop is unrolled at
/// compile time, so masks, signs and indices are constants. `Signed` false: every sign +, the
/// permanents of the same submatrices, in the same order (permanent()).
template <int Top, class T, int K, bool Signed = true>
[[gnu::always_inline]] inline void lower_minors(const Matrix<T, K>& a, std::array<T, (1 << K)>& minor) {
  static_assert(K >= 1 && K <= 8 && Top >= 1 && Top <= K);
  constexpr const auto& table = detail::minor_masks<K>;
  detail::static_for<0, K>([&](auto j) DEWALL_INLINE_LAMBDA { minor[std::size_t{1} << j] = a[K - 1][j]; });
  detail::static_for<2, Top + 1>([&](auto r) DEWALL_INLINE_LAMBDA {
    const auto& row = a[static_cast<std::size_t>(K - r)];
    detail::static_for<table.level_begin[r], table.level_begin[r + 1]>([&](auto t) DEWALL_INLINE_LAMBDA {
      constexpr unsigned mask = table.masks[t];
      constexpr int lowest = std::countr_zero(mask);
      T sum = row[lowest] * minor[mask & ~(1u << lowest)];
      detail::static_for<lowest + 1, K>([&](auto j) DEWALL_INLINE_LAMBDA {
        if constexpr ((mask & (1u << j)) != 0) {
          constexpr bool negate = Signed && std::popcount(mask & ((1u << j) - 1)) % 2 == 1;
          if constexpr (negate) sum -= row[j] * minor[mask & ~(1u << j)];
          else sum += row[j] * minor[mask & ~(1u << j)];
        }
      });
      minor[mask] = sum;
    });
  });
}

/// The permanent of `a` (the expansion above with every sign +), over the
/// same minors in the same order. On a matrix of |entries| it is the sum of
/// the |monomials| of the determinant: the quantity the error of the
/// computed determinant is proportional to (filtered_predicate.hpp, stage 2).
template <class T, int K>
[[gnu::always_inline]] inline T permanent(const Matrix<T, K>& a) {
  if constexpr (K == 1) {
    return a[0][0];
  } else {
    std::array<T, (1 << K)> minor;
    lower_minors<K, T, K, false>(a, minor);
    return minor[(1u << K) - 1];
  }
}

/// The determinant of `a`, computed by the shared-minor Laplace expansion above.
template <class T, int K>
[[gnu::always_inline]] inline T determinant(const Matrix<T, K>& a) {
  if constexpr (K == 1) {
    return a[0][0];
  } else {
    std::array<T, (1 << K)> minor;
    lower_minors<K, T, K>(a, minor);
    return minor[(1u << K) - 1];
  }
}

/// acc += a·b: the recipes' one fused step, in place for exact integers
/// (mpz_addmul: no temporary). For double and Interval the same two operations
/// as `acc += a * b`, in that order (the error bounds count them so).
template <class T>
[[gnu::always_inline]] inline void add_product(T& acc, const T& a, const T& b) {
  if constexpr (requires { mpz_addmul(acc.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t()); })
    mpz_addmul(acc.get_mpz_t(), a.get_mpz_t(), b.get_mpz_t());
  else
    acc += a * b;
}

/// The sign of det(a) over GMP integers, computed by the same expansion as
/// `determinant` into `minor` (2^K integers the caller keeps, so that once
/// their limbs have grown no call allocates: a fresh temporary per product
/// made malloc and free half the exact stage's time).
template <int K, class Integer>
int determinant_sign_in_place(const Matrix<Integer, K>& a, std::array<Integer, (1 << K)>& minor) {
  constexpr const auto& table = detail::minor_masks<K>;
  detail::static_for<0, K>([&](auto j) { minor[std::size_t{1} << j] = a[K - 1][j]; });
  detail::static_for<2, K + 1>([&](auto r) {
    const auto& row = a[static_cast<std::size_t>(K - r)];
    detail::static_for<table.level_begin[r], table.level_begin[r + 1]>([&](auto t) {
      constexpr unsigned mask = table.masks[t];
      constexpr int lowest = std::countr_zero(mask);
      auto* sum = minor[mask].get_mpz_t();
      mpz_mul(sum, row[lowest].get_mpz_t(), minor[mask & ~(1u << lowest)].get_mpz_t());
      detail::static_for<lowest + 1, K>([&](auto j) {
        if constexpr ((mask & (1u << j)) != 0) {
          constexpr bool negate = std::popcount(mask & ((1u << j) - 1)) % 2 == 1;
          if constexpr (negate) mpz_submul(sum, row[j].get_mpz_t(), minor[mask & ~(1u << j)].get_mpz_t());
          else mpz_addmul(sum, row[j].get_mpz_t(), minor[mask & ~(1u << j)].get_mpz_t());
        }
      });
    });
  });
  return mpz_sgn(minor[(1u << K) - 1].get_mpz_t());
}

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
