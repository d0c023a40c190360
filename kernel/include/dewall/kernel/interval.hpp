// Interval arithmetic that needs no rounding-mode switch.
//
// Every operation is computed in the default round-to-nearest mode and its
// bounds are then moved outward by at least one ulp: r ↦ r ∓ (|r|·2^-52 + 2^-1074).
// Why this is enough: for r = m·2^e (1 ≤ |m| < 2) the step |r|·2^-52 is at least
// ulp(r) = 2^(e−52), so the exact value r − step is at most the neighbour of r
// and, rounding being monotone, so is its rounded value; the 2^-1074 term is
// one subnormal ulp, which covers r = 0 and subnormal r. The exact result lies
// within half an ulp of r (round-to-nearest; sums are exact when subnormal),
// so the widened interval always contains it, including under gradual
// underflow: a product that rounds to 0 becomes [-2^-1074, 2^-1074]. Overflow
// gives an infinite or NaN bound; `sign()` reports such an interval as
// undecided, so the cascade moves on to the exact stage.
//
// Two flops per bound instead of a rounding-mode guard (CGAL's
// Protect_FPU_rounding) or a nextafter call: correct whatever the compiler does
// with the rounding mode, as long as it keeps IEEE double arithmetic
// (floating_point.hpp says how the flags and the environment are ensured).
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "dewall/kernel/sign.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::kernel {

class Interval {
 public:
  constexpr Interval() = default;
  constexpr Interval(double v) : lo_(v), hi_(v) {}  // NOLINT: exact conversion
  constexpr Interval(double lo, double hi) : lo_(lo), hi_(hi) {}

  double lo() const { return lo_; }
  double hi() const { return hi_; }

  friend Interval operator+(const Interval& a, const Interval& b) {
    return outward(a.lo_ + b.lo_, a.hi_ + b.hi_);
  }
  friend Interval operator-(const Interval& a, const Interval& b) {
    return outward(a.lo_ - b.hi_, a.hi_ - b.lo_);
  }
  friend Interval operator-(const Interval& a) { return {-a.hi_, -a.lo_}; }
  friend Interval operator*(const Interval& a, const Interval& b) {
    const double p[4] = {a.lo_ * b.lo_, a.lo_ * b.hi_, a.hi_ * b.lo_, a.hi_ * b.hi_};
    double lo = p[0], hi = p[0];
    for (double v : p) {
      if (std::isnan(v)) return nan_interval();
      lo = v < lo ? v : lo;
      hi = v > hi ? v : hi;
    }
    return outward(lo, hi);
  }
  /// Division; the whole line when b contains 0.
  friend Interval operator/(const Interval& a, const Interval& b) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    if (!(b.lo_ > 0 || b.hi_ < 0)) return {-inf, inf};
    const double q[4] = {a.lo_ / b.lo_, a.lo_ / b.hi_, a.hi_ / b.lo_, a.hi_ / b.hi_};
    double lo = q[0], hi = q[0];
    for (double v : q) {
      if (std::isnan(v)) return nan_interval();
      lo = v < lo ? v : lo;
      hi = v > hi ? v : hi;
    }
    return outward(lo, hi);
  }
  /// The largest absolute value in the interval.
  double magnitude() const { return std::fabs(lo_) > std::fabs(hi_) ? std::fabs(lo_) : std::fabs(hi_); }
  Interval& operator+=(const Interval& b) { return *this = *this + b; }
  Interval& operator-=(const Interval& b) { return *this = *this - b; }

  /// The sign of every value in the interval, or nothing when it contains 0
  /// (or is NaN after an overflow).
  Maybe_sign sign() const {
    if (lo_ > 0) return POSITIVE;
    if (hi_ < 0) return NEGATIVE;
    return std::nullopt;
  }

 private:
  static Interval nan_interval() {
    const double n = std::numeric_limits<double>::quiet_NaN();
    return {n, n};
  }
  static Interval outward(double lo, double hi) {
    constexpr double ulp_factor = 0x1p-52, subnormal_ulp = 0x1p-1074;
    return {lo - (std::fabs(lo) * ulp_factor + subnormal_ulp), hi + (std::fabs(hi) * ulp_factor + subnormal_ulp)};
  }
  double lo_ = 0, hi_ = 0;
};

}  // namespace dewall::kernel
DEWALL_FLOATING_POINT_CODE_END
