// The incremental engine's tuning: one value given to Incremental_delaunay's
// constructor, checked there. The defaults are the library's; the MPI
// library turns zones off, tests and the fuzzer choose the paths they want
// to reach. No knob changes the triangulation (a function of the point set),
// only how it is built: the zoned knobs change the cells' slots, never the
// cells, and the slots are the same for any number of threads.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace dewall::detail {

struct Incremental_tuning {
  /// Points after build()'s sample from which they are inserted in zones
  /// (in parallel; the same cells and slots for any number of threads),
  /// and twice the sample's rest from which that is zoned too. SIZE_MAX:
  /// never (dewall::mpi, where each rank runs on one thread).
  std::size_t zoned_insertion_threshold = std::size_t{1} << 16;
  /// A zone whose first zone_probe tries fail more than a quarter of the time
  /// gives up the round (a large zone: half of its first zone_probe, or a
  /// quarter of its first 4·zone_probe): on inputs whose cells cross every
  /// cut, trying on costs more than the points waiting for the next round.
  /// At least 1.
  std::size_t zone_probe = 2048;
  /// Points this many point spacings or nearer the cut wait for the next
  /// round untried (their walk or cavity nearly always meets the other
  /// zone). 0: none waits. Finite, at least 0.
  double near_cut_spacings = 2;
  /// Scales the new slots each zone gets (below 1 zones run out of slots
  /// early, and their points wait for the next round). Finite, above 0.
  double zone_slots_scale = 1;
  /// The sphere tests of one window of the filter-order choice (3D): fewer
  /// let the semi-static bound first run on small inputs. At least 1.
  std::uint32_t filter_order_window = 1u << 16;
  /// Glue every star through the ridge hash table (otherwise, in 2D and 3D,
  /// only very large cavities take it).
  bool ridge_table_only = false;
  /// Ridge keys cut to 3 bits, so that most key matches are no ridge's and
  /// the vertex check must tell them apart (tests, fuzzing).
  bool colliding_ridge_keys = false;
  /// Check the whole data structure (O(n)) after every serial insertion and
  /// every zoned round, throwing std::logic_error at the first failure.
  bool check_each_insertion = false;

  /// \throws std::invalid_argument naming the first value out of range.
  void validate() const {
    const auto refuse = [](const char* what) {
      throw std::invalid_argument(std::string("dewall: Incremental_tuning::") + what);
    };
    if (zone_probe < 1) refuse("zone_probe must be at least 1");
    if (!(std::isfinite(near_cut_spacings) && near_cut_spacings >= 0))
      refuse("near_cut_spacings must be finite and at least 0");
    if (!(std::isfinite(zone_slots_scale) && zone_slots_scale > 0))
      refuse("zone_slots_scale must be finite and above 0");
    if (filter_order_window < 1) refuse("filter_order_window must be at least 1");
  }
};

}  // namespace dewall::detail
