// Points of the 3D file formats (VTK, PLY, OFF, OBJ) as a table: 2D when every
// z is 0, as these formats store a plane drawing (a 3D set in the plane z = 0
// could not be triangulated in E^3 anyway), else 3D.
#pragma once

#include <utility>
#include <vector>

#include "dewall/io/point_reader.hpp"

namespace dewall::io::detail {

/// The table of the points x0 y0 z0 x1 y1 z1 … of `xyz`.
inline Point_table table_from_xyz(std::vector<double> xyz) {
  const std::size_t n = xyz.size();
  bool flat = true;
  for (std::size_t i = 2; i < n && flat; i += 3) flat = xyz[i] == 0;
  Point_table t;
  t.dimension = flat ? 2 : 3;
  if (flat) {
    t.coordinates.reserve(2 * (n / 3));
    for (std::size_t i = 0; i < n; i += 3) t.coordinates.insert(t.coordinates.end(), {xyz[i], xyz[i + 1]});
  } else {
    t.coordinates = std::move(xyz);
  }
  return t;
}

}  // namespace dewall::io::detail
