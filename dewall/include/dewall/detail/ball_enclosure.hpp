// A box that provably contains the closed circumball of a simplex, for pruning
// the grid search. Only double coordinates are used, so it holds for any
// kernel whose points are doubles; it never decides, it only bounds where a
// point inside the ball could be.
//
// The centre c solves 2(s_i − s_0)·(c − s_0) = |s_i − s_0|², i = 1..D. By
// Cramer, (c − s_0)_j = Δ_j / Δ with Δ = det[s_i − s_0] and Δ_j the same with
// column j replaced by |s_i − s_0|²/2. Both are evaluated in double by the
// kernel's `determinant`, with the proven error bounds of error_bounds.hpp
// (Δ has the orientation's rounding factors; Δ_j one lifted column, D + 2 factors
// instead of 1), so the exact values lie in [Δ̂ ± e]. Interval division and
// addition (rounded outward) then enclose c, and |c − s_0| bounds the radius.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "dewall/detail/uniform_grid.hpp"
#include "dewall/kernel/determinant.hpp"
#include "dewall/kernel/error_bounds.hpp"
#include "dewall/kernel/interval.hpp"

namespace dewall::detail {

template <int D>
struct Ball_box {
  Coords<D> lo, hi;
  bool bounded = false;  // false: the enclosure failed (flat simplex, extreme range); use the whole grid
};

template <int D>
Ball_box<D> circumball_box(const std::array<const Coords<D>*, D + 1>& s) {
  using kernel::Interval;
  namespace eb = kernel::error_bounds;
  Ball_box<D> box;
  kernel::Matrix<double, D> a;
  std::array<double, D> half_lift;
  std::array<double, D> col_max{};
  double lift_max = 0, largest = 0;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      a[i][j] = (*s[i + 1])[j] - (*s[0])[j];
      largest = std::fmax(largest, std::fabs(a[i][j]));
    }
  // Very large or very small simplices: scale the differences by a power of two
  // (exact, but for entries that underflow, whose absolute error ≤ 2^-1075 the
  // step-4 underflow allowance of error_bounds.hpp covers) and the centre back.
  int exponent = 0;
  if (largest > 0 && !(largest >= 0x1p-50 && largest <= 0x1p50)) {
    exponent = std::ilogb(largest);
    for (auto& row : a)
      for (double& v : row) v = std::ldexp(v, -exponent);
  }
  for (int i = 0; i < D; ++i) {
    double l = 0;
    for (int j = 0; j < D; ++j) {
      l += a[i][j] * a[i][j];
      col_max[j] = std::fmax(col_max[j], std::fabs(a[i][j]));
    }
    half_lift[i] = 0.5 * l;
    lift_max = std::fmax(lift_max, half_lift[i]);
  }
  double product = 1;
  for (int j = 0; j < D; ++j) {
    if (!(col_max[j] >= eb::min_column_max && col_max[j] <= eb::max_column_max)) return box;
    product *= col_max[j];
  }
  const double det = kernel::determinant<double, D>(a);
  const double det_error = eb::orientation_epsilon(D) * product;
  constexpr int lifted_factors = eb::expansion_factors(D) + (D - 1) + (D + 2);
  const Interval denominator = Interval(det) + Interval(-det_error, det_error);
  if (!denominator.sign()) return box;
  Interval radius2(0.0);
  std::array<Interval, D> centre;
  for (int j = 0; j < D; ++j) {
    auto aj = a;
    for (int i = 0; i < D; ++i) aj[i][j] = half_lift[i];
    const double dj = kernel::determinant<double, D>(aj);
    const double ej = eb::filter_epsilon(lifted_factors, D) * product / col_max[j] * lift_max;
    const Interval offset = (Interval(dj) + Interval(-ej, ej)) / denominator * Interval(std::ldexp(1.0, exponent));
    centre[j] = Interval((*s[0])[j]) + offset;
    const double m = offset.magnitude();
    radius2 += Interval(m) * Interval(m);
  }
  const double radius = std::nextafter(std::sqrt(radius2.hi()), std::numeric_limits<double>::infinity());
  for (int j = 0; j < D; ++j) {
    box.lo[j] = (centre[j] - Interval(radius)).lo();
    box.hi[j] = (centre[j] + Interval(radius)).hi();
    if (!std::isfinite(box.lo[j]) || !std::isfinite(box.hi[j])) return box;
  }
  box.bounded = true;
  return box;
}

}  // namespace dewall::detail
