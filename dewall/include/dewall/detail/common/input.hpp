// Input checks and duplicate removal, before any predicate runs: bad input is an
// exception naming the point (error.hpp), found before it can reach a predicate.
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

#include "dewall/detail/common/assert.hpp"
#include "dewall/error.hpp"
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/kernel/sign.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// The input indices of the distinct points, each the first occurrence of its
/// coordinates, in input order: k ↦ index of the k-th distinct point. The
/// list is kept only when some point repeats; without duplicates (most
/// inputs) it would be 0 … n − 1, 8 bytes a point for nothing — twice at the
/// collecting run's peak, the automatic engine's and the construction's
/// (10^6 points: 16 of its 312 MB).
class Distinct_points {
 public:
  Distinct_points() = default;
  /// `distinct` of an input of `input_size` points; `kept`: their ascending
  /// indices, or empty when every point is distinct (the identity).
  Distinct_points(std::vector<std::size_t> kept, std::size_t distinct, std::size_t input_size) : size_(distinct) {
    DEWALL_ASSERT(kept.size() == (distinct == input_size ? 0 : distinct));
    if (distinct != input_size) kept_ = std::move(kept);
  }
  std::size_t size() const { return size_; }
  std::size_t operator[](std::size_t k) const { return kept_.empty() ? k : kept_[k]; }
  /// The list itself, for a caller that works on it (32-bit: distinct_points
  /// refuses inputs of 2^32 − 1 points or more).
  std::vector<std::uint32_t> indices() const {
    std::vector<std::uint32_t> all(size_);
    for (std::size_t k = 0; k < size_; ++k) all[k] = static_cast<std::uint32_t>((*this)[k]);
    return all;
  }

 private:
  std::vector<std::size_t> kept_;  // empty: every point is distinct
  std::size_t size_ = 0;
};

/// Throws Invalid_input on more than 2^32 - 2 points (indices are 32-bit) or
/// a non-finite coordinate: the checks of distinct_points before the repeats.
template <class K>
void require_finite_points(const K& k, std::span<const typename K::Point_d> points) {
  constexpr int D = K::dimension;
  if (points.size() >= (std::size_t{1} << 32) - 1) throw Invalid_input("too many points (at most 2^32 - 2)");
  const auto coords = k.approximate_coordinates_object();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto x = coords(points[i]);
    for (int j = 0; j < D; ++j)
      if (!kernel::is_finite(x[j]))
        throw Invalid_input(i, "has a non-finite coordinate (NaN or infinity)");
  }
}

/// The distinct points of the input (Distinct_points). Throws Invalid_input
/// as require_finite_points, or on fewer than D + 1 distinct points.
template <class K>
Distinct_points distinct_points(const K& k, std::span<const typename K::Point_d> points) {
  constexpr int D = K::dimension;
  require_finite_points<K>(k, points);
  const auto coords = k.approximate_coordinates_object();
  const std::vector<std::uint32_t> first = kernel::first_occurrences(points, k.compare_lexicographically_d_object(), coords);
  std::size_t distinct = 0;
  for (std::size_t i = 0; i < first.size(); ++i) distinct += first[i] == i ? 1 : 0;
  if (distinct < static_cast<std::size_t>(D + 1))
    throw Invalid_input("need at least " + std::to_string(D + 1) + " distinct points in dimension " +
                        std::to_string(D) + ", got " + std::to_string(distinct));
  // The list only when some point repeats (otherwise it would be the
  // identity, built point by point only to be dropped).
  std::vector<std::size_t> kept;
  if (distinct != points.size()) {
    kept.reserve(distinct);
    for (std::size_t i = 0; i < first.size(); ++i)
      if (first[i] == i) kept.push_back(i);
  }
  return Distinct_points(std::move(kept), distinct, points.size());
}

/// An affine basis grown one point at a time, exactly: the row echelon form of
/// the differences x − origin over the rationals (a double converts to mpq
/// exactly). Used to check that the input spans E^D and to pick the first
/// simplex of the incremental engine.
template <int D>
class Affine_basis {
 public:
  explicit Affine_basis(const std::array<double, D>& origin) : origin_(origin) {}

  /// Adds x when it is affinely independent of the origin and the points
  /// added so far; says whether it was.
  bool add(const std::array<double, D>& x) {
    if (rank() == D) return false;
    std::array<mpq_class, D> v;
    for (int j = 0; j < D; ++j) v[j] = mpq_class(x[j]) - mpq_class(origin_[j]);
    for (std::size_t b = 0; b < basis_.size(); ++b) {
      const int p = pivot_[b];
      if (sgn(v[p]) == 0) continue;
      const mpq_class factor = v[p] / basis_[b][p];
      for (int j = 0; j < D; ++j) v[j] -= factor * basis_[b][j];
    }
    for (int j = 0; j < D; ++j)
      if (sgn(v[j]) != 0) {
        basis_.push_back(v);
        pivot_.push_back(j);
        return true;
      }
    return false;
  }
  /// The affine dimension of the origin and the points added.
  int rank() const { return static_cast<int>(basis_.size()); }

 private:
  std::array<double, D> origin_;
  std::vector<std::array<mpq_class, D>> basis_;
  std::vector<int> pivot_;
};

/// Throws Invalid_input unless the `n` points x(0) … x(n − 1) span E^D.
template <int D, class Coordinates>
void require_full_dimension(std::size_t n, Coordinates&& x) {
  // \pre n >= D + 1 (checked by the caller).
  // Points are taken in a strided order first so that ordered inputs (a plane
  // after a plane) reach full rank after a few rows.
  Affine_basis<D> basis(x(0));
  const std::size_t stride = std::max<std::size_t>(1, n / 64);
  for (std::size_t i = 1; i < n && basis.rank() < D; i += stride) basis.add(x(i));
  for (std::size_t i = 1; i < n && basis.rank() < D; ++i) basis.add(x(i));
  if (basis.rank() < D) {
    static const char* const names[] = {"a point", "collinear", "coplanar", "in one 3-flat", "in one 4-flat",
                                        "in one 5-flat"};
    throw Invalid_input("the points do not span E^" + std::to_string(D) + ": all " + std::to_string(n) +
                        " distinct points are " + names[basis.rank()] + " (affine dimension " +
                        std::to_string(basis.rank()) + ")");
  }
}
template <int D>
void require_full_dimension(std::span<const std::array<double, D>> x) {
  require_full_dimension<D>(x.size(), [&](std::size_t i) -> const std::array<double, D>& { return x[i]; });
}

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
