// CGAL's own Delaunay triangulation of a point set (CGAL's insertion with
// Epick / Epick_d, not DeWall), as a set of sorted index tuples: the reference
// the tests, the triangulate fuzzer and the benchmarks compare dewall with. Not
// part of the installed API (the library's own incremental engine is
// dewall/src/cgal_engine.cpp). Duplicate points map to their first occurrence, the
// convention dewall follows (CGAL keeps whichever copy it inserted first,
// which after its spatial sort need not be the first).
//
// Compiled once (cgal_delaunay.cpp, D = 2 … 6, library dewall_cgal_reference):
// CGAL's triangulations are the slowest templates of the test build to
// instantiate, and a dozen translation units ask for them.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <set>
#include <vector>

#include "dewall/kernel/point.hpp"

namespace dewall::cgal {

template <int D>
using Simplex_set = std::set<std::array<std::uint32_t, D + 1>>;

/// Sorted index tuples of any simplex list.
template <int D, class Range>
Simplex_set<D> as_simplex_set(const Range& simplices) {
  Simplex_set<D> s;
  for (auto t : simplices) {
    std::sort(t.begin(), t.end());
    s.insert(t);
  }
  return s;
}

/// CGAL's triangulation of `points` (finite coordinates; empty when the
/// points do not span E^D). D = 2 … 6.
template <int D>
Simplex_set<D> cgal_delaunay(const std::vector<kernel::Point_d<D>>& points);

extern template Simplex_set<2> cgal_delaunay<2>(const std::vector<kernel::Point_d<2>>&);
extern template Simplex_set<3> cgal_delaunay<3>(const std::vector<kernel::Point_d<3>>&);
extern template Simplex_set<4> cgal_delaunay<4>(const std::vector<kernel::Point_d<4>>&);
extern template Simplex_set<5> cgal_delaunay<5>(const std::vector<kernel::Point_d<5>>&);
extern template Simplex_set<6> cgal_delaunay<6>(const std::vector<kernel::Point_d<6>>&);

}  // namespace dewall::cgal
