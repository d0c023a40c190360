// Signs returned by every predicate, with CGAL's enumerator names so that the
// CGAL adapter is a plain cast.
#pragma once

#include <optional>

namespace dewall::kernel {

/// The sign of a determinant. `orientation_d` may return ZERO; the `_sos`
/// predicates never do.
enum Sign : int { NEGATIVE = -1, ZERO = 0, POSITIVE = 1 };

/// Which side of an oriented sphere a query lies on: for a positively oriented
/// simplex, ON_POSITIVE_SIDE is strictly inside the circumsphere.
enum Oriented_side : int {
  ON_NEGATIVE_SIDE = -1,
  ON_ORIENTED_BOUNDARY = 0,
  ON_POSITIVE_SIDE = 1
};

/// A filter's answer: a Sign, or none when the filter cannot tell, with
/// std::optional's interface. One byte, where std::optional<Sign> is an int
/// and a flag: inlined into the cavity search, GCC stored those two pieces
/// separately and reloaded them as one word, a store-forwarding stall that
/// took a third of the 2D cavity search's samples (points on a circle).
class Maybe_sign {
 public:
  constexpr Maybe_sign() = default;
  constexpr Maybe_sign(std::nullopt_t) {}
  constexpr Maybe_sign(Sign s) : value_(static_cast<signed char>(s)) {}
  constexpr bool has_value() const { return value_ != none; }
  constexpr explicit operator bool() const { return has_value(); }
  /// \pre has_value()
  constexpr Sign operator*() const { return static_cast<Sign>(value_); }
  constexpr operator std::optional<Sign>() const {
    return has_value() ? std::optional<Sign>(static_cast<Sign>(value_)) : std::nullopt;
  }

 private:
  static constexpr signed char none = 2;
  signed char value_ = none;
};
static_assert(sizeof(Maybe_sign) == 1);

enum Comparison_result : int { SMALLER = -1, EQUAL = 0, LARGER = 1 };

constexpr Sign operator-(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }
constexpr Sign operator*(Sign a, Sign b) {
  return static_cast<Sign>(static_cast<int>(a) * static_cast<int>(b));
}

template <class T>
constexpr Sign sign_of(const T& x) {
  return x > 0 ? POSITIVE : (x < 0 ? NEGATIVE : ZERO);
}

}  // namespace dewall::kernel
