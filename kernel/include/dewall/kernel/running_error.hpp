// A double with a bound on its distance from the exact value it stands for:
// running error analysis (Wilkinson; Higham, "Accuracy and Stability of
// Numerical Algorithms", §3.3), the arithmetic of the cascade's second stage
// (filtered_predicate.hpp, stages::running_error).
//
// Why not intervals. Near ties the permanent stage cannot decide (points on a
// circle or a sphere) are decided by the same determinant in double when its
// real rounding error is known; an interval bounds it too, but ours widens
// every bound by up to two ulps (interval.hpp: no rounding-mode switch), and a
// difference of nearby coordinates, which is exact, gets the same widening.
// Here each operation adds u·|result| (round to nearest: half an ulp), and
// the differences of input coordinates carry their exact error (TwoSum: zero
// when the coordinates are within a factor 2, Sterbenz). Measured on the
// calls that reached the exact stage before it existed (2D points on a
// circle, 3D on a sphere): this stage decides 71 % and 61 % of them (57 % and
// 41 % with the query as the rows' origin) where our intervals decide 20 %
// and 13 %, at about the intervals' cost.
//
// Model (valid only under Fp_environment_guard: round to nearest, gradual
// underflow). Let x̂, ŷ be computed values with |x̂ − x| ≤ e_x, |ŷ − y| ≤ e_y,
// x and y exact. For r̂ = fl(x̂ ∘ ŷ), |r̂ − x̂ ∘ ŷ| ≤ u·|r̂| (u = 2^-53;
// fl(z) = z/(1 + δ), |δ| ≤ u, Higham (2.5)) when r̂ is normal; sums that
// underflow are exact, products lose less than 2^-1074 (left to the caller's
// floor). Hence
//   e_{x±y} = e_x + e_y + u·|r̂|,
//   e_{x·y} = |x̂|·e_y + |ŷ|·e_x + e_x·e_y + u·|r̂|.
// The bounds are themselves computed in double: every one is a sum of
// products of nonnegative terms, so the computed bound is at least the exact
// one times (1 − u)^m, m the rounded operations of its whole computation (a
// term e_x·e_y carries the roundings of both operands); the caller
// multiplies by a margin that covers m (filtered_predicate.hpp). An overflow
// makes a bound infinite or NaN, which decides nothing (comparisons false).
#pragma once

#include <cmath>
#include <utility>

#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

class Tracked_double {
 public:
  static constexpr double unit_roundoff = 0x1p-53;  // round to nearest

  constexpr Tracked_double() = default;
  constexpr Tracked_double(double value, double error) : value_(value), error_(error) {}

  double value() const { return value_; }
  /// A bound on |value() − exact|, before the caller's margin.
  double error() const { return error_; }

  friend Tracked_double operator+(const Tracked_double& a, const Tracked_double& b) {
    const double r = a.value_ + b.value_;
    return {r, a.error_ + b.error_ + unit_roundoff * std::fabs(r)};
  }
  friend Tracked_double operator-(const Tracked_double& a, const Tracked_double& b) {
    const double r = a.value_ - b.value_;
    return {r, a.error_ + b.error_ + unit_roundoff * std::fabs(r)};
  }
  friend Tracked_double operator*(const Tracked_double& a, const Tracked_double& b) {
    const double r = a.value_ * b.value_;
    return {r, std::fabs(a.value_) * b.error_ + std::fabs(b.value_) * a.error_ + a.error_ * b.error_ +
                   unit_roundoff * std::fabs(r)};
  }
  Tracked_double& operator+=(const Tracked_double& b) { return *this = *this + b; }
  Tracked_double& operator-=(const Tracked_double& b) { return *this = *this - b; }

 private:
  double value_ = 0, error_ = 0;
};

/// An input coordinate, exact by definition: the recipes only subtract two of
/// them (the matrices' spatial entries), and that difference carries its
/// exact rounding error, found by TwoSum (Knuth; exact in round to nearest
/// without overflow, under gradual underflow too).
struct Exact_coordinate {
  double value;

  friend Tracked_double operator-(Exact_coordinate a, Exact_coordinate b) {
    const double r = a.value - b.value;
    const double b_part = r - a.value;          // −b as carried into r
    const double a_part = r - b_part;           // a as carried into r
    const double error = (a.value - a_part) + (-b.value - b_part);  // exactly a − b − r
    return {r, std::fabs(error)};
  }
};

// DEWALL_TARGET_HAS_FMA: defined where the target's instruction set has a fused multiply-add
// (x86-64 with -mfma or -march=x86-64-v3 and up, AArch64, and others whose
// compiler announces a fast fma).
#if defined(__FP_FAST_FMA) || defined(__FMA__) || defined(__ARM_FEATURE_FMA)
#define DEWALL_TARGET_HAS_FMA 1
#endif

/// a·b − c·d, its products formed exactly and only what remains rounded:
/// where the two products nearly cancel (the 2×2 minors of short, nearly
/// parallel rows: neighbouring points on a circle) the error is about
/// u·|a·b − c·d| instead of u·|a·b|. Two forms of one computation; the
/// operands' own errors reach the result as in operator*, and the caller
/// ensures the condition under which the products' parts are exact, for the
/// computed values â, b̂, ĉ, d̂: each is zero or has magnitude in
/// [2^-484, 2^500]. (Then the exponents of any two satisfy e + e' ≥ −970, so
/// every part of a product below is a multiple of ulp·ulp' ≥ 2^-1074 with at
/// most 53 significant bits, represented exactly even when subnormal, and
/// the error-free transformations hold as they do without underflow; 2^500
/// keeps the products and Veltkamp's splitting from overflowing.)
///
/// Fused (Kahan's algorithm, with an FMA): w = fl(ĉ·d̂), e = fma(−ĉ, d̂, w) =
/// w − ĉ·d̂ exactly, f̂ = fma(â, b̂, −w) = fl(â·b̂ − w), r̂ = fl(f̂ + e). As
/// â·b̂ − ĉ·d̂ = (â·b̂ − w) + e, the two roundings leave |r̂ − (â·b̂ − ĉ·d̂)| ≤
/// u·(|f̂| + |r̂|). No contraction can change it: its one plain product, w,
/// is used only as an fma operand, leaving nothing to contract into.
///
/// Split (without an FMA): â·b̂ = p + p' and ĉ·d̂ = q + q' exactly (TwoProduct
/// by Veltkamp's splitting into 26-bit halves: Dekker, "A floating-point
/// technique for extending the available precision", 1971), r̂ = fl(fl(p − q)
/// + fl(p' − q')): |r̂ − (â·b̂ − ĉ·d̂)| ≤ u·(|fl(p − q)| + |fl(p' − q')| + |r̂|).
/// Compiled only where the target has no FMA instruction
/// (DEWALL_TARGET_HAS_FMA undefined), so none to contract the splitting's
/// products into: GCC with -mfma -ffp-contract=fast fuses Veltkamp's split,
/// which then is not Veltkamp's.
[[gnu::always_inline]] inline double inherited_product_error(const Tracked_double& a, const Tracked_double& b) {
  return std::fabs(a.value()) * b.error() + std::fabs(b.value()) * a.error() + a.error() * b.error();
}
[[gnu::always_inline]] inline Tracked_double difference_of_products_fused(const Tracked_double& a,
                                                                        const Tracked_double& b,
                                                                        const Tracked_double& c,
                                                                        const Tracked_double& d) {
  const double w = c.value() * d.value();
  const double e = std::fma(-c.value(), d.value(), w);
  const double f = std::fma(a.value(), b.value(), -w);
  const double r = f + e;
  return {r, inherited_product_error(a, b) + inherited_product_error(c, d) +
                 Tracked_double::unit_roundoff * (std::fabs(f) + std::fabs(r))};
}
#ifndef DEWALL_TARGET_HAS_FMA
/// Veltkamp's splitting: x = head + tail, each of at most 26 significant bits.
[[gnu::always_inline]] inline std::pair<double, double> split_double(double x) {
  const double scaled = (0x1p27 + 1) * x;
  const double head = scaled - (scaled - x);
  return {head, x - head};
}
[[gnu::always_inline]] inline Tracked_double difference_of_products_split(const Tracked_double& a,
                                                                        const Tracked_double& b,
                                                                        const Tracked_double& c,
                                                                        const Tracked_double& d) {
  const auto exact_product = [](double x, double y) {
    const double high = x * y;
    const auto [xh, xl] = split_double(x);
    const auto [yh, yl] = split_double(y);
    return std::pair{high, ((xh * yh - high) + xh * yl + xl * yh) + xl * yl};
  };
  const auto [p, p_low] = exact_product(a.value(), b.value());
  const auto [q, q_low] = exact_product(c.value(), d.value());
  const double high = p - q, low = p_low - q_low, r = high + low;
  return {r, inherited_product_error(a, b) + inherited_product_error(c, d) +
                 Tracked_double::unit_roundoff * (std::fabs(high) + std::fabs(low) + std::fabs(r))};
}
#endif

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
