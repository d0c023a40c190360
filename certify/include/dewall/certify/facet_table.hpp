// Facet matching over compact records: which simplices share which facet,
// with each facet's opposite vertices and orientations at hand.
//
// Every facet of a simplex is filed under its smallest vertex v (a counting
// sort), as a record of fixed size: the facet's other vertices, the simplex's
// vertex opposite the facet (its apex) and the simplex's row with one bit of
// orientation. Each vertex's bucket — a few dozen records — is then sorted by
// (facet, row), so equal facets come together. The checks of a facet pair need
// nothing else: no simplex row is read again, and "the two apexes lie on
// opposite sides" is a comparison of the two orientation bits.
//
// Steps:
//  1. count the facets per smallest vertex (the caller, while it validates rows);
//  2. cut the vertices into windows whose records fit a memory budget;
//  3. per window, file the records of every valid row (ranges of vertices in
//     parallel; the order inside a bucket does not matter, it is sorted);
//  4. per bucket, sort by (facet, row) and hand out each group of equal facets.
// Exact: keys are compared, never hashed. Topology only: nothing here knows the kernel.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
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
    for (int i = 0, k = 0; i <= D; ++i)
      if (i != j && s[static_cast<std::size_t>(i)] != smallest) rec.rest[static_cast<std::size_t>(k++)] = s[static_cast<std::size_t>(i)];
    rec.apex = s[static_cast<std::size_t>(j)];
    // (smallest, rest…, apex) is the sorted order with s[j] moved to the end:
    // D − j transpositions.
    const bool positive = sorted_positive != ((D - j) % 2 == 1);
    rec.tag = static_cast<Row>(2 * static_cast<Row>(r) + (positive ? 1 : 0));
    f(static_cast<std::size_t>(smallest), rec);
  }
}

/// The facet records of the vertices [first, last), bucketed by smallest vertex.
template <int D, class Row>
class Facet_window {
 public:
  using Record = Facet_record<D, Row>;

  /// \pre counts[v] is the number of facets of valid rows whose smallest vertex
  /// is v. `storage` holds the records (grown when too small; reused from one
  /// window to the next, so that its pages are touched once).
  Facet_window(std::span<const std::uint32_t> counts, std::size_t first, std::size_t last, std::vector<Record>& storage)
      : first_(first), start_(last - first + 1, 0) {
    for (std::size_t v = first; v < last; ++v) start_[v - first + 1] = start_[v - first] + counts[v];
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
  template <class Group, class Ahead>
  void for_groups(std::size_t v_first, std::size_t v_last, Group&& group, Ahead&& ahead) {
    for (std::size_t v = v_first; v < v_last; ++v) {
      Record* begin = records_ + start_[v - first_];
      Record* end = records_ + start_[v - first_ + 1];
      if (v + 1 < v_last)
        ahead(v + 1, std::span<const Record>(records_ + start_[v + 1 - first_], records_ + start_[v + 2 - first_]));
      sort_bucket(begin, end);
      for (Record* i = begin; i != end;) {
        Record* j = i + 1;
        while (j != end && j->same_facet(*i)) ++j;
        group(v, std::span<const Record>(i, j));
        i = j;
      }
    }
  }

  template <class Group>
  void for_groups(std::size_t v_first, std::size_t v_last, Group&& group) {
    for_groups(v_first, v_last, group, [](std::size_t, std::span<const Record>) {});
  }

 private:
  static void sort_bucket(Record* begin, Record* end) {
    // Buckets hold a few dozen records: insertion sort beats std::sort there.
    if (end - begin > 64) {
      std::sort(begin, end);
      return;
    }
    for (Record* i = begin + 1; i < end; ++i) {
      const Record x = *i;
      Record* j = i;
      for (; j != begin && x < *(j - 1); --j) *j = *(j - 1);
      *j = x;
    }
  }

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
void match_facets(std::size_t vertex_count, std::span<const std::array<std::uint32_t, D + 1>> rows, Group&& group) {
  const auto counts = facet_counts<D>(vertex_count, rows);
  std::vector<Facet_record<D, Row>> storage;
  Facet_window<D, Row> window(counts, 0, vertex_count, storage);
  window.file(rows, 0, 0, vertex_count);
  window.for_groups(0, vertex_count, group);
}

}  // namespace dewall::certify::detail
