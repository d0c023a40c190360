// detail::triangulate_incremental and incremental_region_cells for D = 2 … 6
// (incremental_engine.hpp).
#include "incremental_engine.hpp"

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

#include "dewall/detail/incremental/incremental_delaunay.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/filtered_predicate.hpp"  // refuses to build under unsafe flags
#include "incremental_support.hpp"

namespace dewall::detail {
namespace {

/// Cell c's vertices as the caller's ids.
template <int D>
Simplex<D> input_vertices(const Incremental_delaunay<D>& dt, std::size_t c) {
  Simplex<D> s;
  for (int i = 0; i <= D; ++i) s[static_cast<std::size_t>(i)] = dt.input_index(dt.cell(c)[static_cast<std::size_t>(i)]);
  return s;
}

/// An Incremental_delaunay as the cell graph filter_region walks
/// (incremental_support.hpp); the walk's states in an array of the caller's.
template <int D>
struct Incremental_graph {
  using Cell = std::uint32_t;
  const Incremental_delaunay<D>& dt;
  std::vector<std::int32_t>& states;

  template <class F>
  void for_each_cell(F&& f) const {
    for (std::size_t c = 0; c < dt.slots(); ++c)
      if (!dt.is_free(c)) f(static_cast<Cell>(c));
  }
  std::size_t finite_cells() const { return dt.finite_cells(); }
  bool is_infinite(Cell c) const { return dt.is_infinite(c); }
  Cell neighbor(Cell c, int i) const { return static_cast<Cell>(dt.neighbor(c, i)); }
  bool vertex_is_infinite(Cell c, int i) const {
    return dt.cell(c)[static_cast<std::size_t>(i)] == Incremental_delaunay<D>::infinite;
  }
  std::int32_t& state(Cell c) { return states[c]; }
  Simplex<D> vertices(Cell c) const { return input_vertices(dt, c); }
};

/// Passes the finite cells to `output` in slot order (the same for any number
/// of threads) and returns their number. Blocks of slots are converted to the
/// caller's ids in parallel (each cell's reads are cache misses), the pages
/// wholly inside each block released by the task that converted it (a page
/// shared with the next block stays until the object goes), and passed on in
/// order by one thread at a time: at 10^6 points the serial loop it replaces
/// took 0.09 s of a two-thread run's 1.23 s. Released in the serial stage,
/// the pages cost 0.02 s of that stage's 0.07 s: the tool's hand-over on two
/// threads, 0.079–0.092 → 0.061–0.067 s (one thread 0.12–0.13 s either way).
/// What stays serial is the output's own copy, 0.05 s (mostly the first
/// touches of its fresh pages).
template <int D>
std::size_t hand_over_cells(Incremental_delaunay<D>& dt, Simplex_output<D>& output) {
  // 1 MB of 3D cells a block. A block's buffer is reused `in_flight` blocks
  // later: with that many tokens and the last stage in order, block k has
  // been passed on before block k + in_flight is converted.
  constexpr std::size_t slots_per_block = std::size_t{1} << 15;
  constexpr std::size_t in_flight = 4;
  const std::size_t slots = dt.slots(), blocks = (slots + slots_per_block - 1) / slots_per_block;
  const auto end_of = [&](std::size_t block) { return std::min(slots, (block + 1) * slots_per_block); };
  // Each buffer is a block long (allocated when first used, not cleared);
  // the first filled[k] of buffer k hold its block's finite cells.
  std::array<std::unique_ptr<Built_simplex<D>[]>, in_flight> buffers;
  std::array<std::size_t, in_flight> filled{};
  std::size_t next = 0, count = 0;
  const auto take_block = [&](tbb::flow_control& control) -> std::size_t {
    if (next == blocks) control.stop();
    return next == blocks ? 0 : next++;
  };
  const auto convert = [&](std::size_t block) {
    auto& cells = buffers[block % in_flight];
    if (!cells) cells = std::make_unique_for_overwrite<Built_simplex<D>[]>(std::min(slots, slots_per_block));
    // Without a branch on whether a slot holds a finite cell: every slot's
    // cell is written at the next place, which only a finite one takes (on a
    // circle every other slot holds an infinite cell, and the branch was
    // mispredicted: 10^5 points, the conversion 1.7 ms of 42.7). A free or
    // infinite slot reads the caller's id of vertex 0 instead of its own
    // (every slot's vertices are written: a freed cell's are its old ones, a
    // zone's unused slot's are free_slot).
    std::size_t k = 0;
    for (std::size_t c = block * slots_per_block; c < end_of(block); ++c) {
      const auto& v = dt.cell(c);
      const bool finite = dt.holds_finite_cell(c);
      const Index finite_mask = Index{0} - static_cast<Index>(finite);  // all ones when finite (GCC branched on a ?:)
      Built_simplex<D>& s = cells[k];
      for (int i = 0; i <= D; ++i)
        s.vertices[static_cast<std::size_t>(i)] = dt.input_index(v[static_cast<std::size_t>(i)] & finite_mask);
      s.wall_level = 0;
      k += finite;
    }
    filled[block % in_flight] = k;
    dt.release_slots(block * slots_per_block, end_of(block));
    return block;
  };
  const auto pass_on = [&](std::size_t block) {
    const std::span<const Built_simplex<D>> cells(buffers[block % in_flight].get(), filled[block % in_flight]);
    // Isolated: an output running TBB work of its own takes no conversion meanwhile.
    tbb::this_task_arena::isolate([&] { output.put(cells); });
    count += cells.size();
  };
  output.expect(dt.finite_cells());
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_pipeline(in_flight,
                           tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order, take_block) &
                               tbb::make_filter<std::size_t, std::size_t>(tbb::filter_mode::parallel, convert) &
                               tbb::make_filter<std::size_t, void>(tbb::filter_mode::serial_in_order, pass_on));
  });
  return count;
}

/// Gives `graph` the vertices, then the slots in blocks, each block's pages
/// released once it has been read: the receiver's structure grows into them.
/// Returns the number of finite cells.
template <int D>
std::size_t hand_over_graph(Incremental_delaunay<D>& dt, Cell_graph_output<D>& graph) {
  constexpr std::size_t slots_per_block = std::size_t{1} << 15;
  const std::size_t slots = dt.slots(), finite = dt.finite_cells();
  graph.vertices(dt.input_indices());
  graph.begin_cells(slots, finite);
  for (std::size_t first = 0; first < slots; first += slots_per_block) {
    const std::size_t last = std::min(slots, first + slots_per_block);
    graph.cells(first, dt.records(first, last));
    dt.release_slots(first, last);
  }
  return finite;
}

}  // namespace

template <int D>
Statistics triangulate_incremental(std::span<const kernel::Point_d<D>> points, Simplex_output<D>& output,
                                   const Distinct_points* given_distinct) {
  const kernel::Fp_environment_guard guard;
  Incremental_delaunay<D> dt;
  dt.set_progress(output.progress());
  const auto input_no_longer_read = [&] { output.input_no_longer_read(); };
  if (given_distinct) {
    Distinct_points unused;
    const Distinct_points& distinct = checked_distinct_points<D>(points, given_distinct, unused);
    const bool built = dt.build(
        distinct.size(), [&](std::size_t k) -> const std::array<double, D>& { return points[distinct[k]].x; },
        [&](std::size_t k) { return distinct[k]; }, nullptr, input_no_longer_read);
    DEWALL_ASSERT(built);  // the points span E^D: checked above
  } else {
    // The repeats are dropped by the construction's own order (no table of
    // first occurrences: 2D uniform 10^6, 13–26 ms of 450); only an input
    // that fails the checks takes distinct_points, for the error it throws.
    using K = kernel::Filtered_kernel_d<D>;
    require_finite_points<K>(K{}, points);
    if (!dt.build_dropping_repeats(
            points.size(), [&](std::size_t k) -> const std::array<double, D>& { return points[k].x; },
            [](std::size_t k) { return k; }, input_no_longer_read)) {
      Distinct_points distinct;
      checked_distinct_points<D>(points, nullptr, distinct);  // throws: too few distinct points, or flat
      throw std::logic_error("triangulate_incremental: the construction failed on points that span E^D");
    }
  }
  // The output's peak: what the construction no longer needs goes first (the
  // engine keeps the caller's ids), and the cells' pages as they are read, so
  // that the output list grows into them (collecting 10^6 points with the
  // tool: its peak 448 → 312 MB, then the end of the build).
  const std::size_t distinct_count = dt.vertices();  // finish_for_reading frees the points
  dt.finish_for_reading();
  Cell_graph_output<D>* graph = output.cell_graph();
  const std::size_t simplices = graph ? hand_over_graph(dt, *graph) : hand_over_cells(dt, output);
  return incremental_statistics(Engine::incremental, points.size(), distinct_count, simplices);
}

template <int D>
bool incremental_region_cells(std::span<const Index> region, const std::vector<Coords<D>>& coords,
                              Region_filter<D>& filter) {
  const kernel::Fp_environment_guard guard;
  Incremental_delaunay<D> dt;
  if (!dt.build(
          region.size(), [&](std::size_t k) -> const Coords<D>& { return coords[region[k]]; },
          [&](std::size_t k) { return region[k]; }))
    return false;
  std::vector<std::int32_t> states(dt.slots());
  Incremental_graph<D> graph{dt, states};
  filter_region<D>(graph, false, filter);  // its cells are positively oriented
  return true;
}

#define DEWALL_INSTANTIATE_INCREMENTAL_ENGINE(D)                                                            \
  template Statistics triangulate_incremental<D>(std::span<const kernel::Point_d<D>>, Simplex_output<D>&,    \
                                                 const Distinct_points*);                                    \
  template bool incremental_region_cells<D>(std::span<const Index>, const std::vector<Coords<D>>&,           \
                                            Region_filter<D>&);
DEWALL_FOR_EACH_DIMENSION(DEWALL_INSTANTIATE_INCREMENTAL_ENGINE)

}  // namespace dewall::detail
