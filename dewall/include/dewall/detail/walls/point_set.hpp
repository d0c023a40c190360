// Point_set: the distinct input points as the algorithm sees them — kernel
// points by local index, their double coordinates for ranking, the kd-tree,
// and the map back to input indices. Built once, then read-only.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "dewall/detail/walls/face.hpp"
#include "dewall/detail/walls/kd_tree.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/kernel/sign.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <class K>
struct Point_set {
  static constexpr int D = K::dimension;
  using Point = typename K::Point_d;

  /// Whether the predicates take the points from `coords` (exact copies, the
  /// same up to one power of two, which no sign of the project's kernel sees:
  /// scale_to_unit), so that the caller's points are not read after
  /// construction: the walls then tell the output, whose caller may free them
  /// (at 10^6 points in 3D, 24 MB of a streamed run's 120), and a hand-over
  /// to another engine takes them from restore_input. Other kernels read
  /// the caller's points: their coordinates may not be doubles, and their
  /// predicates may see more than the coordinates (a perturbation by address).
  static constexpr bool reads_input = !std::is_same_v<K, kernel::Filtered_kernel_d<D>>;

  K kernel;
  std::span<const Point> input;         // the caller's points (read only when reads_input)
  /// A bound on |x − x̂| for every coordinate x of every point and its value x̂
  /// in `coords` (scaled alike): 0 when the approximations are exact, +∞ when
  /// the kernel states no bound (kernel/concepts.hpp).
  double coordinate_error = 0;
  /// coords = approximations · 2^scale_exponent (scale_to_unit). Before
  /// `coords`: their initialisation sets it.
  int scale_exponent = 0;
  std::vector<Coords<D>> coords;        // approximate coordinates, by local index
  std::vector<Index> input_index;       // local index -> index in `input`
  Kd_tree<D> tree;                      // over positions = local indices

  /// The points input[distinct[k]], renumbered in tree order: local index i is
  /// the tree's position i, so a node's points and their coordinates are
  /// contiguous in memory. 28 bytes a point besides the tree in 3D (the
  /// points themselves are `coords` or the caller's: reads_input): the
  /// streaming run's memory is mostly this.
  Point_set(K k, std::span<const Point> points, std::vector<Index> distinct, std::size_t leaf_size)
      : kernel(k), input(points), coords(approximate(k, points, distinct, coordinate_error, scale_exponent)),
        input_index(std::move(distinct)), tree(coords, input_index, leaf_size) {}

  /// The caller's points, exactly (coords scaled back), for an engine that
  /// takes over after the caller was told they are no longer read: each
  /// distinct point at its input index, the others (later duplicates, which
  /// no engine reads: it is given the distinct list) NaN.
  std::vector<Point> restore_input() const
    requires(!reads_input)
  {
    Point unread;
    unread.x.fill(std::numeric_limits<double>::quiet_NaN());
    std::vector<Point> points(input.size(), unread);
    for (std::size_t i = 0; i < coords.size(); ++i)
      for (std::size_t j = 0; j < D; ++j) points[input_index[i]].x[j] = std::ldexp(coords[i][j], -scale_exponent);
    return points;
  }

  std::size_t size() const { return coords.size(); }
  std::span<const Coords<D>> coords_for_checks() const { return coords; }

  kernel::Sign orientation(const Face<D>& f, Index q) const {
    Points<D + 1> p;
    for (int i = 0; i < D; ++i) p.take(i, *this, f[i]);
    p.take(D, *this, q);
    return kernel.orientation_d_object()(p.refs);
  }
  /// Perturbed: is q inside the circumsphere of the positively oriented simplex s?
  bool inside_sphere(const Simplex<D>& s, Index q) const {
    Points<D + 2> p;
    for (int i = 0; i <= D; ++i) p.take(i, *this, s[i]);
    p.take(D + 1, *this, q);
    return kernel.side_of_oriented_sphere_d_object()(p.refs) == kernel::ON_POSITIVE_SIDE;
  }

 private:
  /// N points as a predicate takes them: the caller's, or copies of `coords`.
  template <int N>
  struct Points {
    std::array<const Point*, N> refs;
    std::conditional_t<reads_input, std::array<char, 0>, std::array<Point, N>> copies;
    void take(int k, const Point_set& ps, Index i) {
      if constexpr (reads_input) {
        refs[static_cast<std::size_t>(k)] = &ps.input[ps.input_index[i]];
      } else {
        copies[static_cast<std::size_t>(k)].x = ps.coords[i];
        refs[static_cast<std::size_t>(k)] = &copies[static_cast<std::size_t>(k)];
      }
    }
  };

  static std::vector<Coords<D>> approximate(const K& k, std::span<const Point> points,
                                            const std::vector<Index>& distinct, double& error, int& scale_exponent) {
    std::vector<Coords<D>> c(distinct.size());
    const auto to_double = k.approximate_coordinates_object();
    for (std::size_t i = 0; i < distinct.size(); ++i) c[i] = to_double(points[distinct[i]]);
    constexpr double relative = kernel::approximate_coordinates_error<K>;
    if constexpr (relative == 0) {
      scale_exponent = scale_to_unit(c);
    } else {
      // |x − x̂| ≤ ε·max(|x̂|, 2^-1022) ≤ ε·max(largest |x̂|, 2^-1022), rounded up;
      // the scaling multiplies it by 2^s like the coordinates.
      double largest = 0x1p-1022;
      for (const auto& x : c)
        for (double v : x) largest = std::max(largest, std::fabs(v));
      error = relative * largest * (1 + 0x1p-50) + 0x1p-1074;
      scale_exponent = scale_to_unit(c);
      error = std::ldexp(error, scale_exponent) * (1 + 0x1p-50) + 0x1p-1074;
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
  /// the same order, and the kernel's predicates see the input points or,
  /// for the project's kernel, these: its orientation and sphere
  /// determinants are multiplied by a positive power of two, its perturbation
  /// orders the points lexicographically, the same order.
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
