// Facet matching over compact records: which simplices share which facet,
// with each facet's opposite vertices and orientations at hand.
//
// Every facet of a simplex is filed under its smallest vertex v (a counting
// sort), as a record of fixed size: the facet's other vertices, the simplex's
// vertex opposite the facet (its apex) and the simplex's row with one bit of
// orientation. Each vertex's bucket — a few dozen records — is then grouped by
// facet, so equal facets come together. The checks of a facet pair need
// nothing else: no simplex row is read again, and "the two apexes lie on
// opposite sides" is a comparison of the two orientation bits.
//
// Steps:
//  1. count the facets per smallest vertex;
//  2. cut the vertices into windows whose records fit a memory budget (or a
//     core's cache);
//  3. per window, file the records of the rows that have a facet there (the
//     order inside a bucket does not matter);
//  4. per bucket, hand out each group of equal facets: sorted, facets in
//     increasing order, or, when the caller does not need that order, matched
//     through a small hash table, in time linear in the bucket.
// Exact: facets are compared, a hash only places them. Topology only: nothing
// here knows the kernel.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

namespace dewall::certify::detail {

/// The K indices of a row in increasing order, and whether sorting them took
/// an odd permutation.
template <std::size_t K>
struct Sorted_row {
  std::array<std::uint32_t, K> v;
  bool odd;
};

template <std::size_t K>
inline Sorted_row<K> sort_row(const std::array<std::uint32_t, K>& row) {
  Sorted_row<K> s{row, false};
  // Odd-even transposition sort without branches (the order of a row's
  // indices is random: branches would mispredict); each exchange flips the parity.
  for (std::size_t round = 0; round < K; ++round)
    for (std::size_t i = round % 2; i + 1 < K; i += 2) {
      const std::uint32_t a = s.v[i], b = s.v[i + 1];
      const bool swap = a > b;
      s.v[i] = swap ? b : a;
      s.v[i + 1] = swap ? a : b;
      s.odd = s.odd != swap;
    }
  return s;
}

/// A facet of a D-simplex, filed under its smallest vertex (the bucket it is in).
/// Row: an unsigned type that holds 2·(row count).
template <int D, class Row>
struct Facet_record {
  std::array<std::uint32_t, D - 1> rest;  // the facet's other vertices, increasing
  std::uint32_t apex;                     // the simplex's vertex opposite the facet
  Row tag;                                // 2·row, + 1 when (smallest, rest…, apex) is positively oriented

  std::size_t row() const { return static_cast<std::size_t>(tag >> 1); }
  bool positive() const { return (tag & 1) != 0; }
  /// Whether the two records are of the same facet.
  bool same_facet(const Facet_record& o) const {
    for (std::size_t i = 0; i < rest.size(); ++i)
      if (rest[i] != o.rest[i]) return false;
    return true;
  }
  /// By facet, then by row (std::array's comparisons call memcmp: slow on 2
  /// words). Up to 3D the facet and the row fit one 128-bit key: one comparison.
  friend bool operator<(const Facet_record& a, const Facet_record& b) {
    if constexpr (D <= 3) {
      return a.key() < b.key();
    } else {
      for (std::size_t i = 0; i < a.rest.size(); ++i)
        if (a.rest[i] != b.rest[i]) return a.rest[i] < b.rest[i];
      return a.tag < b.tag;
    }
  }

 private:
  __extension__ using Key = unsigned __int128;  // GCC and Clang have it on 64-bit targets
  Key key() const {
    static_assert(D <= 3);
    std::uint64_t facet = 0;
    for (std::uint32_t v : rest) facet = (facet << 32) | v;
    return (static_cast<Key>(facet) << 64) | static_cast<std::uint64_t>(tag);
  }
};

/// A valid row as the certifier stores it: its vertices in increasing order
/// when that order is positively oriented, else with the last two exchanged
/// (the vertices are distinct, so the order of the last two tells which). An
/// invalid row (no proper simplex) repeats its first vertex.
template <std::size_t K>
inline std::array<std::uint32_t, K> encode_row(const std::array<std::uint32_t, K>& sorted, bool sorted_positive) {
  std::array<std::uint32_t, K> c = sorted;
  if (!sorted_positive) std::swap(c[K - 2], c[K - 1]);
  return c;
}
template <std::size_t K>
inline std::array<std::uint32_t, K> invalid_row() {
  std::array<std::uint32_t, K> c{};
  return c;
}
template <std::size_t K>
inline bool is_valid_row(const std::array<std::uint32_t, K>& c) {
  return c[0] != c[1];
}
/// The sorted vertices of an encoded valid row; returns whether that order is positive.
template <std::size_t K>
inline bool decode_row(std::array<std::uint32_t, K>& c) {
  const bool positive = c[K - 2] < c[K - 1];
  if (!positive) std::swap(c[K - 2], c[K - 1]);
  return positive;
}

/// Calls f(v, record) for every facet of a valid row, given by its vertices in
/// increasing order `s` and that order's orientation, whose smallest vertex v
/// lies in [first, last).
template <int D, class Row, class F>
inline void for_each_facet_record(const std::array<std::uint32_t, D + 1>& s, std::size_t r, bool sorted_positive,
                                  std::size_t first, std::size_t last, F&& f) {
  // The facets' smallest vertices are s[1] (the facet without s[0]) and s[0]:
  // a row with no vertex in the window files nothing (most rows, most windows).
  if (s[0] >= last || s[1] < first) return;
  for (int j = 0; j <= D; ++j) {
    const std::uint32_t smallest = s[j == 0 ? 1 : 0];
    if (smallest < first || smallest >= last) continue;
    Facet_record<D, Row> rec;
    // The facet but its smallest vertex: s[1 …] without s[j] (s[2 …] when j
    // is 0 or 1), picked without a branch.
    for (int k = 0; k + 1 < D; ++k)
      rec.rest[static_cast<std::size_t>(k)] = s[static_cast<std::size_t>(k + 1 + (k + 1 >= j ? 1 : 0))];
    rec.apex = s[static_cast<std::size_t>(j)];
    // (smallest, rest…, apex) is the sorted order with s[j] moved to the end:
    // D − j transpositions.
    const bool positive = sorted_positive != ((D - j) % 2 == 1);
    rec.tag = static_cast<Row>(2 * static_cast<Row>(r) + (positive ? 1 : 0));
    f(static_cast<std::size_t>(smallest), rec);
  }
}

/// Hands out the groups of equal facets of one bucket (smallest vertex v),
/// sorted: group(v, std::span<const Record>) once per facet, facets in
/// increasing order, each group's records in increasing row order. Sorts the bucket.
template <int D, class Row, class Group>
void sorted_groups(std::size_t v, Facet_record<D, Row>* begin, Facet_record<D, Row>* end, Group&& group) {
  using Record = Facet_record<D, Row>;
  // Buckets hold a few dozen records: insertion sort beats std::sort there.
  if (end - begin > 64) {
    std::sort(begin, end);
  } else {
    for (Record* i = begin + 1; i < end; ++i) {
      const Record x = *i;
      Record* j = i;
      for (; j != begin && x < *(j - 1); --j) *j = *(j - 1);
      *j = x;
    }
  }
  for (Record* i = begin; i != end;) {
    Record* j = i + 1;
    while (j != end && j->same_facet(*i)) ++j;
    group(v, std::span<const Record>(i, j));
    i = j;
  }
}

/// The groups of sorted_groups, each group's records in increasing row order,
/// but the groups in no particular order: the records are matched through a
/// small open-addressing table on the facet's vertices (the hash only places
/// a record: equal facets are found by comparing vertices), in time linear in
/// the bucket. A bucket too large for the table is sorted.
template <int D, class Row, class Group>
void unordered_groups(std::size_t v, Facet_record<D, Row>* begin, Facet_record<D, Row>* end, Group&& group) {
  using Record = Facet_record<D, Row>;
  const auto k = static_cast<std::size_t>(end - begin);
  constexpr std::size_t max_hashed = 127;  // group numbers (from 1) fit a byte, the table 256 slots
  if (k <= 1 || k > max_hashed) {
    sorted_groups(v, begin, end, group);
    return;
  }
  // A facet's vertices as one key: up to 3D one word, else the array. Group 0
  // marks a free slot; its key, all ones, is no facet's (the vertices increase).
  using Key = std::conditional_t<(D <= 3), std::uint64_t, std::array<std::uint32_t, D - 1>>;
  const auto key_of = [](const Record& r) {
    if constexpr (D <= 3) {
      std::uint64_t x = 0;
      for (std::uint32_t u : r.rest) x = (x << 32) | u;
      return x;
    } else {
      return r.rest;
    }
  };
  std::array<Key, max_hashed + 2> keys;
  if constexpr (D <= 3) keys[0] = ~std::uint64_t{0};
  else keys[0].fill(~std::uint32_t{0});
  const std::size_t slots = std::bit_ceil(2 * k);
  const int shift = 64 - std::countr_zero(slots);
  std::array<std::uint8_t, 2 * (max_hashed + 1)> table;  // group numbers, 0 when free
  std::fill_n(table.begin(), slots, std::uint8_t{0});
  // Per group: its first and last record and its size; per record: its group.
  std::array<std::uint8_t, max_hashed + 2> first, last, size;
  std::array<std::uint8_t, max_hashed> group_of;
  std::size_t groups = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Key key = key_of(begin[i]);
    std::uint64_t h = 0;
    for (std::uint32_t x : begin[i].rest) h = (h + x) * 0x9e3779b97f4a7c15u;
    std::size_t s = static_cast<std::size_t>(h >> shift);
    // Stops at a free slot or at the facet's group: one branch, almost always
    // out at once (the table is at most half full), while "free" and "found"
    // are equally likely and would mispredict as branches.
    std::size_t g;
    while (g = table[s], (g != 0) & (keys[g] != key)) s = (s + 1) & (slots - 1);
    const bool is_new = g == 0;
    // The new group, written whether or not it is used.
    const std::size_t fresh = groups + 1;
    keys[fresh] = key;
    first[fresh] = static_cast<std::uint8_t>(i);
    size[fresh] = 0;
    g = is_new ? fresh : g;
    table[s] = static_cast<std::uint8_t>(g);
    last[g] = static_cast<std::uint8_t>(i);
    ++size[g];
    group_of[i] = static_cast<std::uint8_t>(g);
    groups += is_new;
  }
  std::array<Record, max_hashed> members;
  for (std::size_t g = 1; g <= groups; ++g) {
    if (size[g] == 1) {
      group(v, std::span<const Record>(begin + first[g], 1));
    } else if (size[g] == 2) {
      // In row order (the rows of a pair come either way: no branch).
      const bool swap = begin[last[g]].tag < begin[first[g]].tag;
      members[0] = begin[swap ? last[g] : first[g]];
      members[1] = begin[swap ? first[g] : last[g]];
      group(v, std::span<const Record>(members.data(), 2));
    } else {
      // Three records or more (rejected input): all of them, in row order.
      std::size_t count = 0;
      for (std::size_t i = 0; i < k; ++i) {
        if (group_of[i] != g) continue;
        const Record x = begin[i];
        std::size_t j = count++;
        for (; j > 0 && x.tag < members[j - 1].tag; --j) members[j] = members[j - 1];
        members[j] = x;
      }
      group(v, std::span<const Record>(members.data(), count));
    }
  }
}

/// The facet records of the vertices [first, last), bucketed by smallest vertex.
template <int D, class Row>
class Facet_window {
 public:
  using Record = Facet_record<D, Row>;

  /// \pre counts[v - first] is the number of facets of valid rows whose
  /// smallest vertex is v. `storage` holds the records (grown when too small; reused from one
  /// window to the next, so that its pages are touched once).
  Facet_window(std::span<const std::uint32_t> counts, std::size_t first, std::size_t last, std::vector<Record>& storage)
      : first_(first), start_(last - first + 1, 0) {
    for (std::size_t v = first; v < last; ++v) start_[v - first + 1] = start_[v - first] + counts[v - first];
    next_.assign(start_.begin(), start_.end() - 1);
    if (storage.size() < start_.back()) storage.resize(start_.back());
    records_ = storage.data();
  }

  std::size_t first() const { return first_; }
  std::size_t last() const { return first_ + next_.size(); }

  /// Files the facets of row r (encoded: encode_row) whose smallest vertex is
  /// in [v_first, v_last), inside the window. Disjoint vertex ranges may be
  /// filed at once on different threads: they write disjoint buckets (no
  /// atomic counters, whose locked instructions would stall every scattered
  /// store behind them).
  void file(std::array<std::uint32_t, D + 1> row, std::size_t r, std::size_t v_first, std::size_t v_last) {
    if (!is_valid_row(row) || row[0] >= v_last) return;
    const bool positive = decode_row(row);
    for_each_facet_record<D, Row>(row, r, positive, v_first, v_last,
                                  [&](std::size_t v, const Record& rec) { records_[next_[v - first_]++] = rec; });
  }
  /// file() for rows[0 …] numbered from `first_row`.
  void file(std::span<const std::array<std::uint32_t, D + 1>> rows, std::size_t first_row, std::size_t v_first,
            std::size_t v_last) {
    for (std::size_t i = 0; i < rows.size(); ++i) file(rows[i], first_row + i, v_first, v_last);
  }

  /// Calls group(v, std::span<const Record>) once for every distinct facet whose
  /// smallest vertex v is in [v_first, v_last) (inside the window), with its
  /// records in increasing row order; bucket by bucket, facets in increasing
  /// order. Before a bucket's groups, ahead(v + 1, std::span<const Record>) is
  /// given the next bucket's records, unsorted (to prefetch what they need).
  /// Disjoint vertex ranges may be grouped at once on different threads.
  /// With `ordered` false, the facets of a bucket come in no particular order
  /// (unordered_groups: faster).
  template <class Group, class Ahead>
  void for_groups(std::size_t v_first, std::size_t v_last, Group&& group, Ahead&& ahead, bool ordered) {
    for (std::size_t v = v_first; v < v_last; ++v) {
      Record* begin = records_ + start_[v - first_];
      Record* end = records_ + start_[v - first_ + 1];
      if (v + 1 < v_last)
        ahead(v + 1, std::span<const Record>(records_ + start_[v + 1 - first_], records_ + start_[v + 2 - first_]));
      if (ordered) sorted_groups(v, begin, end, group);
      else unordered_groups(v, begin, end, group);
    }
  }

  template <class Group>
  void for_groups(std::size_t v_first, std::size_t v_last, Group&& group, bool ordered = true) {
    for_groups(v_first, v_last, group, [](std::size_t, std::span<const Record>) {}, ordered);
  }

 private:
  std::size_t first_;
  std::vector<std::size_t> start_;  // the buckets, then where each one's next record goes
  std::vector<std::size_t> next_;
  Record* records_;
};

/// Facets per smallest vertex of encoded rows, serially (tests; the
/// certifier counts while it validates).
template <int D>
std::vector<std::uint32_t> facet_counts(std::size_t vertex_count, std::span<const std::array<std::uint32_t, D + 1>> rows) {
  std::vector<std::uint32_t> counts(vertex_count, 0);
  for (auto row : rows) {
    if (!is_valid_row(row)) continue;
    decode_row(row);
    counts[row[0]] += D;
    ++counts[row[1]];
  }
  return counts;
}

/// All the facet groups of encoded rows, serially, in one window: group(v,
/// records) as Facet_window::for_groups calls it. For tests and small inputs.
template <int D, class Row = std::uint64_t, class Group>
void match_facets(std::size_t vertex_count, std::span<const std::array<std::uint32_t, D + 1>> rows, Group&& group,
                  bool ordered = true) {
  const auto counts = facet_counts<D>(vertex_count, rows);
  std::vector<Facet_record<D, Row>> storage;
  Facet_window<D, Row> window(counts, 0, vertex_count, storage);
  window.file(rows, 0, 0, vertex_count);
  window.for_groups(0, vertex_count, group, ordered);
}

}  // namespace dewall::certify::detail
