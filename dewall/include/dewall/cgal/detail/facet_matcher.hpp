// Facet_matcher: pairs the facets of a simplicial complex so that the CGAL
// builders can set neighbour relations without a search.
//
// Each facet of a D-simplex is the sorted tuple of its D vertex ids. In a
// triangulation of a closed (pseudo)manifold every facet is shared by exactly
// two cells, so one open-addressing table suffices: the first cell to offer a
// facet parks it, the second one takes it out and the two become neighbours.
// Cells arrive in DeWall's output order, which is spatially coherent, so the
// table holds about the current front of parked facets, not all of them.
// Deletion shifts the following run back (no tombstones), so probes stay short.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dewall/detail/walls/face.hpp"

namespace dewall::cgal::detail {

/// An open-addressing hash table from facet keys (D sorted vertex ids) to the
/// (cell, facet index) that offered them first. Topology only: knows no geometry.
template <int D>
class Facet_matcher {
 public:
  using Key = std::array<std::uint32_t, D>;
  /// A cell number and the index (0 … D) of the vertex opposite the facet.
  struct Facet_ref {
    std::uint64_t cell;
    int index;
  };

  explicit Facet_matcher(std::size_t expected_live = 1024) {
    std::size_t cap = 64;
    while (cap < 2 * expected_live) cap *= 2;
    slots_.assign(cap, Slot{});
  }

  /// Offers facet `key` of (cell, index). Returns true and sets `partner` when
  /// the facet was parked by another cell (it is then removed); otherwise parks it.
  /// Complexity: expected O(1).
  bool match_or_park(const Key& key, Facet_ref self, Facet_ref& partner) {
    std::size_t i = hash(key) & mask();
    for (;;) {
      Slot& s = slots_[i];
      if (!s.used) break;
      if (s.key == key) {
        partner = s.ref;
        erase_at(i);
        return true;
      }
      i = (i + 1) & mask();
    }
    slots_[i] = Slot{key, self, true};
    if (++size_ * 2 > slots_.size()) grow();
    return false;
  }

  /// Facets parked and never matched (hull facets once every cell was offered).
  std::size_t size() const { return size_; }

  /// Calls f(key, ref) for each parked facet, in table order.
  template <class F>
  void for_each_parked(F&& f) const {
    for (const Slot& s : slots_)
      if (s.used) f(s.key, s.ref);
  }

  /// The facet of `cell` opposite vertex `index`, as a sorted key.
  template <class Cell>
  static Key facet_key(const Cell& cell, int index) {
    Key k;
    std::size_t j = 0;
    for (int v = 0; v <= D; ++v)
      if (v != index) k[j++] = cell[static_cast<std::size_t>(v)];
    std::sort(k.begin(), k.end());
    return k;
  }

 private:
  struct Slot {
    Key key{};
    Facet_ref ref{0, 0};
    bool used = false;
  };

  std::size_t mask() const { return slots_.size() - 1; }

  static std::size_t hash(const Key& k) { return static_cast<std::size_t>(dewall::detail::face_hash<D>(k)); }

  // Backward-shift deletion for linear probing: move later members of the
  // run into the hole when their home slot does not lie cyclically in (hole, j].
  void erase_at(std::size_t hole) {
    --size_;
    std::size_t j = hole;
    for (;;) {
      j = (j + 1) & mask();
      if (!slots_[j].used) break;
      const std::size_t home = hash(slots_[j].key) & mask();
      const bool home_in_gap = hole <= j ? (hole < home && home <= j) : (hole < home || home <= j);
      if (home_in_gap) continue;
      slots_[hole] = slots_[j];
      hole = j;
    }
    slots_[hole].used = false;
  }

  void grow() {
    std::vector<Slot> old(slots_.size() * 2);
    old.swap(slots_);
    for (const Slot& s : old) {
      if (!s.used) continue;
      std::size_t i = hash(s.key) & mask();
      while (slots_[i].used) i = (i + 1) & mask();
      slots_[i] = s;
    }
  }

  std::vector<Slot> slots_;
  std::size_t size_ = 0;
};

}  // namespace dewall::cgal::detail
