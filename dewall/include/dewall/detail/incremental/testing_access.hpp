// The one door tests use into the incremental engine's internals.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "dewall/detail/incremental/incremental_delaunay.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// What tests reach inside an Incremental_delaunay.
struct Incremental_testing_access {
  /// The cells in conflict with q (not a vertex), as insertion would find
  /// them (the walk, then the breadth-first search), sorted. q may lie
  /// outside the points' box: the static filter, whose bound assumes it
  /// inside, is off for the call.
  template <int D>
  static std::vector<std::size_t> cavity(Incremental_delaunay<D>& dt, const kernel::Point_d<D>& q) {
    Bowyer_watson<D>& bw = dt;
    const auto filter = std::exchange(bw.static_filter_, kernel::Static_filter_d<D>());
    bw.template find_cavity<false>(bw.serial_, q, Incremental_delaunay<D>::infinite);
    bw.clear_marks(bw.serial_);
    bw.static_filter_ = filter;
    std::vector<std::size_t> cells(bw.serial_.cavity.begin(), bw.serial_.cavity.end());
    std::sort(cells.begin(), cells.end());
    return cells;
  }
  /// Whether the static filter decides every predicate exactly (the points
  /// lie on a small lattice: kernel/static_filter.hpp).
  template <int D>
  static bool static_filter_exact(const Incremental_delaunay<D>& dt) {
    const Bowyer_watson<D>& bw = dt;
    return bw.static_filter_.exact();
  }
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
