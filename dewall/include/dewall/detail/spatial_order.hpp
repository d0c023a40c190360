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
//    random order). Rounds of at least 250 points: with 1000, an input of up
//    to 4000 points was one round, a single pass along the curve, which
//    builds long thin cells first and destroys them later (two planes, 10^3
//    points: 29,012 cells created against CGAL's 23,063; with 250, 23,046).
//    Measured with an engine driver, 3D, 10^3 points, 1000 → 250: two planes
//    −21 %, uniform −12 %, a sphere −16 %, a torus −10 %; 2D uniform −18 %;
//    4D −10 to −14 %; 10^4 points within ±2 % (64, CGAL's 3D threshold, the
//    same at 10^3 and up to 3 % slower on a circle at 10^4).
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
//    kernel::first_occurrences, which cost 13–26 ms of a 2D construction's
//    450 at 10^6 points (docs/engines.md).
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
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"

namespace dewall::detail {

/// The low 16 bits of v with two zero bits after each (bit b moves to bit
/// 3b): hilbert_index's interleaving in 3D, in four steps, not a loop over
/// every bit.
constexpr std::uint64_t spread_bits_3(std::uint32_t v) {
  std::uint64_t x = v & 0xffffu;
  x = (x | x << 16) & 0x0000ff0000ffull;  // the high byte up by 16
  x = (x | x << 8) & 0x00f00f00f00full;
  x = (x | x << 4) & 0x0c30c30c30c3ull;
  x = (x | x << 2) & 0x249249249249ull;
  return x;
}

/// The plane's Hilbert curve as a machine of four states (whether the frame
/// of the bits still to come is swapped, whether it is complemented),
/// tabulated four levels at a time: entry [state][x's 4 bits][y's 4 bits] is
/// the 4 base-4 digits | the next state << 8. At each level the frame's bits
/// (rx, ry) give the digit 2·rx + (rx ^ ry), and when ry = 0 the frame is
/// swapped, and complemented too when rx = 1.
inline constexpr auto hilbert_table_2 = [] {
  std::array<std::uint16_t, 1024> table{};
  for (unsigned state = 0; state < 4; ++state)
    for (unsigned xb = 0; xb < 16; ++xb)
      for (unsigned yb = 0; yb < 16; ++yb) {
        unsigned swapped = state & 1, complemented = state >> 1, digits = 0;
        for (int level = 3; level >= 0; --level) {
          const unsigned bx = xb >> level & 1, by = yb >> level & 1;
          const unsigned rx = (swapped ? by : bx) ^ complemented, ry = (swapped ? bx : by) ^ complemented;
          digits = digits << 2 | rx << 1 | (rx ^ ry);
          if (!ry) swapped ^= 1, complemented ^= rx;
        }
        table[state << 8 | xb << 4 | yb] = static_cast<std::uint16_t>(digits | (swapped | complemented << 1) << 8);
      }
  return table;
}();

/// Skilling's transform (J. Skilling, "Programming the Hilbert curve", AIP
/// Conf. Proc. 707, 2004): the D coordinates of a grid cell (each `bits`
/// bits, bits ≤ 16 in 3D) become its Hilbert index, interleaved into one
/// integer (D·bits ≤ 64).
template <int D>
constexpr std::uint64_t skilling_hilbert_index(std::array<std::uint32_t, D> x, int bits) {
  // Axes to transposed index: undo the excess work of the Gray code. When
  // bit q of axis i is set, invert the low bits of the first axis, else
  // exchange the low bits of the two; written with masks, not branches (the
  // bits are the points' and a branch on them mispredicts half the time).
  for (std::uint32_t q = std::uint32_t{1} << (bits - 1); q > 1; q >>= 1) {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < D; ++i) {
      const std::uint32_t set = 0u - static_cast<std::uint32_t>((x[i] & q) != 0);  // all ones or zero
      const std::uint32_t t = (x[0] ^ x[i]) & p & ~set;
      x[0] ^= (p & set) | t;
      x[i] ^= t;
    }
  }
  // Gray encode.
  for (int i = 1; i < D; ++i) x[i] ^= x[i - 1];
  std::uint32_t t = 0;
  for (std::uint32_t q = std::uint32_t{1} << (bits - 1); q > 1; q >>= 1)
    t ^= (q - 1) & (0u - static_cast<std::uint32_t>((x[D - 1] & q) != 0));
  for (int i = 0; i < D; ++i) x[i] ^= t;
  // Interleave: bit b of axis i is bit b·D + (D − 1 − i) of the index.
  std::uint64_t index = 0;
  if constexpr (D == 3) {
    for (int i = 0; i < D; ++i) index |= spread_bits_3(x[i]) << (D - 1 - i);
  } else {
    for (int b = bits - 1; b >= 0; --b)
      for (int i = 0; i < D; ++i) index = index << 1 | ((x[i] >> b) & 1u);
  }
  return index;
}

/// Space's Hilbert curve (skilling_hilbert_index's) as a machine of states,
/// one level a lookup: entry [state · 8 + octant] is the level's digit | the
/// next state << 3, the octant being the level's bits of the three axes (the
/// first axis's highest). Derived from the transform itself, at compile time:
/// a state is known by the digits it gives the 8 octants (the curve's copy in
/// a sub-cube is the whole curve moved by a symmetry of the cube, and
/// different symmetries number the octants differently), and each state,
/// reached by a prefix of octants, is probed one level deeper (the transform
/// nests: on a grid of fewer levels a cell's index is the leading digits of
/// its sub-cells'). 24 states; a test checks it against the transform at
/// every level. 8 ns a cell at 9 levels against the transform's 31 (a
/// quarter of the 3D order's time at 10^6 points).
inline constexpr auto hilbert_table_3 = [] {
  constexpr int max_states = 32, max_depth = 15;
  using Prefix = std::array<unsigned, max_depth>;
  const auto digits_below = [](const Prefix& prefix, int length) {
    std::array<std::uint8_t, 8> digits{};
    for (unsigned octant = 0; octant < 8; ++octant) {
      std::array<std::uint32_t, 3> x{};
      for (int k = 0; k <= length; ++k) {
        const unsigned o = k < length ? prefix[static_cast<std::size_t>(k)] : octant;
        for (int i = 0; i < 3; ++i) x[static_cast<std::size_t>(i)] = x[static_cast<std::size_t>(i)] << 1 | ((o >> (2 - i)) & 1u);
      }
      digits[octant] = static_cast<std::uint8_t>(skilling_hilbert_index<3>(x, length + 1) & 7);
    }
    return digits;
  };
  std::array<std::array<std::uint8_t, 8>, max_states> state_digits{};
  std::array<Prefix, max_states> prefixes{};
  std::array<int, max_states> lengths{};
  std::array<std::uint8_t, max_states * 8> entry{};
  int states = 1;
  state_digits[0] = digits_below(prefixes[0], 0);
  for (int k = 0; k < states; ++k)
    for (unsigned octant = 0; octant < 8; ++octant) {
      Prefix prefix = prefixes[static_cast<std::size_t>(k)];
      const int length = lengths[static_cast<std::size_t>(k)];
      if (length == max_depth) throw "hilbert_table_3: a state deeper than expected";
      prefix[static_cast<std::size_t>(length)] = octant;
      const auto digits = digits_below(prefix, length + 1);
      int next = 0;
      while (next < states && state_digits[static_cast<std::size_t>(next)] != digits) ++next;
      if (next == states) {
        if (states == max_states) throw "hilbert_table_3: more states than expected";
        state_digits[static_cast<std::size_t>(next)] = digits;
        prefixes[static_cast<std::size_t>(next)] = prefix;
        lengths[static_cast<std::size_t>(next)] = length + 1;
        ++states;
      }
      entry[static_cast<std::size_t>(k) * 8 + octant] =
          static_cast<std::uint8_t>(state_digits[static_cast<std::size_t>(k)][octant] | next << 3);
    }
  return entry;
}();

/// The Hilbert index of a grid cell (as skilling_hilbert_index, the same
/// curve). In 2D from hilbert_table_2, four lookups (bits ≤ 16; measured:
/// 2.7 ns a cell against 48 ns for the transform, which took a tenth of a 2D
/// construction), in 3D from hilbert_table_3, one a level; the test checks
/// both equal the transform.
template <int D>
std::uint64_t hilbert_index(std::array<std::uint32_t, D> x, int bits) {
  if constexpr (D == 2) {
    // As if padded with zero levels above to 16: a level of zeros gives the
    // digit 0 and swaps the frame, so an odd padding starts swapped.
    unsigned state = static_cast<unsigned>(16 - bits) & 1;
    std::uint64_t index = 0;
    for (int shift = 12; shift >= 0; shift -= 4) {
      const unsigned entry = hilbert_table_2[state << 8 | (x[0] >> shift & 15) << 4 | (x[1] >> shift & 15)];
      index = index << 8 | (entry & 255);
      state = entry >> 8;
    }
    return index;
  } else if constexpr (D == 3) {  // bits ≤ 16
    unsigned state = 0;
    std::uint64_t index = 0;
    for (int b = bits - 1; b >= 0; --b) {
      const unsigned octant = (x[0] >> b & 1u) << 2 | (x[1] >> b & 1u) << 1 | (x[2] >> b & 1u);
      const unsigned entry = hilbert_table_3[state << 3 | octant];
      index = index << 3 | (entry & 7);
      state = entry >> 3;
    }
    return index;
  } else {
    return skilling_hilbert_index<D>(x, bits);
  }
}

/// splitmix64's finalizer: a well-mixed 64-bit hash (the seeded draws of the rounds).
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// Calls f(c) for c = 0 … chunks − 1, as parallel tasks when there are
/// several. Isolated, as parallel_ranges.
template <class F>
void for_each_chunk(std::size_t chunks, F&& f) {
  if (chunks == 1) f(std::size_t{0});
  else tbb::this_task_arena::isolate([&] { tbb::parallel_for(std::size_t{0}, chunks, f); });
}

/// Calls f(range) on ranges of [0, count) of about `grain` indices, as
/// parallel tasks. Isolated: while it waits for them, the calling thread takes
/// no unrelated outer task (a hybrid's region builds inside one).
template <class F>
void parallel_ranges(std::size_t count, std::size_t grain, F&& f) {
  tbb::this_task_arena::isolate(
      [&] { tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain), f); });
}

/// The bits radix_sort sorts by in one pass.
inline constexpr int radix_digit_bits = 11;

/// Sorts `items` stably by bits first_bit … end_bit − 1 of key_of(item)
/// (least significant digit first, 11 bits a pass). Each pass runs over
/// contiguous chunks of the items, in parallel: every chunk counts its
/// digits, a chunk's items of a digit go after those of the chunks before
/// it, and each chunk scatters its items in order — so the result is the one
/// stable order, whatever the chunks and the threads.
template <class Item, class Key_of>
void radix_sort(std::vector<Item>& items, int first_bit, int end_bit, Key_of&& key_of) {
  constexpr int digit = radix_digit_bits;
  constexpr std::size_t buckets = std::size_t{1} << digit;
  const std::size_t n = items.size();
  // Chunks of at least 2^16 items (a chunk's counts are 16 KB), at most 64.
  const std::size_t chunks = std::clamp<std::size_t>(n >> 16, 1, 64);
  const auto chunk_begin = [&](std::size_t c) { return n * c / chunks; };
  std::vector<Item> other(n);
  std::vector<std::size_t> start(chunks * buckets);  // [chunk][digit]
  for (int shift = first_bit; shift < end_bit; shift += digit) {
    const auto digit_of = [shift, &key_of](const Item& item) {
      return (static_cast<std::uint64_t>(key_of(item)) >> shift) & (buckets - 1);
    };
    // Each chunk's bounds are read into locals first: in the loops' own
    // conditions they were divided out again for every item (the counts'
    // stores may alias n and chunks, so the compiler cannot hoist them; the
    // division was a third of the sort's time, 2D circle 10^5).
    for_each_chunk(chunks, [&](std::size_t c) {
      std::size_t* const count = &start[c * buckets];
      std::fill(count, count + buckets, 0);
      const std::size_t begin = chunk_begin(c), end = chunk_begin(c + 1);
      for (std::size_t i = begin; i < end; ++i) ++count[digit_of(items[i])];
    });
    std::size_t sum = 0;
    for (std::size_t d = 0; d < buckets; ++d)
      for (std::size_t c = 0; c < chunks; ++c) sum += std::exchange(start[c * buckets + d], sum);
    for_each_chunk(chunks, [&](std::size_t c) {
      std::size_t* const next = &start[c * buckets];
      const std::size_t begin = chunk_begin(c), end = chunk_begin(c + 1);
      for (std::size_t i = begin; i < end; ++i) other[next[digit_of(items[i])]++] = items[i];
    });
    items.swap(other);
  }
}

/// The smallest box [lo, hi] holding `count` points (coords(i): point i's
/// coordinates); lo = +inf, hi = −inf when there are none.
template <int D>
struct Box {
  std::array<double, D> lo, hi;
};
template <int D, class Coords>
Box<D> bounding_box(std::size_t count, Coords&& coords) {
  Box<D> box;
  box.lo.fill(std::numeric_limits<double>::infinity());
  box.hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < count; ++i) {
    const auto& x = coords(i);
    for (int j = 0; j < D; ++j) {
      box.lo[j] = std::min(box.lo[j], x[j]);
      box.hi[j] = std::max(box.hi[j], x[j]);
    }
  }
  return box;
}

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
  // one pass (a point repeated 10^6 times then sorts nothing: 148 ms sorted,
  // against the hash table's 17), the rest sorted by (point, index), their
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
/// keys and the radix sort (uniform 10^6: 3 passes instead of 5 in 3D and of
/// 4 in 2D).
template <int D>
inline constexpr int max_grid_bits = 60 / D < 16 ? 60 / D : 16;
template <int D>
int grid_bits(std::size_t count) {
  int bits = 2;
  while (bits < max_grid_bits<D> && (std::uint64_t{1} << (D * (bits - 2))) < count) ++bits;
  return bits;
}

/// The Hilbert indices of the cells of a grid of 2^bits cells a side over a
/// box: a function of the point alone (equal points, equal indices). An axis
/// whose extent overflows (|x| near 2^1023) is measured in half units, so
/// that it still orders the points (the halves are exact but for
/// subnormals, which round alike for equal points).
template <int D>
class Hilbert_grid {
 public:
  Hilbert_grid(const Box<D>& box, int bits) : bits_(bits), cells_(static_cast<double>((std::uint32_t{1} << bits) - 1)) {
    for (int j = 0; j < D; ++j) {
      unit_[j] = box.hi[j] - box.lo[j] < std::numeric_limits<double>::infinity() ? 1 : 0.5;
      lo_[j] = box.lo[j] * unit_[j];
      const double extent = box.hi[j] * unit_[j] - lo_[j];
      scale_[j] = extent > 0 && extent < std::numeric_limits<double>::infinity() ? cells_ / extent : 0;
    }
  }
  int bits() const { return bits_; }
  /// The index of x's cell (x in the box), counted from the curve's other
  /// end when `backwards`.
  std::uint64_t index(const std::array<double, D>& x, bool backwards) const {
    std::array<std::uint32_t, D> cell;
    for (int j = 0; j < D; ++j) {
      double t = (x[j] * unit_[j] - lo_[j]) * scale_[j];
      t = t < 0 || !(t == t) ? 0 : t > cells_ ? cells_ : t;  // rounding at the box's ends; tiny extents (scale ∞)
      cell[j] = static_cast<std::uint32_t>(t);
    }
    const std::uint64_t h = hilbert_index<D>(cell, bits_);
    return backwards ? ~h & ((std::uint64_t{1} << (D * bits_)) - 1) : h;
  }

 private:
  std::array<double, D> unit_, lo_, scale_;
  int bits_;
  double cells_;
};

/// brio_order and brio_order_of_distinct: the BRIO order, without the
/// repeated points when Drop_repeats.
template <bool Drop_repeats, int D, class Coords>
std::vector<std::uint32_t> order(std::size_t count, Coords&& coords, const Box<D>& box, std::size_t smallest_round,
                                 std::uint64_t seed) {
  // The grids' scales and the runs' grids in the default environment, not
  // the caller's (rounding mode, denormals-are-zero): the order is a
  // function of the coordinates alone (the review of 2026-11-29).
  const kernel::Fp_environment_guard guard;
  int bits = grid_bits<D>(count);
  // In 2D, finer levels that fit in the same radix passes (and still in one
  // word with the index, when the key did) cost nothing: the table's index
  // reads all 16 levels anyway. They split the cells of points on a curve
  // (10^5 points on a circle: 11 → 14 levels, about 12 → 1.5 points a run;
  // the order 4.4 → 2.9 ms, walk steps 86 → 53 thousand, the construction
  // 28.7 → 25.3 ms). Above 2D each level costs the transform a step.
  if constexpr (D == 2) {
    const auto passes = [](int levels) { return (D * levels + 4 + radix_digit_bits - 1) / radix_digit_bits; };
    const int word_limit = D * bits + 4 <= 32 ? 32 : 64;
    while (bits < max_grid_bits<D> && D * (bits + 1) + 4 <= word_limit && passes(bits + 1) == passes(bits)) ++bits;
  }
  const int round_shift = D * bits;  // the round above the Hilbert index
  const Hilbert_grid<D> grid(box, bits);
  // Rounds: level L (drawn with probability 3/4^(L+1)) is round last − L; the
  // levels beyond `last` (rounds smaller than smallest_round) join round 0.
  int last = 0;
  for (std::size_t n = count; n > smallest_round && last < 15; n /= 4) ++last;
  // Each key is a function of its point alone (equal points, equal keys): computed in parallel.
  const auto key_of_point = [&](std::size_t i) {
    const auto& x = coords(i);
    std::uint64_t draw = mix64(seed ^ kernel::coordinate_hash(x));
    int level = 0;
    while (level < last && (draw & 3) == 0) ++level, draw >>= 2;
    const int round = last - level;
    // Every other round backwards, so that each starts where the last ended.
    return std::uint64_t(round) << round_shift | grid.index(x, round % 2);
  };
  const int key_bits = round_shift + 4;

  // A run of points of one round in one cell (equal keys), indices
  // ascending, goes along the curve of a grid over its own box when it holds
  // min_refined_run points or more, each run of that grid likewise, down to
  // max_refinements levels. Where a few far points set the box, a cluster
  // shares one cell (10^6 points in a box of 10^-6 beside two points at
  // ±10^6: one run, inserted in input order: 2D 96 s, walks of 813 steps a
  // point); points on a curve or surface share a few. Equal points have
  // equal keys at every level: they meet in one leaf, where the repeats go.
  std::vector<std::uint32_t> order;
  order.reserve(count);
  const auto emit = [&](std::span<const std::uint32_t> leaf) {
    if (!Drop_repeats || leaf.size() == 1) order.insert(order.end(), leaf.begin(), leaf.end());
    else append_first_occurrences(leaf, coords, order);
  };
  // In place, depth first from a stack of pending parts (the next on top):
  // memory O(n) however deep (one buffer for each level had grown to 9×
  // uniform points' on points spread log-uniformly over 1000 binades).
  std::vector<std::pair<std::uint64_t, std::uint32_t>> part_keys;
  struct Part {
    std::size_t begin, end;
    int depth;
  };
  std::vector<Part> pending;
  const auto refine = [&](std::span<std::uint32_t> run, bool backwards) {
    pending.assign(1, Part{0, run.size(), 0});
    while (!pending.empty()) {
      const Part part = pending.back();
      pending.pop_back();
      const std::span<std::uint32_t> points = run.subspan(part.begin, part.end - part.begin);
      if (points.size() < min_refined_run || part.depth == max_refinements) {
        emit(points);
        continue;
      }
      const Box<D> part_box = bounding_box<D>(points.size(), [&](std::size_t k) -> decltype(auto) { return coords(points[k]); });
      if (part_box.lo == part_box.hi) {  // one point, repeated
        emit(points);
        continue;
      }
      const Hilbert_grid<D> part_grid(part_box, grid_bits<D>(points.size()));
      part_keys.resize(points.size());
      for (std::size_t k = 0; k < points.size(); ++k) part_keys[k] = {part_grid.index(coords(points[k]), backwards), points[k]};
      // By (index, point index): stable, as the part's indices ascend.
      if (part_keys.size() > 4096) radix_sort(part_keys, 0, D * part_grid.bits(), [](const auto& item) { return item.first; });
      else std::sort(part_keys.begin(), part_keys.end());
      // One cell: no axis splits the part (one point repeated; extents that
      // round to nothing): deeper grids would give the same.
      if (part_keys.front().first == part_keys.back().first) {
        emit(points);
        continue;
      }
      for (std::size_t k = 0; k < part_keys.size(); ++k) points[k] = part_keys[k].second;
      for (std::size_t e = part_keys.size(); e > 0;) {  // its cells' parts, the last pushed first
        std::size_t c = e - 1;
        while (c > 0 && part_keys[c - 1].first == part_keys[e - 1].first) --c;
        pending.push_back(Part{part.begin + c, part.begin + e, part.depth + 1});
        e = c;
      }
    }
  };

  // Keys in parallel, sorted by their key_bits bits from first_bit on, then
  // the indices read off run by run. TBB runs tasks in the environment its
  // arena recorded, not the caller's: without the guard in each range the
  // order would depend on it (the review of 2026-11-26).
  const auto sort_keys = [&](auto item_of, int first_bit, auto key_of, auto index_of) {
    std::vector<decltype(item_of(std::size_t{0}))> keyed(count);
    parallel_ranges(count, 1 << 14, [&](const tbb::blocked_range<std::size_t>& range) {
      const kernel::Fp_environment_guard range_guard;
      for (std::size_t i = range.begin(); i < range.end(); ++i) keyed[i] = item_of(i);
    });
    radix_sort(keyed, first_bit, first_bit + key_bits, key_of);
    std::vector<std::uint32_t> run;
    const auto key = [&](std::size_t k) { return static_cast<std::uint64_t>(key_of(keyed[k])) >> first_bit; };
    for (std::size_t a = 0; a < count;) {  // runs [a, b) of equal keys
      std::size_t b = a + 1;
      while (b < count && key(b) == key(a)) ++b;
      if (b - a == 1) {
        order.push_back(index_of(keyed[a]));
      } else {
        run.clear();
        for (std::size_t k = a; k < b; ++k) run.push_back(index_of(keyed[k]));
        if (run.size() < min_refined_run) emit(run);
        else refine(std::span<std::uint32_t>(run), (key(a) >> round_shift) % 2 != 0);
      }
      a = b;
    }
  };
  if (key_bits <= 32)  // key and index in one word (key above): half the memory each pass moves
    sort_keys([&](std::size_t i) { return key_of_point(i) << 32 | i; }, 32, [](std::uint64_t w) { return w; },
              [](std::uint64_t w) { return static_cast<std::uint32_t>(w); });
  else
    sort_keys([&](std::size_t i) { return std::pair{key_of_point(i), static_cast<std::uint32_t>(i)}; }, 0,
              [](const std::pair<std::uint64_t, std::uint32_t>& item) { return item.first; },
              [](const std::pair<std::uint64_t, std::uint32_t>& item) { return item.second; });
  return order;
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
