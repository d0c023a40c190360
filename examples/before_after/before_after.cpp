// A CGAL program before and after the one-line change to DeWall.
//
// Built twice (examples/CMakeLists.txt): as example_before with CGAL's own
// construction and as example_after with DEWALL_DROP_IN defined. Everything
// after the construction is the same CGAL code: point location, nearest
// vertex, insertion, removal, the Voronoi dual, validity. Both print the same
// summary (CTest compares them).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

#ifdef DEWALL_DROP_IN
#include "dewall/cgal/delaunay_triangulation_3.hpp"
#endif

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using DT = CGAL::Delaunay_triangulation_3<K>;
using Point = K::Point_3;

int main() {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point> points;
  for (int i = 0; i < 20000; ++i) points.emplace_back(u(rng), u(rng), u(rng));

#ifndef DEWALL_DROP_IN
  DT dt(points.begin(), points.end());  // before
#else
  DT dt = dewall::cgal::make_delaunay_triangulation_3<DT>(points.begin(), points.end());  // after
#endif

  // The rest of the program does not change.
  const Point q(0.5, 0.5, 0.5);
  const DT::Cell_handle c = dt.locate(q);
  const DT::Vertex_handle v = dt.nearest_vertex(q);
  const Point centre = dt.dual(c);
  std::printf("valid %d vertices %zu cells %zu\n", dt.is_valid() ? 1 : 0, std::size_t(dt.number_of_vertices()),
              std::size_t(dt.number_of_finite_cells()));
  std::printf("nearest to q: %.6f %.6f %.6f; circumcentre of its cell: %.6f %.6f %.6f\n", v->point().x(),
              v->point().y(), v->point().z(), centre.x(), centre.y(), centre.z());
  dt.insert(q);
  dt.remove(v);
  std::printf("after insert and remove: valid %d cells %zu\n", dt.is_valid() ? 1 : 0,
              std::size_t(dt.number_of_finite_cells()));
  // A fingerprint of the cells: the sorted vertex coordinates of each cell, hashed.
  std::vector<std::array<double, 12>> cells;
  for (auto f = dt.finite_cells_begin(); f != dt.finite_cells_end(); ++f) {
    std::array<Point, 4> p{f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point(), f->vertex(3)->point()};
    std::sort(p.begin(), p.end());
    std::array<double, 12> a;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) a[static_cast<std::size_t>(3 * i + j)] = p[static_cast<std::size_t>(i)][j];
    cells.push_back(a);
  }
  std::sort(cells.begin(), cells.end());
  unsigned long long h = 1469598103934665603ull;
  for (const auto& a : cells)
    for (double x : a) h = (h ^ static_cast<unsigned long long>(x * 1e9)) * 1099511628211ull;
  std::printf("cell fingerprint %016llx\n", h);
  return dt.is_valid() ? 0 : 1;
}
