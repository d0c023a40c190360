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
// few 64-bit limbs; each product is a magnitude's limbs times one 64-bit
// entry (two for the lifted column), its sign a mask, not a branch.
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

/// An integer as its magnitude's limbs and a sign mask (all ones when
/// negative, else 0): the form every product below is taken in, so that a
/// product costs one 64-bit multiplication per pair of magnitude limbs, and
/// its sign enters the sum as a mask instead of a branch (the signs are the
/// data's: the branch on them, in the two's-complement products this
/// replaced, was mispredicted about half the time; 196 → 140 ns a 3D sphere
/// test, −9 % of a triangulation of points on a sphere).
template <int L>
struct Signed_magnitude {
  std::array<std::uint64_t, L> limb{};
  std::uint64_t negative = 0;
};

/// An integer modulo 2^(64·L), read in two's complement: the sums of products.
template <int L>
class Wide_integer {
  static_assert(L >= 1);

 public:
  Wide_integer() = default;

  /// this += (−1)^s·|a|·|b| modulo 2^(64L), s the sign of a·b, flipped when
  /// `negate`: the product's limbs (as many as this has), then this + (p XOR
  /// mask) + (mask AND 1), which is this − p when the mask is all ones.
  template <int A, int B>
  [[gnu::always_inline]] void add_product(const Signed_magnitude<A>& a, const Signed_magnitude<B>& b, bool negate) {
    // b's limbs outermost (b is the entry: one limb, or two for the lifted column).
    std::array<std::uint64_t, L> p{};
    for (int j = 0; j < B; ++j) {
      std::uint64_t carry = 0;
      for (int i = 0; i < A && i + j < L; ++i) {
        const auto k = static_cast<std::size_t>(i + j);
        const Uint128 t = static_cast<Uint128>(a.limb[static_cast<std::size_t>(i)]) * b.limb[static_cast<std::size_t>(j)] +
                          p[k] + carry;
        p[k] = static_cast<std::uint64_t>(t);
        carry = static_cast<std::uint64_t>(t >> 64);
      }
      if (A + j < L) p[static_cast<std::size_t>(A + j)] = carry;
    }
    const std::uint64_t mask = a.negative ^ b.negative ^ (negate ? ~std::uint64_t{0} : 0);
    std::uint64_t carry = mask & 1;
    for (int i = 0; i < L; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const Uint128 t = static_cast<Uint128>(limb_[k]) + (p[k] ^ mask) + carry;
      limb_[k] = static_cast<std::uint64_t>(t);
      carry = static_cast<std::uint64_t>(t >> 64);
    }
  }

  bool negative() const { return (limb_[L - 1] >> 63) != 0; }
  /// -1, 0, +1 for the two's-complement value.
  int sign() const {
    if (negative()) return -1;
    for (const auto x : limb_)
      if (x != 0) return 1;
    return 0;
  }
  /// |value| and its sign, without a branch: (v XOR mask) − mask, as
  /// (v XOR mask) + (mask AND 1). \pre value ≠ −2^(64L−1).
  Signed_magnitude<L> signed_magnitude() const {
    Signed_magnitude<L> r;
    r.negative = negative() ? ~std::uint64_t{0} : 0;
    std::uint64_t carry = r.negative & 1;
    for (int i = 0; i < L; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const Uint128 t = static_cast<Uint128>(limb_[k] ^ r.negative) + carry;
      r.limb[k] = static_cast<std::uint64_t>(t);
      carry = static_cast<std::uint64_t>(t >> 64);
    }
    return r;
  }

 private:
  std::array<std::uint64_t, L> limb_{};
};

/// v as a magnitude and a sign mask.
inline Signed_magnitude<1> signed_magnitude(std::int64_t v) {
  const auto mask = static_cast<std::uint64_t>(v >> 63);
  return {{(static_cast<std::uint64_t>(v) ^ mask) - mask}, mask};
}
inline Signed_magnitude<2> signed_magnitude(Int128 v) {
  const auto mask = static_cast<Uint128>(v >> 127);
  const Uint128 magnitude = (static_cast<Uint128>(v) ^ mask) - mask;
  return {{static_cast<std::uint64_t>(magnitude), static_cast<std::uint64_t>(magnitude >> 64)},
          static_cast<std::uint64_t>(mask)};
}

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
  std::array<Signed_magnitude<2>, (1 << K)> level2;
  detail::static_for<table.level_begin[2], table.level_begin[3]>([&](auto t) {
    constexpr unsigned mask = table.masks[t];
    constexpr int i0 = std::countr_zero(mask), i1 = std::countr_zero(mask & (mask - 1));
    level2[mask] = signed_magnitude(static_cast<Int128>(e[i0][0]) * e[i1][1] -
                                            static_cast<Int128>(e[i1][0]) * e[i0][1]);
  });
  // Levels 3 … K, each in its own width; the column's entries as magnitudes.
  const auto next_level = [&](auto r_constant, const auto& below) {
    constexpr int r = decltype(r_constant)::value;
    constexpr int limbs = detail::minor_limbs(r, lifted && r == K);
    std::array<Signed_magnitude<lifted && r == K ? 2 : 1>, K> column;
    for (int i = 0; i < K; ++i) {
      if constexpr (lifted && r == K) {
        const Uint128 v = a[static_cast<std::size_t>(i)][K - 1];
        column[static_cast<std::size_t>(i)] = {{static_cast<std::uint64_t>(v), static_cast<std::uint64_t>(v >> 64)}, 0};
      } else {
        column[static_cast<std::size_t>(i)] = signed_magnitude(e[i][r - 1]);
      }
    }
    std::array<Wide_integer<limbs>, (1 << K)> level;
    detail::static_for<table.level_begin[r], table.level_begin[r + 1]>([&](auto t) {
      constexpr unsigned mask = table.masks[t];
      Wide_integer<limbs> sum;
      detail::static_for<0, K>([&](auto i) {
        if constexpr ((mask & (1u << i)) != 0) {
          constexpr bool negate = (std::popcount(mask & ((1u << i) - 1)) + r - 1) % 2 == 1;
          sum.add_product(below[mask & ~(1u << i)], column[i], negate);
        }
      });
      level[mask] = sum;
    });
    return level;
  };
  if constexpr (K == 2) {
    return level2[3].limb[0] == 0 && level2[3].limb[1] == 0 ? 0 : level2[3].negative ? -1 : 1;
  } else {
    // Unrolled K − 2 levels, each returning the next width's array.
    auto expand = [&](auto self, auto r_constant, const auto& below) -> int {
      constexpr int r = decltype(r_constant)::value;
      const auto level = next_level(r_constant, below);
      if constexpr (r == K) {
        return level[(1u << K) - 1].sign();
      } else {
        constexpr int limbs = detail::minor_limbs(r, false);
        std::array<Signed_magnitude<limbs>, (1 << K)> magnitudes;
        detail::static_for<table.level_begin[r], table.level_begin[r + 1]>([&](auto t) {
          constexpr unsigned mask = table.masks[t];
          magnitudes[mask] = level[mask].signed_magnitude();
        });
        return self(self, std::integral_constant<int, r + 1>{}, magnitudes);
      }
    };
    return expand(expand, std::integral_constant<int, 3>{}, level2);
  }
}

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
