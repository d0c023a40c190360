// The exact stage's fixed-width path: the sign of a determinant whose spatial
// entries fit 62 bits, in integers exactly as wide as each step needs.
//
// Where it pays: points on spheres and surfaces, whose sphere tests are near
// zero and reach the exact stage, have coordinates of about 53 to 70
// significant bits on one binary scale, and the coordinate differences of
// neighbouring points fit 62 bits. GMP spent its time on per-call overhead
// for such small numbers, and one wide type for every value (512-bit
// integers throughout) was slower still: the cost is in the widths. Here the
// minors grow one column at a time, so the minors of r columns are integers
// of just the r·62 + log2(r!) bits they can reach: 64 bits, then 128, then a
// few 64-bit limbs; each product is a limb vector times one 64-bit entry.
//
// Why modular limb arithmetic is exact: reduction modulo 2^n is a ring
// homomorphism, so a value computed with every operation wrapping modulo 2^n
// is the true value modulo 2^n; when the true value is proven below 2^(n−1)
// in magnitude, the two's-complement reading is the value itself.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "dewall/kernel/determinant.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

/// 128-bit integers (a GCC/Clang extension).
__extension__ typedef __int128 Int128;
__extension__ typedef unsigned __int128 Uint128;

/// An integer modulo 2^(64·L), read in two's complement.
template <int L>
class Wide_integer {
  static_assert(L >= 1);
  template <int>
  friend class Wide_integer;

 public:
  static constexpr int bits = 64 * L;

  Wide_integer() = default;
  /// v, sign-extended (v's value is kept when L ≥ 2).
  static Wide_integer of(Int128 v) {
    Wide_integer r;
    const auto u = static_cast<Uint128>(v);
    const std::uint64_t fill = v < 0 ? ~std::uint64_t{0} : 0;
    for (int i = 0; i < L; ++i)
      r.limb_[static_cast<std::size_t>(i)] = i == 0 ? static_cast<std::uint64_t>(u)
                                             : i == 1 ? static_cast<std::uint64_t>(u >> 64)
                                                      : fill;
    return r;
  }
  /// v, sign-extended to L limbs (M ≤ L: the value is kept).
  template <int M>
  static Wide_integer extended(const Wide_integer<M>& v) {
    static_assert(M <= L);
    Wide_integer r;
    const std::uint64_t fill = v.negative() ? ~std::uint64_t{0} : 0;
    for (int i = 0; i < L; ++i) r.limb_[static_cast<std::size_t>(i)] = i < M ? v.limb_[static_cast<std::size_t>(i)] : fill;
    return r;
  }

  friend Wide_integer operator+(const Wide_integer& a, const Wide_integer& b) {
    Wide_integer r;
    std::uint64_t carry = 0;
    for (int i = 0; i < L; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const Uint128 t = static_cast<Uint128>(a.limb_[k]) + b.limb_[k] + carry;
      r.limb_[k] = static_cast<std::uint64_t>(t);
      carry = static_cast<std::uint64_t>(t >> 64);
    }
    return r;
  }
  friend Wide_integer operator-(const Wide_integer& a, const Wide_integer& b) {
    Wide_integer r;
    std::uint64_t borrow = 0;  // 0 or 1
    for (int i = 0; i < L; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const Uint128 t = static_cast<Uint128>(a.limb_[k]) - b.limb_[k] - borrow;
      r.limb_[k] = static_cast<std::uint64_t>(t);
      borrow = static_cast<std::uint64_t>(t >> 64) & 1;  // the difference wrapped: a borrow
    }
    return r;
  }
  Wide_integer operator-() const { return Wide_integer{} - *this; }
  /// this · m (m read as unsigned), modulo 2^bits: L products.
  Wide_integer times(std::uint64_t m) const {
    Wide_integer r;
    std::uint64_t carry = 0;
    for (int i = 0; i < L; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const Uint128 t = static_cast<Uint128>(limb_[k]) * m + carry;
      r.limb_[k] = static_cast<std::uint64_t>(t);
      carry = static_cast<std::uint64_t>(t >> 64);
    }
    return r;
  }
  /// this · 2^64, modulo 2^bits.
  Wide_integer shifted_limb() const {
    Wide_integer r;
    for (int i = L - 1; i > 0; --i) r.limb_[static_cast<std::size_t>(i)] = limb_[static_cast<std::size_t>(i - 1)];
    return r;
  }
  Wide_integer& operator+=(const Wide_integer& b) { return *this = *this + b; }
  Wide_integer& operator-=(const Wide_integer& b) { return *this = *this - b; }

  bool negative() const { return (limb_[L - 1] >> 63) != 0; }
  /// -1, 0, +1 for the two's-complement value.
  int sign() const {
    if (negative()) return -1;
    for (const auto x : limb_)
      if (x != 0) return 1;
    return 0;
  }
  /// Bits of |value| (the value not −2^(bits−1)).
  int magnitude_bits() const {
    const Wide_integer m = negative() ? -*this : *this;
    for (int i = L - 1; i >= 0; --i)
      if (m.limb_[static_cast<std::size_t>(i)] != 0)
        return 64 * i + static_cast<int>(std::bit_width(m.limb_[static_cast<std::size_t>(i)]));
    return 0;
  }

 private:
  std::array<std::uint64_t, L> limb_{};
};

namespace detail {

constexpr int factorial_bits(int r) {
  long f = 1;
  for (int k = 2; k <= r; ++k) f *= k;
  return static_cast<int>(std::bit_width(static_cast<unsigned long>(f)));
}
/// The bound on the spatial entries: |entry| < 2^62.
inline constexpr int entry_bits = 62;
/// Limbs for a minor of r columns of entries below 2^62, or (`last_lifted`)
/// the full determinant whose last column's entries are below 2^127:
/// |minor| ≤ r!·Π_j M_j < 2^(bits), one bit more for the sign.
constexpr int minor_limbs(int r, bool last_lifted) {
  const int magnitude = last_lifted ? entry_bits * (r - 1) + 127 + factorial_bits(r) : entry_bits * r + factorial_bits(r);
  return (magnitude + 1 + 63) / 64;
}

/// acc ± e·m in acc's width, e a signed 64-bit entry, m a narrower minor.
template <int Lr, int Lm>
[[gnu::always_inline]] inline void add_product(Wide_integer<Lr>& acc, std::int64_t e, const Wide_integer<Lm>& m,
                                               bool negate) {
  const auto magnitude = e < 0 ? 0 - static_cast<std::uint64_t>(e) : static_cast<std::uint64_t>(e);
  const Wide_integer<Lr> product = Wide_integer<Lr>::extended(m).times(magnitude);
  if (negate != (e < 0)) acc -= product;
  else acc += product;
}
/// The same with an entry 0 ≤ e < 2^127 (the lifted column).
template <int Lr, int Lm>
[[gnu::always_inline]] inline void add_product(Wide_integer<Lr>& acc, Uint128 e, const Wide_integer<Lm>& m,
                                               bool negate) {
  const auto wide = Wide_integer<Lr>::extended(m);
  const Wide_integer<Lr> product =
      wide.times(static_cast<std::uint64_t>(e)) + wide.times(static_cast<std::uint64_t>(e >> 64)).shifted_limb();
  if (negate) acc -= product;
  else acc += product;
}

}  // namespace detail

/// The sign of det(a), a K×K matrix of integers given modulo 2^128, whose
/// first `spatial` columns hold values below 2^62 in magnitude and whose other
/// columns (at most one, the last) values 0 ≤ v < 2^127; nothing when an entry
/// is out of those ranges. Laplace expansion column by column: the minors of
/// the first r columns over every row set, each along its last column,
///   M_r(R) = Σ_{i ∈ R} (−1)^(#{R below i} + r − 1) a[i][r−1] · M_{r−1}(R \ i),
/// in integers of minor_limbs(r) limbs (exact: the bound says they fit).
template <int K, int spatial>
std::optional<int> small_entry_determinant_sign(const Matrix<Uint128, K>& a) {
  static_assert((spatial == K && K >= 2) || (spatial == K - 1 && K >= 3));
  constexpr bool lifted = spatial < K;
  std::int64_t e[K][K];  // the spatial entries
  for (int i = 0; i < K; ++i)
    for (int j = 0; j < spatial; ++j) {
      const auto v = static_cast<Int128>(a[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
      if (v >= (Int128{1} << detail::entry_bits) || v <= -(Int128{1} << detail::entry_bits)) return std::nullopt;
      e[i][j] = static_cast<std::int64_t>(v);
    }
  if constexpr (lifted)
    for (int i = 0; i < K; ++i)
      if (a[static_cast<std::size_t>(i)][K - 1] >> 127) return std::nullopt;

  constexpr const auto& table = detail::minor_masks<K>;
  // Level 1 and 2 in native integers: |a·d − b·c| < 2^125.
  std::array<Wide_integer<2>, (1 << K)> level2;
  detail::static_for<table.level_begin[2], table.level_begin[3]>([&](auto t) {
    constexpr unsigned mask = table.masks[t];
    constexpr int i0 = std::countr_zero(mask), i1 = std::countr_zero(mask & (mask - 1));
    level2[mask] = Wide_integer<2>::of(static_cast<Int128>(e[i0][0]) * e[i1][1] -
                                       static_cast<Int128>(e[i1][0]) * e[i0][1]);
  });
  // Levels 3 … K, each in its own width.
  const auto next_level = [&](auto r_constant, const auto& below) {
    constexpr int r = decltype(r_constant)::value;
    constexpr int limbs = detail::minor_limbs(r, lifted && r == K);
    std::array<Wide_integer<limbs>, (1 << K)> level;
    detail::static_for<table.level_begin[r], table.level_begin[r + 1]>([&](auto t) {
      constexpr unsigned mask = table.masks[t];
      Wide_integer<limbs> sum;
      detail::static_for<0, K>([&](auto i) {
        if constexpr ((mask & (1u << i)) != 0) {
          constexpr bool negate = (std::popcount(mask & ((1u << i) - 1)) + r - 1) % 2 == 1;
          if constexpr (lifted && r == K)
            detail::add_product(sum, a[i][K - 1], below[mask & ~(1u << i)], negate);
          else
            detail::add_product(sum, e[i][r - 1], below[mask & ~(1u << i)], negate);
        }
      });
      level[mask] = sum;
    });
    return level;
  };
  if constexpr (K == 2) {
    return level2[3].sign();
  } else {
    // Unrolled K − 2 levels, each returning the next width's array.
    auto expand = [&](auto self, auto r_constant, const auto& below) -> int {
      constexpr int r = decltype(r_constant)::value;
      const auto level = next_level(r_constant, below);
      if constexpr (r == K) return level[(1u << K) - 1].sign();
      else return self(self, std::integral_constant<int, r + 1>{}, level);
    };
    return expand(expand, std::integral_constant<int, 3>{}, level2);
  }
}

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
