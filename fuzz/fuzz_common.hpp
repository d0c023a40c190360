// Shared byte decoding for the libFuzzer harnesses (fuzz_*.cpp).
//
// A harness reads its input through a Byte_source: every read succeeds (an
// exhausted source yields zeros), so each byte string decodes to *some* valid
// input and the fuzzer never wastes executions on rejected ones (the input is
// trimmed to the valid domain first, as spade's fuzz targets do). Small, mutation-friendly
// encodings are preferred: one byte picks a dimension or a family, one byte a
// small integer, eight bytes a raw double. Coordinates come in styles chosen to
// reach the parts of the kernel that plain random doubles never reach:
//  * small integers (exact lattices: collinear, coplanar and cospherical points
//    are common, so the exact stage and the perturbation run);
//  * small integers times a shared power of two from 2^-1074 to 2^1000 (the same
//    degeneracies, but subnormal or huge, outside the float filter's domain);
//  * small integers plus a large shared offset (exact, but the differences
//    cancel catastrophically);
//  * lattice values nudged by a few ulps (nearly degenerate: the filter must
//    fail and the later stages decide);
//  * raw 64-bit patterns (any finite double, subnormals included).
// Harness-specific checks live in the harnesses; this header only decodes.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "dewall/kernel/dimension.hpp"
#include "dewall/kernel/point.hpp"

namespace dewall::fuzz {

/// Sequential reader over the fuzzer's bytes; zeros once exhausted.
class Byte_source {
 public:
  Byte_source(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool exhausted() const { return pos_ >= size_; }
  std::size_t remaining() const { return exhausted() ? 0 : size_ - pos_; }

  std::uint8_t byte() { return exhausted() ? 0 : data_[pos_++]; }

  /// An integer in [lo, hi] from one byte (two when the range needs it).
  /// Modulo keeps every byte value meaningful; the bias does not matter here.
  int integer(int lo, int hi) {
    const unsigned span = static_cast<unsigned>(hi - lo) + 1u;
    unsigned v = byte();
    if (span > 256u) v = (v << 8) | byte();
    return lo + static_cast<int>(v % span);
  }

  /// The next eight bytes as a double's bit pattern (little-endian).
  double raw_double() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= std::uint64_t{byte()} << (8 * i);
    return std::bit_cast<double>(bits);
  }

  /// Like raw_double, but NaN and infinities are folded into finite values by
  /// clearing the top exponent bit, which keeps sign and mantissa (so the
  /// mutation that produced them still means something).
  double finite_double() {
    double v = raw_double();
    if (!std::isfinite(v)) v = std::bit_cast<double>(std::bit_cast<std::uint64_t>(v) & ~(std::uint64_t{1} << 62));
    return v;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// How the coordinates of one input are drawn (see the file comment).
enum class Coordinate_style : int {
  small_integer,      // [-8, 8]
  scaled_integer,     // [-8, 8] · 2^e, one e per input in [-1074, 1000]
  offset_integer,     // [-8, 8] + one large integer offset per input
  nudged_integer,     // [-8, 8] moved by -3 … +3 ulps
  raw,                // any finite double
  mixed,              // one of the above per coordinate
};
inline constexpr int coordinate_style_count = 6;

/// Per-input parameters of the coordinate styles, read once from the header.
struct Coordinate_decoder {
  Coordinate_style style = Coordinate_style::small_integer;
  int exponent = 0;     // for scaled_integer
  double offset = 0;    // for offset_integer: an integer up to 2^45, so offset ± 8 stays exact

  static Coordinate_decoder read(Byte_source& in) {
    Coordinate_decoder d;
    d.style = static_cast<Coordinate_style>(in.integer(0, coordinate_style_count - 1));
    d.exponent = in.integer(-1074, 1000);
    const double high = in.integer(0, 255), low = in.integer(0, 65535);
    d.offset = std::ldexp(high, 37) + std::ldexp(low, 8) * (in.byte() & 1 ? -1 : 1);
    return d;
  }

  double coordinate(Byte_source& in) const { return coordinate(in, style); }

 private:
  double coordinate(Byte_source& in, Coordinate_style s) const {
    switch (s) {
      case Coordinate_style::small_integer:
        return in.integer(-8, 8);
      case Coordinate_style::scaled_integer:
        // Exact: |k| ≤ 8 < 2^53 and the product stays in range for e ≤ 1000;
        // for e near -1074 the values are subnormal multiples of 2^-1074.
        return std::ldexp(static_cast<double>(in.integer(-8, 8)), exponent);
      case Coordinate_style::offset_integer:
        return offset + in.integer(-8, 8);
      case Coordinate_style::nudged_integer: {
        double v = in.integer(-8, 8);
        const int ulps = in.integer(-3, 3);
        for (int i = 0; i < ulps; ++i) v = std::nextafter(v, HUGE_VAL);
        for (int i = 0; i > ulps; --i) v = std::nextafter(v, -HUGE_VAL);
        return v;
      }
      case Coordinate_style::raw:
        return in.finite_double();
      case Coordinate_style::mixed:
        return coordinate(in, static_cast<Coordinate_style>(in.integer(0, coordinate_style_count - 2)));
    }
    return 0;
  }
};

template <int D>
kernel::Point_d<D> read_point(Byte_source& in, const Coordinate_decoder& decoder) {
  kernel::Point_d<D> p;
  for (int j = 0; j < D; ++j) p[j] = decoder.coordinate(in);
  return p;
}

/// Calls f.template operator()<D>() for the runtime dimension d ∈ [2, 6].
template <class F>
void with_dimension(int d, F&& f) {
  if (d >= kernel::min_dimension && d <= kernel::max_dimension)
    kernel::with_dimension(d, [&](auto dimension) { f.template operator()<decltype(dimension)::value>(); });
}

/// Reports a property violation and aborts, which libFuzzer records as a crash
/// with the input saved; the message says which property and on what.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz check failed: %s\n", what);
  std::fflush(stderr);
  std::abort();
}

template <int D>
void print_points(const char* title, std::span<const kernel::Point_d<D>> points) {
  std::fprintf(stderr, "%s (%zu points, D = %d):\n", title, points.size(), D);
  for (const auto& p : points) {
    for (int j = 0; j < D; ++j) std::fprintf(stderr, j ? " %.17g" : "%.17g", p[j]);
    std::fprintf(stderr, "\n");
  }
}

}  // namespace dewall::fuzz

/// Checks a property on the current input; on failure prints the expression
/// and aborts (a libFuzzer finding). Always on, unlike assert().
#define DEWALL_FUZZ_CHECK(expr) ((expr) ? static_cast<void>(0) : ::dewall::fuzz::fail(#expr))
