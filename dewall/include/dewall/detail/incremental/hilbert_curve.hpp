// The Hilbert curve over a grid (the BRIO order's rounds go along it,
// brio_order.hpp): Skilling's transform, and in 2D and 3D tables of the
// curve's states derived from it; Hilbert_grid maps a point of a box to the
// index of its grid cell. Floating point only ranks here.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "dewall/detail/common/box.hpp"

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
/// every level. A lookup a level is a fraction of the transform's cost
/// (docs/engines.md, "order").
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
/// curve). In 2D from hilbert_table_2, four lookups (bits ≤ 16), in 3D from
/// hilbert_table_3, one a level, both far cheaper than the transform; the
/// test checks both equal the transform.
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

namespace brio {

/// The Hilbert indices of the cells of a grid of 2^bits cells a side over a
/// box: a function of the point alone (equal points, equal indices). The
/// cells are cubes, one scale for every axis (the box's longest extent's):
/// on a flat box (a terrain tile, a depth frame's few planes) cells as thin
/// as the box would make the curve jump across the thin axis between
/// neighbours in the plane, and the walks from one point to the next longer
/// (docs/performance.md has the walk's steps per point). An input whose
/// extent overflows (|x| near 2^1023) is measured in half units on every
/// axis, so that it still orders the points (the halves are exact but for
/// subnormals, which round alike for equal points).
template <int D>
class Hilbert_grid {
 public:
  Hilbert_grid(const Box<D>& box, int bits) : bits_(bits), cells_(static_cast<double>((std::uint32_t{1} << bits) - 1)) {
    for (int j = 0; j < D; ++j)
      if (!(box.hi[j] - box.lo[j] < std::numeric_limits<double>::infinity())) unit_ = 0.5;
    double extent = 0;
    for (int j = 0; j < D; ++j) {
      lo_[j] = box.lo[j] * unit_;
      extent = std::max(extent, box.hi[j] * unit_ - lo_[j]);
    }
    scale_ = extent > 0 && extent < std::numeric_limits<double>::infinity() ? cells_ / extent : 0;
  }
  int bits() const { return bits_; }
  /// The index of x's cell (x in the box), counted from the curve's other
  /// end when `backwards`.
  std::uint64_t index(const std::array<double, D>& x, bool backwards) const {
    std::array<std::uint32_t, D> cell;
    for (int j = 0; j < D; ++j) {
      double t = (x[j] * unit_ - lo_[j]) * scale_;
      t = t < 0 || !(t == t) ? 0 : t > cells_ ? cells_ : t;  // rounding at the box's ends; tiny extents (scale ∞)
      cell[j] = static_cast<std::uint32_t>(t);
    }
    const std::uint64_t h = hilbert_index<D>(cell, bits_);
    return backwards ? ~h & ((std::uint64_t{1} << (D * bits_)) - 1) : h;
  }

 private:
  std::array<double, D> lo_;
  double unit_ = 1, scale_ = 0;
  int bits_;
  double cells_;
};

}  // namespace brio
}  // namespace dewall::detail
