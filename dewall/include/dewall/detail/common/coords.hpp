// Coords: a point's approximate (double) coordinates, as the search structures
// and the floating-point filters of dewall/detail see them.
#pragma once

#include <array>

namespace dewall::detail {

template <int D>
using Coords = std::array<double, D>;

}  // namespace dewall::detail
