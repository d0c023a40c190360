// The incremental engine's zoned parallel insertion (step 4 of
// incremental_delaunay.hpp): vertices inserted in rounds of two zones, each
// zone by its own task, with the same cells in the same slots for any number
// of threads.
//
// A round cuts space by a plane, at the median of its points' coordinate
// along one axis (the box's longest first, another each round); every
// vertex, old or new, is in the zone of its side. A zone inserts its points
// in their order, each only when its walk and its cavity stay in cells whose
// vertices are all the zone's; else the point waits for the next round (the
// cavity's cells not yet changed). Why no two zones touch the same data: a
// zone changes only cells with all D + 1 vertices its own (the cavity), and
// the neighbour reference and mark of cells sharing a facet with one, which
// have D of its vertices, so they are no other zone's cavity and share no
// facet with one (two facets of a cell share D − 1 vertices; above 2D the
// infinite vertex, every zone's, is at most one of them, so D − 1 ≥ 2 leaves
// one of the zone's own; in 2D a hull cell {t, ∞, u} would border both
// zones, so there ∞ is no zone's and points outside the hull wait); the walk
// starts in the zone's own cells and stops before any other. So each zone's
// work reads and writes only what no other zone changes in the round, and
// its result (which points wait, which slots hold which cells: its slots are
// fixed before the round) depends on the round's start alone, not on the
// threads' timing: the cells, their slots and the output order are the same
// for any number of threads. The Delaunay triangulation (perturbed) is
// unique, so it is CGAL's in any insertion order. The points still waiting
// after D rounds are inserted one by one.
// Cf. hxt (Marot, Pellerin, Remacle 2019), which partitions along a Hilbert
// curve and lets threads race; here the partition is by planes and nothing
// races.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "dewall/detail/common/box.hpp"
#include "dewall/detail/common/index.hpp"
#include "dewall/detail/incremental/worker.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
class Bowyer_watson;

/// One run of zoned rounds over a Bowyer_watson engine (its friend), for
/// vertices first … last − 1. The steps of a round are the functions below,
/// in the order run calls them.
template <int D>
class Zoned_insertion {
  using Engine = Bowyer_watson<D>;
  using Worker = Insertion_worker<D>;

 public:
  Zoned_insertion(Engine& dt, std::size_t first, std::size_t last, const Box<D>& box)
      : dt_(dt), last_(last), pending_(last - first) {
    for (std::size_t k = first; k < last; ++k) pending_[k - first] = static_cast<Index>(k);
    order_axes(box);
    set_near_cut_scale(box);
  }

  /// The rounds, then the points still waiting one by one.
  void run() {
    for (int round = 0; round < D && !pending_.empty() && pending_.size() >= dt_.tuning_.zoned_insertion_threshold / 16;
         ++round) {
      if (!run_round(axes_[round])) break;
      if (dt_.tuning_.check_each_insertion && !dt_.is_valid())
        throw std::logic_error("Incremental_delaunay: invalid after zoned round " + std::to_string(round));
      if (workers_[0].gave_up || workers_[1].gave_up) break;
    }
    dt_.serial_.new_cells.clear();  // the last serial insertion's: other zones may have reused their slots
    for (const Index v : pending_) dt_.insert_serially(v);
  }

 private:
  /// One round along `axis`; false when it did not run (hopeless: the rounds end).
  bool run_round(int axis) {
    // Cells per point so far (it grows on surfaces): each zone's new slots are sized from it.
    const double per_point = static_cast<double>(dt_.store_.slots() - dt_.serial_.free.size()) /
                             static_cast<double>(last_ - pending_.size());
    dt_.cut_axis_ = axis;
    dt_.cut_ = median_cut(axis);
    near_cut_inserted_ = static_cast<double>(last_ - pending_.size());
    std::array<std::vector<Index>, 2> points;
    for (const Index v : pending_) points[dt_.zone_of(dt_.points_[v])].push_back(v);
    for (std::size_t z = 0; z < 2; ++z) workers_[z].zone = static_cast<std::uint8_t>(z);
    std::array<std::vector<std::size_t>, 2> hints;
    if (!find_hints(points, hints)) return false;
    give_slots(points, per_point);
    ++dt_.serial_.stats.zone_rounds;
    // Isolated: while waiting for the other zone this thread takes no
    // unrelated outer task (a hybrid's region builds inside one).
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(std::size_t{0}, std::size_t{2}, [&](std::size_t z) {
        const kernel::Fp_environment_guard guard;
        insert_zone(workers_[z], points[z], hints[z]);
      });
    });
    take_back_slots();
    merge_workers();
    return true;
  }

  /// The axes of the rounds: the box's longest first.
  void order_axes(const Box<D>& box) {
    for (int j = 0; j < D; ++j) axes_[j] = j;
    std::stable_sort(axes_.begin(), axes_.end(),
                     [&](int a, int b) { return box.hi[a] - box.lo[a] > box.hi[b] - box.lo[b]; });
  }

  /// near_cut's unit: the box's mean extent (geometric: its volume's D-th
  /// root, without the product's overflow at extreme scales). None (the rule
  /// off) when an extent overflows or near_cut_spacings is not > 0.
  void set_near_cut_scale(const Box<D>& box) {
    double log_extents = 0;
    for (int j = 0; j < D; ++j) log_extents += std::log(box.hi[j] - box.lo[j]);
    near_cut_scale_ = 1 / (std::exp(log_extents / D) * dt_.tuning_.near_cut_spacings);
    if (!(std::isfinite(near_cut_scale_) && near_cut_scale_ > 0)) near_cut_scale_ = 0;
  }

  /// The cut: the median of at most cut_sample pending points spread evenly
  /// over the order (it is spread over space; the zones need not be equal,
  /// and the full median costs). Its array is gone before the round (the
  /// cells' peak).
  double median_cut(int axis) const {
    const std::size_t stride = (pending_.size() + cut_sample - 1) / cut_sample;
    std::vector<double> along;
    along.reserve(pending_.size() / stride + 1);
    for (std::size_t k = 0; k < pending_.size(); k += stride) along.push_back(dt_.points_[pending_[k]].x[axis]);
    const auto median = along.begin() + static_cast<std::ptrdiff_t>(along.size() / 2);
    std::nth_element(along.begin(), median, along.end());
    return *median;
  }

  /// Where the zones' walks start: for every hint_spacing-th point of a
  /// zone, the cell holding it now, when all its vertices are the zone's
  /// (found serially, by walking from one to the next: nothing changes yet).
  /// Within the round only the zone changes such a slot; so when not free it
  /// holds a cell of the zone's (usually near: a slot is reused by the
  /// cavity that freed it). Each walk starts where the last one ended,
  /// beyond the hull too.
  ///
  /// In 2D a point beyond the hull waits (owns: ∞ is no zone's; the hull does
  /// not change within a round). As soon as more than 1 in `waits` of all a
  /// zone's hinted points lie there — the share of its first tries whose
  /// failing makes insert_zone give up, here estimated from the hints — the
  /// round is hopeless: false, no slot taken (on a circle every point is on
  /// the hull). The hints are found serially, so the answer is the same for
  /// any number of threads.
  bool find_hints(const std::array<std::vector<Index>, 2>& points, std::array<std::vector<std::size_t>, 2>& hints) {
    bool hopeless = false;
    for (std::size_t z = 0; z < 2 && !hopeless; ++z) {
      const std::size_t count = (points[z].size() + hint_spacing - 1) / hint_spacing;
      const std::size_t waits = points[z].size() >= patient_zone_points ? 2 : 4;
      std::size_t beyond_hull = 0;
      for (std::size_t k = 0; k < points[z].size() && !hopeless; k += hint_spacing) {
        const std::size_t c = dt_.template locate<false>(dt_.serial_, dt_.points_[points[z][k]]);
        const int i = dt_.store_.infinite_position(c);
        dt_.serial_.last = i > D ? c : dt_.store_.neighbor(c, i);
        beyond_hull += i <= D;
        hopeless = D == 2 && beyond_hull * waits > count;
        bool own = i > D;
        for (int j = 0; j <= D; ++j) own = own && dt_.owns(workers_[z], dt_.store_.vertex(c, j));
        hints[z].push_back(own ? c : Engine::no_cell);
      }
    }
    return !hopeless;  // (when hopeless the hints are incomplete: the round must not run)
  }

  /// Each zone's slots: free ones first (the end of the free list), then a
  /// new range; an eighth above the cells per point so far (a zone that runs
  /// out leaves its points to the next round).
  void give_slots(const std::array<std::vector<Index>, 2>& points, double per_point) {
    std::vector<Index>& free = dt_.serial_.free;
    std::size_t grown = dt_.store_.slots();
    for (std::size_t z = 0; z < 2; ++z) {
      Worker& w = workers_[z];
      w.new_cells.clear();
      w.deferred.clear();
      w.out_of_slots = false;
      const auto wanted = static_cast<std::size_t>(
          dt_.tuning_.zone_slots_scale * (per_point * 1.125 * static_cast<double>(points[z].size()) + 1024));
      const std::size_t taken = std::min(wanted, free.size());
      w.free.assign(free.end() - static_cast<std::ptrdiff_t>(taken), free.end());
      free.resize(free.size() - taken);
      w.next_slot = grown;
      w.end_slot = grown += std::min(wanted - taken, Engine::max_slots - std::min(grown, Engine::max_slots));
    }
    dt_.store_.reserve(grown);
    dt_.store_.resize(grown);
  }

  /// The zones' unused slots become free ones (a range ending the array is cut off).
  void take_back_slots() {
    for (std::size_t z = 2; z-- > 0;) {
      Worker& w = workers_[z];
      if (w.end_slot == dt_.store_.slots()) {
        dt_.store_.resize(w.next_slot);
      } else {
        for (std::size_t s = w.next_slot; s < w.end_slot; ++s) {
          dt_.store_.clear_slot(s);  // never a cell: its whole record written
          dt_.serial_.free.push_back(static_cast<Index>(s));
        }
      }
    }
  }

  /// The zones' free slots, counts and last cells back to the serial
  /// worker; the points they left wait for the next round, in order.
  void merge_workers() {
    Worker& serial = dt_.serial_;
    for (Worker& w : workers_) {
      serial.free.insert(serial.free.end(), w.free.begin(), w.free.end());
      dt_.finite_cells_ += static_cast<std::size_t>(w.finite_change);
      w.finite_change = 0;
      serial.stats += w.stats;
      w.stats = {};
      if (w.last != Engine::no_cell) serial.last = w.last;  // alive: nothing ran after its zone
    }
    pending_.clear();
    std::merge(workers_[0].deferred.begin(), workers_[0].deferred.end(), workers_[1].deferred.begin(),
               workers_[1].deferred.end(), std::back_inserter(pending_));
  }

  /// A zone's insertions in a round: each point from the cell the zone made
  /// last (or where its last walk stopped at the zone's edge: locate); when
  /// that walk leaves the zone (after a jump of the points' curve, or near
  /// the zone's edge), again from the hint of the latest hinted point. What
  /// still fails waits in w.deferred. A zone whose first tries fail too
  /// often gives up (gives_up).
  void insert_zone(Worker& w, const std::vector<Index>& points, const std::vector<std::size_t>& hints) {
    w.last = Engine::no_cell;
    w.gave_up = false;
    // Until the zone's first walk, the first hint there is (when the first
    // points have none, each would fail for want of a start: on surface
    // samples often enough that the zone gave up).
    std::size_t hint = Engine::no_cell;
    for (std::size_t h = 0; h < hints.size() && hint == Engine::no_cell; ++h) hint = hints[h];
    const bool patient = points.size() >= patient_zone_points;
    std::size_t tried = 0, failed = 0;  // the zone's tries (near_cut's points are none) and failures
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (k % hint_spacing == 0 && (w.last != Engine::no_cell || hints[k / hint_spacing] != Engine::no_cell))
        hint = hints[k / hint_spacing];
      const Index v = points[k];
      const bool trying = !w.out_of_slots && !w.gave_up;
      const bool near = trying && near_cut(v);
      const bool inserted = trying && !near && (++tried, try_insert(w, v, hint));
      if (inserted) ++w.stats.zoned_points;
      else w.deferred.push_back(v);
      w.stats.near_cut_points += near;
      // Running out of slots is no failure of the zone's (its points wait for the next round).
      failed += trying && !near && !inserted && !w.out_of_slots;
      w.stats.zone_failures += trying && !near && !inserted;
      if (gives_up(tried, failed, patient)) w.gave_up = true;
      if (dt_.progress_ && (k + 1) % Engine::progress_stride == 0) dt_.progress_->advance(Engine::progress_stride);
    }
  }

  /// One try at v: from w.last, then, when that walk could not start or left
  /// the zone, from the hint (which must hold a finite cell of the zone: its
  /// slot may hold an infinite one now).
  bool try_insert(Worker& w, Index v, std::size_t hint) {
    w.walk_failed = false;
    const std::size_t start = w.last;  // (a failed walk moves w.last: locate)
    bool inserted = start != Engine::no_cell && dt_.template insert<true>(w, v);
    if (!inserted && (start == Engine::no_cell || w.walk_failed) && !w.out_of_slots && hint != Engine::no_cell &&
        hint != start && !dt_.store_.is_free(hint) && !dt_.store_.is_infinite(hint)) {
      const std::size_t from = w.last;
      w.last = hint;
      inserted = dt_.template insert<true>(w, v);
      if (!inserted && from != Engine::no_cell) w.last = from;
    }
    return inserted;
  }

  /// Whether a zone gives up the round: more than a quarter of its first
  /// zone_probe tries failed, or for a zone of patient_zone_points or more,
  /// half of them or a quarter of its first 4·zone_probe (a zone's first
  /// points lie where the points' curve enters it, beside the cut, where
  /// more cavities cross it; in a small zone giving up costs little).
  bool gives_up(std::size_t tried, std::size_t failed, bool patient) const {
    const std::size_t probe = dt_.tuning_.zone_probe;
    return (tried == probe && failed * (patient ? 2 : 4) > tried) ||
           (patient && tried == 4 * probe && failed * 4 > tried);
  }

  /// Whether vertex v (a point of the round) lies within near_cut_spacings
  /// point spacings of the cut, the spacing estimated from the box's volume
  /// and the points inserted when v would be (v itself: vertices are
  /// numbered in the planned insertion order; at least those inserted at the
  /// round's start). Such a point waits for the next round untried: its walk
  /// or cavity nearly always meets the other zone. Coordinates and numbers
  /// alone decide, so the answer is the same for any thread count.
  bool near_cut(Index v) const {
    const double distance = std::abs(dt_.points_[v].x[dt_.cut_axis_] - dt_.cut_) * near_cut_scale_;
    double power = distance;  // distance^D · points < 1: within the spacings
    for (int j = 1; j < D; ++j) power *= distance;
    return near_cut_scale_ > 0 && power * std::max(near_cut_inserted_, static_cast<double>(v)) < 1;
  }

  static constexpr std::size_t hint_spacing = 64;
  static constexpr std::size_t cut_sample = std::size_t{1} << 16;
  static constexpr std::size_t patient_zone_points = std::size_t{1} << 19;

  Engine& dt_;
  std::size_t last_;
  std::vector<Index> pending_;  // the points still to insert, in order
  std::array<int, D> axes_;
  std::array<Worker, 2> workers_;
  double near_cut_scale_ = 0;     // 1 / (the box's mean extent · near_cut_spacings); 0: off
  double near_cut_inserted_ = 0;  // points inserted at the round's start
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
