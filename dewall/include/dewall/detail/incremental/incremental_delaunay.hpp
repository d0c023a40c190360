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
// need a different flip set per dimension and are faster only when
// specialised for one. The fastest codes (hxt, Geogram) are cavity based too.
//
// The parts, as CGAL and Geogram split theirs:
//  * cell_store.hpp: the cells' flat records (vertex ids, packed neighbour
//    references), slots, marks, allocation, page release, the topology checks;
//  * cell_geometry.hpp: the points, the static filter, the predicates on
//    cells, the first simplex;
//  * star_gluing.hpp: the new cells glued to each other (step 3c);
//  * zoned_insertion.hpp: the parallel rounds (step 4);
//  * worker.hpp: one thread's scratch and counters;
//  * tuning.hpp: the knobs, one value given to the constructor;
//  * bowyer_watson.hpp: the engine proper (the walk, the cavity, insertion);
//  * testing_access.hpp: the tests' one door to the internals;
//  * this file: the construction (the order, the sample, the zones' hand-off)
//    and the interface.
// One infinite vertex closes the hull: a hull facet's outer neighbour is an
// infinite cell, so every point outside the hull has a cavity like any other.
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
//     c. star: each boundary facet of the cavity plus p is a new cell, glued
//        to the outside across that facet here and to the other new cells
//        by star_gluing.hpp.
//  4. Both cores: from Incremental_tuning::zoned_insertion_threshold points
//     on (the sample from half as many), step 3 runs in rounds of two zones
//     (zoned_insertion.hpp: why the result is the same for any thread count).
// Expected O(n log n) for points in general position (BRIO), the walk and the
// cavities O(1) per point on well-spread data.
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
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>

#include "dewall/detail/common/box.hpp"
#include "dewall/detail/common/index.hpp"
#include "dewall/detail/common/parallel.hpp"
#include "dewall/detail/incremental/brio_order.hpp"
#include "dewall/detail/incremental/bowyer_watson.hpp"
#include "dewall/detail/incremental/cell_geometry.hpp"
#include "dewall/detail/incremental/cell_store.hpp"
#include "dewall/detail/incremental/tuning.hpp"
#include "dewall/detail/incremental/zoned_insertion.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"
#include "dewall/kernel/static_filter.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// The Delaunay triangulation of distinct points, built incrementally.
/// Vertex ids are positions in the insertion order (`input_index` maps them
/// back); cells live in slots, some of them free.
template <int D>
class Incremental_delaunay : public Bowyer_watson<D> {
  using Base = Bowyer_watson<D>;
  using Store = Cell_store<D>;

 public:
  using typename Base::Cell;
  using typename Base::Point;
  using Base::facet_bits;
  using Base::free_slot;
  using Base::infinite;

  /// \throws std::invalid_argument when `tuning` is out of range (Incremental_tuning::validate).
  explicit Incremental_delaunay(const Incremental_tuning& tuning = {}) : Base(tuning) {}

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
  /// build() for points given as Point_d, their ids their positions.
  bool build(std::span<const Point> points) {
    return build(points.size(), [&](std::size_t k) -> const std::array<double, D>& { return points[k].x; },
                 [](std::size_t k) { return k; });
  }

  /// Inserts `count` more points after a successful build (each distinct from
  /// every vertex, and inside the box the static filter was made for: the
  /// `filter_box` given to build, else build's points' box), in BRIO order;
  /// ids as in build. The triangulation is then that of all points inserted.
  /// (dewall::mpi adds the halo points of each round this way.)
  template <class Coordinates, class Id>
  void insert_more(std::size_t count, Coordinates&& coordinates, Id&& id) {
    if (count == 0) return;
    const std::vector<std::uint32_t> order = brio_order<D>(count, coordinates);
    if (static_filter_.on_lattice()) static_filter_.admit_lattice(Base::lattice_unit(count, coordinates));
    const std::size_t first = points_.size();
    points_.resize(first + count);
    input_.resize(first + count);
    for (std::size_t k = 0; k < count; ++k) {
      points_[first + k].x = coordinates(order[k]);
      input_[first + k] = static_cast<Index>(id(order[k]));
    }
    insert_vertices(first, first + count);
  }

  /// Room for `cells` cell slots (Cell_store::reserve; dewall::mpi counts
  /// each rank's peak memory). build() reserves expected_cells.
  void reserve(std::size_t cells) { store_.reserve(cells); }
  /// Cell slots to reserve for `count` points: a little above the cells of
  /// uniform points (2 per point in the plane, 6.8 in space), so that volume
  /// data never grows; surfaces (up to 16 per point) grow once or twice.
  /// Above 3D the count per point varies too much with the input to reserve.
  static constexpr std::size_t expected_cells(std::size_t count) {
    return D == 2 ? 3 * count : D == 3 ? 8 * count : 0;
  }
  /// The number of vertices (finite), ids 0 … vertices() − 1.
  std::size_t vertices() const { return points_.size(); }

  /// The caller's id of vertex v (finite).
  Index input_index(Index v) const { return input_[v]; }
  /// input_index of every vertex, by vertex id.
  std::span<const Index> input_indices() const { return input_; }

  /// For a caller that reads the cells out once, in slot order, and then
  /// drops the object (the collecting output): frees the points and the
  /// search's marks now. Afterwards only slots(), is_free(), is_infinite(),
  /// holds_finite_cell(), cell(), records(), input_index(), input_indices()
  /// and finite_cells() may be called, and after release_slots(first, last)
  /// on none of those slots.
  void finish_for_reading() {
    std::vector<Point>().swap(points_);
    store_.release_marks();
  }
  /// Slots first … last − 1 are not read again (Cell_store::release_slots).
  void release_slots(std::size_t first, std::size_t last) { store_.release_slots(first, last); }

 private:
  using Base::insert_vertices;
  using Base::points_;
  using Base::start;
  using Base::static_filter_;
  using Base::store_;
  using Base::tuning_;

  /// build's steps once the insertion order is known: `order` holds the
  /// indices (among `input_count`, whose box is `box`) of the points to insert.
  template <class Coordinates, class Id, class Gathered>
  bool build_in_order(std::size_t input_count, std::vector<std::uint32_t> order, const Box<D>& box,
                      Coordinates& coordinates, Id& id, const Box<D>* filter_box, Gathered& gathered) {
    const std::size_t count = order.size();
    const Box<D>& filter_bounds = filter_box ? *filter_box : box;
    static_filter_ =
        kernel::Static_filter_d<D>(filter_bounds.lo, filter_bounds.hi, Base::lattice_unit(input_count, coordinates));
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
    const std::size_t sample = std::max<std::size_t>(count / 16, D + 1);
    insert_sample(sample, box);
    if (sample < count) reserve_after_sample(sample, count);
    if (count > sample && count - sample >= tuning_.zoned_insertion_threshold) insert_in_zones(sample, count, box);
    else insert_vertices(sample, count);
    return true;
  }
  /// Cells per point range from 6.5 (volume) to 20 (samples of a torus) in
  /// 3D, and more above: the first sixteenth of the BRIO order (its first
  /// rounds: a random sample) predicts the count. When the arrays would
  /// overflow (the count an eighth above the prediction), they are enlarged
  /// now, with room to spare (the count per point still grows on surfaces),
  /// so that they grow once, early, instead of doubling late (each doubling
  /// copies the cells onto fresh pages). Volume data stays in the first
  /// reservation.
  void reserve_after_sample(std::size_t sample, std::size_t count) {
    const double per_point = static_cast<double>(this->slots()) / static_cast<double>(sample);
    const double predicted = per_point * static_cast<double>(count);
    if (predicted * 1.125 > static_cast<double>(store_.capacity())) {
      try {
        reserve(static_cast<std::size_t>(predicted * 1.5));
      } catch (const std::bad_alloc&) {  // more than the system grants at once: grow as needed
      }
    }
  }



  /// Inserts points D + 1 … sample − 1 (after start): its own first sixteenth
  /// one by one, the rest in zones when that is large enough for them (half
  /// zoned_insertion_threshold: from about 5.6·10^5 points on by default),
  /// as on one core the sample would be a large share of a two-core run. The
  /// zones' result is the same for any thread count.
  void insert_sample(std::size_t sample, const Box<D>& box) {
    const std::size_t inner = std::max<std::size_t>(sample / 16, D + 1);
    if (sample - inner >= tuning_.zoned_insertion_threshold / 2) {
      insert_vertices(D + 1, inner);
      insert_in_zones(inner, sample, box);
    } else {
      insert_vertices(D + 1, sample);
    }
  }



  /// Step 4, for vertices first … last − 1 (zoned_insertion.hpp).
  void insert_in_zones(std::size_t first, std::size_t last, const Box<D>& box) {
    Zoned_insertion<D>(*this, first, last, box).run();
  }



  std::vector<Index> input_;  // the caller's id of each vertex
};
}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
