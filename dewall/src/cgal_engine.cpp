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

#include <optional>
#include <utility>

#include "dewall/detail/input.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags

namespace dewall::detail {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Simplices per Simplex_output::put.
constexpr std::size_t block_size = 8192;

/// CGAL's triangulation of the points `ids` (point(i) gives the coordinates of
/// point i), `expect(count)` told the number of finite cells once built, then
/// each finite cell handed to `emit(vertices, neighbors)`: vertices
/// are ids; with `With_neighbors`, neighbors[i] numbers the cell across the
/// face opposite vertex i in emission order (-1: infinite), else it is left
/// unset (a whole triangulation needs no adjacency, and numbering the cells
/// first is a pass over all of them). Cells come in CGAL's order.
/// False when the points do not span E^D. \pre the ids' points are distinct.
template <int D, bool With_neighbors, class Point_of, class Expect, class Emit>
bool cgal_cells(std::span<const Index> ids, Point_of&& point, Expect&& expect, Emit&& emit) {
  // `info` is the per-cell number CGAL stores for us (-1 for infinite cells).
  auto list = [&](auto& dt, auto begin, auto end, auto&& info, auto&& vertex_id) {
    std::array<Index, D + 1> vertices;
    std::array<std::int32_t, D + 1> neighbors;
    if constexpr (With_neighbors) {
      std::int32_t k = 0;
      for (auto c = begin; c != end; ++c) info(c) = dt.is_infinite(c) ? -1 : k++;
    }
    for (auto c = begin; c != end; ++c) {
      if (dt.is_infinite(c)) continue;
      for (int i = 0; i <= D; ++i) {
        vertices[static_cast<std::size_t>(i)] = vertex_id(c->vertex(i));
        if constexpr (With_neighbors) neighbors[static_cast<std::size_t>(i)] = info(c->neighbor(i));
      }
      emit(vertices, neighbors);
    }
  };
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
    expect(dt.number_of_faces());
    list(dt, dt.all_faces_begin(), dt.all_faces_end(), [](auto c) -> std::int32_t& { return c->info(); },
         [](auto v) { return v->info(); });
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
    expect(dt.number_of_finite_cells());
    list(dt, dt.all_cells_begin(), dt.all_cells_end(), [](auto c) -> std::int32_t& { return c->info(); },
         [](auto v) { return v->info(); });
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
    expect(dt.number_of_finite_full_cells());
    list(dt, dt.full_cells_begin(), dt.full_cells_end(), [](auto c) -> std::int32_t& { return c->data(); },
         [](auto v) { return v->data(); });
  }
  return true;
}

}  // namespace

template <int D>
Statistics triangulate_with_cgal(std::span<const kernel::Point_d<D>> points, Simplex_output<D>& output,
                                 const std::vector<std::size_t>* given_distinct) {
  using K = kernel::Filtered_kernel_d<D>;
  const kernel::Fp_environment_guard guard;  // CGAL's filters assume the default environment too
  const std::vector<std::size_t> distinct = given_distinct ? *given_distinct : distinct_points<K>(K{}, points);
  {
    std::vector<std::array<double, D>> coords(distinct.size());
    for (std::size_t i = 0; i < distinct.size(); ++i) coords[i] = points[distinct[i]].x;
    require_full_dimension<D>(std::span<const std::array<double, D>>(coords));
  }

  const std::vector<Index> ids(distinct.begin(), distinct.end());
  // Positively oriented, as DeWall writes them (TetGen .ele expects it).
  // CGAL's 2D faces and 3D cells are (its validity invariant); its dD cells
  // share one orientation, tested on the first. The engine tests check every
  // simplex. (Testing each cell cost 3 % of the run at 10^6 points.)
  std::optional<bool> flip;
  if constexpr (D <= 3) flip = false;
  std::vector<Built_simplex<D>> block;
  block.reserve(block_size);
  std::size_t count = 0;
  cgal_cells<D, false>(ids, [&](Index i) -> const std::array<double, D>& { return points[i].x; },
                       [&](std::size_t cells) { output.expect(cells); },
                       [&](Simplex<D> s, const auto&) {
                         if (!flip) {
                           std::array<const kernel::Point_d<D>*, D + 1> p;
                           for (int i = 0; i <= D; ++i) p[static_cast<std::size_t>(i)] = &points[s[static_cast<std::size_t>(i)]];
                           flip = K{}.orientation_d_object()(p) == kernel::NEGATIVE;
                         }
                         if (*flip) std::swap(s[0], s[1]);
                         block.push_back({s, 0});
                         if (block.size() == block_size) {
                           output.put(block);
                           count += block.size();
                           block.clear();
                         }
                       });
  output.put(block);
  count += block.size();
  Statistics st;
  st.input_points = points.size();
  st.distinct_points = distinct.size();
  st.simplices = count;
  st.engine = Engine::cgal;
  return st;
}

template <int D>
bool cgal_region_cells(std::span<const Index> region, const std::vector<Coords<D>>& coords,
                       std::vector<Region_cell<D>>& cells) {
  const kernel::Fp_environment_guard guard;
  cells.clear();
  const bool spans = cgal_cells<D, true>(region, [&](Index i) -> const Coords<D>& { return coords[i]; },
                                         [&](std::size_t count) { cells.reserve(count); },
                                         [&](const Simplex<D>& v, const std::array<std::int32_t, D + 1>& nb) {
                                           cells.push_back({v, nb});
                                         });
  if (!spans) cells.clear();
  if constexpr (D > 3) {
    // CGAL's dD cells all have one orientation, not necessarily positive.
    if (spans && !cells.empty()) {
      using K = kernel::Filtered_kernel_d<D>;
      std::array<kernel::Point_d<D>, D + 1> p;
      std::array<const kernel::Point_d<D>*, D + 1> refs;
      for (int i = 0; i <= D; ++i) {
        p[static_cast<std::size_t>(i)].x = coords[cells[0].vertices[static_cast<std::size_t>(i)]];
        refs[static_cast<std::size_t>(i)] = &p[static_cast<std::size_t>(i)];
      }
      if (K{}.orientation_d_object()(refs) == kernel::NEGATIVE)
        for (Region_cell<D>& c : cells) {
          std::swap(c.vertices[0], c.vertices[1]);
          std::swap(c.neighbor[0], c.neighbor[1]);
        }
    }
  }
  return spans;
}

#define DEWALL_INSTANTIATE_CGAL_ENGINE(D)                                                                      \
  template Statistics triangulate_with_cgal<D>(std::span<const kernel::Point_d<D>>, Simplex_output<D>&,         \
                                               const std::vector<std::size_t>*);                                \
  template bool cgal_region_cells<D>(std::span<const Index>, const std::vector<Coords<D>>&,                   \
                                     std::vector<Region_cell<D>>&);
DEWALL_INSTANTIATE_CGAL_ENGINE(2)
DEWALL_INSTANTIATE_CGAL_ENGINE(3)
DEWALL_INSTANTIATE_CGAL_ENGINE(4)
DEWALL_INSTANTIATE_CGAL_ENGINE(5)
DEWALL_INSTANTIATE_CGAL_ENGINE(6)

}  // namespace dewall::detail
