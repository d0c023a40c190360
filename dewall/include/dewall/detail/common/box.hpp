// An axis-aligned box of doubles and the bounding box of a point set
// (floating point: it only ranks and scales, never decides).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>

namespace dewall::detail {

/// The smallest box [lo, hi] holding `count` points (coords(i): point i's
/// coordinates); lo = +inf, hi = −inf when there are none.
template <int D>
struct Box {
  std::array<double, D> lo, hi;
};
template <int D, class Coords>
Box<D> bounding_box(std::size_t count, Coords&& coords) {
  Box<D> box;
  box.lo.fill(std::numeric_limits<double>::infinity());
  box.hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < count; ++i) {
    const auto& x = coords(i);
    for (int j = 0; j < D; ++j) {
      box.lo[j] = std::min(box.lo[j], x[j]);
      box.hi[j] = std::max(box.hi[j], x[j]);
    }
  }
  return box;
}

}  // namespace dewall::detail
