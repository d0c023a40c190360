// The engine proper of the incremental construction (incremental_delaunay.hpp
// builds with it): Bowyer–Watson insertion over the cell geometry — the
// visibility walk to a cell in conflict (step 3a), the cavity breadth-first
// from it (step 3b), the star of its boundary facets (step 3c, glued by
// star_gluing.hpp) — serially, or in a zone of a round (Zoned: the walk and
// the cavity stop at the zone's edge; zoned_insertion.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "dewall/detail/common/assert.hpp"
#include "dewall/detail/common/cell_graph_output.hpp"
#include "dewall/detail/common/index.hpp"
#include "dewall/detail/common/progress_meter.hpp"
#include "dewall/detail/incremental/cell_geometry.hpp"
#include "dewall/detail/incremental/cell_store.hpp"
#include "dewall/detail/incremental/star_gluing.hpp"
#include "dewall/detail/incremental/tuning.hpp"
#include "dewall/detail/incremental/worker.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
class Zoned_insertion;
struct Incremental_testing_access;

template <int D>
class Bowyer_watson : public Cell_geometry<D> {
  using Base = Cell_geometry<D>;
  using Store = Cell_store<D>;

 public:
  using Point = kernel::Point_d<D>;
  using Cell = typename Store::Cell;
  /// The vertex id of the infinite vertex.
  static constexpr Index infinite = Store::infinite;
  /// A free slot's first vertex.
  static constexpr Index free_slot = Store::free_slot;
  /// Bits of a neighbour reference that hold the facet index.
  static constexpr int facet_bits = Store::facet_bits;

  /// \throws std::invalid_argument when `tuning` is out of range (Incremental_tuning::validate).
  explicit Bowyer_watson(const Incremental_tuning& tuning) : tuning_(tuning) { tuning_.validate(); }
  const Incremental_tuning& tuning() const { return tuning_; }
  /// Told of every progress_stride points inserted or tried (Options::progress;
  /// it throws Cancelled when the caller stops the work), or null.
  void set_progress(Progress_meter* meter) { progress_ = meter; }
  static constexpr std::size_t progress_stride = 4096;

  /// The cells (Cell_store says what each returns).
  std::size_t slots() const { return store_.slots(); }
  bool is_free(std::size_t c) const { return store_.is_free(c); }
  bool is_infinite(std::size_t c) const { return store_.is_infinite(c); }
  bool holds_finite_cell(std::size_t c) const { return store_.holds_finite_cell(c); }
  int infinite_position(std::size_t c) const { return store_.infinite_position(c); }
  const Cell& cell(std::size_t c) const { return store_.cell(c); }
  std::size_t neighbor(std::size_t c, int i) const { return store_.neighbor(c, i); }
  std::span<const Cell_record<D>> records(std::size_t first, std::size_t last) const {
    return store_.records(first, last);
  }
  std::size_t finite_cells() const { return finite_cells_ + static_cast<std::size_t>(serial_.finite_change); }
  const Incremental_statistics& statistics() const { return serial_.stats; }
  /// Checks the data structure (Cell_geometry::is_valid).
  using Base::is_valid;

 protected:
  friend class Zoned_insertion<D>;
  friend struct Incremental_testing_access;
  using Worker = Insertion_worker<D>;
  using Record = typename Store::Record;
  using Base::in_conflict;
  using Base::orientation;
  using Base::points_;
  using Base::proven_in_conflict;
  using Base::static_filter_;
  using Base::store_;
  static constexpr std::size_t no_cell = std::numeric_limits<std::size_t>::max();
  static constexpr std::uint32_t facet_mask = Store::facet_mask;
  static constexpr std::size_t max_slots = Store::max_slots;
  static constexpr bool marks_in_cells = Store::marks_in_cells;
  static std::uint32_t reference(std::size_t c, int i) { return Store::reference(c, i); }

  /// Steps 1–2: the first simplex (Cell_geometry::make_first_simplex), the
  /// serial worker set up for it.
  template <class Coordinates>
  bool start(Coordinates&& coordinates, std::vector<std::uint32_t>& order) {
    if (!Base::make_first_simplex(coordinates, order)) return false;
    serial_.free.clear();
    serial_.new_cells.clear();  // start_of_cavity's candidates: none yet
    serial_.stats = {};
    serial_.finite_change = 0;
    finite_cells_ = 1;
    serial_.last = 0;
    return true;
  }

  /// Step 3a: a cell in conflict with q, by a visibility walk from w.last.
  /// Zoned: no_cell when the walk would enter a cell with a vertex outside
  /// w's zone (w.last has none, so no cell it reads is another zone's to
  /// change); w.last is then the cell where it stopped.
  template <bool Zoned>
  std::size_t locate(Worker& w, const Point& q) {
    std::size_t c = w.last, previous = std::numeric_limits<std::size_t>::max();
    if (const int i = infinite_position(c); i <= D) c = neighbor(c, i);
    unsigned rotation = 0;
    for (;;) {
      if (is_infinite(c)) return c;  // q beyond the hull facet crossed last
      bool moved = false;
      for (int i = 0; i <= D; ++i) __builtin_prefetch(&store_[store_[c].n[i] >> facet_bits]);  // the next step's record
      rotation = rotation * 1103515245u + 12345u;  // varies the first facet tried
      const int first = static_cast<int>((rotation >> 16) % (D + 1));
      for (int k = 0; k <= D; ++k) {
        const int i = (first + k) % (D + 1);
        const std::size_t next = neighbor(c, i);
        if (next == previous) continue;
        if (orientation(c, i, &q) == kernel::NEGATIVE) {
          if constexpr (Zoned)
            if (!owns(w, store_[next].v[store_[c].n[i] & facet_mask])) {
              // The next walk starts here, nearer the next point than the
              // last insertion's cell (all c's vertices are w's: it is as
              // good a start; in 2D, points beyond the early hull would each
              // walk far from the same cell).
              w.walk_failed = true;
              w.last = c;
              return no_cell;
            }
          previous = c;
          c = next;
          moved = true;
          ++w.stats.walk_steps;
          break;
        }
      }
      if (!moved) return c;  // q in the closed cell c: strictly inside its sphere
    }
  }

  /// A cell in conflict with q: one of the cells the last insertion made,
  /// when one is (consecutive points are neighbours in space, so q's cavity
  /// often holds a cell of its predecessor's star), else the walk's. The
  /// cavity is the same from any cell in it; a sphere test here saves
  /// several walk steps (docs/engines.md has the figures).
  template <bool Zoned>
  std::size_t start_of_cavity(Worker& w, const Point& q) {
    const std::size_t tries = std::min<std::size_t>(w.new_cells.size(), star_tries);
    if constexpr (D == 2 && !Zoned) {  // (zoned insertions never touch the hull in 2D: owns)
      if (const std::size_t c = along_hull(w, q); c != no_cell) return c;
    }
    for (std::size_t k = 0; k < tries; ++k)
      if (proven_in_conflict(w.new_cells[k], q)) return w.new_cells[k];
    return locate<Zoned>(w, q);
  }

  /// In 2D, when the last point went on the hull, q is often beyond it too
  /// (points on a circle: every one), but seldom beyond the two hull edges
  /// the last star holds: its hull neighbours then may have other points
  /// between them and q on the hull. The visibility walk to q crosses the
  /// polygon's long thin cells, after star tries whose sphere tests are
  /// near ties the filters cannot decide. Here the star's hull edges are tried
  /// first, then up to hull_steps edges each way along the hull, one
  /// orientation a step: a hull edge q sees is in conflict (it is as good a
  /// start as any). no_cell when the star has no hull edge or q sees none of
  /// those tried: the star tries and the walk follow.
  std::size_t along_hull(Worker& w, const Point& q) const {
    std::size_t hull_cell = no_cell;
    for (const std::size_t c : w.new_cells)
      if (is_infinite(c)) {
        if (proven_in_conflict(c, q)) return ++w.stats.hull_starts, c;
        hull_cell = c;
      }
    if (hull_cell == no_cell) return no_cell;
    // Infinite cell (∞, a, b) in cyclic order: across (b, ∞), opposite a, is
    // (∞, b, c), across (∞, a) it is (∞, z, a) (neighbours induce the shared
    // edge in opposite directions), so the same offset from ∞'s position
    // keeps one direction along the hull. Both are tried, a step at a time.
    std::array<std::size_t, 2> at{hull_cell, hull_cell};
    for (int step = 0; step < hull_steps; ++step)
      for (int direction = 0; direction < 2; ++direction) {
        std::size_t& c = at[static_cast<std::size_t>(direction)];
        c = neighbor(c, (infinite_position(c) + 1 + direction) % (D + 1));
        if (proven_in_conflict(c, q)) return ++w.stats.hull_starts, c;
      }
    return no_cell;
  }
  // More steps find no more (the distances along the hull fall off geometrically).
  static constexpr int hull_steps = 16;

  /// Steps 3a–b: w.cavity holds the cells in conflict with q, w.boundary the
  /// facets around them with the new cells' vertices (q as vertex v).
  /// Zoned: false (the search stopped; clear_marks(w) undoes it) when a cell
  /// in conflict has a vertex outside w's zone or the walk left the zone.
  template <bool Zoned>
  bool find_cavity(Worker& w, const Point& q, Index v) {
    Filter_tally tally;
    if constexpr (D != 3) {
      return find_cavity<Zoned, false>(w, q, v, tally);
    } else {
      const bool found = w.semi_static_first ? find_cavity<Zoned, true>(w, q, v, tally)
                                             : find_cavity<Zoned, false>(w, q, v, tally);
      choose_filter_order(w, tally);
      return found;
    }
  }
  /// Which of the static filter's two bounds the sphere tests of w's cavity
  /// searches try first, in 3D (in 2D the box's: its cascade has no
  /// semi-static bound of its own). The box's bound costs a comparison, the
  /// semi-static one the column maxima; but where the box's leaves many
  /// tests (surface samples: a surface's cells are small against its box),
  /// its branch mispredicts,
  /// and the semi-static bound (never looser) first is cheaper. Decided per
  /// window of 2^16 tests from the share the box's bound left in the last:
  /// over a quarter, the semi-static first for the next 15 windows (which do
  /// not count: a count costs in that order), then the box's first again for
  /// one that measures. The order changes no answer, only its cost (the
  /// figures: docs/engines.md, "filter").
  void choose_filter_order(Worker& w, const Filter_tally& tally) {
    w.filter_tally.tests += tally.tests;
    w.filter_tally.box_bound_left += tally.box_bound_left;
    if (w.filter_tally.tests < tuning_.filter_order_window) return;
    w.stats.semi_static_first_windows += w.semi_static_first;
    if (!w.semi_static_first) {
      w.semi_static_first = w.filter_tally.box_bound_left > w.filter_tally.tests / 4;
    } else if (++w.semi_static_windows == 15) {
      w.semi_static_first = false;
      w.semi_static_windows = 0;
    }
    w.filter_tally = {};
  }

  template <bool Zoned, bool Semi_static_first>
  bool find_cavity(Worker& w, const Point& q, Index v, Filter_tally& tally) {
    // The sphere tests in pairs need the static filter's bounds (3D).
    const bool pairing = Base::paired_sphere_tests && static_filter_.valid();
    w.cavity.clear();
    w.boundary.clear();
    const std::size_t start_cell = start_of_cavity<Zoned>(w, q);
    if constexpr (Zoned)
      if (start_cell == no_cell) return false;
    DEWALL_EXPENSIVE_ASSERT(in_conflict(start_cell, q));

    // 3b. The cavity, breadth-first; store_.mark(c): in conflict or not (clear_marks resets both).
    constexpr std::uint8_t in = 1, out = 2;
    // The neighbours' marks and records, then the points of their vertices
    // across the shared facets, are the search's cache misses. So they are asked for a step ahead:
    // a cell's neighbours' records when it joins the cavity, their far
    // vertices' points when it is taken from the queue (its records have
    // arrived by then), both before they are read.
    const auto prefetch_neighbours = [&](std::size_t c) {
      for (int i = 0; i <= D; ++i) {
        const std::size_t n = store_[c].n[i] >> facet_bits;
        if constexpr (!marks_in_cells) __builtin_prefetch(store_.mark_address(n));
        __builtin_prefetch(&store_[n]);
      }
    };
    w.cavity.push_back(start_cell);
    store_.mark(start_cell) = in;
    prefetch_neighbours(start_cell);
    for (std::size_t k = 0; k < w.cavity.size(); ++k) {
      const std::size_t c = w.cavity[k];
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = store_[c].n[i];
        const Index far = store_[ref >> facet_bits].v[ref & facet_mask];
        if (far != infinite) __builtin_prefetch(&points_[far]);
      }
      // The sphere tests of c's finite unmarked neighbours, two at a time
      // up to their first bound (half the arithmetic instructions), before
      // the loop below takes their answers in order. A neighbour's mark
      // changes only at its own turn in that loop (c's neighbours are
      // distinct cells), so the loop asks exactly the tests paired here.
      std::array<double, D + 1> det, bound;
      std::uint32_t paired = 0;  // bit i: det[i], bound[i] hold neighbour i's test
      if constexpr (Base::paired_sphere_tests) {
        if (pairing) {
          std::array<int, D + 1> tested;
          int count = 0;
          for (int i = 0; i <= D; ++i) {
            const std::size_t n = store_[c].n[i] >> facet_bits;
            tested[static_cast<std::size_t>(count)] = i;
            count += store_.mark(n) == 0 && !is_infinite(n);
          }
          // An odd one out goes with itself: both lanes its test.
          for (int t = 0; t < count; t += 2) {
            const int i = tested[static_cast<std::size_t>(t)], j = tested[static_cast<std::size_t>(t + 1 < count ? t + 1 : t)];
            const auto tests = this->template pair_sphere_tests<Semi_static_first>(store_[c].n[i] >> facet_bits,
                                                                                   store_[c].n[j] >> facet_bits, q);
            det[i] = tests.det[0], det[j] = tests.det[1];
            bound[i] = tests.bound[0], bound[j] = tests.bound[1];
            paired |= 1u << i | 1u << j;
          }
        }
      }
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = store_[c].n[i];
        const std::size_t n = ref >> facet_bits;
        std::uint8_t& n_mark = store_.mark(n);
        if (n_mark == in) continue;
        if (n_mark != out) {
          if (paired >> i & 1 ? this->template sphere_holds_given<Semi_static_first>(n, q, det[i], bound[i], tally)
                              : this->template in_conflict<Semi_static_first>(n, q, tally)) {
            // n shares a facet with c, whose vertices are all w's zone's: only its far vertex may not be.
            if constexpr (Zoned)
              if (!owns(w, store_[n].v[ref & facet_mask])) return false;
            n_mark = in;
            w.cavity.push_back(n);
            prefetch_neighbours(n);
            continue;
          }
          n_mark = out;
        }
        // Written in place: a facet built on the stack and copied is
        // stored in pieces and reloaded whole, a store-forwarding stall.
        Boundary_facet<D>& f = w.boundary.emplace_back();
        f.vertices = store_[c].v;
        f.vertices[i] = v;
        f.facet = i;
        f.outside = ref;
      }
    }
    return true;
  }

  /// Step 3 for vertices first … last − 1 (points_ holds them), one by one.
  void insert_vertices(std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      insert_serially(static_cast<Index>(k));
      if (progress_ && (k + 1) % progress_stride == 0) progress_->advance(progress_stride);
    }
  }
  void insert_serially(Index v) {
    insert<false>(serial_, v);
    if (tuning_.check_each_insertion && !is_valid())
      throw std::logic_error("Incremental_delaunay: invalid after inserting vertex " + std::to_string(v));
  }

  /// Resets the marks find_cavity set: on the cavity's cells and on the cells
  /// outside its boundary, the only ones it marks (explicit clearing keeps the
  /// marks one byte per slot, a quarter of the epoch counters it replaces: the
  /// marks are one of the search's cache misses).
  void clear_marks(const Worker& w) {
    for (const std::size_t c : w.cavity) store_.mark(c) = 0;
    for (const Boundary_facet<D>& f : w.boundary) store_.mark(f.outside >> facet_bits) = 0;
  }

  /// Zoned insertion: the zone of point p in the current round, by its side
  /// of the cut (which zone does the work is no geometric decision: either
  /// answer gives the same triangulation). Read from the coordinates, which
  /// the predicates load anyway (a per-vertex zone array was a cache miss).
  std::uint8_t zone_of(const Point& p) const { return p.x[cut_axis_] < cut_ ? 0 : 1; }
  /// Zoned insertion: whether vertex v is in w's zone. The infinite vertex
  /// is in every zone above 2D and in none in 2D (zoned_insertion.hpp says why).
  bool owns(const Worker& w, Index v) const {
    if (v == infinite) return D > 2;
    return zone_of(points_[v]) == w.zone;
  }

  /// Step 3: inserts vertex v (points_[v]). Zoned: false, having changed
  /// nothing, when the cavity is not all w's zone's (find_cavity) or w's
  /// slots would not hold the star.
  template <bool Zoned>
  bool insert(Worker& w, Index v) {
    if (!find_cavity<Zoned>(w, points_[v], v)) {
      clear_marks(w);
      return false;
    }
    if constexpr (Zoned)
      if (w.boundary.size() > w.cavity.size() + w.free.size() + (w.end_slot - w.next_slot)) {
        clear_marks(w);
        w.out_of_slots = true;
        return false;
      }

    // 3c. The star: slots of the cavity first, then free ones, then new ones.
    w.stats.conflict_cells += w.cavity.size();
    w.stats.created_cells += w.boundary.size();
    for (const std::size_t c : w.cavity)
      if (!is_infinite(c)) --w.finite_change;
    std::size_t reused = 0;
    w.new_cells.clear();
    // The next walk starts in the first finite new cell: it holds the facet
    // of the start cell (where q was), so it lies at q; the last one, at the
    // far end of the breadth-first cavity, is often a long cell reaching far
    // away (on surface samples, through the inside): walks from it are longer.
    bool started = false;
    for (const Boundary_facet<D>& f : w.boundary) {
      std::size_t s;
      if (reused < w.cavity.size()) s = w.cavity[reused++];
      else if (!w.free.empty()) s = w.free.back(), w.free.pop_back();
      else if constexpr (Zoned) s = w.next_slot++;
      else s = store_.allocate();
      w.new_cells.push_back(static_cast<Index>(s));
      store_[s].v = f.vertices;
      // Its mark must be 0. Above 2D it is: clear_marks reset the slot when it
      // left a cavity, and growing mark_ fills zeros. In 2D the mark is in the
      // record, which a new slot has not initialised.
      if constexpr (marks_in_cells) store_[s].mark = 0;
      store_[s].n[f.facet] = f.outside;
      store_[f.outside >> facet_bits].n[f.outside & facet_mask] = reference(s, f.facet);
      bool finite = true;
      for (int i = 0; i <= D; ++i)
        if (f.vertices[i] == infinite) finite = false;
      if (finite) {
        ++w.finite_change;
        if (!started) w.last = s, started = true;
      }
    }
    if (w.star.glue(store_, w.boundary, w.new_cells, tuning_.ridge_table_only, tuning_.colliding_ridge_keys))
      ++w.stats.ridge_table_stars;
    clear_marks(w);
    for (; reused < w.cavity.size(); ++reused) {
      store_[w.cavity[reused]].v[0] = free_slot;
      w.free.push_back(static_cast<Index>(w.cavity[reused]));
    }
    return true;
  }

  static constexpr std::size_t star_tries = 64;  // start_of_cavity's cap (stars grow fast above 3D)
  Incremental_tuning tuning_;
  Progress_meter* progress_ = nullptr;
  std::size_t finite_cells_ = 0;
  Worker serial_;
  // Zoned insertion: the current round's cut (zone_of).
  int cut_axis_ = 0;
  double cut_ = 0;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
