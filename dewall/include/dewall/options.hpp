// Options of dewall::triangulate.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace dewall {

/// Which construction builds the triangulation. Each gives the same simplices
/// (the Delaunay triangulation under CGAL's symbolic perturbation); only the
/// time and the statistics differ.
enum class Engine {
  /// DeWall, handing over to the incremental construction when its searches
  /// prove the input is one no gift-wrapping search is fast on (points on or
  /// near one sphere, thin surfaces): see Options::handover_candidates_per_search.
  automatic,
  /// DeWall only.
  dewall,
  /// CGAL's incremental construction only (Delaunay_triangulation_2/_3, the dD
  /// Delaunay_triangulation), compiled into the library.
  cgal,
};

/// "automatic", "dewall" or "cgal".
constexpr const char* engine_name(Engine e) {
  return e == Engine::automatic ? "automatic" : e == Engine::dewall ? "dewall" : "cgal";
}

/// The engine a user names: "auto", "dewall" or "cgal" (the CLI's --engine and
/// the Python bindings' engine=), or nothing for any other name.
constexpr std::optional<Engine> parse_engine(std::string_view name) {
  if (name == "auto") return Engine::automatic;
  if (name == "dewall") return Engine::dewall;
  if (name == "cgal") return Engine::cgal;
  return std::nullopt;
}

struct Options {
  /// Points per leaf of the search structure (a kd-tree; the paper's uniform
  /// grid has about one per cell). Only the speed depends on it.
  std::size_t points_per_leaf = 8;
  /// Recursion levels whose two halves run as parallel tasks (TBB): up to
  /// 2^parallel_depth tasks. 0 runs serially. The output is the same either way.
  int parallel_depth = 6;
  /// The construction. Engines other than DeWall need the project's kernel
  /// (Filtered_kernel_d); with another kernel, automatic means DeWall.
  Engine engine = Engine::automatic;
  /// Engine::automatic hands over to the incremental construction once the
  /// searches of DeWall's walls have examined more than this many candidate
  /// points per search on average (counted from the first, with an allowance of
  /// 64 searches' worth but at most n candidates, so that a few costly
  /// searches near the hull do not decide). A search must look at every point
  /// near the sphere it proves empty. With the kd-tree search the running
  /// average never exceeds 16 on 10^6 uniform 3D points, 25–55 on grids,
  /// clusters and coplanar layers, 26 / 51 / 97 on uniform points in 4D / 5D /
  /// 6D; it is 350–580 on noisy sphere and torus shells (where DeWall is 8–9×
  /// slower than CGAL) and thousands on one sphere or a torus tube.
  /// Measured rule, not a guess about the input's name: see docs/engines.md.
  double handover_candidates_per_search = 150;
};

/// Counters for the paper's Table 1, filled by triangulate.
struct Statistics {
  std::size_t input_points = 0;
  std::size_t distinct_points = 0;
  std::size_t simplices = 0;
  std::size_t first_wall_simplices = 0;
  std::size_t recursion_depth = 0;
  std::size_t simplex_searches = 0;
  std::size_t nodes_visited = 0;       // kd-tree nodes, by all searches
  std::size_t candidates_tested = 0;   // points examined by all searches
  std::size_t tree_leaves = 0;
  Engine engine = Engine::dewall;            // the construction that built the output
  std::size_t searches_before_handover = 0;  // automatic: DeWall's searches before handing over
  double mean_nodes_per_simplex() const { return simplices ? double(nodes_visited) / double(simplices) : 0.0; }
};

}  // namespace dewall
