// Kd_tree: the search structure, adapted to the distribution of the points.
//
// Each node splits its points at the median of its widest axis, down to leaves
// of at most `leaf_size` points, and records the tight bounding box of its
// points. The points are renumbered in tree order (`order()`), so every node's
// points are one range of consecutive local indices and a leaf's coordinates
// are contiguous in memory: a search reads a leaf as one short array.
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
#include <cstdint>
#include <map>
#include <vector>

#include "dewall/detail/coords.hpp"
#include "dewall/detail/face.hpp"
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

  /// Builds the tree over `coords` (indexed by point). Afterwards order()[i] is
  /// the point at position i of the tree order; nodes refer to positions.
  /// \pre coords is not empty; leaf_size ≥ 1.
  Kd_tree(const std::vector<Coords<D>>& coords, std::size_t leaf_size) : leaf_size_(std::max<std::size_t>(1, leaf_size)) {
    // The build permutes (coordinates, index) pairs rather than indices into
    // `coords`: each comparison of the median selections then reads memory in
    // order instead of two random points. (The selections remain a visible
    // share of the 2D hybrid: O(n log n) work where CGAL's 2D is cheap;
    // docs/engines.md.)
    std::vector<Item> items(coords.size());
    for (std::size_t i = 0; i < coords.size(); ++i) items[i] = {coords[i], static_cast<Index>(i)};
    leaf_of_.resize(coords.size());
    count_nodes(coords.size());
    nodes_.resize(subtree_nodes_.at(coords.size()));
    nodes_[0].parent = 0;
    build(items, 0, 0, static_cast<Index>(coords.size()), 1);
    order_.resize(coords.size());
    for (std::size_t i = 0; i < items.size(); ++i) order_[i] = items[i].index;
  }

  const std::vector<Index>& order() const { return order_; }
  const Node& node(Index i) const { return nodes_[i]; }
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t leaf_count() const { return (nodes_.size() + 1) / 2; }
  /// The leaf holding the point at position p.
  Index leaf_of(Index p) const { return leaf_of_[p]; }
  /// The bounding box of all points.
  const Coords<D>& lower() const { return nodes_[0].lo; }
  const Coords<D>& upper() const { return nodes_[0].hi; }

 private:
  struct Item {
    Coords<D> x;
    Index index;
  };

  // The layout is fixed by the sizes alone: a node's children are a pair at
  // `pair`, then the left child's descendants, then the right child's (the
  // order a serial depth-first build allocates them in). So both halves can be
  // built at once, each knowing where its nodes go.
  void build(std::vector<Item>& items, Index at, Index begin, Index end, Index pair) {
    Node& n = nodes_[at];
    n.begin = begin;
    n.end = end;
    n.first_child = 0;
    n.lo = n.hi = items[begin].x;
    for (Index i = begin + 1; i < end; ++i)
      for (int j = 0; j < D; ++j) {
        const double v = items[i].x[j];
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
    // Ties on the axis are broken by the next axes: on a lattice half the
    // points of the median plane go to each side, and an arbitrary half would
    // stretch every box below to that plane (measured: twice the candidates).
    std::nth_element(items.begin() + begin, items.begin() + middle, items.begin() + end,
                     [axis](const Item& p, const Item& q) {
                       if (p.x[axis] != q.x[axis]) return p.x[axis] < q.x[axis];  // nearly always
                       for (int k = 1; k < D; ++k) {
                         const int j = (axis + k) % D;
                         if (p.x[j] != q.x[j]) return p.x[j] < q.x[j];
                       }
                       return false;
                     });
    n.first_child = pair;
    nodes_[pair].parent = nodes_[pair + 1].parent = at;
    const Index left_pairs = pair + 2;
    const auto right_pairs = static_cast<Index>(left_pairs + subtree_nodes_.at(middle - begin) - 1);
    auto left = [&] { build(items, pair, begin, middle, left_pairs); };
    auto right = [&] { build(items, pair + 1, middle, end, right_pairs); };
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
  std::map<std::size_t, std::size_t> subtree_nodes_;  // read-only while building
  std::vector<Index> order_;
  std::vector<Index> leaf_of_;  // by position: a search starts at a face vertex's leaf
  std::vector<Node> nodes_;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
