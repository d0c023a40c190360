// The geometry over the incremental engine's cell store (CGAL's
// Triangulation_3 over its data structure): the points by vertex id, the
// static filter made for their box, and the predicates on cells that the
// walk, the cavity search and the checks ask — every answer exact, the
// filters in front of the kernel's exact stages.
#pragma once

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dewall/detail/common/index.hpp"
#include "dewall/detail/common/input.hpp"
#include "dewall/detail/incremental/cell_store.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "dewall/kernel/static_filter.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// The cavity search's count of its sphere tests, and of those the static
/// filter's box-wide bound left (counted only when it is tried first).
struct Filter_tally {
  std::uint32_t tests = 0, box_bound_left = 0;
};

template <int D>
class Cell_geometry {
 public:
  using Point = kernel::Point_d<D>;

  /// The cell store's topological checks, and every finite cell positively oriented.
  bool is_valid() const {
    if (!store_.links_are_valid()) return false;
    for (std::size_t c = 0; c < store_.slots(); ++c)
      if (!store_.is_free(c) && !store_.is_infinite(c) && orientation(c, -1, nullptr) != kernel::POSITIVE) return false;
    return true;
  }

 protected:
  /// Orientation of cell c (finite) with vertex `replaced` (−1: none) replaced by q.
  kernel::Sign orientation(std::size_t c, int replaced, const Point* q) const {
    const auto refs = orientation_points(c, replaced, q);
    if (const auto s = static_filter_.orientation(refs)) return *s;
    return kernel::orientation_d<D>(refs);
  }
  /// Cell c's vertices, the one at position `replaced` (if any) replaced by q.
  kernel::Point_refs<D, D + 1> orientation_points(std::size_t c, int replaced, const Point* q) const {
    kernel::Point_refs<D, D + 1> refs;
    for (int k = 0; k <= D; ++k) refs[k] = k == replaced ? q : &points_[store_[c].v[k]];
    return refs;
  }
  /// Finite cell c's vertices, then q.
  kernel::Point_refs<D, D + 2> sphere_points(std::size_t c, const Point& q) const {
    kernel::Point_refs<D, D + 2> refs;
    for (int k = 0; k <= D; ++k) refs[k] = &points_[store_[c].v[k]];
    refs[D + 1] = &q;
    return refs;
  }

  /// Whether q lies inside the perturbed sphere of finite cell c, the
  /// semi-static bound tried before the box's when Semi_static_first (3D;
  /// choose_filter_order says when). Inlined in both searches (GCC kept it
  /// out of line in the zoned one: a call per test).
  template <bool Semi_static_first>
  [[gnu::always_inline]] bool sphere_holds(std::size_t c, const Point& q, Filter_tally& tally) const {
    const auto refs = sphere_points(c, q);
    kernel::Sign s;
    if constexpr (D == 3) {
      ++tally.tests;
      s = static_filter_.template side_of_oriented_sphere_sign<Semi_static_first>(refs, tally.box_bound_left);
    } else {
      s = static_filter_.side_of_oriented_sphere_sign(refs);
    }
    if (s != kernel::ZERO) return s == kernel::POSITIVE;
    return exact_zero_perturbed(refs);
  }
  /// Whether find_cavity computes its sphere tests in pairs (pair_sphere_tests).
  static constexpr bool paired_sphere_tests = kernel::Static_filter_d<D>::pairs_sphere_tests;
  using Sphere_pair = typename kernel::Static_filter_d<D>::Sphere_pair;
  /// The sphere tests of finite cells a and b with q, computed together up
  /// to their first bound, for sphere_holds_given. \pre static_filter_.valid().
  template <bool Semi_static_first>
  [[gnu::always_inline]] Sphere_pair pair_sphere_tests(std::size_t a, std::size_t b, const Point& q) const {
    return kernel::Static_filter_d<D>::template side_of_oriented_sphere_pair<Semi_static_first>(
        [&](int k, int i) -> const Point& { return i == D + 1 ? q : points_[store_[k == 0 ? a : b].v[i]]; });
  }
  /// sphere_holds<Semi_static_first>(c, q, tally) given c's test from
  /// pair_sphere_tests: the same answer and counts (3D).
  template <bool Semi_static_first>
  [[gnu::always_inline]] bool sphere_holds_given(std::size_t c, const Point& q, double det, double bound,
                                                 Filter_tally& tally) const {
    ++tally.tests;
    const auto refs = sphere_points(c, q);
    const kernel::Sign s =
        static_filter_.template side_of_oriented_sphere_sign_given<Semi_static_first>(refs, det, bound, tally.box_bound_left);
    if (s != kernel::ZERO) return s == kernel::POSITIVE;
    return exact_zero_perturbed(refs);
  }

  /// sphere_holds for an exact zero: the perturbation's orientations,
  /// through the static filter first (the points are input points, in its
  /// box). Out of line: inlined, it slowed the cavity search on inputs that
  /// never tie.
  [[gnu::noinline]] bool exact_zero_perturbed(const kernel::Sphere_points<D>& refs) const {
    kernel::count(kernel::predicate_stats().side_of_sphere[D].perturbed);
    return kernel::perturbed_side_of_sphere<D>(
               refs,
               [&](const kernel::Orientation_points<D>& o) {
                 if (const auto sign = static_filter_.orientation(o)) return *sign;
                 return kernel::orientation_d<D>(o);
               },
               [](const Point& a, const Point& b) { return kernel::compare_lexicographically(a, b) == kernel::SMALLER; }) ==
           kernel::ON_POSITIVE_SIDE;
  }

  /// The exponent of the coarsest power of two of which every coordinate of
  /// the `count` points is a multiple (INT_MIN where the static filter is
  /// not offered: no use scanning).
  template <class Coordinates>
  static int lattice_unit(std::size_t count, Coordinates&& coordinates) {
    if constexpr (!kernel::Static_filter_d<D>::available) return INT_MIN;
    int unit = INT_MAX;
    for (std::size_t k = 0; k < count; ++k) {
      const auto& x = coordinates(k);
      for (int j = 0; j < D; ++j) unit = std::min(unit, kernel::lowest_bit_exponent(x[j]));
    }
    return unit;
  }

  /// Whether cell c is in conflict with q: destroyed when q is inserted.
  /// An infinite cell is when q lies beyond its hull facet (the cell with the
  /// infinite vertex replaced by q positively oriented). When q lies in the
  /// facet's hyperplane it is exactly when the finite cell behind the facet
  /// is: if that cell goes, the facet is on no finite cell any more (a cell
  /// of q and the facet would be flat) and must go too; if it stays, the facet
  /// stays a hull facet (q does not lie beyond it). This is the answer CGAL's
  /// perturbed in-circle test on the facet gives, by that same argument.
  /// Inlined into the searches (GCC called it).
  template <bool Semi_static_first>
  [[gnu::always_inline]] bool in_conflict(std::size_t c, const Point& q, Filter_tally& tally) const {
    const int i = store_.infinite_position(c);
    if (i > D) return sphere_holds<Semi_static_first>(c, q, tally);
    const kernel::Sign s = orientation(c, i, &q);
    if (s != kernel::ZERO) return s == kernel::POSITIVE;
    return sphere_holds<Semi_static_first>(store_.neighbor(c, i), q, tally);
  }
  bool in_conflict(std::size_t c, const Point& q) const {
    Filter_tally unused;
    return in_conflict<false>(c, q, unused);
  }

  /// Whether the filters prove cell c in conflict with q (false when they
  /// cannot tell: on near-cospherical points the exact stages would cost
  /// more than the walk they save). A sphere test goes on to the semi-static
  /// filter, on the static one's determinant: on surface samples the static
  /// bound alone leaves most tries undecided.
  bool proven_in_conflict(std::size_t c, const Point& q) const {
    const int i = store_.infinite_position(c);
    const auto s = i > D ? static_filter_.side_of_oriented_sphere_filtered(sphere_points(c, q))
                         : static_filter_.orientation(orientation_points(c, i, &q));
    return s && *s == kernel::POSITIVE;
  }

  /// The first simplex (the first D + 1 affinely independent points of
  /// `order`) and its D + 1 infinite neighbours, the points' coordinates
  /// points_[0 … D]; `order` becomes the insertion order with the simplex's
  /// points first. False when the points do not span E^D.
  template <class Coordinates>
  bool make_first_simplex(Coordinates&& coordinates, std::vector<std::uint32_t>& order) {
    Affine_basis<D> basis(coordinates(order[0]));
    std::vector<std::uint32_t> simplex{order[0]}, passed_over;
    std::size_t k = 1;
    for (; k < order.size() && basis.rank() < D; ++k) {
      if (basis.add(coordinates(order[k]))) simplex.push_back(order[k]);
      else passed_over.push_back(order[k]);
    }
    if (basis.rank() < D) return false;
    // order = simplex, passed over, rest (k … end), kept in place.
    std::copy_backward(simplex.begin(), simplex.end(),
                       std::copy_backward(passed_over.begin(), passed_over.end(), order.begin() + static_cast<std::ptrdiff_t>(k)));

    points_.resize(D + 1);
    for (int i = 0; i <= D; ++i) points_[i].x = coordinates(order[i]);
    typename Cell_store<D>::Cell first;
    for (int i = 0; i <= D; ++i) first[i] = static_cast<Index>(i);
    store_.assign_first(first);
    if (orientation(0, -1, nullptr) == kernel::NEGATIVE) std::swap(store_[0].v[0], store_[0].v[1]);
    // The infinite cell across facet i: the simplex with vertex i replaced by
    // the infinite vertex and two others swapped, so that putting a point
    // beyond the facet in the infinite vertex's place orients it positively.
    for (int i = 0; i <= D; ++i) {
      typename Cell_store<D>::Cell c = store_[0].v;
      c[i] = Cell_store<D>::infinite;
      std::swap(c[(i + 1) % (D + 1)], c[(i + 2) % (D + 1)]);
      const std::size_t s = store_.push(typename Cell_store<D>::Record{c, {}, {}});
      store_[0].n[i] = Cell_store<D>::reference(s, i);
      store_[s].n[i] = Cell_store<D>::reference(0, i);
    }
    // The infinite cells meet each other across their facets through the infinite vertex.
    for (int a = 0; a <= D; ++a)
      for (int b = a + 1; b <= D; ++b) {
        const std::size_t ca = 1 + a, cb = 1 + b;
        // Cell a lacks vertex a of the simplex, cell b lacks b: the facet of a
        // opposite (the position of) vertex b, and of b opposite vertex a.
        const int ia = store_.position(ca, store_[0].v[b]), ib = store_.position(cb, store_[0].v[a]);
        store_[ca].n[ia] = Cell_store<D>::reference(cb, ib);
        store_[cb].n[ib] = Cell_store<D>::reference(ca, ia);
      }
    return true;
  }

  Cell_store<D> store_;
  std::vector<Point> points_;                 // by vertex id (insertion order)
  kernel::Static_filter_d<D> static_filter_;  // from the points' box: in front of the kernel's cascade
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
