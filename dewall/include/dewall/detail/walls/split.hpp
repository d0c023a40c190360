// Split: the paper's splitting plane α, orthogonal to an axis, described
// combinatorially so that it never passes through an input point: side 1 holds
// the points whose coordinate is < value (or ≤ value), side 2 the others. Both
// sides are non-empty. Which side a point is on is an exact double comparison.
#pragma once

#include <algorithm>
#include <optional>
#include <span>

#include "dewall/detail/walls/face.hpp"
#include "dewall/detail/common/coords.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
struct Split {
  int axis = 0;
  double value = 0;
  // Side 1: x[axis] < value, and of the points at x[axis] == value those of
  // local index below `tie`: all of them (x[axis] ≤ value) when it is
  // all_tied, none when 0. Anything in between only splits points whose
  // approximate coordinates are all equal (a kernel whose approximations are
  // not exact, kernel/concepts.hpp); any partition of the points is correct.
  Index tie = 0;
  static constexpr Index all_tied = ~Index{0};

  bool on_side1(const Coords<D>& x, Index i) const { return x[axis] < value || (x[axis] == value && i < tie); }
};

/// Chooses a split of `points` near the median on `preferred_axis`, trying the
/// other axes when every point shares that coordinate, and partitions `points`
/// so that side 1 comes first; when every point has the same approximate
/// coordinates, by local index. Returns nothing for fewer than two points.
/// `side1_size` receives |side 1|.
template <int D>
std::optional<Split<D>> choose_split(std::span<Index> points, const std::vector<Coords<D>>& coords,
                                     int preferred_axis, std::size_t& side1_size) {
  if (points.size() < 2) return std::nullopt;
  for (int t = 0; t < D; ++t) {
    const int axis = (preferred_axis + t) % D;
    auto less = [&](Index a, Index b) { return coords[a][axis] < coords[b][axis]; };
    const auto mid = points.begin() + static_cast<std::ptrdiff_t>(points.size() / 2);
    std::nth_element(points.begin(), mid, points.end(), less);
    Split<D> split{axis, coords[*mid][axis], 0};
    auto side2 = std::partition(points.begin(), points.end(), [&](Index p) { return split.on_side1(coords[p], p); });
    if (side2 == points.begin()) {  // nothing below the median value: put it on side 1
      split.tie = Split<D>::all_tied;
      side2 = std::partition(points.begin(), points.end(), [&](Index p) { return split.on_side1(coords[p], p); });
    }
    if (side2 != points.begin() && side2 != points.end()) {
      side1_size = static_cast<std::size_t>(side2 - points.begin());
      return split;
    }
  }
  // Distinct points with one approximation: the lower half of the indices.
  const auto mid = points.begin() + static_cast<std::ptrdiff_t>(points.size() / 2);
  std::nth_element(points.begin(), mid, points.end());
  const Split<D> split{preferred_axis, coords[*mid][preferred_axis], *mid};
  side1_size = points.size() / 2;
  return split;
}

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
