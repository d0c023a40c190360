// An installed dewall used from another project: DeWall's simplices, and
// genuine CGAL triangulations built by DeWall, each compared with CGAL's own
// construction on the same points. What the package must carry for that:
//  * CGAL::TBB_support through dewall::dewall (a Parallel_tag triangulation
//    that silently ran sequentially without CGAL_LINKED_WITH_TBB);
//  * the builders' choice of traits (Projection_traits_xz_3 triangulates x, z).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xz_3.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

#include "dewall/cgal/delaunay_triangulation_2.hpp"
#include "dewall/cgal/delaunay_triangulation_3.hpp"
#include "dewall/dewall.hpp"

#ifndef CGAL_LINKED_WITH_TBB
#error "dewall::dewall must bring CGAL::TBB_support (CGAL_LINKED_WITH_TBB)"
#endif

namespace {

using K = CGAL::Epick;

// Finite cells as sorted point tuples: comparable across triangulations.
template <class DT, class Cells>
std::set<std::vector<typename DT::Point>> cells(const DT& dt, Cells range) {
  std::set<std::vector<typename DT::Point>> out;
  for (auto c : range) {
    std::vector<typename DT::Point> s;
    for (int i = 0; i <= dt.dimension(); ++i) s.push_back(c->vertex(i)->point());
    std::sort(s.begin(), s.end());
    out.insert(s);
  }
  return out;
}

bool report(const char* what, bool valid, bool same) {
  std::printf("%s: valid %d, same cells as CGAL %d\n", what, valid ? 1 : 0, same ? 1 : 0);
  return valid && same;
}

}  // namespace

int main() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<K::Point_3> points;
  std::vector<dewall::kernel::Point_d<3>> coords;
  for (int i = 0; i < 2000; ++i) {
    coords.push_back({{u(rng), u(rng), u(rng)}});
    points.emplace_back(coords.back()[0], coords.back()[1], coords.back()[2]);
  }
  const auto t = dewall::triangulate<3>(coords);
  bool ok = true;
  {
    using DT = CGAL::Delaunay_triangulation_3<K>;
    const DT dt = dewall::cgal::make_delaunay_triangulation_3<DT>(points);
    std::printf("dewall simplices %zu, CGAL finite cells %zu\n", t.simplices.size(),
                std::size_t(dt.number_of_finite_cells()));
    ok &= t.simplices.size() == dt.number_of_finite_cells();
    const DT theirs(points.begin(), points.end());
    ok &= report("Delaunay_triangulation_3", dt.is_valid(),
                 cells(dt, dt.finite_cell_handles()) == cells(theirs, theirs.finite_cell_handles()));
  }
  {
    using DT = CGAL::Delaunay_triangulation_2<CGAL::Projection_traits_xz_3<K>>;
    const DT dt = dewall::cgal::make_delaunay_triangulation_2<DT>(points);
    const DT theirs(points.begin(), points.end());
    ok &= report("Projection_traits_xz_3", dt.is_valid(),
                 cells(dt, dt.finite_face_handles()) == cells(theirs, theirs.finite_face_handles()));
  }
  {
    using Tds = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                                     CGAL::Delaunay_triangulation_cell_base_3<K>, CGAL::Parallel_tag>;
    using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
    DT::Lock_data_structure lock(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 20);
    DT dt = dewall::cgal::make_delaunay_triangulation_3<DT>(points, {}, K(), &lock);
    ok &= dt.get_lock_data_structure() == &lock;
    std::vector<K::Point_3> more;
    for (int i = 0; i < 2000; ++i) more.emplace_back(u(rng), u(rng), u(rng));
    dt.insert(more.begin(), more.end());  // in parallel: a lock data structure and > 50 points
    DT::Lock_data_structure theirs_lock(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 20);
    DT theirs(points.begin(), points.end(), K(), &theirs_lock);
    theirs.insert(more.begin(), more.end());
    ok &= report("Parallel_tag, then parallel insertion", dt.is_valid(),
                 cells(dt, dt.finite_cell_handles()) == cells(theirs, theirs.finite_cell_handles()));
  }
  return ok ? 0 : 1;
}
