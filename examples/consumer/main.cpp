// An installed dewall used from another project: DeWall's simplices, and a
// genuine CGAL::Delaunay_triangulation_3 built by DeWall.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cstdio>
#include <random>
#include <vector>

#include "dewall/cgal/delaunay_triangulation_3.hpp"
#include "dewall/dewall.hpp"

int main() {
  using K = CGAL::Epick;
  using DT = CGAL::Delaunay_triangulation_3<K>;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<K::Point_3> points;
  std::vector<dewall::kernel::Point_d<3>> coords;
  for (int i = 0; i < 2000; ++i) {
    coords.push_back({{u(rng), u(rng), u(rng)}});
    points.emplace_back(coords.back()[0], coords.back()[1], coords.back()[2]);
  }
  const auto t = dewall::triangulate<3>(coords);
  const DT dt = dewall::cgal::make_delaunay_triangulation_3<DT>(points);
  std::printf("dewall simplices %zu, CGAL finite cells %zu, valid %d\n", t.simplices.size(),
              std::size_t(dt.number_of_finite_cells()), dt.is_valid() ? 1 : 0);
  return dt.is_valid() && t.simplices.size() == dt.number_of_finite_cells() ? 0 : 1;
}
