// Which CGAL geometric traits the builders may let DeWall decide for, and on
// which coordinates of the triangulation's points.
//
// A builder's promise is "the triangulation CGAL's own construction gives".
// CGAL decides with the traits' predicates (orientation, in-circle/in-sphere,
// and compare_xy/compare_xyz for the symbolic perturbation, see
// Triangulation_2::side_of_oriented_circle); DeWall decides with ours, exactly,
// on the doubles it is given. The two agree only where the traits' predicates
// are provably the exact predicates on those coordinates, with the same signs
// and the same lexicographic order. That is known here for a short list of
// traits, each checked against the CGAL 5.5 headers; every other traits class
// (a user's, an inexact kernel such as Simple_cartesian<double>, or
// Projection_traits_3 with a normal vector) is "unknown" and the builders hand
// the points to CGAL's own construction.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>

#include <array>
#include <type_traits>

namespace CGAL {
class Epeck;  // Exact_predicates_exact_constructions_kernel.h is heavy; only the name is needed
}  // namespace CGAL

namespace dewall::cgal::detail {

/// True for the kernels whose predicates are exact (filtered, then exact
/// arithmetic) on the points' Cartesian coordinates: CGAL::Epick and
/// CGAL::Epeck. Their orientation, side_of_oriented_circle/_sphere and
/// compare_x/y/z are the signs of the exact determinants and comparisons, as
/// ours; DeWall runs only where every coordinate is exactly a double
/// (to_exact_double), so both decide on the same numbers.
template <class K>
inline constexpr bool is_exact_predicates_kernel = std::is_same_v<K, CGAL::Epick> || std::is_same_v<K, CGAL::Epeck>;

/// Dewall_axes<Gt, D>::axes: for traits Gt of a D-dimensional triangulation,
/// the coordinates of DT::Point that DeWall triangulates (u = axes[0],
/// v = axes[1], …), when Gt's predicates are provably ours on them;
/// `known == false` otherwise (the builders then use CGAL's construction).
/// `projects`: whether DT::Point has more coordinates than DeWall sees (two
/// points may then be one vertex for CGAL and still differ; see
/// make_triangulation).
template <class Gt, int D>
struct Dewall_axes {
  static constexpr bool known = false;
};

template <class Gt, int D>
  requires is_exact_predicates_kernel<Gt>
struct Dewall_axes<Gt, D> {
  static constexpr bool known = true;
  static constexpr bool projects = false;
  static constexpr std::array<int, 3> axes{0, 1, 2};
};

/// Projection_traits_xy_3/_xz_3/_yz_3 derive from
/// internal::Projection_traits_3<K, dim> (Kernel_23/internal/Projection_traits_3.h)
/// with dim = 2, 1, 0, the dropped axis; Projector<K, dim> reads (x, y), (x, z)
/// and (y, z) resp. (x_index, y_index). Over them Orientation_2 and
/// Side_of_oriented_circle_2 are K's 2D predicates on the projected
/// K::Point_2(u, v), and Compare_x_2 / Compare_y_2 are K's Compare_<u>_3 /
/// Compare_<v>_3, so Triangulation_2::compare_xy (the perturbation order) is
/// lexicographic on (u, v): all three are ours on (u, v), no sign flipped.
template <class K, int U, int V>
struct Projected_axes {
  static constexpr bool known = is_exact_predicates_kernel<K>;
  static constexpr bool projects = true;
  static constexpr std::array<int, 3> axes{U, V, -1};
};
template <class K>
struct Dewall_axes<CGAL::Projection_traits_xy_3<K>, 2> : Projected_axes<K, 0, 1> {};
template <class K>
struct Dewall_axes<CGAL::Projection_traits_xz_3<K>, 2> : Projected_axes<K, 0, 2> {};
template <class K>
struct Dewall_axes<CGAL::Projection_traits_yz_3<K>, 2> : Projected_axes<K, 1, 2> {};

}  // namespace dewall::cgal::detail
