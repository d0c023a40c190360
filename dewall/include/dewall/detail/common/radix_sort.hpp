// A stable least-significant-digit radix sort over parallel chunks, with
// the same result for any number of threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "dewall/detail/common/parallel.hpp"

namespace dewall::detail {

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

}  // namespace dewall::detail
