// Exact stage support: doubles as GMP integers on a common binary scale.
//
// Every finite double is m·2^e with an integer |m| < 2^53 and e ≥ -1074. A set of
// doubles multiplied by 2^-E, E the smallest exponent among them, are integers,
// so differences and products of them are exact in mpz. Scaling all spatial
// columns by 2^-E (and the lifted column by 2^-2E) multiplies the determinant by
// a positive number, so its sign is the sign we want.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/wide_integer.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

using Exact_integer = mpz_class;

namespace detail {

struct Split_double {
  std::int64_t mantissa = 0;  // |mantissa| < 2^53
  int exponent = 0;           // value = mantissa · 2^exponent
};

inline Split_double split(double v) {
  if (v == 0) return {0, std::numeric_limits<int>::max()};
  // From the bits (frexp and ldexp were a tenth of a lattice's triangulation):
  // a normal double is (2^52 + fraction)·2^(field − 1075), a subnormal
  // fraction·2^-1074. v is finite (checked at the API boundary).
  const auto bits = std::bit_cast<std::uint64_t>(v);
  const int field = static_cast<int>((bits >> 52) & 0x7ff);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  const std::uint64_t magnitude = field == 0 ? fraction : fraction | (std::uint64_t{1} << 52);
  const int exponent = field == 0 ? -1074 : field - 1075;
  // An odd mantissa keeps small integers small (3.0 is 3·2^0, not 3·2^51·2^-51),
  // which lets the 128-bit path below take exactly degenerate integer inputs.
  const int zeros = std::countr_zero(magnitude);
  const auto m = static_cast<std::int64_t>(magnitude >> zeros);
  return {bits >> 63 ? -m : m, exponent + zeros};
}
}  // namespace detail

/// Converts a batch of doubles to integers on one scale: value·2^-E.
template <int N>
class Common_scale {
 public:
  explicit Common_scale(const double (&values)[N]) {
    for (int i = 0; i < N; ++i) {
      parts_[i] = detail::split(values[i]);
      if (parts_[i].exponent < min_exponent_) min_exponent_ = parts_[i].exponent;
    }
  }
  /// The bits of the largest |values[i]|·2^-E (0 when every value is 0).
  int max_bits() const {
    int bits = 0;
    for (const auto& s : parts_)
      if (s.mantissa != 0)
        bits = std::max(bits, static_cast<int>(std::bit_width(
                                  static_cast<std::uint64_t>(s.mantissa < 0 ? -s.mantissa : s.mantissa))) +
                                  (s.exponent - min_exponent_));
    return bits;
  }
  /// Whether every values[i]·2^-E fits in `bits` bits (plus sign).
  bool fits(int bits) const { return max_bits() <= bits; }
  /// values[i]·2^-E as a 128-bit integer. \pre fits(bits) with bits ≤ 125.
  Int128 small_integer(int i) const {
    const auto& s = parts_[i];
    if (s.mantissa == 0) return 0;
    return static_cast<Int128>(s.mantissa) * (static_cast<Int128>(1) << (s.exponent - min_exponent_));
  }

  /// z = values[i]·2^-E, in place (z keeps its capacity: no allocation once grown).
  void assign_integer(int i, Exact_integer& z) const {
    const auto& s = parts_[i];
    mpz_set_si(z.get_mpz_t(), static_cast<long>(s.mantissa));
    if (s.mantissa != 0)
      mpz_mul_2exp(z.get_mpz_t(), z.get_mpz_t(), static_cast<mp_bitcnt_t>(s.exponent - min_exponent_));
  }
  /// values[i]·2^-E as an exact integer.
  Exact_integer integer(int i) const {
    const auto& s = parts_[i];
    if (s.mantissa == 0) return 0;
    Exact_integer z(static_cast<long>(s.mantissa));
    mpz_mul_2exp(z.get_mpz_t(), z.get_mpz_t(), static_cast<mp_bitcnt_t>(s.exponent - min_exponent_));
    return z;
  }

 private:
  detail::Split_double parts_[N];
  int min_exponent_ = std::numeric_limits<int>::max();
};

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
