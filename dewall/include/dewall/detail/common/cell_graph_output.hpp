// The triangulation with its adjacency, as the project's incremental engine
// holds it (detail/incremental/incremental_delaunay.hpp), handed to a receiver that builds
// another data structure from it by index: the CGAL builders
// (dewall/cgal/detail/graph_assembly.hpp) fill CGAL's cells and neighbours in
// one pass over the engine's records, with no facet to match. Knows no
// geometry and no CGAL.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>

#include "dewall/detail/common/index.hpp"

namespace dewall::detail {

/// One cell slot of the incremental engine: the D + 1 vertex ids of its cell
/// (positively oriented; an infinite cell holds Cell_graph<D>::infinite_vertex
/// and is oriented as if that vertex were a point beyond its hull facet; a
/// free slot's first vertex is Cell_graph<D>::free_slot) and, per vertex i,
/// the neighbour across the facet opposite it, packed as
/// `slot << facet_bits | index of that facet in the neighbour`. Side by side,
/// so that the cell the engine's search reads is the one its star writes in
/// the same cache line; in 2D the search's mark fills the padding.
struct No_cell_mark {};
template <int D>
struct alignas(D <= 3 ? 32 : 8) Cell_record {
  std::array<Index, D + 1> v;
  std::array<std::uint32_t, D + 1> n;
  [[no_unique_address]] std::conditional_t<D == 2, std::uint8_t, No_cell_mark> mark;
};

/// The meaning of a Cell_record's fields.
template <int D>
struct Cell_graph {
  /// The vertex id of the infinite vertex.
  static constexpr Index infinite_vertex = std::numeric_limits<Index>::max();
  /// A free slot's first vertex.
  static constexpr Index free_slot = infinite_vertex - 1;
  /// Bits of a neighbour reference that hold the facet index.
  static constexpr int facet_bits = std::bit_width(static_cast<unsigned>(D));
  static constexpr std::uint32_t facet_mask = (1u << facet_bits) - 1;
  static std::size_t neighbor_slot(std::uint32_t reference) { return reference >> facet_bits; }
  static int neighbor_facet(std::uint32_t reference) { return static_cast<int>(reference & facet_mask); }
};

/// A receiver of the engine's triangulation with its adjacency (a
/// Simplex_output offers one through cell_graph()). The engine calls, in
/// this order and from one thread: vertices() once, begin_cells() once,
/// then cells() for consecutive blocks of slots from slot 0 to the last.
/// A block's records are released by the engine after cells() returns, so
/// the receiver's structure grows as the engine's shrinks.
template <int D>
class Cell_graph_output {
 public:
  /// The finite vertices: vertex v (the id cells use) is the caller's point
  /// input_ids[v]; duplicates were dropped (each point's first occurrence).
  virtual void vertices(std::span<const Index> input_ids) = 0;
  /// `slots` slots follow, `finite_cells` of them holding finite cells.
  virtual void begin_cells(std::size_t slots, std::size_t finite_cells) = 0;
  /// Slots first … first + block.size() − 1.
  virtual void cells(std::size_t first, std::span<const Cell_record<D>> block) = 0;

 protected:
  ~Cell_graph_output() = default;
};

}  // namespace dewall::detail
