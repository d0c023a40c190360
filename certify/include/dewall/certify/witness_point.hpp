// The witness point of the global test: a symbolic point strictly inside one
// simplex, located against any hyperplane by orientation predicates alone.
//
// For a simplex s_0 … s_D take  o(ε) = s_0 + Σ_{k=1..D} ε^k (s_k − s_0)  with
// ε → 0+. Its barycentric coordinates (1 − Σε^k, ε, ε², …, ε^D) are all
// positive, so o lies strictly inside the simplex. The orientation determinant
// is affine in each point, so with a hyperplane given by D points h:
//   orient(h, o) = orient(h, s_0) + Σ_k ε^k (orient(h, s_k) − orient(h, s_0)),
// whose sign for small ε is the first non-zero of orient(h, s_0), orient(h, s_1),
// …, orient(h, s_D) — exact kernel predicates, no constructed coordinates. Not
// all of them vanish (s is full-dimensional), so o lies on no hyperplane
// spanned by input points: it is in general position with respect to every
// facet, which is what the covering-number argument of certify.hpp needs.
// The same idea as the "carefully chosen interior point" of Mehlhorn et al.,
// "Checking geometric programs or verification of geometric structures",
// CGTA 12 (1999), made exact by symbolic perturbation.
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "dewall/kernel/concepts.hpp"

namespace dewall::certify::detail {

template <kernel::DelaunayKernel K>
class Witness_point {
 public:
  static constexpr int D = K::dimension;
  using Point = typename K::Point_d;
  using Cell = std::array<const Point*, D + 1>;

  /// The witness inside `simplex`. \pre simplex is positively oriented.
  Witness_point(const K& k, const Cell& simplex) : orientation_(k.orientation_d_object()), simplex_(simplex) {}

  /// The side of the witness relative to the facet of `cell` opposite position
  /// i: POSITIVE when it is on the side of cell[i] (for a positively oriented
  /// cell). Never ZERO. Cost: at most D + 1 orientation tests, usually one.
  kernel::Sign side_of_facet(const Cell& cell, int i) const {
    Cell c = cell;
    for (int k = 0; k <= D; ++k) {
      c[static_cast<std::size_t>(i)] = simplex_[static_cast<std::size_t>(k)];
      const kernel::Sign s = orientation_(c);
      if (s != kernel::ZERO) return s;
    }
    return kernel::ZERO;  // only when simplex_ is degenerate, excluded by the precondition
  }

  /// Whether the witness lies inside the positively oriented `cell` (never on
  /// its boundary: see side_of_facet).
  bool inside(const Cell& cell) const {
    for (int i = 0; i <= D; ++i)
      if (side_of_facet(cell, i) != kernel::POSITIVE) return false;
    return true;
  }

  /// The input point the witness is infinitesimally close to.
  const Point& anchor() const { return *simplex_[0]; }

 private:
  decltype(std::declval<const K&>().orientation_d_object()) orientation_;
  Cell simplex_;
};

}  // namespace dewall::certify::detail
