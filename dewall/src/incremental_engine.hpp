// The project's own incremental engine (detail/incremental/incremental_delaunay.hpp) as the
// library uses it: a whole triangulation (Engine::incremental, and where
// Engine::automatic leaves the input to an incremental construction) and the
// hybrid's regions. The twin of cgal_engine.hpp, with the same contracts.
#pragma once

#include <span>
#include <vector>

#include "dewall/detail/walls/region.hpp"
#include "dewall/dewall.hpp"

namespace dewall::detail {

/// As triangulate_with_cgal (cgal_engine.hpp), built by Incremental_delaunay:
/// the input checks, then the triangulation of the distinct points handed to
/// `output` as positively oriented input indices, in blocks.
template <int D>
Statistics triangulate_incremental(std::span<const kernel::Point_d<D>> points, Simplex_output<D>& output,
                                   const Distinct_points* distinct = nullptr);

/// As cgal_region_cells: the region's triangulation by Incremental_delaunay,
/// walked by `filter`.
template <int D>
bool incremental_region_cells(std::span<const Index> region, const std::vector<Coords<D>>& coords,
                              Region_filter<D>& filter);

}  // namespace dewall::detail
