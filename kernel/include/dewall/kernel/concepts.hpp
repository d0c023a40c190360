// DelaunayKernel: what the DeWall algorithm and the certifier need from a kernel.
//
// Modelled on CGAL's DelaunayTriangulationTraits: each requirement is a functor
// reached through an `xxx_object()` accessor, so a CGAL kernel fits behind a thin
// adapter (cgal_kernel_adapter.hpp). Models: Filtered_kernel_d<D> (ours) and
// Cgal_kernel_adapter<CGAL kernel, D>. Kernel_archetype<D> (tests/support/
// kernel_archetype.hpp: opaque points, these functors only) proves the
// algorithm uses nothing else.
//
// Requirements, for a kernel K with Point = K::Point_d and D = K::dimension:
//  * `K::dimension`: the static dimension D, 2 ≤ D ≤ 6.
//  * `orientation_d_object()(s)`, s a std::array<const Point*, D + 1>:
//      the sign of det[s_1 − s_0, …, s_D − s_0]; ZERO for affinely dependent
//      points. Exact. Never perturbed.
//  * `side_of_oriented_sphere_d_object()(s)`, s a std::array<const Point*, D + 2>
//      holding a simplex then a query q: ON_POSITIVE_SIDE when q is inside the
//      circumsphere, ON_NEGATIVE_SIDE when outside, resolving the cospherical
//      case by CGAL's lexicographic symbolic perturbation; never
//      ON_ORIENTED_BOUNDARY. \pre the simplex is positively oriented and q is
//      not one of its vertices.
//  * `side_of_oriented_sphere_unperturbed_d_object()(s)`: the same test without
//      the perturbation: ON_ORIENTED_BOUNDARY when q is on the sphere. Exact.
//      (The certifier needs it to tell "Delaunay" from "canonical".)
//  * `compare_lexicographically_d_object()(p, q)`: the exact lexicographic
//      order of the coordinates (the order the perturbation is defined on).
//  * `approximate_coordinates_object()(p)`: the coordinates as
//      std::array<double, D>, finite, equal for equal points (duplicates are
//      found by hashing them, then compared exactly). The algorithm orders
//      its work by them (the splits, the kd-tree, the order of candidates;
//      points with one approximation are split by index) and prunes its
//      searches with them: a kd-tree node is skipped when a floating-point
//      test proves that no point of it can be the apex. The predicates decide
//      everything else. What the pruning may assume is the kernel's to state,
//      through one of two optional members:
//      - `static constexpr bool approximate_coordinates_are_exact = true`: the
//        points *are* those doubles. The pruning takes them as exact, and the
//        algorithm may also decide with its own proven double filters (e.g. a
//        per-face orientation filter), falling back to the kernel's
//        predicates when they cannot prove a sign. (Filtered_kernel_d.)
//      - `static constexpr double approximate_coordinates_error = ε`: every
//        approximation x̂ of a coordinate x has |x − x̂| ≤ ε·max(|x̂|, 2^-1022)
//        (ε = 2^-52 covers a correctly rounded or truncated conversion of an
//        exact number to double; 0 says they are exact but the algorithm
//        shall not decide with them, as Cgal_kernel_adapter over double
//        coordinates). Every box the pruning proves is widened by that error,
//        so no point is skipped that the exact coordinates would keep.
//      Without either, nothing bounds the approximations and the searches
//      prune nothing: every search looks at every point (quadratic time;
//      correct for any approximations).
//      The check that the points span E^D (detail/common/input.hpp) is an exact rank
//      of the approximations: with a non-exact kernel whose rounding flattens
//      the points, or rounds a flat set into general position, that check is
//      wrong.
#pragma once

#include <array>
#include <concepts>
#include <limits>

#include "dewall/kernel/sign.hpp"

namespace dewall::kernel {

template <class K>
concept DelaunayKernel =
    requires { typename K::Point_d; } && std::convertible_to<decltype(K::dimension), int> &&
    K::dimension >= 2 && K::dimension <= 6 &&
    requires(const K& k, const typename K::Point_d& p,
             const std::array<const typename K::Point_d*, K::dimension + 1>& simplex,
             const std::array<const typename K::Point_d*, K::dimension + 2>& simplex_and_query) {
      { k.orientation_d_object()(simplex) } -> std::same_as<Sign>;
      { k.side_of_oriented_sphere_d_object()(simplex_and_query) } -> std::same_as<Oriented_side>;
      { k.side_of_oriented_sphere_unperturbed_d_object()(simplex_and_query) } -> std::same_as<Oriented_side>;
      { k.compare_lexicographically_d_object()(p, p) } -> std::same_as<Comparison_result>;
      { k.approximate_coordinates_object()(p) } -> std::convertible_to<std::array<double, K::dimension>>;
    };

/// True when K declares its points to be exactly their double coordinates.
template <class K>
inline constexpr bool approximate_coordinates_are_exact = requires {
  requires K::approximate_coordinates_are_exact;
};

/// The relative error ε of K's approximate coordinates that the pruning
/// honours: 0 when they are exact, K::approximate_coordinates_error when K
/// states one, +∞ (no pruning) otherwise.
template <class K>
inline constexpr double approximate_coordinates_error = [] {
  if constexpr (approximate_coordinates_are_exact<K>) return 0.0;
  else if constexpr (requires { requires K::approximate_coordinates_error >= 0; })
    return static_cast<double>(K::approximate_coordinates_error);
  else return std::numeric_limits<double>::infinity();
}();

}  // namespace dewall::kernel
