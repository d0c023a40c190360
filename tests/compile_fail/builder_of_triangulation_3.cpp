// Must not compile: CGAL::Triangulation_3 is not a Delaunay triangulation, and
// make_delaunay_triangulation_3 says what it builds (CTest
// cgal_builder_refuses_triangulation_3 checks the message).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_3.h>

#include <vector>

#include "dewall/cgal/delaunay_triangulation_3.hpp"

int main() {
  using T = CGAL::Triangulation_3<CGAL::Epick>;
  const std::vector<CGAL::Epick::Point_3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const T t = dewall::cgal::make_delaunay_triangulation_3<T>(points);
  return t.is_valid() ? 0 : 1;
}
