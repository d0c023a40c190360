// Interval arithmetic that needs no rounding-mode switch.
//
// Every operation is computed in the default round-to-nearest mode and its
// bounds are then moved one ulp outward with nextafter. Round-to-nearest is
// within half an ulp of the exact result (and exact for subnormal sums), so the
// widened interval always contains it, including under gradual underflow: a
// product that rounds to 0 becomes [-denorm_min, +denorm_min]. Overflow gives
// an infinite bound, and inf - inf gives NaN; `sign()` reports such an interval
// as undecided, so the cascade moves on to the exact stage.
//
// This costs two nextafter calls per operation instead of a rounding-mode
// guard (CGAL's Protect_FPU_rounding); the stage only runs when the static
// filter failed, so its speed matters little, and it stays correct whatever
// the compiler does with the floating-point environment.
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "dewall/kernel/sign.hpp"

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
      lo = std::fmin(lo, v);
      hi = std::fmax(hi, v);
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
      lo = std::fmin(lo, v);
      hi = std::fmax(hi, v);
    }
    return outward(lo, hi);
  }
  /// The largest absolute value in the interval.
  double magnitude() const { return std::fmax(std::fabs(lo_), std::fabs(hi_)); }
  Interval& operator+=(const Interval& b) { return *this = *this + b; }
  Interval& operator-=(const Interval& b) { return *this = *this - b; }

  /// The sign of every value in the interval, or nothing when it contains 0
  /// (or is NaN after an overflow).
  std::optional<Sign> sign() const {
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
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {std::nextafter(lo, -inf), std::nextafter(hi, inf)};
  }
  double lo_ = 0, hi_ = 0;
};

}  // namespace dewall::kernel
