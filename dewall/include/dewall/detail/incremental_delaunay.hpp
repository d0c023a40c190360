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
//  1. Order: BRIO rounds along a Hilbert curve (spatial_order.hpp).
//  2. First simplex: the first D + 1 affinely independent points in that
//     order (exact rank, Affine_basis); the points passed over are inserted
//     next.
//  3. Insert each point p:
//     a. locate: a visibility walk (orientation tests) from the last cell
//        created to a cell holding p, or to an infinite cell whose hull
//        facet p sees;
//     b. cavity: the cells in conflict with p, found breadth-first from there
//        (a finite cell: p inside its perturbed sphere; an infinite cell: p
//        beyond its hull facet, or in that facet's hyperplane and in conflict
//        with the finite cell behind it — see in_conflict);
//     c. star: each boundary facet of the cavity plus p is a new cell; the new
//        cells are glued to the outside across that facet and to each other
//        across their facets through p: in 2D and 3D through a table indexed
//        by the facets' directed keys (glue_star_directed), above 3D and for
//        very large cavities by their D − 1 other vertices in a hash table.
// Expected O(n log n) for points in general position (BRIO), the walk and the
// cavities O(1) per point on well-spread data.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
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

#include "dewall/detail/assert.hpp"
#include "dewall/detail/face.hpp"
#include "dewall/detail/input.hpp"
#include "dewall/detail/spatial_order.hpp"
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
  static constexpr Index infinite = std::numeric_limits<Index>::max();
  /// A free slot's first vertex.
  static constexpr Index free_slot = infinite - 1;
  /// Bits of a neighbour reference that hold the facet index.
  static constexpr int facet_bits = std::bit_width(static_cast<unsigned>(D));

  /// Triangulates `count` points (distinct, finite): point k's coordinates
  /// are coordinates(k) (an array of D doubles), its id for the caller id(k)
  /// (input_index returns it). Returns false when the points do not span E^D
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
    if (count < static_cast<std::size_t>(D + 1)) return false;
    const Box<D> box = bounding_box<D>(count, coordinates);
    std::vector<std::uint32_t> order = brio_order<D>(count, coordinates, box);
    const Box<D>& filter_bounds = filter_box ? *filter_box : box;
    static_filter_ = kernel::Static_filter_d<D>(filter_bounds.lo, filter_bounds.hi, lattice_unit(count, coordinates));
    if (!start(coordinates, order)) return false;
    reserve(expected_cells(count));
    points_.resize(count);
    input_.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      points_[k].x = coordinates(order[k]);
      input_[k] = static_cast<Index>(id(order[k]));
    }
    std::vector<std::uint32_t>().swap(order);
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
    insert_vertices(D + 1, sample);
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
    insert_vertices(sample, count);
    return true;
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
    if (static_filter_.exact()) static_filter_.admit_lattice(lattice_unit(count, coordinates));
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
    mark_.reserve(std::min(cells, max_slots));
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

  /// Tests: run is_valid() after every insertion (O(n) each), throwing
  /// std::logic_error at the first failure.
  bool check_each_insertion = false;
  /// Tests: whether the static filter decides every predicate exactly (the
  /// points lie on a small lattice: kernel/static_filter.hpp).
  bool static_filter_exact() const { return static_filter_.exact(); }
  /// Tests: glue every star through the ridge hash table (in 2D and 3D only
  /// cavities of 127 boundary vertices or more take it otherwise).
  bool ridge_table_only = false;

  /// Tests: the cells in conflict with q (not a vertex), as insertion would
  /// find them (the walk, then the breadth-first search), sorted.
  /// q may lie outside the points' box: the static filter, whose bound
  /// assumes it inside, is off for the call.
  std::vector<std::size_t> cavity(const Point& q) {
    const auto filter = std::exchange(static_filter_, kernel::Static_filter_d<D>());
    find_cavity(q, infinite);
    clear_marks();
    static_filter_ = filter;
    std::vector<std::size_t> cells = cavity_;
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
  std::size_t finite_cells() const { return finite_cells_; }
  const Incremental_statistics& statistics() const { return stats_; }

  /// Checks the data structure (tests): neighbours are
  /// mutual and share D vertices, finite cells are positively oriented.
  bool is_valid() const {
    for (std::size_t c = 0; c < slots(); ++c) {
      if (is_free(c)) continue;
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = cells_[c].n[i];
        const std::size_t n = ref >> facet_bits;
        const int j = static_cast<int>(ref & facet_mask);
        if (n >= slots() || is_free(n) || (cells_[n].n[j] >> facet_bits) != c) return false;
        for (int k = 0; k <= D; ++k)
          if (k != i && std::find(cells_[n].v.begin(), cells_[n].v.end(), cells_[c].v[k]) == cells_[n].v.end()) return false;
      }
      if (!is_infinite(c) && orientation(c, -1, nullptr) != kernel::POSITIVE) return false;
    }
    return true;
  }

 private:
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

  /// Whether q lies inside the perturbed sphere of finite cell c.
  bool sphere_holds(std::size_t c, const Point& q) const {
    const auto refs = sphere_points(c, q);
    if (const auto s = static_filter_.side_of_oriented_sphere(refs)) {
      if (*s != kernel::ZERO) return *s == kernel::POSITIVE;
      return exact_zero_perturbed(refs);
    }
    return kernel::side_of_oriented_sphere_d_sos<D>(refs) == kernel::ON_POSITIVE_SIDE;
  }
  /// sphere_holds for an exact zero of the static filter (exact on this
  /// lattice): the perturbation's orientations, through the same filter.
  /// Out of line: inlined, it slowed the cavity search on inputs that never
  /// tie.
  [[gnu::noinline]] bool exact_zero_perturbed(const kernel::Sphere_points<D>& refs) const {
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
  bool in_conflict(std::size_t c, const Point& q) const {
    const int i = infinite_position(c);
    if (i > D) return sphere_holds(c, q);
    const kernel::Sign s = orientation(c, i, &q);
    if (s != kernel::ZERO) return s == kernel::POSITIVE;
    return sphere_holds(neighbor(c, i), q);
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
    cells_.assign(1, Record{first, {}});
    if (orientation(0, -1, nullptr) == kernel::NEGATIVE) std::swap(cells_[0].v[0], cells_[0].v[1]);
    // The infinite cell across facet i: the simplex with vertex i replaced by
    // the infinite vertex and two others swapped, so that putting a point
    // beyond the facet in the infinite vertex's place orients it positively.
    for (int i = 0; i <= D; ++i) {
      Cell c = cells_[0].v;
      c[i] = infinite;
      std::swap(c[(i + 1) % (D + 1)], c[(i + 2) % (D + 1)]);
      cells_.push_back(Record{c, {}});
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
    free_.clear();
    new_cells_.clear();  // start_of_cavity's candidates: none yet
    stats_ = {};
    finite_cells_ = 1;
    last_ = 0;
    mark_.assign(cells_.size(), 0);
    return true;
  }

  int position(std::size_t c, Index v) const {
    for (int i = 0; i <= D; ++i)
      if (cells_[c].v[i] == v) return i;
    DEWALL_ASSERT(false);
    return -1;
  }

  /// Step 3a: a cell in conflict with q, by a visibility walk from last_.
  std::size_t locate(const Point& q) {
    std::size_t c = last_, previous = std::numeric_limits<std::size_t>::max();
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
          previous = c;
          c = next;
          moved = true;
          ++stats_.walk_steps;
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
  std::size_t start_of_cavity(const Point& q) {
    const std::size_t tries = std::min<std::size_t>(new_cells_.size(), star_tries);
    for (std::size_t k = 0; k < tries; ++k)
      if (proven_in_conflict(new_cells_[k], q)) return new_cells_[k];
    return locate(q);
  }

  /// Whether the static filter alone proves cell c in conflict with q (false
  /// when it cannot tell: on near-cospherical points the exact stage would
  /// cost more than the walk it saves).
  bool proven_in_conflict(std::size_t c, const Point& q) const {
    const int i = infinite_position(c);
    const auto s = i > D ? static_filter_.side_of_oriented_sphere(sphere_points(c, q))
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

  /// Steps 3a–b: cavity_ holds the cells in conflict with q, boundary_ the
  /// facets around them with the new cells' vertices (q as vertex v).
  void find_cavity(const Point& q, Index v) {
    const std::size_t start_cell = start_of_cavity(q);
    DEWALL_EXPENSIVE_ASSERT(in_conflict(start_cell, q));

    // 3b. The cavity, breadth-first; mark_: in conflict or not (clear_marks resets both).
    constexpr std::uint8_t in = 1, out = 2;
    cavity_.clear();
    boundary_.clear();
    // The neighbours' marks and records, then the points of their vertices
    // across the shared facets, are the search's cache misses (measured on a
    // torus: most of find_cavity's time). So they are asked for a step ahead:
    // a cell's neighbours' records when it joins the cavity, their far
    // vertices' points when it is taken from the queue (its records have
    // arrived by then), both before they are read.
    const auto prefetch_neighbours = [&](std::size_t c) {
      for (int i = 0; i <= D; ++i) {
        const std::size_t n = cells_[c].n[i] >> facet_bits;
        __builtin_prefetch(&mark_[n]);
        __builtin_prefetch(&cells_[n]);
      }
    };
    cavity_.push_back(start_cell);
    mark_[start_cell] = in;
    prefetch_neighbours(start_cell);
    for (std::size_t k = 0; k < cavity_.size(); ++k) {
      const std::size_t c = cavity_[k];
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = cells_[c].n[i];
        const Index far = cells_[ref >> facet_bits].v[ref & facet_mask];
        if (far != infinite) __builtin_prefetch(&points_[far]);
      }
      for (int i = 0; i <= D; ++i) {
        const std::uint32_t ref = cells_[c].n[i];
        const std::size_t n = ref >> facet_bits;
        if (mark_[n] == in) continue;
        if (mark_[n] != out) {
          if (in_conflict(n, q)) {
            mark_[n] = in;
            cavity_.push_back(n);
            prefetch_neighbours(n);
            continue;
          }
          mark_[n] = out;
        }
        // Written in place: a facet built on the stack and copied is
        // stored in pieces and reloaded whole, a store-forwarding stall
        // (measured in 2D: the hottest instruction of the search).
        Boundary_facet& f = boundary_.emplace_back();
        f.vertices = cells_[c].v;
        f.vertices[i] = v;
        f.facet = i;
        f.outside = ref;
      }
    }
  }

  /// Step 3 for vertices first … last − 1 (points_ holds them).
  void insert_vertices(std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      insert(static_cast<Index>(k));
      if (check_each_insertion && !is_valid())
        throw std::logic_error("Incremental_delaunay: invalid after inserting vertex " + std::to_string(k));
    }
  }

  /// Resets the marks find_cavity set: on the cavity's cells and on the cells
  /// outside its boundary, the only ones it marks (explicit clearing keeps the
  /// marks one byte per slot, a quarter of the epoch counters it replaces: the
  /// marks are one of the search's cache misses).
  void clear_marks() {
    for (const std::size_t c : cavity_) mark_[c] = 0;
    for (const Boundary_facet& f : boundary_) mark_[f.outside >> facet_bits] = 0;
  }

  /// Step 3: inserts vertex v (points_[v]).
  void insert(Index v) {
    find_cavity(points_[v], v);

    // 3c. The star: slots of the cavity first, then free ones, then new ones.
    stats_.conflict_cells += cavity_.size();
    stats_.created_cells += boundary_.size();
    for (const std::size_t c : cavity_)
      if (!is_infinite(c)) --finite_cells_;
    std::size_t reused = 0;
    new_cells_.clear();
    for (const Boundary_facet& f : boundary_) {
      std::size_t s;
      if (reused < cavity_.size()) s = cavity_[reused++];
      else if (!free_.empty()) s = free_.back(), free_.pop_back();
      else {
        s = cells_.size();
        if (s >= max_slots)
          throw std::length_error("dewall: the incremental engine's 32-bit cell references hold at most " +
                                  std::to_string(max_slots) + " cells");
        cells_.emplace_back();
        mark_.push_back(0);
      }
      new_cells_.push_back(static_cast<Index>(s));
      cells_[s].v = f.vertices;  // its mark is 0: clear_marks reset the slot when it left a cavity
      cells_[s].n[f.facet] = f.outside;
      cells_[f.outside >> facet_bits].n[f.outside & facet_mask] = reference(s, f.facet);
      bool finite = true;
      for (int i = 0; i <= D; ++i)
        if (f.vertices[i] == infinite) finite = false;
      if (finite) {
        ++finite_cells_;
        last_ = s;
      }
    }
    if (ridge_table_only || !glue_star_directed()) {
      glue_star_by_ridges();
      ++stats_.ridge_table_stars;
    }
    clear_marks();
    for (; reused < cavity_.size(); ++reused) {
      cells_[cavity_[reused]].v[0] = free_slot;
      free_.push_back(static_cast<Index>(cavity_[reused]));
    }
  }

  /// Step 3c's gluing: each new cell's facets through the new point matched
  /// with the other new cell on them, by their other D − 1 vertices.
  void glue_star_by_ridges() {
    ridges_.begin(boundary_.size() * D / 2);  // each ridge parked once
    for (std::size_t b = 0; b < boundary_.size(); ++b) {
      const Boundary_facet& f = boundary_[b];
      const std::size_t s = new_cells_[b];
      for (int i = 0; i <= D; ++i) {
        if (i == f.facet) continue;
        if (const std::uint32_t partner = ridges_.match_or_park(ridge_key(f.vertices, f.facet, i), reference(s, i));
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
  bool glue_star_directed() {
    if constexpr (D > 3) {
      return false;
    } else {
      if constexpr (D == 2)
        if (boundary_.size() <= fan_scan_limit) {
          glue_fan();
          return true;
        }
      // The boundary's vertices numbered through a small open-addressing
      // table (in cache, unlike an array over all vertices), stamped per insertion.
      const std::uint32_t stamp = ++local_stamp_;
      if (stamp == 0) {  // wrapped around: forget every old stamp
        std::fill(local_.begin(), local_.end(), Local{});
        local_stamp_ = 1;
        return glue_star_directed();
      }
      std::uint32_t m = 1;  // 0: the infinite vertex
      auto local = [&](Index w) -> std::uint32_t {
        if (w == infinite) return 0;
        for (std::uint32_t i = (w * 0x9e3779b9u) >> (32 - local_bits);; i = (i + 1) & (local_table_size - 1)) {
          Local& l = local_[i];
          if (l.stamp != stamp) {
            l = {w, stamp, m};
            return m++;
          }
          if (l.vertex == w) return l.number;
        }
      };
      // keys_[b·D + e]: the directed key of new cell b's e-th facet through p
      // (star_facets[facet][e]), and of its reverse.
      keys_.resize(boundary_.size() * D);
      for (std::size_t b = 0; b < boundary_.size(); ++b) {
        const Boundary_facet& f = boundary_[b];
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
      for (std::size_t b = 0; b < boundary_.size(); ++b) {
        const auto& facets = star_facets[boundary_[b].facet];
        for (int e = 0; e < D; ++e) star_table_[keys_[b * D + e][0]] = reference(new_cells_[b], facets[e].k);
      }
      for (std::size_t b = 0; b < boundary_.size(); ++b) {
        const auto& facets = star_facets[boundary_[b].facet];
        for (int e = 0; e < D; ++e) cells_[new_cells_[b]].n[facets[e].k] = star_table_[keys_[b * D + e][1]];
      }
      return true;
    }
  }

  /// In 2D the star is a fan: new cell (p, a, b), counterclockwise (p at
  /// position f, a at f + 1, b at f + 2), meets across its edge (b, p) the
  /// new cell whose a is b. With the fan's few cells (6 on uniform points) a
  /// scan of their a's is faster than numbering the vertices through a hash
  /// table (measured: glue_star_directed was a tenth of a 2D run).
  void glue_fan() {
    constexpr int after[3] = {1, 2, 0}, before[3] = {2, 0, 1};  // positions f + 1, f + 2 (mod 3)
    const std::size_t m = boundary_.size();
    std::array<Index, fan_scan_limit> a_of;  // each new cell's a
    for (std::size_t x = 0; x < m; ++x) a_of[x] = boundary_[x].vertices[after[boundary_[x].facet]];
    for (std::size_t x = 0; x < m; ++x) {
      const int fx = boundary_[x].facet;
      const Index b = boundary_[x].vertices[before[fx]];
      // The boundary is a closed polygon: b is exactly one cell's a. A scan
      // of fixed length with a conditional move: an early exit's branch
      // mispredicted (measured: most of the gluing's time).
      std::size_t y = 0;
      for (std::size_t k = 0; k < m; ++k) y = a_of[k] == b ? k : y;
      DEWALL_ASSERT(a_of[y] == b);
      const int fy = boundary_[y].facet;
      // x's edge (b, p) is opposite x's a; y's edge (p, b) is opposite y's own b.
      cells_[new_cells_[x]].n[after[fx]] = reference(new_cells_[y], before[fy]);
      cells_[new_cells_[y]].n[before[fy]] = reference(new_cells_[x], after[fx]);
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

  /// The D − 1 vertices of a facet through the new point other than it: in 2D
  /// and 3D packed in one integer (smaller first), above sorted in an array.
  using Ridge = std::conditional_t<(D <= 3), std::uint64_t, std::array<Index, D - 1>>;
  /// The vertices of cell w other than those at positions a and b.
  static Ridge ridge_key(const Cell& w, int a, int b) {
    std::array<Index, D - 1> r;
    int k = 0;
    for (int i = 0; i <= D; ++i)
      if (i != a && i != b) r[k++] = w[i];
    if constexpr (D == 2) {
      return r[0];
    } else if constexpr (D == 3) {
      const auto [lo, hi] = std::minmax(r[0], r[1]);
      return std::uint64_t{lo} << 32 | hi;
    } else {
      std::sort(r.begin(), r.end());
      return r;
    }
  }
  static std::uint64_t ridge_hash(const Ridge& key) {
    if constexpr (D <= 3) {
      return key * 0x9e3779b97f4a7c15ull;
    } else {
      std::uint64_t h = 0;
      for (Index x : key) h = (h ^ x) * 0x9e3779b97f4a7c15ull;
      return h;
    }
  }

  /// The facets through the new point, matched in pairs by their other D − 1
  /// vertices: open addressing; a slot is empty unless stamped with the
  /// current insertion, so nothing is cleared between insertions.
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
    /// The reference parked under `key`, removed; or parks `ref` and returns none.
    std::uint32_t match_or_park(const Ridge& key, std::uint32_t ref) {
      for (std::size_t i = (ridge_hash(key) >> 40) & mask_;; i = (i + 1) & mask_) {
        Slot& s = slots_[i];
        if (s.stamp != stamp_) {
          s = {key, ref, stamp_};
          return none;
        }
        if (s.ref != taken && s.key == key) {
          const std::uint32_t partner = s.ref;
          s.ref = taken;  // a tombstone: later probes pass over it
          return partner;
        }
      }
    }

   private:
    static constexpr std::uint32_t taken = none - 1;
    struct Slot {
      Ridge key{};
      std::uint32_t ref = none;
      std::uint32_t stamp = 0;
    };
    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
    std::uint32_t stamp_ = 0;
  };

  std::vector<Point> points_;    // by vertex id (insertion order)
  std::vector<Index> input_;     // the caller's id of each vertex
  /// A cell slot: its vertices and its neighbour references side by side, so
  /// that the cell the cavity search reads (vertices) is the one the star
  /// writes (a neighbour) in the same cache line.
  struct alignas(D == 3 ? 32 : 8) Record {
    Cell v;
    std::array<std::uint32_t, D + 1> n;
  };
  std::vector<Record> cells_;    // by slot
  std::vector<std::uint8_t> mark_;  // 0, or find_cavity's in / out, by slot
  std::vector<Index> free_;      // free slots
  std::size_t finite_cells_ = 0;
  std::size_t last_ = 0;         // a finite cell made last: the next walk starts there
  std::vector<std::size_t> cavity_;
  std::vector<Boundary_facet> boundary_;
  Ridge_table ridges_;
  std::vector<Index> new_cells_;  // the slot of each boundary facet's new cell
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
  std::vector<Local> local_ = std::vector<Local>(D <= 3 ? local_table_size : 0);
  std::uint32_t local_stamp_ = 0;
  std::vector<std::array<std::uint32_t, 2>> keys_;
  std::vector<std::uint32_t> star_table_ =
      std::vector<std::uint32_t>(D == 3 ? star_table_side * star_table_side : D == 2 ? 2 * star_table_side : 0);
  Incremental_statistics stats_;
  kernel::Static_filter_d<D> static_filter_;  // from the points' box: in front of the kernel's cascade
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
