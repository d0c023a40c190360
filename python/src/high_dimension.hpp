// Dimensions above the library's (D = 7 and up, any D >= 2 accepted): the
// Delaunay triangulation, the exact predicates and point location with the
// dimension known at run time, by CGAL's dD code (high_dimension.cpp, the only
// file of the module that includes CGAL). The library's kernel and engines are
// compiled for D = 2 … 6 only; here CGAL's `Delaunay_triangulation` over
// `Epick_d<Dynamic_dimension_tag>` (filtered exact predicates, CGAL's symbolic
// perturbation) is the triangulation, so its simplices are CGAL's by definition
// — the answer the library gives in 2 … 6 dimensions.
//
// Arrays are row-major and checked by the caller (dewall_module.cpp): points
// (n × d doubles), simplices and neighbors (m × (d + 1) int32).
#pragma once

#include <cstddef>
#include <functional>
#include <cstdint>
#include <vector>

namespace dewall_python::high_dimension {

/// A triangulation: `count` simplices of d + 1 input indices each, every one
/// positively oriented (orientation as the library's: the sign of
/// det[p1 − p0, …, pd − p0]); neighbors[i·(d+1) + j] is the simplex across the
/// facet opposite vertex j, −1 on the hull.
struct Cells {
  std::size_t count = 0;
  std::vector<std::int32_t> simplices;
  std::vector<std::int32_t> neighbors;
};

/// CGAL's Delaunay triangulation of the n points in E^d. Duplicates are one
/// vertex, the first occurrence (as the library). \throws dewall::Invalid_input
/// with the library's messages: a non-finite coordinate, fewer than d + 1
/// distinct points, points that do not span E^d. Complexity: CGAL's
/// incremental insertion after a spatial sort. `progress` is told the
/// fraction of the points inserted every few points; what it throws stops the
/// work (and is passed on).
Cells triangulate(const double* points, std::size_t n, int d, const std::function<void(double)>& progress);

/// The exact predicates on rows of point indices (python's predicate_signs):
/// kind 0, orientation of d + 1 indices; 1, the side of the last of d + 2
/// indices with respect to the sphere through the first d + 1 (+1 inside, 0 on,
/// −1 outside; the simplex positively oriented); 2, the same under CGAL's
/// symbolic perturbation (never 0; the query is not a vertex of the simplex).
/// \pre every index < n (checked by the caller).
void predicate_signs(const double* points, std::size_t n, int d, const std::uint32_t* rows, std::size_t count,
                     int kind, std::int8_t* out);

/// The simplex containing each query (closed), −1 outside the hull: a
/// visibility walk with the exact orientation from the previous answer, a scan
/// of all simplices if a walk runs too long. `cells` must triangulate the
/// convex hull of the points (a Delaunay triangulation from triangulate()).
void locate(const double* points, std::size_t n, int d, const std::int32_t* simplices,
            const std::int32_t* neighbors, std::size_t count, const double* queries, std::size_t query_count,
            std::int32_t* out);

}  // namespace dewall_python::high_dimension
