// The incremental engine: CGAL's own construction (Delaunay_triangulation_2/_3,
// the dD Delaunay_triangulation), which uses the same lexicographic perturbation
// and so builds the same simplices as DeWall. Options::engine chooses it, and
// Engine::automatic hands over to it when DeWall's searches prove too costly
// (dewall/options.hpp). Private to the library: CGAL compiles slowly, and here it
// is compiled once, with the project's flags.
#pragma once

#include <span>
#include <vector>

#include "dewall/detail/walls/region.hpp"
#include "dewall/dewall.hpp"

namespace dewall::detail {

/// The same input checks as DeWall's (Invalid_input: non-finite coordinates,
/// too few distinct points, points not spanning E^D), then CGAL's triangulation
/// of the distinct points (the first occurrence of each), handed to `output`
/// as positively oriented input indices, in CGAL's cell order, in blocks as
/// they are listed (the triangulation itself is whole in memory).
/// `distinct`, when given, is distinct_points(points), computed by the caller.
template <int D>
Statistics triangulate_with_cgal(std::span<const kernel::Point_d<D>> points, Simplex_output<D>& output,
                                 const Distinct_points* distinct = nullptr);

/// The region triangulator of Engine::hybrid (region.hpp): CGAL's
/// triangulation of the points `region`, walked by `filter` in place.
template <int D>
bool cgal_region_cells(std::span<const Index> region, const std::vector<Coords<D>>& coords, Region_filter<D>& filter);

}  // namespace dewall::detail
