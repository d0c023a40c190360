// The CGAL reference of the tests: CGAL's own triangulation as sorted index
// tuples (cgal_delaunay.hpp), with the tests' names.
#pragma once

#include "support/cgal_delaunay.hpp"

namespace dewall::test {

template <int D>
using Simplex_set = cgal::Simplex_set<D>;

template <int D, class Range>
Simplex_set<D> as_set(const Range& simplices) {
  return cgal::as_simplex_set<D>(simplices);
}

using cgal::cgal_delaunay;

}  // namespace dewall::test
