// CGAL's own Delaunay triangulation of a point set (CGAL's insertion with
// Epick / Epick_d, not DeWall), as a set of sorted index tuples: the reference
// the tests, the triangulate fuzzer and the benchmarks compare dewall with. Not
// part of the installed API (the library's own incremental engine is
// dewall/src/cgal_engine.cpp). Duplicate points map to their first occurrence, the
// convention dewall follows (CGAL keeps whichever copy it inserted first,
// which after its spatial sort need not be the first).
#pragma once

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "dewall/kernel/point.hpp"

namespace dewall::cgal {

template <int D>
using Simplex_set = std::set<std::array<std::uint32_t, D + 1>>;

/// Sorted index tuples of any simplex list.
template <int D, class Range>
Simplex_set<D> as_simplex_set(const Range& simplices) {
  Simplex_set<D> s;
  for (auto t : simplices) {
    std::sort(t.begin(), t.end());
    s.insert(t);
  }
  return s;
}

/// CGAL's triangulation of `points` (finite coordinates; empty when the
/// points do not span E^D).
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

}  // namespace dewall::cgal
