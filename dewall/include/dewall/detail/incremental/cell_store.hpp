// The incremental engine's cell store (CGAL's triangulation data structure,
// Geogram's and hxt's flat cell arrays): per slot, a cell's D + 1 vertex ids
// and D + 1 packed neighbour references (cell << facet_bits | the facet's
// index in that neighbour), side by side; the search marks; slot allocation
// without initialising; giving pages back; the topological checks.
// Topology only: no predicate here (the engine checks orientations).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#if __has_include(<sys/mman.h>) && __has_include(<unistd.h>)
#include <sys/mman.h>
#include <unistd.h>
#define DEWALL_CAN_RELEASE_PAGES 1
#endif

#include "dewall/detail/common/assert.hpp"
#include "dewall/detail/common/cell_graph_output.hpp"
#include "dewall/detail/common/index.hpp"

namespace dewall::detail {

template <int D>
class Cell_store {
 public:
  using Cell = std::array<Index, D + 1>;
  /// A cell slot (cell_graph_output.hpp): its vertices and its neighbour
  /// references side by side; in 2D, its mark.
  using Record = Cell_record<D>;
  /// The vertex id of the infinite vertex.
  static constexpr Index infinite = Cell_graph<D>::infinite_vertex;
  /// A free slot's first vertex.
  static constexpr Index free_slot = Cell_graph<D>::free_slot;
  /// Bits of a neighbour reference that hold the facet index.
  static constexpr int facet_bits = Cell_graph<D>::facet_bits;
  static constexpr std::uint32_t facet_mask = (1u << facet_bits) - 1;
  /// The largest reference stays below the ridge table's two sentinels
  /// (none = 2^32 − 1, taken = 2^32 − 2).
  static constexpr std::size_t max_slots = ((std::size_t{1} << 32) - 2) >> facet_bits;
  /// In 2D a cell's search mark lives in its record: the 24-byte record is
  /// padded to 32 (none straddles two cache lines) and the mark fits, so the
  /// search reads one line per neighbour instead of two; in 3D the 32-byte
  /// record is full (docs/engines.md).
  static constexpr bool marks_in_cells = D == 2;
  static_assert(std::is_same_v<decltype(Record::v), Cell>);
  static_assert(std::is_same_v<decltype(Record::mark), std::uint8_t> == marks_in_cells);

  /// The reference to the facet opposite vertex i of cell c.
  static std::uint32_t reference(std::size_t c, int i) {
    return static_cast<std::uint32_t>(c) << facet_bits | static_cast<std::uint32_t>(i);
  }

  /// Cell slots, free ones included: cells are 0 … slots() − 1.
  std::size_t slots() const { return cells_.size(); }
  std::size_t capacity() const { return cells_.capacity(); }
  bool is_free(std::size_t c) const { return cells_[c].v[0] == free_slot; }
  bool is_infinite(std::size_t c) const { return infinite_position(c) <= D; }
  /// Whether slot c holds a finite cell (!is_free(c) && !is_infinite(c)),
  /// without a branch: the hand-over asks it of every slot, and on a circle
  /// every other slot holds an infinite cell (no pattern to predict).
  bool holds_finite_cell(std::size_t c) const {
    const Cell& v = cells_[c].v;
    bool finite = v[0] != free_slot;
    for (int i = 0; i <= D; ++i) finite &= v[i] != infinite;
    return finite;
  }
  /// The position of the infinite vertex in cell c, or D + 1 when it is finite.
  int infinite_position(std::size_t c) const {
    for (int i = 0; i <= D; ++i)
      if (cells_[c].v[i] == infinite) return i;
    return D + 1;
  }
  /// The position of vertex v in cell c (which holds it).
  int position(std::size_t c, Index v) const {
    for (int i = 0; i <= D; ++i)
      if (cells_[c].v[i] == v) return i;
    DEWALL_ASSERT(false);
    return -1;
  }
  const Cell& cell(std::size_t c) const { return cells_[c].v; }
  Index vertex(std::size_t c, int i) const { return cells_[c].v[i]; }
  /// The cell across the facet opposite vertex i of c.
  std::size_t neighbor(std::size_t c, int i) const { return cells_[c].n[i] >> facet_bits; }
  /// The records of slots first … last − 1 (cell_graph_output.hpp says what they hold).
  std::span<const Cell_record<D>> records(std::size_t first, std::size_t last) const {
    return {cells_.data() + first, last - first};
  }

  /// Slot c's record, to write (the engine's).
  Record& operator[](std::size_t c) { return cells_[c]; }
  const Record& operator[](std::size_t c) const { return cells_[c]; }
  /// Cell c's search mark (the cavity search's in / out, else 0).
  std::uint8_t& mark(std::size_t c) {
    if constexpr (marks_in_cells) return cells_[c].mark;
    else return mark_[c];
  }
  /// Where mark(c) lives, for a prefetch (above 2D; in 2D it is in the record).
  const std::uint8_t* mark_address(std::size_t c) const { return &mark_[c]; }

  /// Room for `cells` slots, so that the arrays grow without copying up to
  /// that many: a copy writes fresh pages the kernel must clear first, and
  /// holds the old and the new array at once. Pages are touched only when
  /// cells use them.
  void reserve(std::size_t cells) {
    cells_.reserve(std::min(cells, max_slots));
    if constexpr (!marks_in_cells) mark_.reserve(std::min(cells, max_slots));
  }
  /// One slot, the first cell's, and nothing else.
  void assign_first(const Cell& first) {
    cells_.assign(1, Record{first, {}, {}});
    if constexpr (!marks_in_cells) mark_.assign(1, 0);
  }
  /// A new slot at the end holding `record`, marked 0 (the first simplex's neighbours).
  std::size_t push(const Record& record) {
    cells_.push_back(record);
    if constexpr (!marks_in_cells) mark_.push_back(0);
    return cells_.size() - 1;
  }
  /// A new slot at the end, uninitialised but for its mark (0 above 2D: in
  /// 2D the record, mark included, is written by the caller).
  /// \throws std::length_error beyond max_slots.
  std::size_t allocate() {
    const std::size_t s = cells_.size();
    if (s >= max_slots)
      throw std::length_error("dewall: the incremental engine's 32-bit cell references hold at most " +
                              std::to_string(max_slots) + " cells");
    cells_.emplace_back();
    if constexpr (!marks_in_cells) mark_.push_back(0);
    return s;
  }
  /// Grows (new slots uninitialised, marks 0) or cuts the slots to `count`.
  void resize(std::size_t count) {
    cells_.resize(count);
    if constexpr (!marks_in_cells) mark_.resize(count, 0);
  }
  /// Slot s holds no cell any more (its whole record written: the hand-over
  /// reads a free slot's record).
  void clear_slot(std::size_t s) { cells_[s].v.fill(free_slot); }

  /// The marks go (finish_for_reading: nothing is searched any more).
  void release_marks() { std::vector<std::uint8_t>().swap(mark_); }
  /// Slots first … last − 1 are not read again: the whole pages within them
  /// go back to the system (madvise MADV_DONTNEED), so the output, growing
  /// as the cells are read, does not add to their peak. A page shared with
  /// slots outside the range stays. Nothing below 8 MB of cells: a later
  /// construction of the process would fault the pages in again. Without
  /// <sys/mman.h>, nothing.
  void release_slots(std::size_t first, std::size_t last) {
#ifdef DEWALL_CAN_RELEASE_PAGES
    if (cells_.size() * sizeof(Record) < (std::size_t{8} << 20)) return;
    static const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
    const auto base = reinterpret_cast<std::uintptr_t>(cells_.data());
    const std::uintptr_t begin = (base + first * sizeof(Record) + page - 1) / page * page;
    const std::uintptr_t end = (base + std::min(last, cells_.size()) * sizeof(Record)) / page * page;
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_DONTNEED);
#else
    (void)first, (void)last;
#endif
  }

  /// The topology's checks: neighbours are other cells, mutual (each refers
  /// back to the facet that refers to it) and share exactly the D vertices
  /// of that facet.
  bool links_are_valid() const {
    for (std::size_t c = 0; c < slots(); ++c) {
      if (is_free(c)) continue;
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = cells_[c].n[i];
        const std::size_t n = ref >> facet_bits;
        const int j = static_cast<int>(ref & facet_mask);
        if (n >= slots() || n == c || is_free(n) || cells_[n].n[j] != reference(c, i)) return false;
        const auto holds = [](const Cell& cell, Index x) { return std::find(cell.begin(), cell.end(), x) != cell.end(); };
        for (int k = 0; k <= D; ++k)
          if (k != i && !holds(cells_[n].v, cells_[c].v[k])) return false;
        if (holds(cells_[c].v, cells_[n].v[j])) return false;
      }
    }
    return true;
  }

 private:
  /// Allocates without initialising: a new slot is written whole before it
  /// is read, so growing the array does not clear it first (zoned insertion
  /// grows it by the zones' ranges at once, whose pages are then first
  /// touched by the zone's thread).
  template <class T>
  struct Uninitialised_allocator : std::allocator<T> {
    template <class U>
    struct rebind {
      using other = Uninitialised_allocator<U>;
    };
    Uninitialised_allocator() = default;
    template <class U>
    Uninitialised_allocator(const Uninitialised_allocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept {
      ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
  };
  std::vector<Record, Uninitialised_allocator<Record>> cells_;  // by slot
  std::vector<std::uint8_t> mark_;  // by slot (empty when marks_in_cells)
};

}  // namespace dewall::detail
