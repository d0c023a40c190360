// A share's screen of the rows (certify_share): every share reads every row,
// and keeps those with a vertex in its range. The screen is the one pass over
// all rows that does not shrink with the number of shares, so it is kept to a
// few loads per row: a bit per vertex (an eighth of a byte map, it stays in a
// core's cache) and no branch on the common row.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace dewall::certify::detail {

/// A set of the vertices 0 … n − 1, a bit each.
class Vertex_set {
 public:
  Vertex_set() = default;
  explicit Vertex_set(std::size_t n) : n_(n), words_((n + 63) / 64, 0) {}
  std::size_t universe() const { return n_; }
  void insert(std::size_t v) { words_[v >> 6] |= std::uint64_t{1} << (v & 63); }
  bool contains(std::size_t v) const { return v < n_ && ((words_[v >> 6] >> (v & 63)) & 1); }
  const std::uint64_t* words() const { return words_.data(); }

 private:
  std::size_t n_ = 0;
  std::vector<std::uint64_t> words_;
};

/// The rows rows[a, b) that matter to share `part` of `parts`: those with a
/// vertex in `mine`, and those with an index out of range (≥ mine.universe())
/// whose number r0 + i the share reports (r mod parts = part). Appends their
/// indices i, in increasing order, to `out`.
template <std::size_t K>
void screen_rows(std::span<const std::array<std::uint32_t, K>> rows, std::size_t a, std::size_t b, std::size_t r0,
                 const Vertex_set& mine, std::size_t part, std::size_t parts, std::vector<std::uint32_t>& out) {
  if (b <= a) return;
  const std::size_t n = mine.universe(), start = out.size();
  const std::uint64_t* words = mine.words();
  out.resize(start + (b - a));
  std::uint32_t* o = out.data() + start;
  std::size_t k = 0;
  for (std::size_t i = a; i < b; ++i) {
    const auto& c = rows[i];
    bool outside = false;
    for (std::uint32_t v : c) outside |= v >= n;
    // Written always, kept when counted: k ≤ i − a, so o[k] is in the space made above.
    o[k] = static_cast<std::uint32_t>(i);
    if (outside) [[unlikely]] {
      k += (r0 + i) % parts == part;
      continue;
    }
    std::uint64_t hit = 0;
    for (std::uint32_t v : c) hit |= words[v >> 6] >> (v & 63);
    k += hit & 1;
  }
  out.resize(start + k);
}

}  // namespace dewall::certify::detail
