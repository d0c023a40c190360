// Symbolic perturbation of the sphere predicate: CGAL's lexicographic scheme.
//
// CGAL (Delaunay_triangulation_3::side_of_oriented_sphere with perturb = true,
// Triangulation_2::side_of_oriented_circle, and the dD
// Delaunay_triangulation::perturbed_side_of_positive_sphere) resolves a zero
// sphere test by lifting each point p to |p|² + ε^(rank p) for an infinitesimal
// ε, where a lexicographically larger point gets a *larger* perturbation (a
// smaller exponent). Expanding the lifted determinant along the lifted column,
// the coefficient of point p_i's perturbation is ± the orientation of the other
// D + 1 points. Taking the points from the lexicographically largest down:
//  * if the largest remaining point is q, its coefficient is ±orientation(p_0 … p_D),
//    which is POSITIVE by precondition; q is lifted up, so it is outside:
//    ON_NEGATIVE_SIDE;
//  * if it is p_i, the sign of the term is the orientation of the simplex with
//    p_i replaced by q (same position, same sign convention); if that is non-zero
//    it decides, otherwise the next point's term is examined.
// Since p_0 … p_D are affinely independent the walk ends at q at the latest, so
// the result is never ON_ORIENTED_BOUNDARY. The result depends on the points'
// coordinates only (never on addresses or argument order beyond the orientation
// sign), which is what makes the triangulation a function of the point set.
#pragma once

#include <array>
#include <bit>

#include "dewall/kernel/point.hpp"
#include "dewall/kernel/sign.hpp"

namespace dewall::kernel {

/// The perturbed answer for a sphere test whose unperturbed value is zero.
/// `points` holds p_0 … p_D then q; `orientation` evaluates the (exact)
/// orientation of D + 1 point references; `less` is the strict lexicographic order.
/// Generic over the point type so that the CGAL adapter shares it.
/// \pre orientation(p_0 … p_D) == POSITIVE.
template <int D, class PointRef, class Orientation, class Less>
Oriented_side perturbed_side_of_sphere(const std::array<PointRef, D + 2>& points,
                                       const Orientation& orientation, const Less& less) {
  // The largest remaining point is selected when needed, not the points
  // sorted first: the first or second point decides nearly every call (a
  // sort of the D + 2 points was a third of a lattice sphere's run).
  unsigned remaining = (1u << (D + 2)) - 1;
  for (int round = 0; round < D + 2; ++round) {
    int i = std::countr_zero(remaining);
    for (unsigned rest = remaining & (remaining - 1); rest != 0; rest &= rest - 1) {
      const int j = std::countr_zero(rest);
      if (less(*points[static_cast<std::size_t>(i)], *points[static_cast<std::size_t>(j)])) i = j;
    }
    if (i == D + 1) return ON_NEGATIVE_SIDE;
    std::array<PointRef, D + 1> replaced;
    for (int j = 0; j <= D; ++j) replaced[static_cast<std::size_t>(j)] = points[static_cast<std::size_t>(j)];
    replaced[static_cast<std::size_t>(i)] = points[D + 1];
    const Sign s = orientation(replaced);
    if (s != ZERO) return static_cast<Oriented_side>(s);
    remaining &= ~(1u << i);
  }
  return ON_NEGATIVE_SIDE;  // unreachable: the walk reaches q
}

}  // namespace dewall::kernel
