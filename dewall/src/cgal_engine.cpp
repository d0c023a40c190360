// detail::triangulate_with_cgal for D = 2 … 6 (cgal_engine.hpp).
#include "cgal_engine.hpp"

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Spatial_sort_traits_adapter_d.h>

#include <type_traits>
#include <utility>

#include "dewall/detail/common/input.hpp"
#include "dewall/kernel/point.hpp"
#include "incremental_support.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::detail {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

/// One of CGAL's triangulations seen alike in every dimension, as the cell
/// graph filter_region walks (incremental_support.hpp): its cells from begin
/// to end (infinite ones included; `finite` finite), each cell's int32 info
/// (ours to use), its vertices as ids.
template <int D, class Dt, class Iterator>
struct Cgal_graph {
  using Cell = decltype(std::declval<Iterator>()->neighbor(0));
  Dt& dt;
  Iterator begin, end;
  std::size_t finite;

  template <class F>
  void for_each_cell(F&& f) const {
    for (auto c = begin; c != end; ++c) f(Cell(c));
  }
  std::size_t finite_cells() const { return finite; }
  bool is_infinite(Cell c) const { return dt.is_infinite(c); }
  static Cell neighbor(Cell c, int i) { return c->neighbor(i); }
  bool vertex_is_infinite(Cell c, int i) const { return c->vertex(i) == dt.infinite_vertex(); }
  static std::int32_t& state(Cell c) {
    if constexpr (D <= 3) return c->info();
    else return c->data();
  }
  static Simplex<D> vertices(Cell c) {
    Simplex<D> s;
    for (int i = 0; i <= D; ++i) {
      if constexpr (D <= 3) s[static_cast<std::size_t>(i)] = c->vertex(i)->info();
      else s[static_cast<std::size_t>(i)] = c->vertex(i)->data();
    }
    return s;
  }
};

template <int D, class Dt, class Iterator>
Cgal_graph<D, Dt, Iterator> make_graph(Dt& dt, Iterator begin, Iterator end, std::size_t finite_cells) {
  return {dt, begin, end, finite_cells};
}

/// CGAL's triangulation of the points `ids` (point(i) gives the coordinates
/// of point i), passed to `use(graph)` once built; a Cgal_graph of it lets the
/// code below walk its cells alike in every dimension. False, having called
/// nothing, when the points do not span E^D. \pre the ids' points are distinct.
template <int D, class Point_of, class Use>
bool with_cgal_triangulation(std::span<const Index> ids, Point_of&& point, Use&& use) {
  // 2D and 3D: the (point, id) pairs are spatially sorted themselves and
  // inserted in that order with a hint, which is what CGAL's insert of a range
  // with info does, minus its sort of indices into the points (a random read
  // per comparison: a fifth of the 2D construction's time).
  // `cell_of(v)`: a cell at vertex v, where the next point's search starts.
  auto insert_sorted = [](auto& dt, auto& items, auto sort_traits, auto&& cell_of) {
    CGAL::spatial_sort(items.begin(), items.end(), sort_traits);
    decltype(cell_of(dt.infinite_vertex())) hint{};
    for (const auto& [p, id] : items) {
      const auto before = dt.number_of_vertices();
      const auto v = dt.insert(p, hint);
      if (dt.number_of_vertices() != before) v->info() = id;
      hint = cell_of(v);
    }
    std::remove_reference_t<decltype(items)>().swap(items);  // not needed while the cells are walked
  };
  if constexpr (D == 2) {
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, Epick>;
    using Fb = CGAL::Triangulation_face_base_with_info_2<std::int32_t, Epick>;
    using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
    using Item = std::pair<Epick::Point_2, Index>;
    std::vector<Item> items;
    items.reserve(ids.size());
    for (Index i : ids) items.emplace_back(Epick::Point_2(point(i)[0], point(i)[1]), i);
    CGAL::Delaunay_triangulation_2<Epick, Tds> dt;
    insert_sorted(dt, items, CGAL::Spatial_sort_traits_adapter_2<Epick, CGAL::First_of_pair_property_map<Item>>(),
                  [](auto v) { return v->face(); });
    if (dt.dimension() < 2) return false;
    use(make_graph<D>(dt, dt.all_faces_begin(), dt.all_faces_end(), dt.number_of_faces()));
  } else if constexpr (D == 3) {
    using Vb = CGAL::Triangulation_vertex_base_with_info_3<Index, Epick>;
    using Cb = CGAL::Triangulation_cell_base_with_info_3<std::int32_t, Epick,
                                                         CGAL::Delaunay_triangulation_cell_base_3<Epick>>;
    using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
    using Item = std::pair<Epick::Point_3, Index>;
    std::vector<Item> items;
    items.reserve(ids.size());
    for (Index i : ids) items.emplace_back(Epick::Point_3(point(i)[0], point(i)[1], point(i)[2]), i);
    CGAL::Delaunay_triangulation_3<Epick, Tds> dt;
    insert_sorted(dt, items, CGAL::Spatial_sort_traits_adapter_3<Epick, CGAL::First_of_pair_property_map<Item>>(),
                  [](auto v) { return v->cell(); });
    if (dt.dimension() < 3) return false;
    use(make_graph<D>(dt, dt.all_cells_begin(), dt.all_cells_end(), dt.number_of_finite_cells()));
  } else {
    using K = CGAL::Epick_d<CGAL::Dimension_tag<D>>;
    using Vertex = CGAL::Triangulation_vertex<K, Index>;
    using Tds = CGAL::Triangulation_data_structure<CGAL::Dimension_tag<D>, Vertex,
                                                   CGAL::Triangulation_full_cell<K, std::int32_t>>;
    CGAL::Delaunay_triangulation<K, Tds> dt(D);
    // Spatially sorted insertion, as the range insert does, but keeping the index.
    std::vector<typename K::Point_d> p;
    p.reserve(ids.size());
    for (Index i : ids) p.emplace_back(point(i).begin(), point(i).end());
    std::vector<std::size_t> order(ids.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    using Sort_traits =
        CGAL::Spatial_sort_traits_adapter_d<K, typename CGAL::Pointer_property_map<typename K::Point_d>::type>;
    CGAL::spatial_sort(order.begin(), order.end(), Sort_traits(CGAL::make_property_map(p)));
    typename CGAL::Delaunay_triangulation<K, Tds>::Full_cell_handle hint;
    for (std::size_t k : order) {
      const auto v = dt.insert(p[k], hint);
      v->data() = ids[k];
      hint = v->full_cell();
    }
    if (dt.current_dimension() < D) return false;
    use(make_graph<D>(dt, dt.full_cells_begin(), dt.full_cells_end(), dt.number_of_finite_full_cells()));
  }
  return true;
}

/// Whether CGAL's cells are negatively oriented: in 2D and 3D never (its
/// validity invariant); its dD cells share one orientation, tested on the
/// first finite cell with our exact orientation_d_object. The engine tests
/// check every simplex. (Testing each cell showed in the run: docs/engines.md.)
template <int D, class Graph, class Point_of>
bool cells_negative(const Graph& graph, Point_of&& point) {
  if constexpr (D <= 3) {
    return false;
  } else {
    for (auto c = graph.begin; c != graph.end; ++c) {
      if (graph.dt.is_infinite(c)) continue;
      std::array<kernel::Point_d<D>, D + 1> p;
      std::array<const kernel::Point_d<D>*, D + 1> refs;
      const Simplex<D> s = graph.vertices(c);
      for (int i = 0; i <= D; ++i) {
        p[static_cast<std::size_t>(i)].x = point(s[static_cast<std::size_t>(i)]);
        refs[static_cast<std::size_t>(i)] = &p[static_cast<std::size_t>(i)];
      }
      return kernel::Filtered_kernel_d<D>{}.orientation_d_object()(refs) == kernel::NEGATIVE;
    }
    return false;
  }
}

}  // namespace

template <int D>
Statistics triangulate_with_cgal(std::span<const kernel::Point_d<D>> points, Simplex_output<D>& output,
                                 const Distinct_points* given_distinct) {
  const kernel::Fp_environment_guard guard;  // CGAL's filters assume the default environment too
  Distinct_points own;
  const Distinct_points& distinct = checked_distinct_points<D>(points, given_distinct, own);
  std::vector<Index> ids(distinct.size());
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = static_cast<Index>(distinct[k]);
  // Positively oriented, as DeWall writes them (TetGen .ele expects it).
  auto point = [&](Index i) -> const std::array<double, D>& { return points[i].x; };
  std::size_t count = 0;
  with_cgal_triangulation<D>(ids, point, [&](const auto& graph) {
    Block_writer<D> writer(output, graph.finite);
    const bool flip = cells_negative<D>(graph, point);
    for (auto c = graph.begin; c != graph.end; ++c) {
      if (graph.dt.is_infinite(c)) continue;
      Simplex<D> s = graph.vertices(c);
      if (flip) std::swap(s[0], s[1]);
      writer.put(s);
    }
    count = writer.finish();
  });
  return incremental_statistics(Engine::cgal, points.size(), distinct.size(), count);
}

template <int D>
bool cgal_region_cells(std::span<const Index> region, const std::vector<Coords<D>>& coords, Region_filter<D>& filter) {
  const kernel::Fp_environment_guard guard;
  auto point = [&](Index i) -> const Coords<D>& { return coords[i]; };
  return with_cgal_triangulation<D>(region, point, [&](const auto& graph) {
    auto walked = graph;  // filter_region writes the cells' infos, not the graph
    filter_region<D>(walked, cells_negative<D>(graph, point), filter);
  });
}

#define DEWALL_INSTANTIATE_CGAL_ENGINE(D)                                                                      \
  template Statistics triangulate_with_cgal<D>(std::span<const kernel::Point_d<D>>, Simplex_output<D>&,         \
                                               const Distinct_points*);                                         \
  template bool cgal_region_cells<D>(std::span<const Index>, const std::vector<Coords<D>>&, Region_filter<D>&);
DEWALL_FOR_EACH_DIMENSION(DEWALL_INSTANTIATE_CGAL_ENGINE)

}  // namespace dewall::detail
