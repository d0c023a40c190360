// dewall::cgal::make_delaunay_triangulation_2: a genuine
// CGAL::Delaunay_triangulation_2, computed by dewall's engine and assembled
// directly in its triangulation data structure (no point is re-inserted). The 2D twin of
// delaunay_triangulation_3.hpp (cells are CGAL's faces).
//
// The one-line change for a CGAL program:
//
//   DT dt(points.begin(), points.end());                                   // before
//   DT dt = dewall::cgal::make_delaunay_triangulation_2<DT>(points.begin(), points.end());  // after
//
// The result is the object CGAL would have built: the same finite cells (as
// vertex sets; DeWall uses CGAL's symbolic perturbation, so even cospherical
// points give CGAL's cells), valid (is_valid(true)), and usable with every
// CGAL operation (locate, nearest_vertex, insert, remove, dual, I/O, meshing).
#pragma once

#include <CGAL/Delaunay_triangulation_2.h>

#include <array>
#include <cstddef>
#include <iterator>
#include <type_traits>
#include <vector>

#include "dewall/cgal/detail/assemble.hpp"
#include "dewall/options.hpp"

namespace dewall::cgal {

namespace detail {

// Triangulation_hierarchy_2<DT> (CGAL's fast-location variant) names its base level Tr_Base.
template <class DT>
inline constexpr bool is_hierarchy_2 = requires { typename DT::Tr_Base; };

/// Builds dt (freshly constructed) from items with DeWall; Assembly::none
/// when DeWall does not apply (see make_delaunay_triangulation_2) and dt is
/// untouched.
template <class DT, class Item>
Assembly build_with_dewall_2(DT& dt, std::vector<Item>& items, const Options& options) {
  if constexpr (is_hierarchy_2<DT>) {
    return Assembly::none;
  } else {
    return build_with_dewall<2>(dt, items, options);
  }
}

}  // namespace detail

/// The Delaunay triangulation of the points in [first, last), as a DT.
///
/// DT: a CGAL::Delaunay_triangulation_2<Gt, Tds> (or a class derived from
/// one, e.g. CGAL::Triangulation_hierarchy_2) for any traits Gt and data
/// structure Tds (vertex and face bases of the caller's choice); anything else
/// is refused at compile time.
/// The range holds what CGAL's range insert takes: DT::Point, or, when the
/// vertex base carries an Info, std::pair<DT::Point, Info> or a
/// boost::zip_iterator of (point, info); any input iterator. Each vertex gets
/// the info of its point's first occurrence in the range.
///
/// Built by dewall::triangulate and assembled directly in dt.tds(): one vertex
/// per distinct point (the first occurrence), the triangles
/// (counterclockwise) and infinite faces with their neighbours, dimension 2:
/// from the incremental engine's own cells and adjacency in one pass
/// (detail/graph_assembly.hpp), or from another engine's triangles, their
/// edges matched through a hash table (detail/assemble.hpp). The result is exactly the
/// triangulation CGAL's own insertion would give (the same cells as vertex
/// sets, also for cospherical points, by the shared symbolic perturbation).
///
/// DeWall runs only for traits whose predicates are provably DeWall's on the
/// coordinates it is given (detail/geom_traits.hpp): CGAL::Epick and
/// CGAL::Epeck on (x, y), and CGAL::Projection_traits_xy_3/_xz_3/_yz_3 over
/// them on (x, y), (x, z), (y, z). Everything else is CGAL's own range
/// insertion (same result, CGAL's speed):
///  * other traits (Projection_traits_3 with a normal vector, inexact or
///    user kernels): DeWall would decide with other predicates;
///  * under a projection, two input points equal in the projected
///    coordinates but not as points: CGAL keeps the one its spatial sort
///    inserts first, which DeWall cannot tell;
///  * the distinct points are fewer than 3 or collinear: CGAL then builds its
///    lower-dimensional triangulation (dimension -1 … 1), which DeWall does not;
///  * some coordinate is not exactly a double (e.g. an exact kernel holding
///    1/3): DeWall decides on doubles, and cells built from rounded
///    coordinates could be inverted or non-Delaunay for the true points;
///  * DT is a CGAL::Triangulation_hierarchy_2 (whose upper levels are built
///    by insertion).
///
/// \pre every coordinate is finite.
/// \throws dewall::Invalid_input for a NaN or infinite coordinate.
/// Complexity: the engine's (expected O(n log n) for uniform points) plus O(n +
/// number of cells) for the assembly.
template <class DT, class InputIterator>
DT make_delaunay_triangulation_2(InputIterator first, InputIterator last, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits()) {
  constexpr bool is_delaunay_2 = detail::derives_from_template<DT, CGAL::Delaunay_triangulation_2>;
  static_assert(is_delaunay_2,
                "make_delaunay_triangulation_2 builds a CGAL::Delaunay_triangulation_2<Gt, Tds> (any traits and data "
                "structure, or a Triangulation_hierarchy_2 of one); for 3D use make_delaunay_triangulation_3, for "
                "dD make_delaunay_triangulation_d");
  if constexpr (is_delaunay_2)
    return detail::make_triangulation<DT>([&] { return DT(traits); }, first, last, options, [](DT& dt, auto& items, const Options& o) {
      return detail::build_with_dewall_2(dt, items, o);
    });
  else
    return DT(traits);
}

/// Convenience overload for a whole range (e.g. a std::vector of points).
template <class DT, class Range>
DT make_delaunay_triangulation_2(const Range& range, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits()) {
  return make_delaunay_triangulation_2<DT>(std::begin(range), std::end(range), options, traits);
}

}  // namespace dewall::cgal
