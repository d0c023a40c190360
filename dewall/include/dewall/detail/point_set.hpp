// Point_set: the distinct input points as the algorithm sees them — kernel
// points by local index, their double coordinates for ranking, the kd-tree,
// and the map back to input indices. Built once, then read-only.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "dewall/detail/face.hpp"
#include "dewall/detail/kd_tree.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/sign.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <class K>
struct Point_set {
  static constexpr int D = K::dimension;
  using Point = typename K::Point_d;

  K kernel;
  std::span<const Point> input;         // the caller's points
  /// A bound on |x − x̂| for every coordinate x of every point and its value x̂
  /// in `coords` (scaled alike): 0 when the approximations are exact, +∞ when
  /// the kernel states no bound (kernel/concepts.hpp).
  double coordinate_error = 0;
  std::vector<Coords<D>> coords;        // approximate coordinates, by local index
  std::vector<Index> input_index;       // local index -> index in `input`
  Kd_tree<D> tree;                      // over positions = local indices

  /// The points input[distinct[k]], renumbered in tree order: local index i is
  /// the tree's position i, so a node's points and their coordinates are
  /// contiguous in memory. 28 bytes a point besides the tree in 3D (the
  /// points themselves are the caller's, reached through input_index): the
  /// streaming run's memory is mostly this.
  Point_set(K k, std::span<const Point> points, std::vector<Index> distinct, std::size_t leaf_size)
      : kernel(k), input(points), coords(approximate(k, points, distinct, coordinate_error)),
        input_index(std::move(distinct)), tree(coords, input_index, leaf_size) {}

  const Point& point(Index i) const { return input[input_index[i]]; }
  std::size_t size() const { return coords.size(); }
  std::span<const Coords<D>> coords_for_checks() const { return coords; }

  kernel::Sign orientation(const Face<D>& f, Index q) const {
    std::array<const Point*, D + 1> s;
    for (int i = 0; i < D; ++i) s[i] = &point(f[i]);
    s[D] = &point(q);
    return kernel.orientation_d_object()(s);
  }
  /// Perturbed: is q inside the circumsphere of the positively oriented simplex s?
  bool inside_sphere(const Simplex<D>& s, Index q) const {
    std::array<const Point*, D + 2> p;
    for (int i = 0; i <= D; ++i) p[i] = &point(s[i]);
    p[D + 1] = &point(q);
    return kernel.side_of_oriented_sphere_d_object()(p) == kernel::ON_POSITIVE_SIDE;
  }

 private:
  static std::vector<Coords<D>> approximate(const K& k, std::span<const Point> points,
                                            const std::vector<Index>& distinct, double& error) {
    std::vector<Coords<D>> c(distinct.size());
    const auto to_double = k.approximate_coordinates_object();
    for (std::size_t i = 0; i < distinct.size(); ++i) c[i] = to_double(points[distinct[i]]);
    constexpr double relative = kernel::approximate_coordinates_error<K>;
    if constexpr (relative == 0) {
      scale_to_unit(c);
    } else {
      // |x − x̂| ≤ ε·max(|x̂|, 2^-1022) ≤ ε·max(largest |x̂|, 2^-1022), rounded up;
      // the scaling multiplies it by 2^s like the coordinates.
      double largest = 0x1p-1022;
      for (const auto& x : c)
        for (double v : x) largest = std::max(largest, std::fabs(v));
      error = relative * largest * (1 + 0x1p-50) + 0x1p-1074;
      error = std::ldexp(error, scale_to_unit(c)) * (1 + 0x1p-50) + 0x1p-1074;
    }
    return c;
  }

  /// Scales every coordinate by one power of two 2^s, bringing the largest to
  /// [1, 2), when that is exact for all of them (each result zero or a normal
  /// double). The algorithm's own double computations — tree boxes, ball
  /// boxes, the face and sphere filters — then work near 1 whatever the input's
  /// scale: at 2^±600 they overflow or underflow (a 4D grid of 625 points
  /// scaled by 2^600 took minutes instead of 0.05 s). Nothing changes meaning:
  /// every sign these computations prove (orientations, in-sphere tests) is
  /// invariant under an exact uniform scaling, splits compare coordinates in
  /// the same order, and the kernel's predicates still see the input points.
  /// Returns s (0 when the coordinates are left as they are).
  static int scale_to_unit(std::vector<Coords<D>>& c) {
    double largest = 0, smallest = std::numeric_limits<double>::infinity();
    for (const auto& x : c)
      for (double v : x)
        if (v != 0) {
          largest = std::max(largest, std::fabs(v));
          smallest = std::min(smallest, std::fabs(v));
        }
    if (largest == 0 || !std::isfinite(largest)) return 0;
    const int s = -std::ilogb(largest);
    if (s == 0 || std::ilogb(smallest) + s < std::numeric_limits<double>::min_exponent - 1) return 0;
    for (auto& x : c)
      for (double& v : x) v = std::ldexp(v, s);
    return s;
  }
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
