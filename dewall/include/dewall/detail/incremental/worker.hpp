// What one thread of the incremental engine's insertions works with, and the
// counters of a construction.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dewall/detail/common/index.hpp"
#include "dewall/detail/incremental/cell_geometry.hpp"
#include "dewall/detail/incremental/scratch_list.hpp"
#include "dewall/detail/incremental/star_gluing.hpp"

namespace dewall::detail {

/// Counters of one construction (what the profile of a run is made of).
struct Incremental_statistics {
  std::size_t walk_steps = 0;     // cells crossed while locating
  std::size_t conflict_cells = 0; // cells destroyed, summed over insertions
  std::size_t created_cells = 0;  // cells made, summed over insertions
  std::size_t ridge_table_stars = 0;  // stars glued through the ridge hash table
  std::size_t zoned_points = 0;   // points a zone inserted (Zoned_insertion)
  std::size_t zone_rounds = 0;    // rounds whose zones ran (Zoned_insertion)
  std::size_t near_cut_points = 0;  // waits untried beside the cut (near_cut), summed over rounds
  std::size_t zone_failures = 0;  // tries of a zone that failed (the walk or the cavity met the other zone)
  std::size_t hull_starts = 0;    // 2D: cavities started on a hull edge found along the hull
  std::size_t semi_static_first_windows = 0;  // 3D: windows of sphere tests with the semi-static bound first (choose_filter_order)
  Incremental_statistics& operator+=(const Incremental_statistics& o) {
    walk_steps += o.walk_steps;
    hull_starts += o.hull_starts;
    conflict_cells += o.conflict_cells;
    created_cells += o.created_cells;
    ridge_table_stars += o.ridge_table_stars;
    zoned_points += o.zoned_points;
    zone_rounds += o.zone_rounds;
    near_cut_points += o.near_cut_points;
    zone_failures += o.zone_failures;
    semi_static_first_windows += o.semi_static_first_windows;
    return *this;
  }
};

/// What one thread of insertions works with: the search's and the star's
/// scratch, its free slots, where its walks start. The serial insertions
/// have one (Incremental_delaunay::serial_), each zone of a zoned round its own.
template <int D>
struct Insertion_worker {
  std::vector<Index> free;      // free slots (serial_'s: every free slot)
  bool semi_static_first = false;   // choose_filter_order's state
  std::uint8_t semi_static_windows = 0;
  Filter_tally filter_tally;
  // A finite cell the last insertion made (or where a zone's failed walk stopped): the next walk starts there.
  std::size_t last = 0;
  std::ptrdiff_t finite_change = 0;  // finite cells made minus destroyed, not yet in finite_cells_
  Incremental_statistics stats;
  Scratch_list<std::size_t> cavity;
  std::vector<Boundary_facet<D>> boundary;
  Scratch_list<Index> new_cells;  // the slot of each boundary facet's new cell
  Star_gluing<D> star;
  // Zoned insertion only: the zone, its new slots next_slot … end_slot − 1,
  // the vertices it left to the next round.
  std::uint8_t zone = 0;
  std::size_t next_slot = 0, end_slot = 0;
  bool out_of_slots = false;
  bool walk_failed = false;
  bool gave_up = false;  // too many of the zone's points waited (Incremental_tuning::zone_probe)
  std::vector<Index> deferred;
};

}  // namespace dewall::detail
