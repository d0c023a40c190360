// The insertion order of the incremental engine (incremental_delaunay.hpp):
// biased randomized insertion order (BRIO; Amenta, Choi, Rote, "Incremental
// constructions con BRIO", SoCG 2003) with each round along a Hilbert curve.
//
// Why: an incremental Delaunay construction spends its time locating each new
// point (a walk from the last cell created) and in cache misses on the cells it
// touches. Consecutive points close in space make both short; the random rounds
// keep the cavities small in expectation (a pure curve order can build long
// thin cells first, on a lattice for example).
//
// 1. Rounds: each point draws its round from a seeded hash of its
//    coordinates (our own generator: the order, hence the output's cell
//    order, is the same on every platform; of the coordinates, not of the
//    index, so that equal points draw the same round: step 4): the last
//    round with probability 3/4, the one before
//    with 3/16, and so on, the first round taking all points that would come
//    before a round of `smallest_round` points (CGAL's multiscale sort uses the
//    same ratio; the draws replace its shuffle, which reads the points in
//    random order). Rounds of at least 250 points: with larger ones a small
//    input is one round, a single pass along the curve, which builds long
//    thin cells first and destroys them later (docs/engines.md, "order").
// 2. Each round sorted by the Hilbert index of its points (J. Skilling,
//    "Programming the Hilbert curve", AIP Conf. Proc. 707, 2004: the
//    transposed index from the axes, then the bits interleaved; in 2D and 3D
//    as tables of the curve's states, derived from it), on a grid over the points' bounding box
//    sized for their number (grid_bits; in 2D finer where that costs no
//    radix pass); every other round runs the curve backwards, so that each
//    round starts near where the last one ended. Points of one round that
//    share a cell, when there are 4 or more, go along a grid over their own
//    box, and so on down (a cluster beside a few far points, a curve in the
//    plane): the order adapts to the points' spread, as a sort by medians
//    would (CGAL's), at a grid's cost where they are spread evenly.
// 3. One sort of (round, index) keys: the keys are computed in input order
//    (the coordinates read once, in sequence) and radix sorted (stable: equal
//    keys keep input order); both in parallel, with the same result for any
//    number of threads (the serial parts of a two-core build: docs/engines.md).
// 4. Optionally, repeated points dropped on the way (brio_order_of_distinct):
//    equal points have equal keys, so after the sort they lie in one run of
//    equal keys, in input order; comparing the points within each run (most
//    runs are one point long) finds them without the hash table of
//    kernel::first_occurrences (docs/engines.md has the figures).
// Floating point only ranks here: the order changes the time, never the
// triangulation (which is a function of the point set).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>

#include "dewall/detail/common/box.hpp"
#include "dewall/detail/common/hashing.hpp"
#include "dewall/detail/common/parallel.hpp"
#include "dewall/detail/common/radix_sort.hpp"
#include "dewall/detail/incremental/hilbert_curve.hpp"
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"

namespace dewall::detail {

namespace brio {

/// Runs of equal keys of this many points or more go along a grid of their
/// own (order): below, that costs more than it saves (runs of 2 or 3 are
/// common in volume data, about 3 on surfaces in 3D: no fewer walk steps).
inline constexpr std::size_t min_refined_run = 4;
/// The levels of those grids, at most (an input whose runs never shrink much,
/// 2^-k for k = 1, 2, …, takes a level for every few points).
inline constexpr int max_refinements = 24;

/// Appends to `order` the first occurrence of each point of `run` (indices of
/// points with one key, ascending): the points not equal to an earlier one.
/// Equal as the kernel's exact lexicographic order has it (on the bits: a
/// subnormal is not 0 even with denormals-are-zero on; −0 and +0 alike).
template <class Coords>
void append_first_occurrences(std::span<const std::uint32_t> run, Coords& coords, std::vector<std::uint32_t>& order) {
  const auto compare = [&](std::uint32_t a, std::uint32_t b) {
    return kernel::compare_lexicographically(coords(a), coords(b));
  };
  if (run.size() <= 16) {  // the usual case by far: compare each point with those kept before it
    const std::size_t kept_before = order.size();
    for (const std::uint32_t i : run) {
      bool repeated = false;
      for (std::size_t k = kept_before; k < order.size() && !repeated; ++k)
        repeated = compare(order[k], i) == kernel::EQUAL;
      if (!repeated) order.push_back(i);
    }
    return;
  }
  // Many points in one grid cell of one round: one point repeated many
  // times, or a cluster. The copies of the run's first point are found in
  // one pass (a point repeated many times then sorts nothing), the rest sorted by (point, index), their
  // coordinates copied rather than read through the index at every
  // comparison, and each after the first of its group repeats.
  std::vector<std::uint32_t> repeats;
  std::vector<std::pair<std::remove_cvref_t<decltype(coords(run[0]))>, std::uint32_t>> others;
  for (const std::uint32_t i : run.subspan(1)) {
    if (compare(run[0], i) == kernel::EQUAL) repeats.push_back(i);
    else others.push_back({coords(i), i});
  }
  std::sort(others.begin(), others.end(), [](const auto& a, const auto& b) {
    const kernel::Comparison_result c = kernel::compare_lexicographically(a.first, b.first);
    return c == kernel::SMALLER || (c == kernel::EQUAL && a.second < b.second);
  });
  for (std::size_t k = 1; k < others.size(); ++k)
    if (kernel::compare_lexicographically(others[k - 1].first, others[k].first) == kernel::EQUAL)
      repeats.push_back(others[k].second);
  std::sort(repeats.begin(), repeats.end());
  for (const std::uint32_t i : run)
    if (!std::binary_search(repeats.begin(), repeats.end(), i)) order.push_back(i);
}

/// The levels of the Hilbert order's grid for `count` points: at least 4
/// cells a point spacing of uniform points (2^(D·(bits − 2)) ≥ count). Finer
/// grids only split cells that hold no two points, and each level costs the
/// keys and the radix sort.
template <int D>
inline constexpr int max_grid_bits = 60 / D < 16 ? 60 / D : 16;
template <int D>
int grid_bits(std::size_t count) {
  int bits = 2;
  while (bits < max_grid_bits<D> && (std::uint64_t{1} << (D * (bits - 2))) < count) ++bits;
  return bits;
}


/// The levels of the key grid for `count` points: grid_bits, and in 2D the
/// finer levels that fit in the same radix passes (and still in one word
/// with the index, when the key did): they cost nothing there, as the
/// table's index reads all 16 levels anyway, and they split the cells of
/// points on a curve. Above 2D each level costs the transform a step.
template <int D>
int key_grid_bits(std::size_t count) {
  int bits = grid_bits<D>(count);
  if constexpr (D == 2) {
    const auto passes = [](int levels) { return (D * levels + 4 + radix_digit_bits - 1) / radix_digit_bits; };
    const int word_limit = D * bits + 4 <= 32 ? 32 : 64;
    while (bits < max_grid_bits<D> && D * (bits + 1) + 4 <= word_limit && passes(bits + 1) == passes(bits)) ++bits;
  }
  return bits;
}

/// The last round of `count` points: level L (drawn with probability
/// 3/4^(L+1)) is round last − L; the levels beyond it (rounds smaller than
/// smallest_round) join round 0.
inline int last_round(std::size_t count, std::size_t smallest_round) {
  int last = 0;
  for (std::size_t n = count; n > smallest_round && last < 15; n /= 4) ++last;
  return last;
}

/// The work of brio_order and brio_order_of_distinct (one object per call):
/// the BRIO order, without the repeated points when Drop_repeats. Steps:
/// key_of_point for every point, sort_keys, and for each run of equal keys
/// refine, whose leaves go to emit.
template <bool Drop_repeats, int D, class Coords>
class Order_builder {
 public:
  /// To be made in the default floating-point environment (order's guard):
  /// the grid's scales are computed here.
  Order_builder(std::size_t count, Coords& coords, const Box<D>& box, std::size_t smallest_round, std::uint64_t seed)
      : count_(count),
        coords_(coords),
        seed_(seed),
        round_shift_(D * key_grid_bits<D>(count)),
        key_bits_(round_shift_ + 4),
        last_(last_round(count, smallest_round)),
        grid_(box, round_shift_ / D) {}

  std::vector<std::uint32_t> run() && {
    order_.reserve(count_);
    if (key_bits_ <= 32)  // key and index in one word (key above): half the memory each pass moves
      sort_keys([&](std::size_t i) { return key_of_point(i) << 32 | i; }, 32, [](std::uint64_t w) { return w; },
                [](std::uint64_t w) { return static_cast<std::uint32_t>(w); });
    else
      sort_keys([&](std::size_t i) { return std::pair{key_of_point(i), static_cast<std::uint32_t>(i)}; }, 0,
                [](const std::pair<std::uint64_t, std::uint32_t>& item) { return item.first; },
                [](const std::pair<std::uint64_t, std::uint32_t>& item) { return item.second; });
    return std::move(order_);
  }

 private:
  /// Point i's key: its round above its Hilbert index, a function of the
  /// point alone (equal points, equal keys), so computed in parallel.
  std::uint64_t key_of_point(std::size_t i) const {
    const auto& x = coords_(i);
    std::uint64_t draw = mix64(seed_ ^ kernel::coordinate_hash(x));
    int level = 0;
    while (level < last_ && (draw & 3) == 0) ++level, draw >>= 2;
    const int round = last_ - level;
    // Every other round backwards, so that each starts where the last ended.
    return std::uint64_t(round) << round_shift_ | grid_.index(x, round % 2);
  }

  /// Keys in parallel, sorted by their key_bits_ bits from first_bit on,
  /// then the indices read off run by run. TBB runs tasks in the environment
  /// its arena recorded, not the caller's: without the guard in each range
  /// the order would depend on it.
  template <class Item_of, class Key_of, class Index_of>
  void sort_keys(Item_of item_of, int first_bit, Key_of key_of, Index_of index_of) {
    std::vector<decltype(item_of(std::size_t{0}))> keyed(count_);
    parallel_ranges(count_, 1 << 14, [&](const tbb::blocked_range<std::size_t>& range) {
      const kernel::Fp_environment_guard range_guard;
      for (std::size_t i = range.begin(); i < range.end(); ++i) keyed[i] = item_of(i);
    });
    radix_sort(keyed, first_bit, first_bit + key_bits_, key_of);
    std::vector<std::uint32_t> run;
    const auto key = [&](std::size_t k) { return static_cast<std::uint64_t>(key_of(keyed[k])) >> first_bit; };
    for (std::size_t a = 0; a < count_;) {  // runs [a, b) of equal keys
      std::size_t b = a + 1;
      while (b < count_ && key(b) == key(a)) ++b;
      if (b - a == 1) {
        order_.push_back(index_of(keyed[a]));
      } else {
        run.clear();
        for (std::size_t k = a; k < b; ++k) run.push_back(index_of(keyed[k]));
        if (run.size() < min_refined_run) emit(run);
        else refine(std::span<std::uint32_t>(run), (key(a) >> round_shift_) % 2 != 0);
      }
      a = b;
    }
  }

  /// A run of points of one round in one cell (equal keys), indices
  /// ascending, goes along the curve of a grid over its own box when it
  /// holds min_refined_run points or more, each run of that grid likewise,
  /// down to max_refinements levels: where a few far points set the box, a
  /// cluster shares one cell; points on a curve or surface share a few.
  /// Equal points have equal keys at every level: they meet in one leaf,
  /// where the repeats go. In place, depth first from a stack of pending
  /// parts (the next on top): memory O(n) however deep.
  void refine(std::span<std::uint32_t> run, bool backwards) {
    pending_.assign(1, Part{0, run.size(), 0});
    while (!pending_.empty()) {
      const Part part = pending_.back();
      pending_.pop_back();
      const std::span<std::uint32_t> points = run.subspan(part.begin, part.end - part.begin);
      if (points.size() < min_refined_run || part.depth == max_refinements) {
        emit(points);
        continue;
      }
      const Box<D> part_box =
          bounding_box<D>(points.size(), [&](std::size_t k) -> decltype(auto) { return coords_(points[k]); });
      if (part_box.lo == part_box.hi) {  // one point, repeated
        emit(points);
        continue;
      }
      const Hilbert_grid<D> part_grid(part_box, grid_bits<D>(points.size()));
      part_keys_.resize(points.size());
      for (std::size_t k = 0; k < points.size(); ++k)
        part_keys_[k] = {part_grid.index(coords_(points[k]), backwards), points[k]};
      // By (index, point index): stable, as the part's indices ascend.
      if (part_keys_.size() > 4096)
        radix_sort(part_keys_, 0, D * part_grid.bits(), [](const auto& item) { return item.first; });
      else
        std::sort(part_keys_.begin(), part_keys_.end());
      // One cell: no axis splits the part (one point repeated; extents that
      // round to nothing): deeper grids would give the same.
      if (part_keys_.front().first == part_keys_.back().first) {
        emit(points);
        continue;
      }
      for (std::size_t k = 0; k < part_keys_.size(); ++k) points[k] = part_keys_[k].second;
      for (std::size_t e = part_keys_.size(); e > 0;) {  // its cells' parts, the last pushed first
        std::size_t c = e - 1;
        while (c > 0 && part_keys_[c - 1].first == part_keys_[e - 1].first) --c;
        pending_.push_back(Part{part.begin + c, part.begin + e, part.depth + 1});
        e = c;
      }
    }
  }

  /// Appends a leaf of refine (or a short run) to the order, its repeats
  /// left out when Drop_repeats.
  void emit(std::span<const std::uint32_t> leaf) {
    if (!Drop_repeats || leaf.size() == 1) order_.insert(order_.end(), leaf.begin(), leaf.end());
    else append_first_occurrences(leaf, coords_, order_);
  }

  struct Part {
    std::size_t begin, end;
    int depth;
  };
  std::size_t count_;
  Coords& coords_;
  std::uint64_t seed_;
  int round_shift_;  // the round above the Hilbert index
  int key_bits_;
  int last_;
  Hilbert_grid<D> grid_;
  std::vector<std::uint32_t> order_;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> part_keys_;  // refine's scratch
  std::vector<Part> pending_;                                      // refine's stack
};

/// brio_order and brio_order_of_distinct: the BRIO order, without the
/// repeated points when Drop_repeats. The grids' scales and the runs' grids
/// in the default environment, not the caller's (rounding mode,
/// denormals-are-zero): the order is a function of the coordinates alone.
template <bool Drop_repeats, int D, class Coords>
std::vector<std::uint32_t> order(std::size_t count, Coords&& coords, const Box<D>& box, std::size_t smallest_round,
                                 std::uint64_t seed) {
  const kernel::Fp_environment_guard guard;
  return Order_builder<Drop_repeats, D, std::remove_reference_t<Coords>>(count, coords, box, smallest_round, seed)
      .run();
}

}  // namespace brio

/// The BRIO order of `count` points: a permutation of 0 … count − 1.
/// `coords(i)` gives point i's coordinates (an array of D doubles, finite;
/// called from several threads at once);
/// `box` is bounding_box(count, coords). Deterministic: a function of the
/// coordinates and `seed`.
template <int D, class Coords>
std::vector<std::uint32_t> brio_order(std::size_t count, Coords&& coords, const Box<D>& box,
                                      std::size_t smallest_round = 250, std::uint64_t seed = 0x5eed) {
  return brio::order<false, D>(count, coords, box, smallest_round, seed);
}

/// The BRIO order of the distinct points among `count` (as brio_order; equal
/// coordinates, −0 and +0 alike, are one point): of each set of equal points
/// only the first occurrence (the smallest index) appears, the others are
/// left out. The order of the points kept is brio_order's with the others
/// removed.
template <int D, class Coords>
std::vector<std::uint32_t> brio_order_of_distinct(std::size_t count, Coords&& coords, const Box<D>& box,
                                                  std::size_t smallest_round = 250, std::uint64_t seed = 0x5eed) {
  return brio::order<true, D>(count, coords, box, smallest_round, seed);
}

/// The same, computing the box.
template <int D, class Coords>
std::vector<std::uint32_t> brio_order(std::size_t count, Coords&& coords) {
  const kernel::Fp_environment_guard guard;  // the box too (subnormals under denormals-are-zero)
  return brio_order<D>(count, coords, bounding_box<D>(count, coords));
}

}  // namespace dewall::detail
