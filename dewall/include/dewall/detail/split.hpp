// Split: the paper's splitting plane α, orthogonal to an axis, described
// combinatorially so that it never passes through an input point: side 1 holds
// the points whose coordinate is < value (or ≤ value), side 2 the others. Both
// sides are non-empty. Which side a point is on is an exact double comparison.
#pragma once

#include <algorithm>
#include <optional>
#include <span>

#include "dewall/detail/face.hpp"
#include "dewall/detail/coords.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
struct Split {
  int axis = 0;
  double value = 0;
  bool inclusive = false;  // side 1 is x[axis] <= value (else x[axis] < value)

  bool on_side1(const Coords<D>& x) const { return inclusive ? x[axis] <= value : x[axis] < value; }
};

/// Chooses a split of `points` near the median on `preferred_axis`, trying the
/// other axes when every point shares that coordinate, and partitions `points`
/// so that side 1 comes first. Returns nothing (and leaves `points` permuted)
/// when all points coincide on every axis. `side1_size` receives |side 1|.
template <int D>
std::optional<Split<D>> choose_split(std::span<Index> points, const std::vector<Coords<D>>& coords,
                                     int preferred_axis, std::size_t& side1_size) {
  if (points.size() < 2) return std::nullopt;
  for (int t = 0; t < D; ++t) {
    const int axis = (preferred_axis + t) % D;
    auto less = [&](Index a, Index b) { return coords[a][axis] < coords[b][axis]; };
    const auto mid = points.begin() + static_cast<std::ptrdiff_t>(points.size() / 2);
    std::nth_element(points.begin(), mid, points.end(), less);
    Split<D> split{axis, coords[*mid][axis], false};
    auto side2 = std::partition(points.begin(), points.end(), [&](Index p) { return split.on_side1(coords[p]); });
    if (side2 == points.begin()) {  // nothing below the median value: put it on side 1
      split.inclusive = true;
      side2 = std::partition(points.begin(), points.end(), [&](Index p) { return split.on_side1(coords[p]); });
    }
    if (side2 != points.begin() && side2 != points.end()) {
      side1_size = static_cast<std::size_t>(side2 - points.begin());
      return split;
    }
  }
  return std::nullopt;
}

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
