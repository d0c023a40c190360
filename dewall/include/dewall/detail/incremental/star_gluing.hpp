// Gluing the star of one insertion (the incremental engine's step 3c): the
// new cells, one per boundary facet of the cavity, each glued to the outside
// across that facet by the engine, are glued here to each other across their
// facets through the new point. Three ways, the same result: in 2D a scan
// of the fan; in 2D and 3D a table indexed by the facets' directed keys
// (hxt's idea); above 3D, and for very large cavities, a hash table of
// ridges. Topology only: no predicate.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "dewall/detail/common/assert.hpp"
#include "dewall/detail/common/hashing.hpp"
#include "dewall/detail/common/index.hpp"
#include "dewall/detail/incremental/cell_store.hpp"
#include "dewall/detail/incremental/scratch_list.hpp"

namespace dewall::detail {

/// A boundary facet of the cavity: the new cell's vertices (the old cell's,
/// with the one opposite the facet replaced by the new point) and the
/// neighbour reference outside.
template <int D>
struct Boundary_facet {
  std::array<Index, D + 1> vertices;
  int facet;
  std::uint32_t outside;
};

/// The gluing's scratch, one per thread of insertions (reused from one
/// insertion to the next: nothing is cleared between them).
template <int D>
class Star_gluing {
 public:
  /// Glues new cell b (slot new_cells[b], made from boundary[b]) to the other
  /// new cells across its facets through the new point. Returns whether the
  /// ridge table did it (always when ridge_table_only).
  bool glue(Cell_store<D>& cells, const std::vector<Boundary_facet<D>>& boundary, const Scratch_list<Index>& new_cells,
            bool ridge_table_only, bool colliding_keys) {
    if (!ridge_table_only && glue_directed(cells, boundary, new_cells)) return false;
    glue_by_ridges(cells, boundary, new_cells, colliding_keys);
    return true;
  }

 private:
  using Cell = typename Cell_store<D>::Cell;
  static constexpr int facet_bits = Cell_store<D>::facet_bits;
  static constexpr std::uint32_t facet_mask = Cell_store<D>::facet_mask;
  static constexpr Index infinite = Cell_store<D>::infinite;
  static std::uint32_t reference(std::size_t c, int i) { return Cell_store<D>::reference(c, i); }

  /// Step 3c's gluing: each new cell's facets through the new point matched
  /// with the other new cell on them, by their other D − 1 vertices (the
  /// ridge). A ridge's key is the sum of its vertices' hashes, so a cell's D
  /// keys cost D hashes and a subtraction each; a key is no proof, so a match
  /// is checked on the candidate's vertices (same_ridge); cheaper than sorting
  /// each ridge's vertices.
  void glue_by_ridges(Cell_store<D>& cells, const std::vector<Boundary_facet<D>>& boundary,
                       const Scratch_list<Index>& new_cells, bool colliding_keys) {
    ridges_.begin(boundary.size() * D / 2);  // each ridge parked once
    const std::uint64_t key_mask = colliding_keys ? 7 : ~std::uint64_t{0};
    for (std::size_t b = 0; b < boundary.size(); ++b) {
      const Boundary_facet<D>& f = boundary[b];
      const std::size_t s = new_cells[b];
      std::array<std::uint64_t, D + 1> hashes;
      std::uint64_t sum = 0;
      for (int i = 0; i <= D; ++i) {
        hashes[i] = i == f.facet ? 0 : mix64(f.vertices[i]);
        sum += hashes[i];
      }
      for (int i = 0; i <= D; ++i) {
        if (i == f.facet) continue;
        const auto same = [&](std::uint32_t candidate) { return same_ridge(cells, candidate, f.vertices, f.facet, i); };
        if (const std::uint32_t partner = ridges_.match_or_park((sum - hashes[i]) & key_mask, reference(s, i), same);
            partner != Ridge_table::none) {
          cells[s].n[i] = partner;
          cells[partner >> facet_bits].n[partner & facet_mask] = reference(s, i);
        }
      }
    }
  }

  /// The same in 2D and 3D with a direct table (hxt's idea). The facet
  /// opposite vertex k of a new cell, oriented as the cell induces it, holds
  /// the new point p: in 3D it reads (p, a, b) for an edge (a, b) of the
  /// cavity's boundary, in 2D (p, a) or (a, p) for a boundary vertex a. The
  /// other new cell on that facet, positively oriented too, induces the
  /// opposite orientation: (p, b, a), resp. the other direction. So with the
  /// boundary's vertices numbered 0 … m − 1, a table indexed by the directed
  /// key matches each facet with the entry of the reversed key: one write and
  /// one read per facet, no search, no collision, nothing to clear (every
  /// entry read was written in this insertion). False, having glued nothing,
  /// above 3D and for cavities of star_table_side − 1 finite boundary
  /// vertices or more (number 0 is the infinite vertex's).
  bool glue_directed(Cell_store<D>& cells, const std::vector<Boundary_facet<D>>& boundary,
                     const Scratch_list<Index>& new_cells) {
    if constexpr (D > 3) {
      return false;
    } else {
      if constexpr (D == 2)
        if (boundary.size() <= fan_scan_limit) {
          glue_fan(cells, boundary, new_cells);
          return true;
        }
      if (!directed_keys(boundary)) return false;
      for (std::size_t b = 0; b < boundary.size(); ++b) {
        const auto& facets = star_facets[boundary[b].facet];
        for (int e = 0; e < D; ++e) star_table_[keys_[b * D + e][0]] = reference(new_cells[b], facets[e].k);
      }
      for (std::size_t b = 0; b < boundary.size(); ++b) {
        const auto& facets = star_facets[boundary[b].facet];
        for (int e = 0; e < D; ++e) cells[new_cells[b]].n[facets[e].k] = star_table_[keys_[b * D + e][1]];
      }
      return true;
    }
  }

  /// glue_directed's keys: keys_[b·D + e] is the directed key of new cell
  /// b's e-th facet through the new point (star_facets[facet][e]), and of its
  /// reverse. False when the boundary has star_table_side − 1 finite
  /// vertices or more.
  bool directed_keys(const std::vector<Boundary_facet<D>>& boundary) {
    // The boundary's vertices numbered through a small open-addressing
    // table (in cache, unlike an array over all vertices), stamped per insertion.
    const std::uint32_t stamp = ++local_stamp_;
    if (stamp == 0) {  // wrapped around: forget every old stamp
      std::fill(local_.begin(), local_.end(), Local{});
      local_stamp_ = 1;
      return directed_keys(boundary);
    }
    std::uint32_t m = 1;  // 0: the infinite vertex
    // Whether x is new or seen has no pattern a branch predictor could
    // learn (a boundary vertex is met about five times, the first time
    // new): so the answer is selected by masks, not by a branch (GCC made
    // conditional expressions branches again).
    // Probing on only passes a slot another vertex holds.
    auto local = [&](Index x) -> std::uint32_t {
      if (x == infinite) return 0;
      std::uint32_t i = (x * 0x9e3779b9u) >> (32 - local_bits);
      // (& on the two tests' values, not &&: one branch, not two.)
      while (static_cast<unsigned>(local_[i].stamp == stamp) & static_cast<unsigned>(local_[i].vertex != x))
        i = (i + 1) & (local_table_size - 1);
      Local& l = local_[i];
      const std::uint32_t fresh = l.stamp != stamp, keep = fresh - 1;  // keep: all ones when seen
      l.vertex = x;
      l.stamp = stamp;
      l.number = (l.number & keep) | (m & ~keep);
      m += fresh;
      return l.number;
    };
    // keys_[b·D + e]: the directed key of new cell b's e-th facet through p
    // (star_facets[facet][e]), and of its reverse.
    keys_.resize(boundary.size() * D);
    for (std::size_t b = 0; b < boundary.size(); ++b) {
      const Boundary_facet<D>& f = boundary[b];
      const auto& facets = star_facets[f.facet];
      // Each boundary vertex's number once per facet (each is in D − 1 of its keys).
      std::array<std::uint32_t, D + 1> number;
      for (int e = 0; e < D; ++e) number[facets[e].k] = local(f.vertices[facets[e].k]);
      if (m >= star_table_side) return false;
      for (int e = 0; e < D; ++e) {
        const Star_facet& t = facets[e];
        if constexpr (D == 3) {
          const std::uint32_t x = number[t.a], y = number[t.b];
          keys_[b * D + e] = {x * star_table_side + y, y * star_table_side + x};
        } else {
          const std::uint32_t x = number[t.a];
          keys_[b * D + e] = {2 * x + t.b, 2 * x + (1 - t.b)};
        }
      }
    }
    return true;
  }

  /// In 2D the star is a fan: new cell (p, a, b), counterclockwise (p at
  /// position f, a at f + 1, b at f + 2), meets across its edge (b, p) the
  /// new cell whose a is b. With the fan's few cells (6 on uniform points) a
  /// scan of their a's is faster than numbering the vertices through a hash
  /// table.
  void glue_fan(Cell_store<D>& cells, const std::vector<Boundary_facet<D>>& boundary, const Scratch_list<Index>& new_cells) {
    constexpr int after[3] = {1, 2, 0}, before[3] = {2, 0, 1};  // positions f + 1, f + 2 (mod 3)
    const std::size_t m = boundary.size();
    std::array<Index, fan_scan_limit> a_of;  // each new cell's a
    for (std::size_t x = 0; x < m; ++x) a_of[x] = boundary[x].vertices[after[boundary[x].facet]];
    for (std::size_t x = 0; x < m; ++x) {
      const int fx = boundary[x].facet;
      const Index b = boundary[x].vertices[before[fx]];
      // The boundary is a closed polygon: b is exactly one cell's a. A scan
      // of fixed length with a conditional move: an early exit's branch
      // mispredicts.
      std::size_t y = 0;
      for (std::size_t k = 0; k < m; ++k) y = a_of[k] == b ? k : y;
      DEWALL_ASSERT(a_of[y] == b);
      const int fy = boundary[y].facet;
      // x's edge (b, p) is opposite x's a; y's edge (p, b) is opposite y's own b.
      cells[new_cells[x]].n[after[fx]] = reference(new_cells[y], before[fy]);
      cells[new_cells[y]].n[before[fy]] = reference(new_cells[x], after[fx]);
    }
  }
  static constexpr std::size_t fan_scan_limit = 32;

  /// glue_directed's facets of a new cell through the new point p, which
  /// sits at position `facet`: for each other position k (ascending), the
  /// facet opposite k as the cell induces it, read from p on. In 3D it is
  /// (p, a, b), a and b positions; in 2D (p, a) (b = 0) or (a, p) (b = 1).
  /// Computed once from each facet's induced order: positions T[k], with
  /// (k, T[k]) an even permutation of (0 … D) (in 2D the counterclockwise edges).
  struct Star_facet {
    int k, a, b;
  };
  static constexpr auto star_facets = [] {
    constexpr int T3[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    constexpr int T2[3][2] = {{1, 2}, {2, 0}, {0, 1}};
    std::array<std::array<Star_facet, D>, D + 1> table{};
    if constexpr (D <= 3) {
      for (int p = 0; p <= D; ++p)
        for (int k = 0, e = 0; k <= D; ++k) {
          if (k == p) continue;
          if constexpr (D == 3) {
            const int* t = T3[k];
            const int r = t[0] == p ? 0 : t[1] == p ? 1 : 2;  // rotated to (p, a, b)
            table[p][e++] = {k, t[(r + 1) % 3], t[(r + 2) % 3]};
          } else {
            const bool p_first = T2[k][0] == p;
            table[p][e++] = {k, T2[k][p_first ? 1 : 0], p_first ? 0 : 1};
          }
        }
    }
    return table;
  }();

  /// Whether the new cell referenced by `candidate` (a facet through the new
  /// point) has the ridge of `cell` (a new cell's vertices, the new point at
  /// `apex`) without vertex `i`: whether each of that ridge's D − 1 vertices is
  /// among the candidate's other than at its facet. (Both cells hold the new
  /// point, and only facets through it are parked — the candidate's facet is
  /// never opposite the new point — so the candidate's facet then has the
  /// same D vertices.)
  static bool same_ridge(const Cell_store<D>& cells, std::uint32_t candidate, const Cell& cell, int apex, int i) {
    const Cell& other = cells[candidate >> facet_bits].v;
    const int facet = static_cast<int>(candidate & facet_mask);
    for (int k = 0; k <= D; ++k) {
      if (k == apex || k == i) continue;
      bool found = false;
      for (int m = 0; m <= D; ++m) found |= m != facet && other[m] == cell[k];
      if (!found) return false;
    }
    return true;
  }

  /// The facets through the new point, matched in pairs by their ridges' keys
  /// (a key match confirmed by `same`): open addressing; a slot is empty
  /// unless stamped with the current insertion, so nothing is cleared
  /// between insertions.
  class Ridge_table {
   public:
    static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    /// Starts an insertion that parks at most `entries` ridges.
    void begin(std::size_t entries) {
      if (++stamp_ == 0 || slots_.size() < 2 * entries) {
        std::size_t size = std::max<std::size_t>(slots_.size(), 256);
        while (size < 2 * entries) size *= 2;
        slots_.assign(size, Slot{});
        mask_ = size - 1;
        stamp_ = 1;
      }
    }
    /// A reference parked under `key` that `same` accepts, removed; or parks
    /// `ref` and returns none.
    template <class Same>
    std::uint32_t match_or_park(std::uint64_t key, std::uint32_t ref, Same&& same) {
      for (std::size_t i = (key * 0x9e3779b97f4a7c15ull >> 40) & mask_;; i = (i + 1) & mask_) {
        Slot& s = slots_[i];
        if (s.stamp != stamp_) {
          s = {key, ref, stamp_};
          return none;
        }
        if (s.ref != taken && s.key == key && same(s.ref)) {
          const std::uint32_t partner = s.ref;
          s.ref = taken;  // a tombstone: later probes pass over it
          return partner;
        }
      }
    }

   private:
    static constexpr std::uint32_t taken = none - 1;
    struct Slot {
      std::uint64_t key = 0;
      std::uint32_t ref = none;
      std::uint32_t stamp = 0;
    };
    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
    std::uint32_t stamp_ = 0;
  };

  // glue_directed: the boundary vertices' numbers, the facets' directed
  // keys (and their reverses), the table by directed key.
  static constexpr std::uint32_t star_table_side = 128;  // + D < local_table_size: the table never fills
  static constexpr int local_bits = 8;
  static constexpr std::uint32_t local_table_size = 1u << local_bits;
  struct Local {
    Index vertex = 0;
    std::uint32_t stamp = 0, number = 0;
  };
  Ridge_table ridges_;
  std::vector<Local> local_ = std::vector<Local>(D <= 3 ? local_table_size : 0);
  std::uint32_t local_stamp_ = 0;
  std::vector<std::array<std::uint32_t, 2>> keys_;
  std::vector<std::uint32_t> star_table_ =
      std::vector<std::uint32_t>(D == 3 ? star_table_side * star_table_side : D == 2 ? 2 * star_table_side : 0);
};

}  // namespace dewall::detail
