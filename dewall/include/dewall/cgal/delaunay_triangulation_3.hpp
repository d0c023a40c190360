// dewall::cgal::make_delaunay_triangulation_3: a genuine
// CGAL::Delaunay_triangulation_3, computed by dewall's engine and assembled
// directly in its triangulation data structure (no point is re-inserted).
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
#include <cstdlib>
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
Assembly build_with_dewall_3(DT& dt, std::vector<Item>& items, const Options& options) {
  if constexpr (is_fast_location_3<DT>) {
    return Assembly::none;
  } else {
    return build_with_dewall<3>(dt, items, options);
  }
}

}  // namespace detail

namespace detail {

/// The CGAL::Delaunay_triangulation_3 that DT is or derives from.
template <class... A>
CGAL::Delaunay_triangulation_3<A...> delaunay_3_base(const CGAL::Delaunay_triangulation_3<A...>*);
template <class DT>
using Delaunay_3_base = decltype(delaunay_3_base(static_cast<const DT*>(nullptr)));

/// An empty DT with the caller's traits and lock data structure (the
/// Delaunay hierarchy, Fast_location, takes none), or nothing when DT
/// cannot be made so.
template <class DT>
inline constexpr bool makes_empty_3 =
    std::is_constructible_v<DT, const typename DT::Geom_traits&, typename DT::Lock_data_structure*> ||
    std::is_constructible_v<DT, const typename DT::Geom_traits&>;

/// How a DT that derives from a Delaunay_triangulation_3 B is built: B
/// itself, or a class whose state is B's (constructible empty from B's
/// traits), is assembled in place; a class with state of its own built from
/// a B (CGAL::Alpha_shape_3(B&), Fixed_alpha_shape_3(B&): their range
/// constructors are that constructor after B's) is made from the B the
/// builder assembles.
template <class DT>
inline constexpr bool built_from_base_3 =
    !std::is_same_v<DT, Delaunay_3_base<DT>> && std::is_constructible_v<DT, Delaunay_3_base<DT>&>;

template <class DT, class InputIterator>
DT build_delaunay_3(InputIterator first, InputIterator last, const Options& options,
                    const typename DT::Geom_traits& traits, typename DT::Lock_data_structure* lock_ds) {
  if constexpr (built_from_base_3<DT>) {
    using Base = Delaunay_3_base<DT>;
    Base base = build_delaunay_3<Base>(first, last, options, traits, lock_ds);
    return DT(base);
  } else {
    auto make_empty = [&] {
      if constexpr (std::is_constructible_v<DT, const typename DT::Geom_traits&, typename DT::Lock_data_structure*>)
        return DT(traits, lock_ds);
      else
        return DT(traits);
    };
    return make_triangulation<DT>(make_empty, first, last, options, [](DT& dt, auto& items, const Options& o) {
      return build_with_dewall_3(dt, items, o);
    });
  }
}

}  // namespace detail

/// The Delaunay triangulation of the points in [first, last), as a DT: a
/// CGAL::Delaunay_triangulation_3<Gt, Tds, Location_policy, Lock_data_structure>
/// for any traits Gt and data structure Tds, Sequential_tag or Parallel_tag,
/// or a class derived from one: one that adds no state (constructible empty
/// from the traits) is assembled in place, one built from the triangulation
/// (CGAL::Alpha_shape_3<DT>, Fixed_alpha_shape_3<DT>: constructible from a
/// DT&) is constructed from the triangulation the builder makes, which is
/// what their range constructors do after CGAL's insertion; anything else
/// is refused at compile time.
/// Everything make_delaunay_triangulation_2 says holds, one dimension up: the
/// range holds what CGAL's range insert takes (DT::Point, or with an Info
/// std::pair<DT::Point, Info> or a boost::zip_iterator of (point, info));
/// the cells are assembled in dt.tds() (from the incremental engine's cells
/// and neighbours, with its infinite cells), exactly the triangulation
/// CGAL's insertion gives. DeWall runs for Gt = CGAL::Epick or
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
/// Complexity: the incremental engine's (expected O(n log n)) plus one pass
/// over its cells.
template <class DT, class InputIterator>
DT make_delaunay_triangulation_3(InputIterator first, InputIterator last, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits(),
                                 typename DT::Lock_data_structure* lock_ds = nullptr) {
  constexpr bool is_delaunay_3 = detail::derives_from_template<DT, CGAL::Delaunay_triangulation_3>;
  static_assert(is_delaunay_3,
                "make_delaunay_triangulation_3 builds a CGAL::Delaunay_triangulation_3<Gt, Tds, Location_policy, "
                "Lock_data_structure> (any traits and data structure); CGAL::Triangulation_3 and "
                "Regular_triangulation_3 are not Delaunay triangulations of points");
  if constexpr (is_delaunay_3) {
    constexpr bool buildable = detail::built_from_base_3<DT> || detail::makes_empty_3<DT>;
    static_assert(buildable,
                  "make_delaunay_triangulation_3 builds a class derived from CGAL::Delaunay_triangulation_3 only "
                  "when it can be made empty from the traits (DT(gt) or DT(gt, lock_ds)) or from the "
                  "triangulation (DT(dt&), as CGAL::Alpha_shape_3); build the Delaunay_triangulation_3 and "
                  "construct your class from it");
    if constexpr (buildable) return detail::build_delaunay_3<DT>(first, last, options, traits, lock_ds);
  }
  // Refused above: what follows only keeps the compiler to the static_assert's message.
  std::abort();
}

/// As CGAL's constructor DT(first, last, lock_ds, gt): the lock data
/// structure before the traits.
template <class DT, class InputIterator>
  requires(!std::is_void_v<typename DT::Lock_data_structure>)
DT make_delaunay_triangulation_3(InputIterator first, InputIterator last, typename DT::Lock_data_structure* lock_ds,
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits(),
                                 const Options& options = {}) {
  return make_delaunay_triangulation_3<DT>(first, last, options, traits, lock_ds);
}

/// Convenience overload for a whole range (e.g. a std::vector of points).
template <class DT, class Range>
DT make_delaunay_triangulation_3(const Range& range, const Options& options = {},
                                 const typename DT::Geom_traits& traits = typename DT::Geom_traits(),
                                 typename DT::Lock_data_structure* lock_ds = nullptr) {
  return make_delaunay_triangulation_3<DT>(std::begin(range), std::end(range), options, traits, lock_ds);
}

}  // namespace dewall::cgal
