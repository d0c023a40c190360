// `dewall triangulate --engine cgal`: CGAL's own Delaunay triangulation (its
// incremental insertion with Epick / Epick_d), written like DeWall's. It is
// there to compare with: fuzz/differential runs it beside DeWall and Qhull, and
// a user can time or check either engine on the same file with the same tool.
// This is the only CLI file that includes CGAL (its headers compile slowly).
#include <chrono>
#include <span>

#include "cli.hpp"
#include "dewall/cgal/cgal_delaunay.hpp"
#include "dewall/detail/input.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"

namespace dewall::cli {
namespace {

template <int D>
Run triangulate_table_with_cgal(const io::Point_table& table) {
  using K = kernel::Filtered_kernel_d<D>;
  const auto points = kernel_points<D>(table);
  // The same checks and messages as DeWall's (NaN/inf, too few distinct
  // points, not spanning E^D): CGAL would build a lower-dimensional
  // triangulation, or misbehave on NaN, instead of saying so.
  const std::vector<std::size_t> distinct = dewall::detail::distinct_points<K>(K{}, points);
  std::vector<std::array<double, D>> coords(distinct.size());
  for (std::size_t i = 0; i < distinct.size(); ++i) coords[i] = points[distinct[i]].x;
  dewall::detail::require_full_dimension<D>(std::span<const std::array<double, D>>(coords));

  Run run;
  run.simplices.vertices_per_simplex = D + 1;
  const auto start = std::chrono::steady_clock::now();
  const auto simplices = cgal::cgal_delaunay<D>(points);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto orientation = K{}.orientation_d_object();
  for (auto s : simplices) {
    // Positively oriented, as DeWall writes them (TetGen .ele expects it).
    std::array<const kernel::Point_d<D>*, D + 1> p;
    for (int i = 0; i <= D; ++i) p[static_cast<std::size_t>(i)] = &points[s[static_cast<std::size_t>(i)]];
    if (orientation(p) == kernel::NEGATIVE) std::swap(s[0], s[1]);
    run.simplices.indices.insert(run.simplices.indices.end(), s.begin(), s.end());
  }
  run.stats.input_points = points.size();
  run.stats.distinct_points = distinct.size();
  run.stats.simplices = simplices.size();
  return run;
}

}  // namespace

Run triangulate_any_with_cgal(const io::Point_table& table) {
  return with_dimension(table.dimension, [&](auto d) { return triangulate_table_with_cgal<d()>(table); });
}

}  // namespace dewall::cli
