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

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
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
    Coords<D> lo, hi;    // the bounding box of the node's points (their exact coordinates)
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
    order_.resize(coords.size());
    leaf_of_.resize(coords.size());
    std::iota(order_.begin(), order_.end(), Index{0});
    nodes_.reserve(2 * (coords.size() / leaf_size_ + 1));
    nodes_.push_back({});
    nodes_[0].parent = 0;
    build(coords, 0, 0, static_cast<Index>(coords.size()));
  }

  const std::vector<Index>& order() const { return order_; }
  const Node& root() const { return nodes_[0]; }
  const Node& node(Index i) const { return nodes_[i]; }
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t leaf_count() const { return (nodes_.size() + 1) / 2; }
  std::size_t leaf_size() const { return leaf_size_; }
  /// The leaf holding the point at position p.
  Index leaf_of(Index p) const { return leaf_of_[p]; }
  /// The bounding box of all points.
  const Coords<D>& lower() const { return nodes_[0].lo; }
  const Coords<D>& upper() const { return nodes_[0].hi; }

 private:
  void build(const std::vector<Coords<D>>& coords, Index at, Index begin, Index end) {
    Node& n = nodes_[at];
    n.begin = begin;
    n.end = end;
    n.first_child = 0;
    n.lo = n.hi = coords[order_[begin]];
    for (Index i = begin + 1; i < end; ++i)
      for (int j = 0; j < D; ++j) {
        const double v = coords[order_[i]][j];
        n.lo[j] = std::min(n.lo[j], v);
        n.hi[j] = std::max(n.hi[j], v);
      }
    int axis = 0;
    for (int j = 1; j < D; ++j)
      if (n.hi[j] - n.lo[j] > n.hi[axis] - n.lo[axis]) axis = j;
    // A box of zero width holds points with equal approximate coordinates
    // (distinct only in a kernel with more precise points): a leaf, whatever its size.
    if (end - begin <= leaf_size_ || !(n.hi[axis] > n.lo[axis])) {
      std::fill(leaf_of_.begin() + begin, leaf_of_.begin() + end, at);
      return;
    }
    const Index middle = begin + (end - begin) / 2;
    // Ties on the axis are broken by the next axes: on a lattice half the
    // points of the median plane go to each side, and an arbitrary half would
    // stretch every box below to that plane (measured: twice the candidates).
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](Index p, Index q) {
      for (int k = 0; k < D; ++k) {
        const int j = (axis + k) % D;
        if (coords[p][j] != coords[q][j]) return coords[p][j] < coords[q][j];
      }
      return false;
    });
    const auto child = static_cast<Index>(nodes_.size());
    nodes_[at].first_child = child;  // `n` may dangle after the push_back below
    nodes_.push_back({});
    nodes_.push_back({});
    nodes_[child].parent = nodes_[child + 1].parent = at;
    build(coords, child, begin, middle);
    build(coords, child + 1, middle, end);
  }

  std::size_t leaf_size_ = 8;
  std::vector<Index> order_;
  std::vector<Index> leaf_of_;  // by position: a search starts at a face vertex's leaf
  std::vector<Node> nodes_;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
