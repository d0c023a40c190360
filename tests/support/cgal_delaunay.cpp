// CGAL's Delaunay triangulation as sorted index tuples (cgal_delaunay.hpp),
// instantiated here once for D = 2 … 6.
#include "support/cgal_delaunay.hpp"

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <map>

namespace dewall::cgal {

template <int D>
Simplex_set<D> cgal_delaunay(const std::vector<kernel::Point_d<D>>& points) {
  std::map<std::array<double, D>, std::uint32_t> first;
  for (std::size_t i = points.size(); i-- > 0;) first[points[i].x] = static_cast<std::uint32_t>(i);
  Simplex_set<D> out;
  // CGAL 5.5's dD spatial_sort dereferences begin() of an empty range.
  if (points.empty()) return out;
  auto add = [&](auto&& coords_of_vertex) {
    std::array<std::uint32_t, D + 1> t;
    for (int i = 0; i <= D; ++i) t[i] = first.at(coords_of_vertex(i));
    std::sort(t.begin(), t.end());
    out.insert(t);
  };
  if constexpr (D == 2) {
    CGAL::Delaunay_triangulation_2<CGAL::Epick> dt;
    std::vector<CGAL::Epick::Point_2> p;
    for (const auto& q : points) p.emplace_back(q[0], q[1]);
    dt.insert(p.begin(), p.end());
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      add([&](int i) { const auto& v = f->vertex(i)->point(); return std::array<double, 2>{v.x(), v.y()}; });
  } else if constexpr (D == 3) {
    CGAL::Delaunay_triangulation_3<CGAL::Epick> dt;
    std::vector<CGAL::Epick::Point_3> p;
    for (const auto& q : points) p.emplace_back(q[0], q[1], q[2]);
    dt.insert(p.begin(), p.end());
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
      add([&](int i) {
        const auto& v = c->vertex(i)->point();
        return std::array<double, 3>{v.x(), v.y(), v.z()};
      });
  } else {
    using K = CGAL::Epick_d<CGAL::Dimension_tag<D>>;
    CGAL::Delaunay_triangulation<K> dt(D);
    std::vector<typename K::Point_d> p;
    for (const auto& q : points) p.emplace_back(q.x.begin(), q.x.end());
    dt.insert(p.begin(), p.end());
    if (dt.current_dimension() < D) return out;  // not full-dimensional: no D-simplices
    for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c)
      add([&](int i) {
        const auto& v = c->vertex(i)->point();
        std::array<double, D> a;
        for (int j = 0; j < D; ++j) a[j] = v[j];
        return a;
      });
  }
  return out;
}

template Simplex_set<2> cgal_delaunay<2>(const std::vector<kernel::Point_d<2>>&);
template Simplex_set<3> cgal_delaunay<3>(const std::vector<kernel::Point_d<3>>&);
template Simplex_set<4> cgal_delaunay<4>(const std::vector<kernel::Point_d<4>>&);
template Simplex_set<5> cgal_delaunay<5>(const std::vector<kernel::Point_d<5>>&);
template Simplex_set<6> cgal_delaunay<6>(const std::vector<kernel::Point_d<6>>&);

}  // namespace dewall::cgal
