// dewall::cgal::make_delaunay_triangulation_3: a genuine
// CGAL::Delaunay_triangulation_3, computed by DeWall and assembled directly in
// its triangulation data structure (no point is re-inserted).
//
// The one-line change for a CGAL program:
//
//   DT dt(points.begin(), points.end());                                   // before
//   DT dt = dewall::cgal::make_delaunay_triangulation_3<DT>(points.begin(), points.end());  // after
//
// The result is the object CGAL would have built: the same finite cells (as
// vertex sets; DeWall uses CGAL's symbolic perturbation, so even cospherical
// points give CGAL's cells), valid (is_valid(true)), and usable with every
// CGAL operation (locate, nearest_vertex, insert, remove, dual, I/O, meshing).
#pragma once

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Location_policy.h>

#include <array>
#include <cstddef>
#include <iterator>
#include <type_traits>
#include <vector>

#include "dewall/cgal/detail/assemble.hpp"
#include "dewall/options.hpp"

namespace dewall::cgal {

namespace detail {

// TDS access for Triangulation_data_structure_3 (see assemble()).
template <class DT, class Item, class Traits>
struct Tds3_access {
  using Tds = typename DT::Triangulation_data_structure;
  using Vertex_handle = typename Tds::Vertex_handle;
  using Cell_handle = typename Tds::Cell_handle;

  Tds& tds;
  Vertex_handle infinite;
  const std::vector<Item>& items;  // by input index
  Vertex_handle infinite_vertex() const { return infinite; }
  Vertex_handle create_vertex(std::size_t i) {
    Vertex_handle v = tds.create_vertex();
    v->set_point(Traits::point(items[i]));
    if constexpr (Traits::has_info) v->info() = items[i].second;
    return v;
  }
  Cell_handle create_cell(const std::array<Vertex_handle, 4>& w) {
    Cell_handle c = tds.create_cell(w[0], w[1], w[2], w[3]);
    for (const Vertex_handle& v : w) v->set_cell(c);
    return c;
  }
  void reserve(std::size_t vertices, std::size_t cells) {
    if constexpr (requires { tds.cells().reserve(cells); }) {  // not in the concurrent container
      tds.vertices().reserve(vertices);
      tds.cells().reserve(cells);
    }
  }
  static void set_neighbors(Cell_handle a, int i, Cell_handle b, int j) {
    a->set_neighbor(i, b);
    b->set_neighbor(j, a);
  }
};

template <class DT>
inline constexpr bool is_fast_location_3 = std::is_same_v<typename DT::Location_policy, CGAL::Fast_location>;

/// Builds dt (freshly constructed) from items with DeWall; false when DeWall
/// does not apply (see make_delaunay_triangulation_3) and dt is untouched.
template <class DT, class Item>
bool build_with_dewall_3(DT& dt, const std::vector<Item>& items, const Options& options) {
  if constexpr (is_fast_location_3<DT>) {
    return false;
  } else {
    return build_with_dewall<3, Tds3_access>(dt, items, options,
                                          [](const typename DT::Point& p, int j) { return j == 0 ? p.x() : j == 1 ? p.y() : p.z(); });
  }
}

}  // namespace detail

/// The Delaunay triangulation of the points in [first, last), as a DT.
///
/// DT: a CGAL::Delaunay_triangulation_3<K, Tds> for any kernel K and data
/// structure Tds (vertex and cell bases of the caller's choice).
/// The range holds DT::Point, or std::pair<DT::Point, Info> when the vertex
/// base carries an Info (as for CGAL's range insert); each vertex gets the info
/// of its first occurrence in the range.
///
/// Built by dewall::triangulate and assembled directly in dt.tds(): one vertex
/// per distinct point (the first occurrence, in input order), DeWall's cells,
/// one infinite cell per hull facet, all neighbour relations (matched through
/// a hash table of facets), dimension 3. The result is exactly the
/// triangulation CGAL's own insertion would give (the same cells as vertex
/// sets, also for cospherical points, by the shared symbolic perturbation).
///
/// Falls back to CGAL's own insertion (same result, CGAL's speed) when
///  * the distinct points are fewer than 4 or coplanar: CGAL then builds its
///    lower-dimensional triangulation (dimension -1 … 2), which DeWall does not;
///  * some coordinate is not exactly a double (e.g. an exact kernel holding
///    1/3): DeWall decides on doubles, and cells built from rounded
///    coordinates could be inverted or non-Delaunay for the true points;
///  * DT uses CGAL::Fast_location (a Delaunay hierarchy, whose upper levels
///    are built by insertion).
/// With CGAL::Epick every finite point is exactly doubles: DeWall always runs
/// on full-dimensional input.
///
/// \pre every coordinate is finite.
/// \throws dewall::Invalid_input for a NaN or infinite coordinate.
/// Complexity: DeWall's (expected O(n log n) for uniform points) plus O(n +
/// number of cells) for the assembly.
template <class DT, class InputIterator>
DT make_delaunay_triangulation_3(InputIterator first, InputIterator last, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits()) {
  using Item = typename std::iterator_traits<InputIterator>::value_type;
  const std::vector<Item> items(first, last);
  DT dt(traits);
  if (!detail::build_with_dewall_3(dt, items, options)) dt.insert(items.begin(), items.end());
  return dt;
}

/// Convenience overload for a whole range (e.g. a std::vector of points).
template <class DT, class Range>
DT make_delaunay_triangulation_3(const Range& range, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits()) {
  return make_delaunay_triangulation_3<DT>(std::begin(range), std::end(range), options, traits);
}

}  // namespace dewall::cgal
