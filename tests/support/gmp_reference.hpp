// The test oracle for the kernel predicates: plain GMP rational arithmetic.
//
// Deliberately independent of the kernel's evaluation: no shared determinant
// routine (the kernel expands minors, this eliminates), no common-scale integer
// conversion (mpq_class converts a finite double exactly), no translation by a
// point (the matrices below are the textbook homogeneous ones). Only the sign
// enums are shared, so that answers compare directly.
//
//   orientation:  det | 1  p_0 |          side_of_sphere: det | 1  p_0  |p_0|² |
//                     | …   …  |   (D+1)²                     | …   …     …    |   (D+2)²
//                     | 1  p_D |                              | 1  p_D  |p_D|² |
//                                                             | 1  q    |q|²   |
//
// Sign conventions. Subtracting row 0 from the others and expanding along the
// first column gives det[1 p] = det[p_i − p_0]_{i=1..D}: the kernel's (and CGAL's)
// orientation, unchanged. For the sphere, subtract the q row and expand along
// the first column, whose only 1 is then in row D+1: det = (−1)^(D+1)·M with
// M = det[p_i − q, |p_i|² − |q|²]; the column operation lifted −= 2·q_j·col_j
// turns |p_i|² − |q|² into |p_i − q|². M(q) is a quadratic in q, −κ|q|² + …, with
// κ = det[p_i, 1] = (−1)^D·orientation, vanishing on the sphere; so for a
// positively oriented simplex (−1)^D·M is positive inside, i.e. det < 0 inside.
// Hence ON_POSITIVE_SIDE (inside, CGAL's convention) ⇔ det < 0. The tests check
// this on the unit simplex and its centroid rather than trusting the algebra.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "dewall/kernel/point.hpp"
#include "dewall/kernel/sign.hpp"

namespace dewall::test {

/// det(a) for a square matrix of rationals, by Gaussian elimination with a
/// non-zero pivot from the rows below (each row swap flips the sign): the
/// product of the pivots. Destroys `a`. Complexity: O(n³) rational operations.
inline mpq_class gmp_determinant(std::vector<std::vector<mpq_class>>& a) {
  const std::size_t n = a.size();
  mpq_class det = 1;
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    while (pivot < n && sgn(a[pivot][col]) == 0) ++pivot;
    if (pivot == n) return 0;
    if (pivot != col) {
      std::swap(a[pivot], a[col]);
      det = -det;
    }
    det *= a[col][col];
    for (std::size_t row = col + 1; row < n; ++row) {
      if (sgn(a[row][col]) == 0) continue;
      const mpq_class factor = a[row][col] / a[col][col];
      for (std::size_t k = col + 1; k < n; ++k) a[row][k] -= factor * a[col][k];
      a[row][col] = 0;
    }
  }
  return det;
}

/// The sign of det(a). Destroys `a`.
inline kernel::Sign gmp_determinant_sign(std::vector<std::vector<mpq_class>>& a) {
  return static_cast<kernel::Sign>(sgn(gmp_determinant(a)));
}

/// The exact orientation of p_0 … p_D: sign det[p_1 − p_0, …, p_D − p_0].
template <int D>
kernel::Sign gmp_orientation(const std::array<kernel::Point_d<D>, D + 1>& p) {
  std::vector<std::vector<mpq_class>> a(D + 1, std::vector<mpq_class>(D + 1));
  for (int i = 0; i <= D; ++i) {
    a[i][0] = 1;
    for (int j = 0; j < D; ++j) a[i][j + 1] = mpq_class(p[i][j]);
  }
  return gmp_determinant_sign(a);
}

/// The exact side of q with respect to the sphere through p_0 … p_D, CGAL's
/// convention: ON_POSITIVE_SIDE inside when p_0 … p_D is positively oriented.
/// Not perturbed: ON_ORIENTED_BOUNDARY when cospherical (or degenerate).
template <int D>
kernel::Oriented_side gmp_side_of_oriented_sphere(const std::array<kernel::Point_d<D>, D + 1>& p,
                                                  const kernel::Point_d<D>& q) {
  std::vector<std::vector<mpq_class>> a(D + 2, std::vector<mpq_class>(D + 2));
  for (int i = 0; i <= D + 1; ++i) {
    const kernel::Point_d<D>& r = i <= D ? p[i] : q;
    a[i][0] = 1;
    mpq_class lifted = 0;
    for (int j = 0; j < D; ++j) {
      a[i][j + 1] = mpq_class(r[j]);
      lifted += a[i][j + 1] * a[i][j + 1];
    }
    a[i][D + 1] = lifted;
  }
  return static_cast<kernel::Oriented_side>(-gmp_determinant_sign(a));
}

}  // namespace dewall::test
