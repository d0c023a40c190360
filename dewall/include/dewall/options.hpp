// Options of dewall::triangulate.
#pragma once

#include <cstddef>

namespace dewall {

struct Options {
  /// Grid cells per point (the paper uses about one).
  double cells_per_point = 1.0;
  /// Recursion levels whose two halves run as parallel tasks (TBB): up to
  /// 2^parallel_depth tasks. 0 runs serially. The output is the same either way.
  int parallel_depth = 6;
};

/// Counters for the paper's Table 1, filled by triangulate.
struct Statistics {
  std::size_t input_points = 0;
  std::size_t distinct_points = 0;
  std::size_t simplices = 0;
  std::size_t first_wall_simplices = 0;
  std::size_t recursion_depth = 0;
  std::size_t simplex_searches = 0;
  std::size_t cells_visited = 0;       // by all searches
  std::size_t candidates_tested = 0;   // points examined by all searches
  std::size_t grid_cells = 0;
  std::size_t max_points_in_cell = 0;
  double mean_cells_per_simplex() const { return simplices ? double(cells_visited) / double(simplices) : 0.0; }
};

}  // namespace dewall
