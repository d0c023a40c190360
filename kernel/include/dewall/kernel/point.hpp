// Point_d<D>: a point of E^D with double coordinates (static dimension).
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "dewall/kernel/sign.hpp"

namespace dewall::kernel {

/// The smallest and largest dimensions the kernel is instantiated and tested for.
inline constexpr int min_dimension = 2;
inline constexpr int max_dimension = 6;
/// X(2) X(3) X(4) X(5) X(6): the supported dimensions, the one list that the
/// compiled libraries' explicit instantiations and with_dimension expand.
#define DEWALL_FOR_EACH_DIMENSION(X) X(2) X(3) X(4) X(5) X(6)
static_assert(min_dimension == 2 && max_dimension == 6, "DEWALL_FOR_EACH_DIMENSION lists min_dimension … max_dimension");

/// A point of E^D over double. An aggregate (`Point_d<3>{{1, 2, 3}}`) so that
/// arrays of points are contiguous and trivially copyable.
template <int D>
struct Point_d {
  static_assert(D >= 1 && D <= max_dimension, "dimension out of range");
  static constexpr int dimension = D;
  std::array<double, D> x;

  constexpr double operator[](int i) const { return x[static_cast<std::size_t>(i)]; }
  constexpr double& operator[](int i) { return x[static_cast<std::size_t>(i)]; }
  friend constexpr bool operator==(const Point_d&, const Point_d&) = default;
};

/// N points by reference, as the predicates take them.
template <int D, int N>
using Point_refs = std::array<const Point_d<D>*, N>;

/// A key whose integer order is the numeric order of finite doubles, −0 and +0
/// alike. Computed from the bits, so that it holds in any floating-point
/// environment: with denormals-are-zero (DAZ) on, the hardware compares a
/// subnormal as equal to 0 (floating_point.hpp).
constexpr std::int64_t order_key(double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  if ((bits << 1) == 0) return 0;  // ±0
  const auto magnitude = static_cast<std::int64_t>(bits & ~(std::uint64_t{1} << 63));
  return bits >> 63 ? -magnitude : magnitude;
}

/// Lexicographic comparison of the coordinates (x, then y, ...), exact.
/// This is the total order of CGAL's `compare_xyz` / `Compare_lexicographically_d`,
/// which the symbolic perturbation is defined on.
template <std::size_t D>
constexpr Comparison_result compare_lexicographically(const std::array<double, D>& a, const std::array<double, D>& b) {
  for (std::size_t i = 0; i < D; ++i) {
    const std::int64_t x = order_key(a[i]), y = order_key(b[i]);
    if (x < y) return SMALLER;
    if (x > y) return LARGER;
  }
  return EQUAL;
}
template <int D>
constexpr Comparison_result compare_lexicographically(const Point_d<D>& a, const Point_d<D>& b) {
  return compare_lexicographically(a.x, b.x);
}

/// True when v is neither NaN nor infinite, decided on the bits (exponent not
/// all ones): std::isfinite folds to true in files compiled with
/// -ffinite-math-only, which would let a NaN through.
constexpr bool is_finite(double v) {
  constexpr std::uint64_t exponent = std::uint64_t{0x7ff} << 52;
  return (std::bit_cast<std::uint64_t>(v) & exponent) != exponent;
}

/// True when every coordinate is finite (neither NaN nor infinite).
template <int D>
constexpr bool is_finite(const Point_d<D>& p) {
  for (int i = 0; i < D; ++i)
    if (!is_finite(p[i])) return false;
  return true;
}

}  // namespace dewall::kernel
