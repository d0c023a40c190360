// Signs returned by every predicate, with CGAL's enumerator names so that the
// CGAL adapter is a plain cast.
#pragma once

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
