// Points from a flat coordinate array (x0 y0 … x1 y1 …), the layout the readers
// and generators of dewall::io produce.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "dewall/kernel/point.hpp"

namespace dewall::kernel {

/// The points of `coordinates`, D values per point. \pre coordinates.size() % D == 0.
template <int D>
std::vector<Point_d<D>> points_from_coordinates(std::span<const double> coordinates) {
  std::vector<Point_d<D>> points(coordinates.size() / D);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int j = 0; j < D; ++j) points[i][j] = coordinates[i * D + static_cast<std::size_t>(j)];
  return points;
}

}  // namespace dewall::kernel
