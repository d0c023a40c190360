// detail::triangulate_with_cgal for D = 2 … 6 (cgal_engine.hpp).
#include "cgal_engine.hpp"

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Spatial_sort_traits_adapter_d.h>

#include <utility>

#include "dewall/detail/input.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::detail {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

/// CGAL's cells over the distinct points, each vertex carrying its input index:
/// `cell(i)` of each finite cell gives the index of its vertex i.
template <int D, class Emit>
void cgal_cells(std::span<const kernel::Point_d<D>> points, const std::vector<std::size_t>& distinct, Emit&& emit) {
  if constexpr (D == 2) {
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Epick>;
    using Tds = CGAL::Triangulation_data_structure_2<Vb>;
    std::vector<std::pair<Epick::Point_2, std::uint32_t>> items;
    items.reserve(distinct.size());
    for (std::size_t i : distinct) items.emplace_back(Epick::Point_2(points[i][0], points[i][1]), std::uint32_t(i));
    CGAL::Delaunay_triangulation_2<Epick, Tds> dt(items.begin(), items.end());
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      emit([&](int i) { return f->vertex(i)->info(); });
  } else if constexpr (D == 3) {
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Epick>;
    using Tds = CGAL::Triangulation_data_structure_3<Vb, CGAL::Delaunay_triangulation_cell_base_3<Epick>>;
    std::vector<std::pair<Epick::Point_3, std::uint32_t>> items;
    items.reserve(distinct.size());
    for (std::size_t i : distinct)
      items.emplace_back(Epick::Point_3(points[i][0], points[i][1], points[i][2]), std::uint32_t(i));
    CGAL::Delaunay_triangulation_3<Epick, Tds> dt(items.begin(), items.end());
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
      emit([&](int i) { return c->vertex(i)->info(); });
  } else {
    using K = CGAL::Epick_d<CGAL::Dimension_tag<D>>;
    using Vertex = CGAL::Triangulation_vertex<K, std::uint32_t>;
    using Tds = CGAL::Triangulation_data_structure<CGAL::Dimension_tag<D>, Vertex,
                                                   CGAL::Triangulation_full_cell<K>>;
    CGAL::Delaunay_triangulation<K, Tds> dt(D);
    // Spatially sorted insertion, as the range insert does, but keeping the index.
    std::vector<typename K::Point_d> p;
    p.reserve(distinct.size());
    for (std::size_t i : distinct) p.emplace_back(points[i].x.begin(), points[i].x.end());
    std::vector<std::size_t> order(distinct.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    using Sort_traits =
        CGAL::Spatial_sort_traits_adapter_d<K, typename CGAL::Pointer_property_map<typename K::Point_d>::type>;
    CGAL::spatial_sort(order.begin(), order.end(), Sort_traits(CGAL::make_property_map(p)));
    typename CGAL::Delaunay_triangulation<K, Tds>::Full_cell_handle hint;
    for (std::size_t k : order) {
      const auto v = dt.insert(p[k], hint);
      v->data() = static_cast<std::uint32_t>(distinct[k]);
      hint = v->full_cell();
    }
    for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c)
      emit([&](int i) { return c->vertex(i)->data(); });
  }
}

}  // namespace

template <int D>
Statistics triangulate_with_cgal(std::span<const kernel::Point_d<D>> points, std::vector<Simplex<D>>& simplices) {
  using K = kernel::Filtered_kernel_d<D>;
  const kernel::Fp_environment_guard guard;  // CGAL's filters assume the default environment too
  const std::vector<std::size_t> distinct = distinct_points<K>(K{}, points);
  std::vector<std::array<double, D>> coords(distinct.size());
  for (std::size_t i = 0; i < distinct.size(); ++i) coords[i] = points[distinct[i]].x;
  require_full_dimension<D>(std::span<const std::array<double, D>>(coords));

  const std::size_t before = simplices.size();
  const auto orientation = K{}.orientation_d_object();
  cgal_cells<D>(points, distinct, [&](auto&& vertex) {
    Simplex<D> s;
    std::array<const kernel::Point_d<D>*, D + 1> p;
    for (int i = 0; i <= D; ++i) {
      s[static_cast<std::size_t>(i)] = vertex(i);
      p[static_cast<std::size_t>(i)] = &points[s[static_cast<std::size_t>(i)]];
    }
    // Positively oriented, as DeWall writes them (TetGen .ele expects it).
    if (orientation(p) == kernel::NEGATIVE) std::swap(s[0], s[1]);
    simplices.push_back(s);
  });
  Statistics st;
  st.input_points = points.size();
  st.distinct_points = distinct.size();
  st.simplices = simplices.size() - before;
  st.engine = Engine::cgal;
  return st;
}

#define DEWALL_INSTANTIATE_CGAL_ENGINE(D) \
  template Statistics triangulate_with_cgal<D>(std::span<const kernel::Point_d<D>>, std::vector<Simplex<D>>&);
DEWALL_INSTANTIATE_CGAL_ENGINE(2)
DEWALL_INSTANTIATE_CGAL_ENGINE(3)
DEWALL_INSTANTIATE_CGAL_ENGINE(4)
DEWALL_INSTANTIATE_CGAL_ENGINE(5)
DEWALL_INSTANTIATE_CGAL_ENGINE(6)

}  // namespace dewall::detail
