// Input checks and duplicate removal, before any predicate runs (STYLE 6, 11).
//  * Every coordinate must be finite: NaN and ±inf are errors naming the point.
//  * Duplicates collapse to their first occurrence (CGAL's insert keeps the
//    vertex already there), so a later copy's index never appears.
//  * At least D + 1 distinct points spanning E^D, checked by exact rank
//    computation over GMP rationals (a double converts to mpq exactly).
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dewall/error.hpp"
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/kernel/sign.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// Input indices of the distinct points, each the first occurrence of its
/// coordinates, in input order. Throws Invalid_input on more than 2^32 - 2
/// points (indices are 32-bit), non-finite coordinates, or fewer than D + 1
/// distinct points.
template <class K>
std::vector<std::size_t> distinct_points(const K& k, std::span<const typename K::Point_d> points) {
  constexpr int D = K::dimension;
  if (points.size() >= (std::size_t{1} << 32) - 1) throw Invalid_input("too many points (at most 2^32 - 2)");
  const auto coords = k.approximate_coordinates_object();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto x = coords(points[i]);
    for (int j = 0; j < D; ++j)
      if (!kernel::is_finite(x[j]))
        throw Invalid_input("point " + std::to_string(i) + " has a non-finite coordinate (NaN or infinity)", i);
  }
  const std::vector<std::uint32_t> first = kernel::first_occurrences(points, k.compare_lexicographically_d_object(), coords);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < first.size(); ++i)
    if (first[i] == i) kept.push_back(i);
  if (kept.size() < static_cast<std::size_t>(D + 1))
    throw Invalid_input("need at least " + std::to_string(D + 1) + " distinct points in dimension " +
                        std::to_string(D) + ", got " + std::to_string(kept.size()));
  return kept;
}

/// Throws Invalid_input unless the points span E^D.
template <int D>
void require_full_dimension(std::span<const std::array<double, D>> x) {
  // \pre x.size() >= D + 1 (checked by the caller).
  // Row echelon form of the differences x_i − x_0 over the rationals. Points are
  // taken in a strided order first so that ordered inputs (a plane after a
  // plane) reach full rank after a few rows.
  std::vector<std::array<mpq_class, D>> basis;
  std::vector<int> pivot;
  auto add = [&](std::size_t i) {
    std::array<mpq_class, D> v;
    for (int j = 0; j < D; ++j) v[j] = mpq_class(x[i][j]) - mpq_class(x[0][j]);
    for (std::size_t b = 0; b < basis.size(); ++b) {
      const int p = pivot[b];
      if (sgn(v[p]) == 0) continue;
      const mpq_class factor = v[p] / basis[b][p];
      for (int j = 0; j < D; ++j) v[j] -= factor * basis[b][j];
    }
    for (int j = 0; j < D; ++j)
      if (sgn(v[j]) != 0) {
        basis.push_back(v);
        pivot.push_back(j);
        return;
      }
  };
  const std::size_t n = x.size();
  const std::size_t stride = std::max<std::size_t>(1, n / 64);
  for (std::size_t i = 1; i < n && basis.size() < D; i += stride) add(i);
  for (std::size_t i = 1; i < n && basis.size() < D; ++i) add(i);
  if (basis.size() < D) {
    static const char* const names[] = {"a point", "collinear", "coplanar", "in one 3-flat", "in one 4-flat",
                                        "in one 5-flat"};
    throw Invalid_input("the points do not span E^" + std::to_string(D) + ": all " + std::to_string(n) +
                        " distinct points are " + names[basis.size()] + " (affine dimension " +
                        std::to_string(basis.size()) + ")");
  }
}

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
