// dewall: Delaunay triangulation in E^D (D = 2 … 6) by the DeWall algorithm,
// P. Cignoni, C. Montani, R. Scopigno, "DeWall: A fast divide and conquer
// Delaunay triangulation algorithm in E^d", Computer-Aided Design 30(5), 1998.
//
// The output is the Delaunay triangulation under CGAL's symbolic perturbation:
// the same simplices as CGAL's Delaunay_triangulation_2/_3 and dD
// Delaunay_triangulation, on every input, degenerate ones included.
//
// Where each step of the paper lives:
//   splitting plane α ............ detail/split.hpp
//   DeWall recursion and wall .... detail/wall.hpp
//   MakeFirstSimplex ............. detail/first_simplex.hpp
//   active face lists, Update .... detail/active_face_list.hpp, detail/face.hpp
//   MakeSimplex (dd-nearest) ..... detail/make_simplex.hpp, detail/simplex_sphere.hpp,
//                                  detail/face_side_filter.hpp, detail/pencil_rank.hpp
//   uniform grid ................. detail/uniform_grid.hpp
//   input checks, duplicates ..... detail/input.hpp
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "dewall/detail/input.hpp"
#include "dewall/detail/point_set.hpp"
#include "dewall/detail/wall.hpp"
#include "dewall/error.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/options.hpp"

namespace dewall {

/// A simplex as D + 1 indices into the input, positively oriented.
template <int D>
using Simplex = std::array<std::uint32_t, D + 1>;

/// The Delaunay triangulation of `points`, handed to `sink(simplex)` once for
/// each simplex (a dewall::Simplex<D> of input indices, positively oriented), in
/// DeWall's depth-first order (the same for any number of threads). The
/// simplices are handed over once the triangulation is complete; true streaming
/// (memory near the size of the walls) is future work. A sink callable as
/// sink(simplex, level) also receives the recursion level of the wall that
/// built the simplex (0: the first wall; the paper's Figures 2, 4, 5).
/// \throws Invalid_input for non-finite coordinates, fewer than D + 1 distinct
/// points, or points that do not span E^D.
/// Complexity: expected O(n log n) on uniformly distributed points.
template <kernel::DelaunayKernel K, class Sink>
Statistics triangulate_to(std::span<const typename K::Point_d> points, Sink&& sink, const Options& options = {},
                          const K& k = {}) {
  constexpr int D = K::dimension;
  const std::vector<std::size_t> input = detail::distinct_points<K>(k, points);
  std::vector<const typename K::Point_d*> refs(input.size());
  for (std::size_t i = 0; i < input.size(); ++i) refs[i] = &points[input[i]];
  const detail::Point_set<K> ps(k, std::move(refs), input, options.cells_per_point);
  detail::require_full_dimension<D>(ps.coords_for_checks());

  detail::Wall_builder<K> builder(ps, options.parallel_depth);
  std::vector<detail::Index> all(ps.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<detail::Index>(i);
  std::vector<detail::Built_simplex<D>> local;
  builder.run(all, local);
  for (const auto& s : local) {
    Simplex<D> out;
    for (int i = 0; i <= D; ++i) out[i] = static_cast<std::uint32_t>(ps.input_index[s.vertices[i]]);
    if constexpr (std::is_invocable_v<Sink, const Simplex<D>&, int>) sink(out, static_cast<int>(s.wall_level));
    else sink(out);
  }

  Statistics st;
  st.input_points = points.size();
  st.distinct_points = ps.size();
  st.simplices = builder.stats().simplices;
  st.first_wall_simplices = builder.stats().first_wall_simplices;
  st.recursion_depth = builder.stats().max_depth;
  st.simplex_searches = builder.search_stats().searches;
  st.cells_visited = builder.search_stats().cells_visited;
  st.candidates_tested = builder.search_stats().candidates;
  st.grid_cells = ps.grid.cell_count();
  st.max_points_in_cell = ps.grid.max_points_in_cell();
  return st;
}

/// The triangulation as a list of simplices.
template <int D>
struct Triangulation {
  std::vector<Simplex<D>> simplices;
  Statistics statistics;
};

/// The Delaunay triangulation of `points` with kernel K (default: the project's
/// filtered exact kernel). See triangulate_to.
template <kernel::DelaunayKernel K>
Triangulation<K::dimension> triangulate(std::span<const typename K::Point_d> points, const Options& options = {},
                                        const K& k = {}) {
  Triangulation<K::dimension> t;
  t.statistics = triangulate_to<K>(points, [&](const Simplex<K::dimension>& s) { t.simplices.push_back(s); },
                                   options, k);
  return t;
}

template <int D>
Triangulation<D> triangulate(std::span<const kernel::Point_d<D>> points, const Options& options = {}) {
  return triangulate<kernel::Filtered_kernel_d<D>>(points, options);
}
template <int D>
Triangulation<D> triangulate(const std::vector<kernel::Point_d<D>>& points, const Options& options = {}) {
  return triangulate<D>(std::span<const kernel::Point_d<D>>(points), options);
}

}  // namespace dewall
