// What the two incremental engines of the library share (cgal_engine.cpp:
// CGAL's construction; incremental_engine.cpp: the project's own,
// detail/incremental/incremental_delaunay.hpp): the input checks, the hand-over of the
// finite cells in blocks, and Region_filter's walk over a region's cells.
// Private to dewall/src.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "dewall/detail/common/input.hpp"
#include "dewall/detail/walls/region.hpp"
#include "dewall/detail/common/simplex_output.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "dewall/options.hpp"

namespace dewall::detail {

/// The same input checks as DeWall's (Invalid_input: non-finite coordinates,
/// too few distinct points, points not spanning E^D); the distinct points
/// (first occurrences): `given` when the caller computed them, else found
/// and kept in `own`.
template <int D>
const Distinct_points& checked_distinct_points(std::span<const kernel::Point_d<D>> points,
                                               const Distinct_points* given, Distinct_points& own) {
  using K = kernel::Filtered_kernel_d<D>;
  const Distinct_points& distinct = given ? *given : (own = distinct_points<K>(K{}, points));
  require_full_dimension<D>(distinct.size(),
                            [&](std::size_t i) -> const std::array<double, D>& { return points[distinct[i]].x; });
  return distinct;
}

/// What an incremental engine reports: the points, the simplices and itself
/// (the walls' counters stay zero).
inline Statistics incremental_statistics(Engine engine, std::size_t input_points, std::size_t distinct_points,
                                         std::size_t simplices) {
  Statistics st;
  st.input_points = input_points;
  st.distinct_points = distinct_points;
  st.simplices = simplices;
  st.engine = engine;
  return st;
}

/// Hands simplices to a Simplex_output in blocks (wall level 0: no wall built them).
template <int D>
class Block_writer {
 public:
  explicit Block_writer(Simplex_output<D>& output, std::size_t expected) : output_(output) {
    output_.expect(expected);
    block_.reserve(block_size);
  }
  void put(const Simplex<D>& s) {
    block_.push_back({s, 0});
    if (block_.size() == block_size) flush();
  }
  /// Passes on the last block; the number of simplices put.
  std::size_t finish() {
    flush();
    return count_;
  }

 private:
  static constexpr std::size_t block_size = 8192;
  void flush() {
    output_.put(block_);
    count_ += block_.size();
    block_.clear();
  }
  Simplex_output<D>& output_;
  std::vector<Built_simplex<D>> block_;
  std::size_t count_ = 0;
};

/// Region_filter's walk (region.hpp) over a region's triangulation seen as a
/// cell graph `g`, which provides
///   Cell                               a cell (handle or index),
///   for_each_cell(f)                   every cell, infinite ones included,
///   bool is_infinite(Cell), Cell neighbor(Cell, int i), bool vertex_is_infinite(Cell, int i),
///   Simplex<D> vertices(Cell)          the finite cell's vertex ids,
///   std::int32_t& state(Cell)          room for this walk,
///   std::size_t finite_cells().
/// `flip`: the cells are negatively oriented.
template <int D, class Graph>
void filter_region(Graph& g, bool flip, Region_filter<D>& filter) {
  using Cell = typename Graph::Cell;
  // NEAR_OPEN: a neighbour is infinite or dropped (only such a cell, when
  // kept, reads its neighbours' states: they are scattered in memory).
  enum : std::int32_t { UNTESTED = 0, KEPT = 1, DROPPED = 2, INFINITE = 3, STATE = 3, NEAR_OPEN = 4 };
  auto oriented = [&](Cell c) {
    Simplex<D> s = g.vertices(c);
    if (flip) std::swap(s[0], s[1]);
    return s;
  };
  filter.begin(g.finite_cells());
  std::vector<Cell> infinite, hull, queue;
  g.for_each_cell([&](Cell c) {
    const bool inf = g.is_infinite(c);
    g.state(c) = inf ? INFINITE : UNTESTED;
    if (inf) infinite.push_back(c);
  });
  for (const Cell c : infinite)
    for (int i = 0; i <= D; ++i) {
      g.state(g.neighbor(c, i)) |= NEAR_OPEN;
      if (g.vertex_is_infinite(c, i)) hull.push_back(g.neighbor(c, i));
    }
  const bool walk = !filter.asks_every_cell();
  auto test = [&](Cell c) {
    std::int32_t& state = g.state(c);
    if ((state & STATE) != UNTESTED) return;
    if (filter.empty_of_others(oriented(c))) {
      state |= KEPT;
    } else {
      state |= DROPPED;
      if (walk) queue.push_back(c);
      for (int i = 0; i <= D; ++i) g.state(g.neighbor(c, i)) |= NEAR_OPEN;
    }
  };
  if (!walk) {
    g.for_each_cell(test);  // (infinite cells are not UNTESTED: skipped)
  } else {
    for (const Cell c : hull) test(c);
    while (!queue.empty()) {
      const Cell c = queue.back();
      queue.pop_back();
      for (int i = 0; i <= D; ++i) test(g.neighbor(c, i));
    }
  }
  g.for_each_cell([&](Cell c) {
    const std::int32_t state = g.state(c);
    if ((state & STATE) == INFINITE || (state & STATE) == DROPPED) return;
    unsigned open = 0;
    if (state & NEAR_OPEN)
      for (int i = 0; i <= D; ++i) {
        const std::int32_t across = g.state(g.neighbor(c, i)) & STATE;
        if (across == INFINITE || across == DROPPED) open |= 1u << i;
      }
    if (flip) open = (open & ~3u) | (open >> 1 & 1u) | (open << 1 & 2u);
    filter.keep(oriented(c), open);
  });
}

}  // namespace dewall::detail
