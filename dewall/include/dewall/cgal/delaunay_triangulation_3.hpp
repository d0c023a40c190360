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

template <class DT>
inline constexpr bool is_fast_location_3 = std::is_same_v<typename DT::Location_policy, CGAL::Fast_location>;

/// Builds dt (freshly constructed) from items with DeWall; Assembly::none
/// when DeWall does not apply (see make_delaunay_triangulation_3) and dt is
/// untouched.
template <class DT, class Item>
Assembly build_with_dewall_3(DT& dt, const std::vector<Item>& items, const Options& options) {
  if constexpr (is_fast_location_3<DT>) {
    return Assembly::none;
  } else {
    return build_with_dewall<3>(dt, items, options);
  }
}

}  // namespace detail

/// The Delaunay triangulation of the points in [first, last), as a DT: a
/// CGAL::Delaunay_triangulation_3<Gt, Tds, Location_policy, Lock_data_structure>
/// (or a class derived from one) for any traits Gt and data structure Tds,
/// Sequential_tag or Parallel_tag; anything else is refused at compile time.
/// Everything make_delaunay_triangulation_2 says holds, one dimension up: the
/// range holds what CGAL's range insert takes (DT::Point, or with an Info
/// std::pair<DT::Point, Info> or a boost::zip_iterator of (point, info));
/// DeWall's cells are assembled in dt.tds() with one infinite cell per hull
/// facet (neighbours matched through a hash table of facets), exactly the
/// triangulation CGAL's insertion gives. DeWall runs for Gt = CGAL::Epick or
/// CGAL::Epeck (detail/geom_traits.hpp); CGAL's own insertion builds it
/// instead for other traits, when the distinct points are fewer than 4 or
/// coplanar, a coordinate is not exactly a double, or DT uses
/// CGAL::Fast_location (a Delaunay hierarchy).
///
/// `lock_ds`: as in CGAL's constructor DT(first, last, gt, lock_ds); the
/// result's get_lock_data_structure() is lock_ds, so a Parallel_tag DT built
/// with one takes parallel insertions and removals afterwards.
///
/// \pre every coordinate is finite.
/// \throws dewall::Invalid_input for a NaN or infinite coordinate.
template <class DT, class InputIterator>
DT make_delaunay_triangulation_3(InputIterator first, InputIterator last, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits(),
                                 typename DT::Lock_data_structure* lock_ds = nullptr) {
  constexpr bool is_delaunay_3 = detail::derives_from_template<DT, CGAL::Delaunay_triangulation_3>;
  static_assert(is_delaunay_3,
                "make_delaunay_triangulation_3 builds a CGAL::Delaunay_triangulation_3<Gt, Tds, Location_policy, "
                "Lock_data_structure> (any traits and data structure); CGAL::Triangulation_3 and "
                "Regular_triangulation_3 are not Delaunay triangulations of points");
  // The Delaunay hierarchy (Fast_location) takes no lock data structure.
  auto make_empty = [&] {
    if constexpr (std::is_constructible_v<DT, const typename DT::Geom_traits&, typename DT::Lock_data_structure*>)
      return DT(traits, lock_ds);
    else
      return DT(traits);
  };
  if constexpr (is_delaunay_3)
    return detail::make_triangulation<DT>(make_empty, first, last, options,
                                      [](DT& dt, const auto& items, const Options& o) {
                                        return detail::build_with_dewall_3(dt, items, o);
                                      });
  else
    return make_empty();
}

/// Convenience overload for a whole range (e.g. a std::vector of points).
template <class DT, class Range>
DT make_delaunay_triangulation_3(const Range& range, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits(),
                                 typename DT::Lock_data_structure* lock_ds = nullptr) {
  return make_delaunay_triangulation_3<DT>(std::begin(range), std::end(range), options, traits, lock_ds);
}

}  // namespace dewall::cgal
