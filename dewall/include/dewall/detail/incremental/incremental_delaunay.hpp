// The project's own incremental Delaunay construction in E^D (D = 2 … 6):
// Bowyer–Watson (A. Bowyer, "Computing Dirichlet tessellations", and D. F.
// Watson, "Computing the n-dimensional Delaunay tessellation...", both The
// Computer Journal 24(2), 1981) over the project's kernel, every decision an
// exact filtered predicate, ties broken by CGAL's symbolic perturbation, so the
// cells are CGAL's on every input.
//
// Why Bowyer–Watson and not flips: one insertion is one breadth-first search
// over the cells whose spheres hold the new point (the cavity) and one star of
// new cells glued to its boundary, the same code in every dimension; flips
// need a different flip set per dimension (2-3/3-2/4-4 in 3D, more above) and
// are faster only when specialised for one. The fastest codes (hxt, Geogram)
// are cavity based too.
//
// Data (flat arrays, no per-cell allocation; hxt's and Geogram's layout):
//  * points in insertion order, one contiguous array (vertex id = position);
//  * per cell slot, its D + 1 vertex ids and D + 1 packed neighbour references
//    (cell << facet_bits | facet index in that neighbour), positively oriented;
//  * one infinite vertex closing the hull: a hull facet's outer neighbour is an
//    infinite cell, so every point outside the hull has a cavity like any other;
//  * slots of cells a cavity destroys are reused by the new cells;
//  * in 2D and 3D a static filter whose bound comes once from the points' box
//    (kernel/static_filter.hpp) in front of the kernel's semi-static filter,
//    interval and exact stages.
//
// Steps:
//  1. Order: BRIO rounds along a Hilbert curve (brio_order.hpp).
//  2. First simplex: the first D + 1 affinely independent points in that
//     order (exact rank, Affine_basis); the points passed over are inserted
//     next.
//  3. Insert each point p:
//     a. locate: a visibility walk (orientation tests) from the first cell
//        the last insertion created (the one at its point) to a cell
//        holding p, or to an infinite cell whose hull facet p sees;
//     b. cavity: the cells in conflict with p, found breadth-first from there
//        (a finite cell: p inside its perturbed sphere; an infinite cell: p
//        beyond its hull facet, or in that facet's hyperplane and in conflict
//        with the finite cell behind it — see in_conflict);
//     c. star: each boundary facet of the cavity plus p is a new cell; the new
//        cells are glued to the outside across that facet and to each other
//        across their facets through p: in 2D and 3D through a table indexed
//        by the facets' directed keys (glue_star_directed), above 3D and for
//        very large cavities by their D − 1 other vertices in a hash table.
//  4. Both cores: from zoned_insertion_threshold points on (the sample from
//     half as many), step 3 runs in rounds of two zones (half-spaces), each
//     a task inserting only where its walk and cavity stay in its own cells
//     (insert_in_zones: why the tasks share nothing and the result is the
//     same for any thread count).
// Expected O(n log n) for points in general position (BRIO), the walk and the
// cavities O(1) per point on well-spread data.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#if __has_include(<sys/mman.h>) && __has_include(<unistd.h>)
#include <sys/mman.h>
#include <unistd.h>
#define DEWALL_CAN_RELEASE_PAGES 1
#endif

#include "dewall/detail/common/assert.hpp"
#include "dewall/detail/common/box.hpp"
#include "dewall/detail/common/cell_graph_output.hpp"
#include "dewall/detail/common/hashing.hpp"
#include "dewall/detail/common/index.hpp"
#include "dewall/detail/common/input.hpp"
#include "dewall/detail/common/parallel.hpp"
#include "dewall/detail/incremental/brio_order.hpp"
#include "dewall/detail/incremental/scratch_list.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "dewall/kernel/static_filter.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// Counters of one construction (what the profile of a run is made of).
struct Incremental_statistics {
  std::size_t walk_steps = 0;     // cells crossed while locating
  std::size_t conflict_cells = 0; // cells destroyed, summed over insertions
  std::size_t created_cells = 0;  // cells made, summed over insertions
  std::size_t ridge_table_stars = 0;  // stars glued through the ridge hash table
  std::size_t zoned_points = 0;   // points a zone inserted (insert_in_zones)
  std::size_t zone_rounds = 0;    // rounds whose zones ran (insert_in_zones)
  std::size_t near_cut_points = 0;  // waits untried beside the cut (near_cut), summed over rounds
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
    semi_static_first_windows += o.semi_static_first_windows;
    return *this;
  }
};

/// The Delaunay triangulation of distinct points, built incrementally.
/// Vertex ids are positions in the insertion order (`input_index` maps them
/// back); cells live in slots, some of them free.
template <int D>
class Incremental_delaunay {
 public:
  using Point = kernel::Point_d<D>;
  using Cell = std::array<Index, D + 1>;
  /// The vertex id of the infinite vertex.
  static constexpr Index infinite = Cell_graph<D>::infinite_vertex;
  /// A free slot's first vertex.
  static constexpr Index free_slot = Cell_graph<D>::free_slot;
  /// Bits of a neighbour reference that hold the facet index.
  static constexpr int facet_bits = Cell_graph<D>::facet_bits;

  /// Triangulates `count` points (distinct, finite): point k's coordinates
  /// are coordinates(k) (an array of D doubles), its id for the caller id(k)
  /// (input_index returns it; both are called from several threads at
  /// once). Returns false when the points do not span E^D
  /// (the object then holds nothing usable). \throws std::length_error beyond
  /// max_slots cells (2^30 in 2D and 3D, 2^29 above); after an exception the
  /// object is unusable.
  template <class Coordinates, class Id>
  bool build(std::size_t count, Coordinates&& coordinates, Id&& id) {
    return build(count, coordinates, id, nullptr);
  }
  /// As build(count, coordinates, id), the static filter made for the points
  /// inside `filter_box` (which must hold these points and every point
  /// insert_more will insert; null: the points' bounding box).
  template <class Coordinates, class Id>
  bool build(std::size_t count, Coordinates&& coordinates, Id&& id, const Box<D>* filter_box) {
    return build(count, coordinates, id, filter_box, [] {});
  }
  /// As build(count, coordinates, id, filter_box), calling gathered() once
  /// coordinates and id will not be called again (the points are copied in
  /// insertion order; none is inserted yet): the caller may free its points.
  template <class Coordinates, class Id, class Gathered>
  bool build(std::size_t count, Coordinates&& coordinates, Id&& id, const Box<D>* filter_box, Gathered&& gathered) {
    if (count < static_cast<std::size_t>(D + 1)) return false;
    const Box<D> box = bounding_box<D>(count, coordinates);
    return build_in_order(count, brio_order<D>(count, coordinates, box), box, coordinates, id, filter_box, gathered);
  }
  /// As build(count, coordinates, id, nullptr, gathered) for points that may
  /// repeat (finite): of equal points (−0 and +0 alike) only the first, the
  /// smallest k, becomes a vertex (vertices() counts them), as CGAL keeps the
  /// vertex already there. The BRIO order finds the repeats on the way
  /// (brio_order_of_distinct), so the caller needs no
  /// kernel::first_occurrences beforehand. Returns false when the distinct
  /// points do not span E^D (fewer than D + 1 of them included).
  template <class Coordinates, class Id, class Gathered>
  bool build_dropping_repeats(std::size_t count, Coordinates&& coordinates, Id&& id, Gathered&& gathered) {
    if (count < static_cast<std::size_t>(D + 1)) return false;
    const Box<D> box = bounding_box<D>(count, coordinates);
    return build_in_order(count, brio_order_of_distinct<D>(count, coordinates, box), box, coordinates, id, nullptr,
                          gathered);
  }

 private:
  /// build's steps once the insertion order is known: `order` holds the
  /// indices (among `input_count`, whose box is `box`) of the points to insert.
  template <class Coordinates, class Id, class Gathered>
  bool build_in_order(std::size_t input_count, std::vector<std::uint32_t> order, const Box<D>& box,
                      Coordinates& coordinates, Id& id, const Box<D>* filter_box, Gathered& gathered) {
    const std::size_t count = order.size();
    const Box<D>& filter_bounds = filter_box ? *filter_box : box;
    static_filter_ =
        kernel::Static_filter_d<D>(filter_bounds.lo, filter_bounds.hi, lattice_unit(input_count, coordinates));
    if (!start(coordinates, order)) return false;
    reserve(expected_cells(count));
    points_.resize(count);
    input_.resize(count);
    // A gather from the whole input (a cache miss a point): in parallel.
    parallel_ranges(count, 1 << 14, [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t k = range.begin(); k < range.end(); ++k) {
        points_[k].x = coordinates(order[k]);
        input_[k] = static_cast<Index>(id(order[k]));
      }
    });
    std::vector<std::uint32_t>().swap(order);
    gathered();
    // Cells per point range from 6.5 (volume) to 20 (samples of a torus) in
    // 3D, and more above: the first sixteenth of the BRIO order (its first
    // rounds: a random sample) predicts the count. When the arrays would
    // overflow (the count an eighth above the prediction), they are enlarged
    // now, with room to spare (the count per point still grows on surfaces:
    // on a 10^6-point torus an eighth more than the sample's was too little),
    // so that they grow once, early, instead of doubling late (each doubling
    // copies the cells onto fresh pages: 13 % of a 10^6-point torus's time).
    // Volume data stays in the first reservation (reallocating it anyway
    // measured up to 25 % slower).
    const std::size_t sample = std::max<std::size_t>(count / 16, D + 1);
    insert_sample(sample, box);
    if (sample < count) {
      const double per_point = static_cast<double>(cells_.size()) / static_cast<double>(sample);
      const double predicted = per_point * static_cast<double>(count);
      if (predicted * 1.125 > static_cast<double>(cells_.capacity())) {
        try {
          reserve(static_cast<std::size_t>(predicted * 1.5));
        } catch (const std::bad_alloc&) {  // more than the system grants at once: grow as needed
        }
      }
    }
    if (count > sample && count - sample >= zoned_insertion_threshold) insert_in_zones(sample, count, box);
    else insert_vertices(sample, count);
    return true;
  }

 public:

  /// Inserts `count` more points after a successful build (each distinct from
  /// every vertex, and inside the box the static filter was made for: the
  /// `filter_box` given to build, else build's points' box), in BRIO order;
  /// ids as in build. The triangulation is then that of all points inserted.
  /// (dewall::mpi adds the halo points of each round this way.)
  template <class Coordinates, class Id>
  void insert_more(std::size_t count, Coordinates&& coordinates, Id&& id) {
    if (count == 0) return;
    const std::vector<std::uint32_t> order = brio_order<D>(count, coordinates);
    if (static_filter_.on_lattice()) static_filter_.admit_lattice(lattice_unit(count, coordinates));
    const std::size_t first = points_.size();
    points_.resize(first + count);
    input_.resize(first + count);
    for (std::size_t k = 0; k < count; ++k) {
      points_[first + k].x = coordinates(order[k]);
      input_[first + k] = static_cast<Index>(id(order[k]));
    }
    insert_vertices(first, first + count);
  }

  /// Room for `cells` cell slots, so that the cell arrays grow without
  /// copying up to that many: a copy writes fresh pages the kernel must clear
  /// first (measured: docs/engines.md) and holds the old and
  /// the new array at once (dewall::mpi counts each rank's peak memory).
  /// Pages are touched only when cells use them: what is reserved and never
  /// used stays unbacked address space. build() reserves expected_cells.
  void reserve(std::size_t cells) {
    cells_.reserve(std::min(cells, max_slots));
    if constexpr (!marks_in_cells) mark_.reserve(std::min(cells, max_slots));
  }
  /// Cell slots to reserve for `count` points: a little above the cells of
  /// uniform points (2 per point in the plane, 6.8 in space), so that volume
  /// data never grows; surfaces (up to 16 per point) grow once or twice.
  /// Above 3D the count per point varies too much with the input (32 to 1000
  /// and more) to reserve: the arrays grow.
  static constexpr std::size_t expected_cells(std::size_t count) {
    return D == 2 ? 3 * count : D == 3 ? 8 * count : 0;
  }
  /// The number of vertices (finite), ids 0 … vertices() − 1.
  std::size_t vertices() const { return points_.size(); }

  /// Tests: run is_valid() after every serial insertion and after every
  /// round of zoned insertion (O(n) each), throwing std::logic_error at the
  /// first failure.
  bool check_each_insertion = false;
  /// Tests: whether the static filter decides every predicate exactly (the
  /// points lie on a small lattice: kernel/static_filter.hpp).
  bool static_filter_exact() const { return static_filter_.exact(); }
  /// Points after build()'s sample from which they are inserted in zones
  /// (insert_in_zones: in parallel, the same cells and slots for any number
  /// of threads), and twice the sample's rest from which that is zoned too
  /// (insert_sample); tests lower it.
  std::size_t zoned_insertion_threshold = std::size_t{1} << 16;
  /// A zone whose first zone_probe tries fail more than a quarter of the
  /// time gives up the round, and the rounds end (the points near_cut
  /// leaves untried are no tries; running out of slots is no failure): on a
  /// torus cut through its hole, whose cells cross every such plane, 40 % of
  /// the points waited after long partial searches, and one thread took
  /// twice its time (tests lower it). A zone of at least patient_zone_points
  /// gives up only when more than half of its first zone_probe tries, or a
  /// quarter of its first 4·zone_probe, failed: a zone's first points lie
  /// where the points' curve enters it, beside the cut, where more cavities
  /// cross it (2·10^6 uniform points: 27 % of the first 2,048 waited, then
  /// the zone's 937,500 points went one by one, and two threads took one's
  /// time: 3.54 s, patient 2.01 s). Smaller zones keep the quarter: there
  /// giving up costs little, and going on can cost more than it gives (a
  /// torus with noise, 10^5 points: patient, one thread 0.195 → 0.231 s,
  /// two 0.188 → 0.125 s). (These figures are from before near_cut, when
  /// every point was tried and every wait counted.)
  std::size_t zone_probe = 2048;
  /// Zoned insertion: points this many point spacings or nearer the cut
  /// wait for the next round without trying (near_cut; tests set 0: none).
  /// 2, 2.5 and 3 measured alike on uniform 3D 10^6 points (walk steps 2.31
  /// → 1.73 million; one thread 1–2.5 % faster in rows and drivers, two 4 %).
  double near_cut_spacings = 2;
  /// Tests: scales the new slots each zone gets (below 1 zones run out of
  /// slots early, and their points wait for the next round).
  double zone_slots_scale = 1;
  /// The sphere tests of one window of choose_filter_order (tests set fewer,
  /// so that the semi-static bound first runs on small inputs).
  std::uint32_t filter_order_window = 1u << 16;
  /// Tests: glue every star through the ridge hash table (in 2D and 3D only
  /// cavities of 127 boundary vertices or more take it otherwise).
  bool ridge_table_only = false;
  /// Tests: ridge keys cut to 3 bits, so that most key matches are no
  /// ridge's and same_ridge must tell them apart.
  bool colliding_ridge_keys = false;

  /// Tests: the cells in conflict with q (not a vertex), as insertion would
  /// find them (the walk, then the breadth-first search), sorted.
  /// q may lie outside the points' box: the static filter, whose bound
  /// assumes it inside, is off for the call.
  std::vector<std::size_t> cavity(const Point& q) {
    const auto filter = std::exchange(static_filter_, kernel::Static_filter_d<D>());
    find_cavity<false>(serial_, q, infinite);
    clear_marks(serial_);
    static_filter_ = filter;
    std::vector<std::size_t> cells(serial_.cavity.begin(), serial_.cavity.end());
    std::sort(cells.begin(), cells.end());
    return cells;
  }
  /// build() for points given as Point_d, their ids their positions.
  bool build(std::span<const Point> points) {
    return build(points.size(), [&](std::size_t k) -> const std::array<double, D>& { return points[k].x; },
                 [](std::size_t k) { return k; });
  }

  /// Cell slots, free ones included: cells are 0 … slots() − 1.
  std::size_t slots() const { return cells_.size(); }
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
  const Cell& cell(std::size_t c) const { return cells_[c].v; }
  /// The cell across the facet opposite vertex i of c.
  std::size_t neighbor(std::size_t c, int i) const { return cells_[c].n[i] >> facet_bits; }
  /// The caller's id of vertex v (finite).
  Index input_index(Index v) const { return input_[v]; }
  /// input_index of every vertex, by vertex id.
  std::span<const Index> input_indices() const { return input_; }
  /// The records of slots first … last − 1 (cell_graph_output.hpp says what they hold).
  std::span<const Cell_record<D>> records(std::size_t first, std::size_t last) const {
    return {cells_.data() + first, last - first};
  }
  std::size_t finite_cells() const { return finite_cells_ + static_cast<std::size_t>(serial_.finite_change); }
  const Incremental_statistics& statistics() const { return serial_.stats; }

  /// For a caller that reads the cells out once, in slot order, and then
  /// drops the object (the collecting output): frees the points and the
  /// search's marks now (above 2D; in 2D they are in the cells). Afterwards
  /// only slots(), is_free(), is_infinite(), holds_finite_cell(), cell(),
  /// records(), input_index(), input_indices() and finite_cells() may be
  /// called, and after
  /// release_slots(first, last) on none of those slots.
  void finish_for_reading() {
    std::vector<Point>().swap(points_);
    std::vector<std::uint8_t>().swap(mark_);
  }
  /// Slots first … last − 1 are not read again: the whole pages within
  /// them go back to the system (madvise MADV_DONTNEED; on Linux they would
  /// read as zeros). So the output, growing as the cells are read, does not
  /// add to their peak: at 10^6 points 218 MB of cells and 108 MB of
  /// collected simplices. A page shared with slots outside the range stays
  /// (the caller may still be reading those: the hand-over releases each
  /// block from the task that read it, in parallel); it goes with the object.
  /// Nothing below 8 MB of cells (then the output is small too): the pages
  /// given back there were faulted in again by the next construction of the
  /// process (10^4 points on a circle, built 100 times: page faults and
  /// madvise 5 % of the time). Without <sys/mman.h>, nothing.
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

  /// Checks the data structure (tests): neighbours are other cells, mutual
  /// (each refers back to the facet that refers to it) and share exactly the
  /// D vertices of that facet; finite cells are positively oriented.
  bool is_valid() const {
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
      if (!is_infinite(c) && orientation(c, -1, nullptr) != kernel::POSITIVE) return false;
    }
    return true;
  }

 private:
  struct Worker;
  static constexpr std::size_t no_cell = std::numeric_limits<std::size_t>::max();
  static constexpr std::uint32_t facet_mask = (1u << facet_bits) - 1;
  // The largest reference stays below the ridge table's two sentinels
  // (none = 2^32 − 1, taken = 2^32 − 2).
  static constexpr std::size_t max_slots = ((std::size_t{1} << 32) - 2) >> facet_bits;
  static std::uint32_t reference(std::size_t c, int i) {
    return static_cast<std::uint32_t>(c) << facet_bits | static_cast<std::uint32_t>(i);
  }

  /// Orientation of cell c (finite) with vertex `replaced` (−1: none) replaced by q.
  kernel::Sign orientation(std::size_t c, int replaced, const Point* q) const {
    const auto refs = orientation_points(c, replaced, q);
    if (const auto s = static_filter_.orientation(refs)) return *s;
    return kernel::orientation_d<D>(refs);
  }
  /// Cell c's vertices, the one at position `replaced` (if any) replaced by q.
  kernel::Point_refs<D, D + 1> orientation_points(std::size_t c, int replaced, const Point* q) const {
    kernel::Point_refs<D, D + 1> refs;
    for (int k = 0; k <= D; ++k) refs[k] = k == replaced ? q : &points_[cells_[c].v[k]];
    return refs;
  }
  /// Finite cell c's vertices, then q.
  kernel::Point_refs<D, D + 2> sphere_points(std::size_t c, const Point& q) const {
    kernel::Point_refs<D, D + 2> refs;
    for (int k = 0; k <= D; ++k) refs[k] = &points_[cells_[c].v[k]];
    refs[D + 1] = &q;
    return refs;
  }

  /// The cavity search's count of its sphere tests, and of those the static
  /// filter's box-wide bound left (counted only when it is tried first).
  struct Filter_tally {
    std::uint32_t tests = 0, box_bound_left = 0;
  };
  /// Whether q lies inside the perturbed sphere of finite cell c, the
  /// semi-static bound tried before the box's when Semi_static_first (3D;
  /// choose_filter_order says when). Inlined in both searches (GCC kept it
  /// out of line in the zoned one: a call per test).
  template <bool Semi_static_first>
  [[gnu::always_inline]] bool sphere_holds(std::size_t c, const Point& q, Filter_tally& tally) const {
    const auto refs = sphere_points(c, q);
    kernel::Sign s;
    if constexpr (D == 3) {
      ++tally.tests;
      s = static_filter_.template side_of_oriented_sphere_sign<Semi_static_first>(refs, tally.box_bound_left);
    } else {
      s = static_filter_.side_of_oriented_sphere_sign(refs);
    }
    if (s != kernel::ZERO) return s == kernel::POSITIVE;
    return exact_zero_perturbed(refs);
  }
  /// sphere_holds for an exact zero: the perturbation's orientations,
  /// through the static filter first (the points are input points, in its
  /// box). Out of line: inlined, it slowed the cavity search on inputs that
  /// never tie.
  [[gnu::noinline]] bool exact_zero_perturbed(const kernel::Sphere_points<D>& refs) const {
    kernel::count(kernel::predicate_stats().side_of_sphere[D].perturbed);
    return kernel::perturbed_side_of_sphere<D>(
               refs,
               [&](const kernel::Orientation_points<D>& o) {
                 if (const auto sign = static_filter_.orientation(o)) return *sign;
                 return kernel::orientation_d<D>(o);
               },
               [](const Point& a, const Point& b) { return kernel::compare_lexicographically(a, b) == kernel::SMALLER; }) ==
           kernel::ON_POSITIVE_SIDE;
  }

  /// The exponent of the coarsest power of two of which every coordinate of
  /// the `count` points is a multiple (INT_MIN where the static filter is
  /// not offered: no use scanning).
  template <class Coordinates>
  static int lattice_unit(std::size_t count, Coordinates&& coordinates) {
    if constexpr (!kernel::Static_filter_d<D>::available) return INT_MIN;
    int unit = INT_MAX;
    for (std::size_t k = 0; k < count; ++k) {
      const auto& x = coordinates(k);
      for (int j = 0; j < D; ++j) unit = std::min(unit, kernel::lowest_bit_exponent(x[j]));
    }
    return unit;
  }

  /// Whether cell c is in conflict with q: destroyed when q is inserted.
  /// An infinite cell is when q lies beyond its hull facet (the cell with the
  /// infinite vertex replaced by q positively oriented). When q lies in the
  /// facet's hyperplane it is exactly when the finite cell behind the facet
  /// is: if that cell goes, the facet is on no finite cell any more (a cell
  /// of q and the facet would be flat) and must go too; if it stays, the facet
  /// stays a hull facet (q does not lie beyond it). This is the answer CGAL's
  /// perturbed in-circle test on the facet gives, by that same argument.
  /// Inlined into the searches (GCC called it: uniform 10^6 −1 %).
  template <bool Semi_static_first>
  [[gnu::always_inline]] bool in_conflict(std::size_t c, const Point& q, Filter_tally& tally) const {
    const int i = infinite_position(c);
    if (i > D) return sphere_holds<Semi_static_first>(c, q, tally);
    const kernel::Sign s = orientation(c, i, &q);
    if (s != kernel::ZERO) return s == kernel::POSITIVE;
    return sphere_holds<Semi_static_first>(neighbor(c, i), q, tally);
  }
  bool in_conflict(std::size_t c, const Point& q) const {
    Filter_tally unused;
    return in_conflict<false>(c, q, unused);
  }

  /// Steps 1–2: the first simplex and its D + 1 infinite neighbours; `order`
  /// becomes the insertion order with the simplex's points first.
  template <class Coordinates>
  bool start(Coordinates&& coordinates, std::vector<std::uint32_t>& order) {
    Affine_basis<D> basis(coordinates(order[0]));
    std::vector<std::uint32_t> simplex{order[0]}, passed_over;
    std::size_t k = 1;
    for (; k < order.size() && basis.rank() < D; ++k) {
      if (basis.add(coordinates(order[k]))) simplex.push_back(order[k]);
      else passed_over.push_back(order[k]);
    }
    if (basis.rank() < D) return false;
    // order = simplex, passed over, rest (k … end), kept in place.
    std::copy_backward(simplex.begin(), simplex.end(),
                       std::copy_backward(passed_over.begin(), passed_over.end(), order.begin() + static_cast<std::ptrdiff_t>(k)));

    points_.resize(D + 1);
    for (int i = 0; i <= D; ++i) points_[i].x = coordinates(order[i]);
    Cell first;
    for (int i = 0; i <= D; ++i) first[i] = static_cast<Index>(i);
    cells_.assign(1, Record{first, {}, {}});
    if (orientation(0, -1, nullptr) == kernel::NEGATIVE) std::swap(cells_[0].v[0], cells_[0].v[1]);
    // The infinite cell across facet i: the simplex with vertex i replaced by
    // the infinite vertex and two others swapped, so that putting a point
    // beyond the facet in the infinite vertex's place orients it positively.
    for (int i = 0; i <= D; ++i) {
      Cell c = cells_[0].v;
      c[i] = infinite;
      std::swap(c[(i + 1) % (D + 1)], c[(i + 2) % (D + 1)]);
      cells_.push_back(Record{c, {}, {}});
      cells_[0].n[i] = reference(cells_.size() - 1, i);
      cells_.back().n[i] = reference(0, i);
    }
    // The infinite cells meet each other across their facets through the infinite vertex.
    for (int a = 0; a <= D; ++a)
      for (int b = a + 1; b <= D; ++b) {
        const std::size_t ca = 1 + a, cb = 1 + b;
        // Cell a lacks vertex a of the simplex, cell b lacks b: the facet of a
        // opposite (the position of) vertex b, and of b opposite vertex a.
        const int ia = position(ca, cells_[0].v[b]), ib = position(cb, cells_[0].v[a]);
        cells_[ca].n[ia] = reference(cb, ib);
        cells_[cb].n[ib] = reference(ca, ia);
      }
    serial_.free.clear();
    serial_.new_cells.clear();  // start_of_cavity's candidates: none yet
    serial_.stats = {};
    serial_.finite_change = 0;
    finite_cells_ = 1;
    serial_.last = 0;
    if constexpr (!marks_in_cells) mark_.assign(cells_.size(), 0);
    return true;
  }

  int position(std::size_t c, Index v) const {
    for (int i = 0; i <= D; ++i)
      if (cells_[c].v[i] == v) return i;
    DEWALL_ASSERT(false);
    return -1;
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
      for (int i = 0; i <= D; ++i) __builtin_prefetch(&cells_[cells_[c].n[i] >> facet_bits]);  // the next step's record
      rotation = rotation * 1103515245u + 12345u;  // varies the first facet tried
      const int first = static_cast<int>((rotation >> 16) % (D + 1));
      for (int k = 0; k <= D; ++k) {
        const int i = (first + k) % (D + 1);
        const std::size_t next = neighbor(c, i);
        if (next == previous) continue;
        if (orientation(c, i, &q) == kernel::NEGATIVE) {
          if constexpr (Zoned)
            if (!owns(w, cells_[next].v[cells_[c].n[i] & facet_mask])) {
              // The next walk starts here, nearer the next point than the
              // last insertion's cell (all c's vertices are w's: it is as
              // good a start). In 2D, points beyond the early hull each
              // walked ~500 steps from the same far cell (2D uniform 10^6:
              // walk steps 1.36 → 1.15 million).
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
  /// polygon's long thin cells (10^5 points on a circle: 5 steps a point,
  /// most of them failing the star tries first: their sphere tests are near
  /// ties the filters cannot decide). Here the star's hull edges are tried
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
  // Points on a circle, 10^5: 8 edges each way left 1.9 walk steps a point, 16 left 1.2 (2–3 %
  // less time), 32 and 64 no less (the distances along the hull fall off geometrically).
  static constexpr int hull_steps = 16;

  /// Whether the filters prove cell c in conflict with q (false when they
  /// cannot tell: on near-cospherical points the exact stages would cost
  /// more than the walk they save). A sphere test goes on to the semi-static
  /// filter, on the static one's determinant: on surface samples the static
  /// bound alone left most tries undecided (torus with noise, 10^6 points:
  /// walk steps a point 5.9 -> 3.3, time −9 %).
  bool proven_in_conflict(std::size_t c, const Point& q) const {
    const int i = infinite_position(c);
    const auto s = i > D ? static_filter_.side_of_oriented_sphere_filtered(sphere_points(c, q))
                         : static_filter_.orientation(orientation_points(c, i, &q));
    return s && *s == kernel::POSITIVE;
  }

  /// A boundary facet of the cavity: the new cell's vertices (the old
  /// cell's, with the one opposite the facet replaced by the new point) and
  /// the neighbour reference outside.
  struct Boundary_facet {
    Cell vertices;
    int facet;
    std::uint32_t outside;
  };

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
  /// tests (surface samples: a surface's cells are small against its box;
  /// torus with noise, 10^6 points, 57 % of them), its branch mispredicts,
  /// and the semi-static bound (never looser) first is cheaper. Decided per
  /// window of 2^16 tests from the share the box's bound left in the last:
  /// over a quarter, the semi-static first for the next 15 windows (which do
  /// not count: a count costs in that order), then the box's first again for
  /// one that measures. The order changes no answer, only its cost. Engine
  /// driver, one thread, alternated, against the box's bound always first:
  /// torus with noise 10^6 3,048–3,076 → 2,876–2,891 ms (the semi-static first
  /// always: 2,863–2,879), uniform 10^6 2,717–2,733 → 2,728–2,764 (the
  /// semi-static always first: 2,888–2,965), torus without noise 3·10^5
  /// 2,750–2,793 → 2,642–2,669, points on a sphere 10^5 unchanged.
  void choose_filter_order(Worker& w, const Filter_tally& tally) {
    w.filter_tally.tests += tally.tests;
    w.filter_tally.box_bound_left += tally.box_bound_left;
    if (w.filter_tally.tests < filter_order_window) return;
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
    w.cavity.clear();
    w.boundary.clear();
    const std::size_t start_cell = start_of_cavity<Zoned>(w, q);
    if constexpr (Zoned)
      if (start_cell == no_cell) return false;
    DEWALL_EXPENSIVE_ASSERT(in_conflict(start_cell, q));

    // 3b. The cavity, breadth-first; mark(c): in conflict or not (clear_marks resets both).
    constexpr std::uint8_t in = 1, out = 2;
    // The neighbours' marks and records, then the points of their vertices
    // across the shared facets, are the search's cache misses (measured on a
    // torus: most of find_cavity's time). So they are asked for a step ahead:
    // a cell's neighbours' records when it joins the cavity, their far
    // vertices' points when it is taken from the queue (its records have
    // arrived by then), both before they are read.
    const auto prefetch_neighbours = [&](std::size_t c) {
      for (int i = 0; i <= D; ++i) {
        const std::size_t n = cells_[c].n[i] >> facet_bits;
        if constexpr (!marks_in_cells) __builtin_prefetch(&mark_[n]);
        __builtin_prefetch(&cells_[n]);
      }
    };
    w.cavity.push_back(start_cell);
    mark(start_cell) = in;
    prefetch_neighbours(start_cell);
    for (std::size_t k = 0; k < w.cavity.size(); ++k) {
      const std::size_t c = w.cavity[k];
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = cells_[c].n[i];
        const Index far = cells_[ref >> facet_bits].v[ref & facet_mask];
        if (far != infinite) __builtin_prefetch(&points_[far]);
      }
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = cells_[c].n[i];
        const std::size_t n = ref >> facet_bits;
        std::uint8_t& n_mark = mark(n);
        if (n_mark == in) continue;
        if (n_mark != out) {
          if (in_conflict<Semi_static_first>(n, q, tally)) {
            // n shares a facet with c, whose vertices are all w's zone's: only its far vertex may not be.
            if constexpr (Zoned)
              if (!owns(w, cells_[n].v[ref & facet_mask])) return false;
            n_mark = in;
            w.cavity.push_back(n);
            prefetch_neighbours(n);
            continue;
          }
          n_mark = out;
        }
        // Written in place: a facet built on the stack and copied is
        // stored in pieces and reloaded whole, a store-forwarding stall
        // (measured in 2D: the hottest instruction of the search).
        Boundary_facet& f = w.boundary.emplace_back();
        f.vertices = cells_[c].v;
        f.vertices[i] = v;
        f.facet = i;
        f.outside = ref;
      }
    }
    return true;
  }

  /// Step 3 for vertices first … last − 1 (points_ holds them), one by one.
  void insert_vertices(std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) insert_serially(static_cast<Index>(k));
  }
  void insert_serially(Index v) {
    insert<false>(serial_, v);
    if (check_each_insertion && !is_valid())
      throw std::logic_error("Incremental_delaunay: invalid after inserting vertex " + std::to_string(v));
  }

  /// Resets the marks find_cavity set: on the cavity's cells and on the cells
  /// outside its boundary, the only ones it marks (explicit clearing keeps the
  /// marks one byte per slot, a quarter of the epoch counters it replaces: the
  /// marks are one of the search's cache misses).
  void clear_marks(const Worker& w) {
    for (const std::size_t c : w.cavity) mark(c) = 0;
    for (const Boundary_facet& f : w.boundary) mark(f.outside >> facet_bits) = 0;
  }

  /// Zoned insertion: the zone of point p in the current round, by its side
  /// of the cut (which zone does the work is no geometric decision: either
  /// answer gives the same triangulation). Read from the coordinates, which
  /// the predicates load anyway (a per-vertex zone array was a cache miss).
  std::uint8_t zone_of(const Point& p) const { return p.x[cut_axis_] < cut_ ? 0 : 1; }
  /// Zoned insertion: whether vertex v is in w's zone. The infinite vertex
  /// is in every zone above 2D and in none in 2D (insert_in_zones says why).
  bool owns(const Worker& w, Index v) const {
    if (v == infinite) return D > 2;
    return zone_of(points_[v]) == w.zone;
  }

  /// Inserts points D + 1 … sample − 1 (after start): its own first sixteenth
  /// one by one, the rest in zones when that is large enough for them (half
  /// zoned_insertion_threshold: from about 5.6·10^5 points on by default; at
  /// 10^7 the sample's 625,000 points inserted on one core were a ninth of a
  /// two-core run, at 10^6 its 62,500 a tenth — 0.10 of 1.07 s; zoned,
  /// 0.07 s, the one-thread time unchanged). The zones' result is the same
  /// for any thread count (insert_in_zones), so the output stays the same
  /// bytes.
  void insert_sample(std::size_t sample, const Box<D>& box) {
    const std::size_t inner = std::max<std::size_t>(sample / 16, D + 1);
    if (sample - inner >= zoned_insertion_threshold / 2) {
      insert_vertices(D + 1, inner);
      insert_in_zones(inner, sample, box);
    } else {
      insert_vertices(D + 1, sample);
    }
  }

  /// Step 3 for vertices first … last − 1 in rounds of two zones, each zone
  /// inserted by its own task (in parallel when the arena has two threads).
  ///
  /// A round cuts space by a plane, at the median of its points' coordinate
  /// along one axis (the box's longest first, another each round); every
  /// vertex, old or new, is in the zone of its side. A zone inserts its
  /// points in their order, each only when its walk and its cavity stay in
  /// cells whose vertices are all the zone's; else the point waits for the
  /// next round (the cavity's cells not yet changed). Why no two zones touch
  /// the same data: a zone changes only cells with all D + 1 vertices its
  /// own (the cavity), and the neighbour reference and mark of cells
  /// sharing a facet with one, which have D of its vertices, so they are no
  /// other zone's cavity and share no facet with one (two facets of a cell
  /// share D − 1 vertices; above 2D the infinite vertex, every zone's, is at
  /// most one of them, so D − 1 ≥ 2 leaves one of the zone's own; in 2D a
  /// hull cell {t, ∞, u} would border both zones, so there ∞ is no zone's
  /// and points outside the hull wait); the walk
  /// starts in the zone's own cells and stops before any other. So each
  /// zone's work reads and writes only what no other zone changes in the
  /// round, and its result (which points wait, which slots hold which
  /// cells: its slots are fixed before the round) depends on the round's
  /// start alone, not on the threads' timing: the cells, their slots and
  /// the output order are the same for any number of threads. The
  /// Delaunay triangulation (perturbed) is unique, so it is CGAL's in any
  /// insertion order. The points still waiting after D rounds are inserted
  /// one by one.
  /// Cf. hxt (Marot, Pellerin, Remacle 2019), which partitions along a
  /// Hilbert curve and lets threads race; here the partition is by planes
  /// and nothing races.
  void insert_in_zones(std::size_t first, std::size_t last, const Box<D>& box) {
    std::vector<Index> pending(last - first);
    for (std::size_t k = first; k < last; ++k) pending[k - first] = static_cast<Index>(k);
    std::array<int, D> axes;
    for (int j = 0; j < D; ++j) axes[j] = j;
    std::stable_sort(axes.begin(), axes.end(),
                     [&](int a, int b) { return box.hi[a] - box.lo[a] > box.hi[b] - box.lo[b]; });
    // near_cut's unit: the box's mean extent (geometric: its volume's D-th
    // root, without the product's overflow at extreme scales). None (the
    // rule off) when an extent overflows or near_cut_spacings is not > 0.
    double log_extents = 0;
    for (int j = 0; j < D; ++j) log_extents += std::log(box.hi[j] - box.lo[j]);
    near_cut_scale_ = 1 / (std::exp(log_extents / D) * near_cut_spacings);
    if (!(std::isfinite(near_cut_scale_) && near_cut_scale_ > 0)) near_cut_scale_ = 0;
    std::array<Worker, 2> workers;
    for (int round = 0; round < D && !pending.empty() && pending.size() >= zoned_insertion_threshold / 16; ++round) {
      const int axis = axes[round];
      // Cells per point so far (it grows on surfaces): each zone's new slots are sized from it.
      const double per_point =
          static_cast<double>(slots() - serial_.free.size()) / static_cast<double>(last - pending.size());
      // The median of at most cut_sample points spread evenly over the
      // order (it is spread over space; the zones need not be equal: the
      // full median was 2 % of a one-thread 2D run at 10^6 points). Its
      // array is gone before the round: the cells' peak.
      const double cut = [&] {
        const std::size_t stride = (pending.size() + cut_sample - 1) / cut_sample;
        std::vector<double> along;
        along.reserve(pending.size() / stride + 1);
        for (std::size_t k = 0; k < pending.size(); k += stride) along.push_back(points_[pending[k]].x[axis]);
        const auto median = along.begin() + static_cast<std::ptrdiff_t>(along.size() / 2);
        std::nth_element(along.begin(), median, along.end());
        return *median;
      }();
      cut_axis_ = axis;
      cut_ = cut;
      near_cut_inserted_ = static_cast<double>(last - pending.size());
      std::array<std::vector<Index>, 2> points;
      for (const Index v : pending) points[zone_of(points_[v])].push_back(v);
      for (std::size_t z = 0; z < 2; ++z) workers[z].zone = static_cast<std::uint8_t>(z);
      // Where the zones' walks start: for every hint_spacing-th point of a
      // zone, the cell holding it now, when all its vertices are the zone's
      // (found serially, by walking from one to the next: nothing changes
      // yet). Within the round only the zone changes such a slot; so when
      // not free it holds a cell of the zone's (usually near: a slot is
      // reused by the cavity that freed it). Each walk starts where the last
      // one ended, beyond the hull too (only finite cells had been kept: on a
      // circle, every hinted point beyond the hull, each walk went from the
      // same old cell, 34,000 extra steps at 10^5 points).
      //
      // In 2D a point beyond the hull waits (owns: ∞ is no zone's; the hull
      // does not change within a round). As soon as more than 1 in `waits`
      // of all a zone's hinted points lie there — the share of its first
      // tries whose failing makes insert_zone give up, here estimated from
      // the hints — the rounds end, no slot taken: on a circle every point
      // is on the hull, and the zones' tries were 2 % of a one-thread run at
      // 10^5 points. The hints are found serially, so the answer is the same
      // for any number of threads.
      std::array<std::vector<std::size_t>, 2> hints;
      bool hopeless = false;
      for (std::size_t z = 0; z < 2 && !hopeless; ++z) {
        const std::size_t count = (points[z].size() + hint_spacing - 1) / hint_spacing;
        const std::size_t waits = points[z].size() >= patient_zone_points ? 2 : 4;
        std::size_t beyond_hull = 0;
        for (std::size_t k = 0; k < points[z].size() && !hopeless; k += hint_spacing) {
          const std::size_t c = locate<false>(serial_, points_[points[z][k]]);
          const int i = infinite_position(c);
          serial_.last = i > D ? c : neighbor(c, i);
          beyond_hull += i <= D;
          hopeless = D == 2 && beyond_hull * waits > count;
          bool own = i > D;
          for (int j = 0; j <= D; ++j) own = own && owns(workers[z], cells_[c].v[j]);
          hints[z].push_back(own ? c : no_cell);
        }
      }
      if (hopeless) break;  // (its hints incomplete: the round must not run)
      // Each zone's slots: free ones first (the end of the free list), then a new range.
      std::size_t grown = slots();
      for (std::size_t z = 0; z < 2; ++z) {
        Worker& w = workers[z];
        w.new_cells.clear();
        w.deferred.clear();
        w.out_of_slots = false;
        // An eighth above the cells per point so far (a zone that runs out
        // leaves its points to the next round).
        const auto wanted = static_cast<std::size_t>(
            zone_slots_scale * (per_point * 1.125 * static_cast<double>(points[z].size()) + 1024));
        const std::size_t taken = std::min(wanted, serial_.free.size());
        w.free.assign(serial_.free.end() - static_cast<std::ptrdiff_t>(taken), serial_.free.end());
        serial_.free.resize(serial_.free.size() - taken);
        w.next_slot = grown;
        w.end_slot = grown += std::min(wanted - taken, max_slots - std::min(grown, max_slots));
      }
      reserve(grown);
      cells_.resize(grown);
      if constexpr (!marks_in_cells) mark_.resize(grown, 0);
      ++serial_.stats.zone_rounds;
      // Isolated: while waiting for the other zone this thread takes no
      // unrelated outer task (a hybrid's region builds inside one).
      tbb::this_task_arena::isolate([&] {
        tbb::parallel_for(std::size_t{0}, std::size_t{2}, [&](std::size_t z) {
          const kernel::Fp_environment_guard guard;
          insert_zone(workers[z], points[z], hints[z]);
        });
      });
      // The zones' unused slots become free ones (a range ending the array is cut off).
      for (std::size_t z = 2; z-- > 0;) {
        Worker& w = workers[z];
        if (w.end_slot == slots()) {
          cells_.resize(w.next_slot);
          if constexpr (!marks_in_cells) mark_.resize(w.next_slot);
        } else {
          for (std::size_t s = w.next_slot; s < w.end_slot; ++s) {
            // Every vertex written: the hand-over reads a free slot's whole
            // record (hand_over_cells), and this one was never a cell.
            cells_[s].v.fill(free_slot);
            serial_.free.push_back(static_cast<Index>(s));
          }
        }
      }
      for (Worker& w : workers) {
        serial_.free.insert(serial_.free.end(), w.free.begin(), w.free.end());
        finite_cells_ += static_cast<std::size_t>(w.finite_change);
        w.finite_change = 0;
        serial_.stats += w.stats;
        w.stats = {};
        if (w.last != no_cell) serial_.last = w.last;  // alive: nothing ran after its zone
      }
      pending.clear();
      std::merge(workers[0].deferred.begin(), workers[0].deferred.end(), workers[1].deferred.begin(),
                 workers[1].deferred.end(), std::back_inserter(pending));
      if (check_each_insertion && !is_valid())
        throw std::logic_error("Incremental_delaunay: invalid after zoned round " + std::to_string(round));
      if (workers[0].gave_up || workers[1].gave_up) break;
    }
    serial_.new_cells.clear();  // the last serial insertion's: other zones may have reused their slots
    for (const Index v : pending) insert_serially(v);
  }

  /// A zone's insertions in a round (insert_in_zones): each point from the
  /// cell the zone made last (or where its last walk stopped at the zone's
  /// edge: locate); when that walk leaves the zone (after a jump
  /// of the points' curve, or near the zone's edge), again from the hint of
  /// the latest hinted point. Without the second try one failed walk left
  /// the next ones to start far away, and on a torus every later point of
  /// the zone waited. What still fails waits in w.deferred.
  void insert_zone(Worker& w, const std::vector<Index>& points, const std::vector<std::size_t>& hints) {
    w.last = no_cell;
    w.gave_up = false;
    std::size_t hint = no_cell;
    const bool patient = points.size() >= patient_zone_points;
    std::size_t tried = 0, failed = 0;  // the zone's tries (near_cut's points are none) and failures
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (k % hint_spacing == 0) hint = hints[k / hint_spacing];
      const Index v = points[k];
      const bool trying = !w.out_of_slots && !w.gave_up;
      const bool near = trying && near_cut(v);
      bool inserted = false;
      if (trying && !near) {
        ++tried;
        w.walk_failed = false;
        const std::size_t start = w.last;  // (a failed walk moves w.last: locate)
        if (start != no_cell) inserted = insert<true>(w, v);
        // A walk must start in a finite cell of the zone: the hint's slot may
        // hold an infinite one now.
        if (!inserted && (start == no_cell || w.walk_failed) && !w.out_of_slots && hint != no_cell &&
            hint != start && !is_free(hint) && !is_infinite(hint)) {
          const std::size_t from = w.last;
          w.last = hint;
          inserted = insert<true>(w, v);
          if (!inserted && from != no_cell) w.last = from;
        }
      }
      if (inserted) ++w.stats.zoned_points;
      else w.deferred.push_back(v);
      w.stats.near_cut_points += near;
      // Running out of slots is no failure of the zone's (its points wait for the next round).
      failed += trying && !near && !inserted && !w.out_of_slots;
      if ((tried == zone_probe && failed * (patient ? 2 : 4) > tried) ||
          (patient && tried == 4 * zone_probe && failed * 4 > tried))
        w.gave_up = true;
    }
  }

  /// Zoned insertion: whether vertex v (a point of the round) lies within
  /// near_cut_spacings point spacings of the cut, the spacing estimated from
  /// the box's volume and the points inserted when v would be (v itself:
  /// vertices are numbered in the planned insertion order; at least those
  /// inserted at the round's start). Such a point waits for the next round
  /// untried: its walk or cavity nearly always meets the other zone
  /// (uniform 3D, 10^6 points, all rounds, before this rule: 98 % of the
  /// tries within 2 spacings failed, after a walk and a partial search; 75
  /// % of those 2–3 spacings away, 16 % of those 4–5 away). Coordinates and
  /// numbers alone decide, so the answer is the same for any thread count.
  bool near_cut(Index v) const {
    const double distance = std::abs(points_[v].x[cut_axis_] - cut_) * near_cut_scale_;
    double power = distance;  // distance^D · points < 1: within the spacings
    for (int j = 1; j < D; ++j) power *= distance;
    return near_cut_scale_ > 0 && power * std::max(near_cut_inserted_, static_cast<double>(v)) < 1;
  }
  static constexpr std::size_t hint_spacing = 64;
  static constexpr std::size_t cut_sample = std::size_t{1} << 16;
  static constexpr std::size_t patient_zone_points = std::size_t{1} << 19;  // zone_probe's comment


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
    // away (on surface samples, through the inside), and walks from it were
    // twice as long (a torus of 2·10^5 points: 49 steps a point against 24).
    bool started = false;
    for (const Boundary_facet& f : w.boundary) {
      std::size_t s;
      if (reused < w.cavity.size()) s = w.cavity[reused++];
      else if (!w.free.empty()) s = w.free.back(), w.free.pop_back();
      else if constexpr (Zoned) s = w.next_slot++;
      else {
        s = cells_.size();
        if (s >= max_slots)
          throw std::length_error("dewall: the incremental engine's 32-bit cell references hold at most " +
                                  std::to_string(max_slots) + " cells");
        cells_.emplace_back();
        if constexpr (!marks_in_cells) mark_.push_back(0);
      }
      w.new_cells.push_back(static_cast<Index>(s));
      cells_[s].v = f.vertices;
      // Its mark must be 0. Above 2D it is: clear_marks reset the slot when it
      // left a cavity, and growing mark_ fills zeros. In 2D the mark is in the
      // record, which a new slot has not initialised.
      if constexpr (marks_in_cells) cells_[s].mark = 0;
      cells_[s].n[f.facet] = f.outside;
      cells_[f.outside >> facet_bits].n[f.outside & facet_mask] = reference(s, f.facet);
      bool finite = true;
      for (int i = 0; i <= D; ++i)
        if (f.vertices[i] == infinite) finite = false;
      if (finite) {
        ++w.finite_change;
        if (!started) w.last = s, started = true;
      }
    }
    if (ridge_table_only || !glue_star_directed(w)) {
      glue_star_by_ridges(w);
      ++w.stats.ridge_table_stars;
    }
    clear_marks(w);
    for (; reused < w.cavity.size(); ++reused) {
      cells_[w.cavity[reused]].v[0] = free_slot;
      w.free.push_back(static_cast<Index>(w.cavity[reused]));
    }
    return true;
  }

  /// Step 3c's gluing: each new cell's facets through the new point matched
  /// with the other new cell on them, by their other D − 1 vertices (the
  /// ridge). A ridge's key is the sum of its vertices' hashes, so a cell's D
  /// keys cost D hashes and a subtraction each; a key is no proof, so a match
  /// is checked on the candidate's vertices (same_ridge). The sorted vertex
  /// array it replaces (a sort and a 16-byte compare per ridge) took 43 % of
  /// a 5D construction (uniform 2·10^4 points, engine driver, one thread:
  /// 6.43 s).
  void glue_star_by_ridges(Worker& w) {
    w.ridges.begin(w.boundary.size() * D / 2);  // each ridge parked once
    const std::uint64_t key_mask = colliding_ridge_keys ? 7 : ~std::uint64_t{0};
    for (std::size_t b = 0; b < w.boundary.size(); ++b) {
      const Boundary_facet& f = w.boundary[b];
      const std::size_t s = w.new_cells[b];
      std::array<std::uint64_t, D + 1> hashes;
      std::uint64_t sum = 0;
      for (int i = 0; i <= D; ++i) {
        hashes[i] = i == f.facet ? 0 : mix64(f.vertices[i]);
        sum += hashes[i];
      }
      for (int i = 0; i <= D; ++i) {
        if (i == f.facet) continue;
        const auto same = [&](std::uint32_t candidate) { return same_ridge(candidate, f.vertices, f.facet, i); };
        if (const std::uint32_t partner = w.ridges.match_or_park((sum - hashes[i]) & key_mask, reference(s, i), same);
            partner != Ridge_table::none) {
          cells_[s].n[i] = partner;
          cells_[partner >> facet_bits].n[partner & facet_mask] = reference(s, i);
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
  bool glue_star_directed(Worker& w) {
    if constexpr (D > 3) {
      return false;
    } else {
      if constexpr (D == 2)
        if (w.boundary.size() <= fan_scan_limit) {
          glue_fan(w);
          return true;
        }
      // The boundary's vertices numbered through a small open-addressing
      // table (in cache, unlike an array over all vertices), stamped per insertion.
      const std::uint32_t stamp = ++w.local_stamp;
      if (stamp == 0) {  // wrapped around: forget every old stamp
        std::fill(w.local.begin(), w.local.end(), Local{});
        w.local_stamp = 1;
        return glue_star_directed(w);
      }
      std::uint32_t m = 1;  // 0: the infinite vertex
      // Whether x is new or seen has no pattern a branch predictor could
      // learn (a boundary vertex is met about five times, the first time
      // new): so the answer is selected by masks, not by a branch (GCC made
      // conditional expressions branches again; measured: uniform 10^6 −3 %).
      // Probing on only passes a slot another vertex holds.
      auto local = [&](Index x) -> std::uint32_t {
        if (x == infinite) return 0;
        std::uint32_t i = (x * 0x9e3779b9u) >> (32 - local_bits);
        // (& on the two tests' values, not &&: one branch, not two.)
        while (static_cast<unsigned>(w.local[i].stamp == stamp) & static_cast<unsigned>(w.local[i].vertex != x))
          i = (i + 1) & (local_table_size - 1);
        Local& l = w.local[i];
        const std::uint32_t fresh = l.stamp != stamp, keep = fresh - 1;  // keep: all ones when seen
        l.vertex = x;
        l.stamp = stamp;
        l.number = (l.number & keep) | (m & ~keep);
        m += fresh;
        return l.number;
      };
      // w.keys[b·D + e]: the directed key of new cell b's e-th facet through p
      // (star_facets[facet][e]), and of its reverse.
      w.keys.resize(w.boundary.size() * D);
      for (std::size_t b = 0; b < w.boundary.size(); ++b) {
        const Boundary_facet& f = w.boundary[b];
        const auto& facets = star_facets[f.facet];
        // Each boundary vertex's number once per facet (each is in D − 1 of its keys).
        std::array<std::uint32_t, D + 1> number;
        for (int e = 0; e < D; ++e) number[facets[e].k] = local(f.vertices[facets[e].k]);
        if (m >= star_table_side) return false;
        for (int e = 0; e < D; ++e) {
          const Star_facet& t = facets[e];
          if constexpr (D == 3) {
            const std::uint32_t x = number[t.a], y = number[t.b];
            w.keys[b * D + e] = {x * star_table_side + y, y * star_table_side + x};
          } else {
            const std::uint32_t x = number[t.a];
            w.keys[b * D + e] = {2 * x + t.b, 2 * x + (1 - t.b)};
          }
        }
      }
      for (std::size_t b = 0; b < w.boundary.size(); ++b) {
        const auto& facets = star_facets[w.boundary[b].facet];
        for (int e = 0; e < D; ++e) w.star_table[w.keys[b * D + e][0]] = reference(w.new_cells[b], facets[e].k);
      }
      for (std::size_t b = 0; b < w.boundary.size(); ++b) {
        const auto& facets = star_facets[w.boundary[b].facet];
        for (int e = 0; e < D; ++e) cells_[w.new_cells[b]].n[facets[e].k] = w.star_table[w.keys[b * D + e][1]];
      }
      return true;
    }
  }

  /// In 2D the star is a fan: new cell (p, a, b), counterclockwise (p at
  /// position f, a at f + 1, b at f + 2), meets across its edge (b, p) the
  /// new cell whose a is b. With the fan's few cells (6 on uniform points) a
  /// scan of their a's is faster than numbering the vertices through a hash
  /// table (measured: glue_star_directed was a tenth of a 2D run).
  void glue_fan(Worker& w) {
    constexpr int after[3] = {1, 2, 0}, before[3] = {2, 0, 1};  // positions f + 1, f + 2 (mod 3)
    const std::size_t m = w.boundary.size();
    std::array<Index, fan_scan_limit> a_of;  // each new cell's a
    for (std::size_t x = 0; x < m; ++x) a_of[x] = w.boundary[x].vertices[after[w.boundary[x].facet]];
    for (std::size_t x = 0; x < m; ++x) {
      const int fx = w.boundary[x].facet;
      const Index b = w.boundary[x].vertices[before[fx]];
      // The boundary is a closed polygon: b is exactly one cell's a. A scan
      // of fixed length with a conditional move: an early exit's branch
      // mispredicted (measured: most of the gluing's time).
      std::size_t y = 0;
      for (std::size_t k = 0; k < m; ++k) y = a_of[k] == b ? k : y;
      DEWALL_ASSERT(a_of[y] == b);
      const int fy = w.boundary[y].facet;
      // x's edge (b, p) is opposite x's a; y's edge (p, b) is opposite y's own b.
      cells_[w.new_cells[x]].n[after[fx]] = reference(w.new_cells[y], before[fy]);
      cells_[w.new_cells[y]].n[before[fy]] = reference(w.new_cells[x], after[fx]);
    }
  }
  static constexpr std::size_t fan_scan_limit = 32;

  /// glue_star_directed's facets of a new cell through the new point p, which
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
  bool same_ridge(std::uint32_t candidate, const Cell& cell, int apex, int i) const {
    const Cell& other = cells_[candidate >> facet_bits].v;
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

  std::vector<Point> points_;    // by vertex id (insertion order)
  std::vector<Index> input_;     // the caller's id of each vertex
  /// In 2D a cell's search mark lives in its record: the record (24 bytes
  /// of vertices and neighbours) is padded to 32, so that none straddles two
  /// cache lines and the mark fits, and the search then reads one line per
  /// neighbour instead of two (the record and mark_). The cost: 32 bytes a
  /// slot instead of 24 + 1 (about 14 bytes more a point). Engine driver,
  /// one thread, best of 20 or 5, three alternated series: 10^5 points on a
  /// circle 39.6–40.3 → 38.7–39.2 ms, uniform 10^5 36.7 → 36.1–36.3, uniform
  /// 10^6 413–417 → 413–415, a 10^5 grid 50.5–50.6 → 50.3–50.4. In 3D the
  /// 32-byte record is full (and larger ones cost more lines than the mark
  /// saves).
  static constexpr bool marks_in_cells = D == 2;
  /// A cell slot (cell_graph_output.hpp): its vertices and its neighbour
  /// references side by side; in 2D, its mark.
  using Record = Cell_record<D>;
  static_assert(std::is_same_v<decltype(Record::v), Cell>);
  static_assert(std::is_same_v<decltype(Record::mark), std::uint8_t> == marks_in_cells);
  /// Allocates without initialising: a new slot is written whole before it
  /// is read (its vertices, then each neighbour reference), so growing the
  /// array does not clear it first (zoned insertion grows it by the zones'
  /// ranges at once; their pages are then first touched by the zone's thread).
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
  std::vector<std::uint8_t> mark_;  // 0, or find_cavity's in / out, by slot (empty when marks_in_cells)
  /// Cell c's search mark (find_cavity's in / out, else 0).
  std::uint8_t& mark(std::size_t c) {
    if constexpr (marks_in_cells) return cells_[c].mark;
    else return mark_[c];
  }
  std::size_t finite_cells_ = 0;

  // glue_star_directed: the boundary vertices' numbers, the facets' directed
  // keys (and their reverses), the table by directed key.
  static constexpr std::size_t star_tries = 64;  // start_of_cavity's cap (stars grow fast above 3D)
  static constexpr std::uint32_t star_table_side = 128;  // + D < local_table_size: the table never fills
  static constexpr int local_bits = 8;
  static constexpr std::uint32_t local_table_size = 1u << local_bits;
  struct Local {
    Index vertex = 0;
    std::uint32_t stamp = 0, number = 0;
  };
  /// What one thread of insertions works with: the search's and the star's
  /// scratch, its free slots, where its walks start. The serial insertions
  /// have one (serial_), each zone of a zoned round its own.
  struct Worker {
    std::vector<Index> free;      // free slots (serial_'s: every free slot)
    bool semi_static_first = false;   // choose_filter_order's state
    std::uint8_t semi_static_windows = 0;
    Filter_tally filter_tally;
    // A finite cell the last insertion made (or where a zone's failed walk stopped): the next walk starts there.
    std::size_t last = 0;
    std::ptrdiff_t finite_change = 0;  // finite cells made minus destroyed, not yet in finite_cells_
    Incremental_statistics stats;
    Scratch_list<std::size_t> cavity;
    std::vector<Boundary_facet> boundary;
    Scratch_list<Index> new_cells;  // the slot of each boundary facet's new cell
    Ridge_table ridges;
    std::vector<Local> local = std::vector<Local>(D <= 3 ? local_table_size : 0);
    std::uint32_t local_stamp = 0;
    std::vector<std::array<std::uint32_t, 2>> keys;
    std::vector<std::uint32_t> star_table =
        std::vector<std::uint32_t>(D == 3 ? star_table_side * star_table_side : D == 2 ? 2 * star_table_side : 0);
    // Zoned insertion only: the zone, its new slots next_slot … end_slot − 1,
    // the vertices it left to the next round.
    std::uint8_t zone = 0;
    std::size_t next_slot = 0, end_slot = 0;
    bool out_of_slots = false;
    bool walk_failed = false;
    bool gave_up = false;  // insert_zone: too many points waited (zone_probe)
    std::vector<Index> deferred;
  };
  Worker serial_;
  // Zoned insertion: the current round's cut (zone_of).
  int cut_axis_ = 0;
  double cut_ = 0;
  double near_cut_scale_ = 0;     // near_cut: 1 / (the box's mean extent · near_cut_spacings); 0: off
  double near_cut_inserted_ = 0;  // near_cut: points inserted at the round's start
  kernel::Static_filter_d<D> static_filter_;  // from the points' box: in front of the kernel's cascade
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
