// Must not compile: a class derived from CGAL::Delaunay_triangulation_3 that
// can be made neither empty from the traits nor from a triangulation; the
// builder says so (CTest cgal_builder_refuses_unbuildable_derived_3 checks
// the message).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <vector>

#include "dewall/cgal/delaunay_triangulation_3.hpp"

struct Labelled : CGAL::Delaunay_triangulation_3<CGAL::Epick> {
  explicit Labelled(int label) : label(label) {}
  int label;
};

int main() {
  const std::vector<CGAL::Epick::Point_3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Labelled t = dewall::cgal::make_delaunay_triangulation_3<Labelled>(points);
  return t.is_valid() ? 0 : 1;
}
