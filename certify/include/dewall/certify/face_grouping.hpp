// Grouping the (k−1)-faces of k-vertex rows: which rows share which facet.
//
// The certifier matches the facets of the simplices (k = D + 1) and the ridges
// of the boundary facets (k = D). Instead of one global sort or a hash map of
// facet keys, every face is filed under its smallest vertex (a counting sort,
// linear in the number of faces), then each vertex's bucket — a few dozen faces
// in practice — is sorted by the full key. Exact (keys are compared, never only
// hashed), O(F + n) plus the small sorts, and cache friendly. Topology only:
// nothing here knows the kernel.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace dewall::certify::detail {

/// A face of row `row`: the row without its vertex at position `position`.
struct Face_ref {
  std::size_t row;
  int position;
};

/// The (K−1)-faces of k-vertex rows filed by smallest vertex (a counting sort);
/// `for_buckets` then groups the faces of a range of buckets. Ranges are
/// independent: disjoint ranges may be grouped at once, on different threads.
/// Few rows among many vertices (the boundary of a large triangulation) are
/// filed under their own smallest vertices only, so that the memory follows the
/// rows, not the vertex count.
/// \pre every index < vertex_count; the K indices of a row are distinct.
template <std::size_t K>
class Face_buckets {
 public:
  Face_buckets(std::size_t vertex_count, std::span<const std::array<std::uint32_t, K>> rows) : rows_(rows), n_(vertex_count) {
    static_assert(K >= 2);
    if (rows.size() * K < vertex_count / 8) {
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (int p = 0; p < static_cast<int>(K); ++p) vertices_.push_back(smallest(r, p));
      std::sort(vertices_.begin(), vertices_.end());
      vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
    }
    const std::size_t buckets = vertices_.empty() ? vertex_count : vertices_.size();
    start_.assign(buckets + 1, 0);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int p = 0; p < static_cast<int>(K); ++p) ++start_[bucket_of(smallest(r, p)) + 1];
    for (std::size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
    // Packed as row·K + position: one 64-bit word per face.
    refs_.resize(start_[buckets]);
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int p = 0; p < static_cast<int>(K); ++p)
        refs_[next[bucket_of(smallest(r, p))]++] = static_cast<std::uint64_t>(r) * K + static_cast<std::uint64_t>(p);
  }

  std::size_t vertex_count() const { return n_; }

  /// Calls `group(std::span<const Face_ref>)` once for every distinct face
  /// whose smallest vertex is in [first, last), with every row/position that
  /// has it (in increasing row order within a group), bucket by bucket.
  template <class Group>
  void for_buckets(std::size_t first, std::size_t last, Group&& group) const {
    std::vector<std::pair<Key, std::uint64_t>> bucket;
    std::vector<Face_ref> members;
    for (std::size_t b = first_bucket(first), end = first_bucket(last); b < end; ++b) {
      bucket.clear();
      for (std::size_t i = start_[b]; i < start_[b + 1]; ++i)
        bucket.emplace_back(key_of(static_cast<std::size_t>(refs_[i] / K), static_cast<int>(refs_[i] % K)), refs_[i]);
      std::sort(bucket.begin(), bucket.end());
      for (std::size_t i = 0; i < bucket.size();) {
        std::size_t j = i;
        members.clear();
        for (; j < bucket.size() && bucket[j].first == bucket[i].first; ++j)
          members.push_back({static_cast<std::size_t>(bucket[j].second / K), static_cast<int>(bucket[j].second % K)});
        group(std::span<const Face_ref>(members));
        i = j;
      }
    }
  }

 private:
  using Key = std::array<std::uint32_t, K - 1>;
  Key key_of(std::size_t row, int position) const {
    Key key;
    for (int j = 0, k = 0; j < static_cast<int>(K); ++j)
      if (j != position) key[static_cast<std::size_t>(k++)] = rows_[row][static_cast<std::size_t>(j)];
    std::sort(key.begin(), key.end());
    return key;
  }
  std::uint32_t smallest(std::size_t row, int position) const {
    std::uint32_t m = UINT32_MAX;
    for (int j = 0; j < static_cast<int>(K); ++j)
      if (j != position) m = std::min(m, rows_[row][static_cast<std::size_t>(j)]);
    return m;
  }

  /// The bucket of smallest vertex v (v one of them when filed sparsely).
  std::size_t bucket_of(std::uint32_t v) const {
    return vertices_.empty() ? v : static_cast<std::size_t>(std::lower_bound(vertices_.begin(), vertices_.end(), v) - vertices_.begin());
  }
  /// The first bucket of a smallest vertex ≥ v.
  std::size_t first_bucket(std::size_t v) const {
    if (vertices_.empty()) return std::min(v, n_);
    return static_cast<std::size_t>(std::lower_bound(vertices_.begin(), vertices_.end(), v) - vertices_.begin());
  }

  std::span<const std::array<std::uint32_t, K>> rows_;
  std::size_t n_;
  std::vector<std::uint32_t> vertices_;  // sparse: the smallest vertices, increasing (empty: every vertex a bucket)
  std::vector<std::size_t> start_;
  std::vector<std::uint64_t> refs_;
};

/// Calls `group(std::span<const Face_ref>)` once for every distinct (K−1)-face
/// of the rows, with every row/position that has it (in increasing row order
/// within a group). Groups come bucket by bucket (by smallest vertex).
/// \pre every index < vertex_count; the K indices of a row are distinct.
/// Complexity: O(rows·K + vertex_count) plus sorting each bucket (O(b log b) each).
template <std::size_t K, class Group>
void group_faces(std::size_t vertex_count, std::span<const std::array<std::uint32_t, K>> rows, Group&& group) {
  const Face_buckets<K> buckets(vertex_count, rows);
  buckets.for_buckets(0, vertex_count, group);
}

/// group_faces, telling `progress(fraction)` the share of the buckets grouped
/// every few thousand of them (what it throws stops the work).
template <std::size_t K, class Group, class Progress>
void group_faces(std::size_t vertex_count, std::span<const std::array<std::uint32_t, K>> rows, Group&& group,
                 Progress&& progress) {
  constexpr std::size_t block = std::size_t{1} << 14;
  const Face_buckets<K> buckets(vertex_count, rows);
  for (std::size_t first = 0; first < vertex_count; first += block) {
    progress(static_cast<double>(first) / static_cast<double>(vertex_count));
    buckets.for_buckets(first, std::min(vertex_count, first + block), group);
  }
}

}  // namespace dewall::certify::detail
