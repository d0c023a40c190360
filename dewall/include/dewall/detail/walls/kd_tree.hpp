// Kd_tree: the search structure, adapted to the distribution of the points.
//
// Each node splits its points at the median of its widest axis, down to leaves
// of at most `leaf_size` points, and records the tight bounding box of its
// points. The points are renumbered in tree order (their coordinates and ids
// permuted in place), so every node's points are one range of consecutive
// local indices and a leaf's coordinates are contiguous in memory: a search
// reads a leaf as one short array.
//
// Why not the paper's uniform grid: a grid sized by n has about one point per
// cell on volume data only. On a surface sample most cells are empty and the
// others hold tens of points, and a cluster crowds hundreds into one cell; the
// median split keeps every leaf at `leaf_size` points whatever the
// distribution, and the tight boxes hug a surface.
//
// Like the grid, the tree only orders and prunes a search: a node is skipped
// when a test proves its box cannot hold a point of interest; every decision
// about a point is an exact predicate (make_simplex.hpp).
#pragma once

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "dewall/detail/common/assert.hpp"
#include "dewall/detail/common/coords.hpp"
#include "dewall/detail/walls/face.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <int D>
class Kd_tree {
 public:
  struct Node {
    Coords<D> lo, hi;    // the bounding box of the node's points (Point_set's coordinates: scaled by
                         // a power of two, exact when the kernel's points are doubles)
    Index begin, end;    // the node's points: positions [begin, end) in tree order
    Index first_child;   // the children are first_child and first_child + 1; 0 for a leaf
    Index parent;        // the root is its own parent
    bool is_leaf() const { return first_child == 0; }
  };

  Kd_tree() = default;

  /// Builds the tree over `coords`, permuting `coords` and `ids` alike into
  /// tree order (ids[i] then says which point came to position i); nodes
  /// refer to positions. In place: the build needs no copy of the points
  /// beside them (the streaming run's peak was that copy: 32 bytes a point
  /// beside the 24 of the coordinates). \pre coords is not empty and as
  /// long as ids; leaf_size ≥ 1. `quickselect_rounds` (tests): the rounds
  /// a median selection may take before its fallback (select), when ≥ 0.
  Kd_tree(std::vector<Coords<D>>& coords, std::vector<Index>& ids, std::size_t leaf_size, int quickselect_rounds = -1)
      : leaf_size_(std::max<std::size_t>(1, leaf_size)), quickselect_rounds_(quickselect_rounds) {
    DEWALL_ASSERT(!coords.empty() && coords.size() == ids.size());
    leaf_of_.resize(coords.size());
    count_nodes(coords.size());
    nodes_.resize(subtree_nodes_.at(coords.size()));
    nodes_[0].parent = 0;
    build({coords, ids}, 0, 0, static_cast<Index>(coords.size()), 1);
  }

  const Node& node(Index i) const { return nodes_[i]; }
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t leaf_count() const { return (nodes_.size() + 1) / 2; }
  /// The leaf holding the point at position p.
  Index leaf_of(Index p) const { return leaf_of_[p]; }
  /// The bounding box of all points.
  const Coords<D>& lower() const { return nodes_[0].lo; }
  const Coords<D>& upper() const { return nodes_[0].hi; }

 private:
  /// The points being ordered: coordinates and ids, permuted together.
  struct Points {
    std::vector<Coords<D>>& x;
    std::vector<Index>& id;
    void swap(Index i, Index j) const {
      std::swap(x[i], x[j]);
      std::swap(id[i], id[j]);
    }
  };

  /// The order a node's median splits in: along `axis`, ties broken by the
  /// next axes. On a lattice half the points of the median plane then go to
  /// each side; an arbitrary half would stretch every box below to that
  /// plane (measured: twice the candidates).
  static bool before(const Coords<D>& p, const Coords<D>& q, int axis) {
    if (p[axis] != q[axis]) return p[axis] < q[axis];  // nearly always
    for (int k = 1; k < D; ++k) {
      const int j = (axis + k) % D;
      if (p[j] != q[j]) return p[j] < q[j];
    }
    return false;
  }

  /// std::nth_element's contract on two arrays at once: the point of rank
  /// `middle` (in before's order) at position middle of [begin, end), none
  /// after it before it, none before it after it. Quickselect with a
  /// three-way partition around the median of three (points with equal
  /// coordinates, possible in kernels more precise than double, are one
  /// class, so every round removes at least the pivot's); an input that
  /// defeats the median of three, detected by the round count, is finished
  /// by std::nth_element on a copy of that range.
  void select(const Points& p, Index begin, Index middle, Index end, int axis) const {
    const auto less = [axis](const Coords<D>& a, const Coords<D>& b) { return before(a, b, axis); };
    int rounds_left = quickselect_rounds_ >= 0 ? quickselect_rounds_ : 2 * static_cast<int>(std::bit_width(end - begin)) + 8;
    while (end - begin > 8) {
      if (rounds_left-- == 0) return select_by_copy(p, begin, middle, end, axis);
      const Index m = begin + (end - begin) / 2;
      if (less(p.x[m], p.x[begin])) p.swap(m, begin);
      if (less(p.x[end - 1], p.x[begin])) p.swap(end - 1, begin);
      if (less(p.x[end - 1], p.x[m])) p.swap(end - 1, m);
      const Coords<D> pivot = p.x[m];
      Index lt = begin, i = begin, gt = end;  // [begin, lt) <, [lt, i) =, [gt, end) > pivot
      while (i < gt) {
        if (less(p.x[i], pivot)) p.swap(lt++, i++);
        else if (less(pivot, p.x[i])) p.swap(i, --gt);
        else ++i;
      }
      if (middle < lt) end = lt;
      else if (middle >= gt) begin = gt;
      else return;
    }
    for (Index i = begin + 1; i < end; ++i)  // insertion sort
      for (Index j = i; j > begin && less(p.x[j], p.x[j - 1]); --j) p.swap(j, j - 1);
  }
  static void select_by_copy(const Points& p, Index begin, Index middle, Index end, int axis) {
    std::vector<std::pair<Coords<D>, Index>> items;
    items.reserve(end - begin);
    for (Index i = begin; i < end; ++i) items.emplace_back(p.x[i], p.id[i]);
    std::nth_element(items.begin(), items.begin() + (middle - begin), items.end(),
                     [axis](const auto& a, const auto& b) { return before(a.first, b.first, axis); });
    for (Index i = begin; i < end; ++i) std::tie(p.x[i], p.id[i]) = items[i - begin];
  }

  // The layout is fixed by the sizes alone: a node's children are a pair at
  // `pair`, then the left child's descendants, then the right child's (the
  // order a serial depth-first build allocates them in). So both halves can be
  // built at once, each knowing where its nodes go.
  void build(const Points& points, Index at, Index begin, Index end, Index pair) {
    Node& n = nodes_[at];
    n.begin = begin;
    n.end = end;
    n.first_child = 0;
    n.lo = n.hi = points.x[begin];
    for (Index i = begin + 1; i < end; ++i)
      for (int j = 0; j < D; ++j) {
        const double v = points.x[i][j];
        n.lo[j] = std::min(n.lo[j], v);
        n.hi[j] = std::max(n.hi[j], v);
      }
    int axis = 0;
    for (int j = 1; j < D; ++j)
      if (n.hi[j] - n.lo[j] > n.hi[axis] - n.lo[axis]) axis = j;
    // (A box of zero width, points with equal approximate coordinates in a
    // kernel with more precise points, is split like any other: the layout
    // depends on the sizes only.)
    if (end - begin <= leaf_size_) {
      std::fill(leaf_of_.begin() + begin, leaf_of_.begin() + end, at);
      return;
    }
    const Index middle = begin + (end - begin) / 2;
    select(points, begin, middle, end, axis);
    n.first_child = pair;
    nodes_[pair].parent = nodes_[pair + 1].parent = at;
    const Index left_pairs = pair + 2;
    const auto right_pairs = static_cast<Index>(left_pairs + subtree_nodes_.at(middle - begin) - 1);
    auto left = [&] { build(points, pair, begin, middle, left_pairs); };
    auto right = [&] { build(points, pair + 1, middle, end, right_pairs); };
    if (end - begin >= parallel_points) tbb::parallel_invoke(left, right);
    else {
      left();
      right();
    }
  }

  /// subtree_nodes_[m]: the nodes of a subtree over m points. Halving gives at
  /// most two sizes per level (m and m + 1 split into sizes b and b + 1), so
  /// the table has O(log n) entries.
  void count_nodes(std::size_t n) {
    std::vector<std::vector<std::size_t>> levels{{n}};
    while (levels.back().front() > leaf_size_ || levels.back().back() > leaf_size_) {
      std::vector<std::size_t> next;
      for (std::size_t m : levels.back())
        if (m > leaf_size_) next.insert(next.end(), {m / 2, m - m / 2});
      std::sort(next.begin(), next.end());
      next.erase(std::unique(next.begin(), next.end()), next.end());
      levels.push_back(next);
    }
    for (auto level = levels.rbegin(); level != levels.rend(); ++level)
      for (std::size_t m : *level)
        subtree_nodes_[m] = m <= leaf_size_ ? 1 : 1 + subtree_nodes_.at(m / 2) + subtree_nodes_.at(m - m / 2);
  }

  // Subtrees of fewer points are built serially (a task costs more than that).
  static constexpr Index parallel_points = 1 << 15;
  std::size_t leaf_size_ = 8;
  int quickselect_rounds_ = -1;
  std::map<std::size_t, std::size_t> subtree_nodes_;  // read-only while building
  std::vector<Index> leaf_of_;  // by position: a search starts at a face vertex's leaf
  std::vector<Node> nodes_;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
