// dewall::cgal::make_delaunay_triangulation_d: a genuine dD
// CGAL::Delaunay_triangulation (e.g. over CGAL::Epick_d<CGAL::Dimension_tag<4>>),
// computed by DeWall and assembled directly in its
// Triangulation_data_structure (full cells, mirror indices), without
// re-inserting any point.
//
// The one-line change for a CGAL program:
//
//   DT dt(D); dt.insert(points.begin(), points.end());                      // before
//   DT dt = dewall::cgal::make_delaunay_triangulation_d<DT>(points.begin(), points.end());  // after
#pragma once

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Epick_d.h>

#include <array>
#include <cstddef>
#include <iterator>
#include <type_traits>
#include <vector>

#include "dewall/cgal/detail/assemble.hpp"
#include "dewall/options.hpp"

namespace dewall::cgal {

namespace detail {

// TDS access for the dD Triangulation_data_structure (see assemble()).
template <class DT, int D>
struct Tds_d_access {
  using Tds = typename DT::Triangulation_ds;
  using Vertex_handle = typename Tds::Vertex_handle;
  using Cell_handle = typename Tds::Full_cell_handle;
  using Point = typename DT::Point;

  Tds& tds;
  Vertex_handle infinite;
  const std::vector<Point>& points;  // by input index
  Vertex_handle infinite_vertex() const { return infinite; }
  Vertex_handle create_vertex(std::size_t i) {
    Vertex_handle v = tds.new_vertex();
    v->set_point(points[i]);
    return v;
  }
  Cell_handle create_cell(const std::array<Vertex_handle, D + 1>& w) {
    Cell_handle c = tds.new_full_cell();
    for (int i = 0; i <= D; ++i) tds.associate_vertex_with_full_cell(c, i, w[static_cast<std::size_t>(i)]);
    return c;
  }
  void set_neighbors(Cell_handle a, int i, Cell_handle b, int j) { tds.set_neighbors(a, i, b, j); }
};

template <class DT>
constexpr int static_dimension() {
  using Dim = typename DT::Maximal_dimension;
  static_assert(requires { Dim::value; },
                "make_delaunay_triangulation_d needs a static dimension (CGAL::Dimension_tag<D>)");
  return Dim::value;
}

/// Builds dt (freshly constructed) from points with DeWall; false when DeWall
/// does not apply (see make_delaunay_triangulation_d) and dt is untouched.
template <class DT>
bool build_with_dewall_d(DT& dt, const std::vector<typename DT::Point>& points, const Options& options) {
  constexpr int D = static_dimension<DT>();
  static_assert(D >= kernel::min_dimension && D <= kernel::max_dimension, "DeWall runs in dimensions 2 … 6");
  using Point = typename DT::Point;
  using Traits = Item_traits<Point>;
  // Epick_d's predicates are exact on the points' doubles, and its
  // perturbation order (Triangulation/internal/utilities.h) is ours; other dD
  // traits (Epeck_d, Cartesian_d, a user's) are left to CGAL.
  if constexpr (!std::is_same_v<typename DT::Geom_traits, CGAL::Epick_d<CGAL::Dimension_tag<D>>>) return false;
  else {
  auto coords = to_dewall_points<D, std::vector<Point>, Traits>(points, [](const Point& p, int j) { return p[j]; });
  if (!coords) return false;
  // Triangulation keeps its infinite vertex in a member without a setter, so
  // keep the one its constructor made and drop only its full cells.
  const auto prepared = [&] {
    auto& tds = dt.tds();
    std::vector<typename Tds_d_access<DT, D>::Cell_handle> old;
    for (auto c = tds.full_cells_begin(); c != tds.full_cells_end(); ++c) old.push_back(c);
    for (auto c : old) tds.delete_full_cell(c);
    tds.set_current_dimension(D);
    return Tds_d_access<DT, D>{tds, dt.infinite_vertex(), points};
  };
  return triangulate_into<D, Tds_d_access<DT, D>>(*coords, options, prepared) != Assembly::none;
  }
}

}  // namespace detail

/// The Delaunay triangulation of the points in [first, last), as a DT.
///
/// DT: a CGAL::Delaunay_triangulation<K, Tds> (or a class derived from one) of
/// static dimension D, 2 ≤ D ≤ 6; anything else is refused at compile time.
/// DeWall runs for K = CGAL::Epick_d<CGAL::Dimension_tag<D>>, other kernels go
/// to CGAL's insertion. The range holds values convertible to DT::Point (CGAL's
/// dD range insert takes no vertex data either); any input iterator.
///
/// Built by dewall::triangulate and assembled directly in dt.tds(): one vertex
/// per distinct point (the first occurrence), the full cells (positively
/// oriented) and infinite full cells with their neighbours and mirror
/// indices, current dimension D: from the incremental engine's own cells and
/// adjacency (detail/graph_assembly.hpp; the default engine in 4D and up),
/// or from another engine's simplices, their facets matched through a hash
/// table (detail/assemble.hpp). The finite full cells are exactly those of CGAL's own
/// insertion (as vertex sets, cospherical points included).
///
/// Falls back to CGAL's own insertion (same result, CGAL's speed) when the
/// distinct points are fewer than D + 1 or lie in a hyperplane (CGAL then
/// builds its lower-dimensional triangulation), or when some coordinate is
/// not exactly a double (exact dD kernels).
///
/// \pre every coordinate is finite.
/// \throws dewall::Invalid_input for a NaN or infinite coordinate.
/// Complexity: DeWall's plus O(n + number of full cells) for the assembly.
template <class DT, class InputIterator>
DT make_delaunay_triangulation_d(InputIterator first, InputIterator last, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits()) {
  static_assert(detail::derives_from_template<DT, CGAL::Delaunay_triangulation>,
                "make_delaunay_triangulation_d builds a dD CGAL::Delaunay_triangulation<K, Tds> of static dimension "
                "(K e.g. CGAL::Epick_d<CGAL::Dimension_tag<D>>); for 2D and 3D triangulations use "
                "make_delaunay_triangulation_2 / _3");
  const auto points = detail::read_items<typename DT::Point, void>(first, last);
  DT dt(detail::static_dimension<DT>(), traits);
  // CGAL 5.5's dD range insert dereferences begin() of an empty range inside
  // spatial_sort (UBSan: reference binding to null): an empty input is an
  // empty triangulation without asking CGAL.
  if (points.empty()) return dt;
  if (!detail::build_with_dewall_d(dt, points, options)) dt.insert(points.begin(), points.end());
  return dt;
}

/// Convenience overload for a whole range (e.g. a std::vector of points).
template <class DT, class Range>
DT make_delaunay_triangulation_d(const Range& range, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits()) {
  return make_delaunay_triangulation_d<DT>(std::begin(range), std::end(range), options, traits);
}

}  // namespace dewall::cgal
