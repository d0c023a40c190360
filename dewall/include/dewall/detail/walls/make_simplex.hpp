// MakeSimplex: the Delaunay simplex on the outer side of a face (the paper's
// "dd-nearest" point), found through the kd-tree.
//
// Exactness. Among the points strictly on the outer side of f (exact
// orientation), the apex is the one whose sphere with f contains no other such
// point — decided by the exact perturbed sphere predicate: a candidate q
// replaces the current best b when q is inside sphere(f, b). Under the
// perturbation this is a strict total order on the outer points (the spheres
// through f form a pencil), so the result is unique and equals CGAL's.
//
// Search. From the subtree around a vertex of f upwards, each time through the
// subtree on the other side, depth first with the child of smaller pencil key
// first (pencil_rank.hpp: about the smallest sphere parameter t a point of the
// node could have), until the ball of the best lies inside the box of the
// subtree searched so far (no point outside it can then be better). The apex is usually among the first outer points met, so
// the ball of sphere(f, b) is small from the start. A node is skipped when a
// floating-point test with a proven margin shows that its box holds no point
// strictly on the outer side of f (face_side_filter.hpp) or does not meet the
// closed ball of the current best's sphere (simplex_sphere.hpp): a better point
// lies inside that ball, whose outer part only shrinks as the best improves.
// Floating point thus only orders the visit and prunes; every choice is exact.
// The pruning tests run on the kernel's approximate coordinates: taken as
// exact when the kernel says they are, widened by the error it states
// otherwise, and off when it states none (kernel/concepts.hpp).
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "dewall/detail/common/assert.hpp"
#include "dewall/detail/walls/face_side_filter.hpp"
#include "dewall/detail/walls/pencil_rank.hpp"
#include "dewall/detail/walls/handover_rule.hpp"
#include "dewall/detail/walls/simplex_sphere.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/detail/walls/point_set.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// Counters for the paper's Table 1.
struct Search_stats {
  std::size_t searches = 0;
  std::size_t nodes_visited = 0;
  std::size_t candidates = 0;
};

template <class K>
class Simplex_search {
  static constexpr int D = K::dimension;
  using Node = typename Kd_tree<D>::Node;
  // The kernel's approximations are not exact: every pruning test allows for
  // Point_set::coordinate_error (kernel/concepts.hpp).
  static constexpr bool widened = kernel::approximate_coordinates_error<K> != 0;

 public:
  /// budget: when given, every search and emptiness test is charged to (a
  /// copy of) it, and throws Search_budget_spent when it is spent.
  explicit Simplex_search(const Point_set<K>& ps, const std::optional<Search_budget>& budget = std::nullopt)
      : ps_(ps), budget_(budget) {}

  /// The apex of the Delaunay simplex on the outer side of f, or nothing when
  /// f is on the convex hull (no point strictly outside).
  /// \pre f is a face of the Delaunay triangulation.
  std::optional<Index> make_simplex(const Face<D>& f) {
    ++stats_.searches;
    if (budget_) budget_->begin_search();
    const Kd_tree<D>& tree = ps_.tree;
    Apex_search search(*this, f);
    // 1. The neighbourhood of f: every point of the smallest subtree around
    //    the leaf of f_0 that holds `near_points`.
    Index from = tree.leaf_of(f[0]);
    while (from != 0 && tree.node(from).end - tree.node(from).begin < near_points) from = tree.node(from).parent;
    search.scan(tree.node(from).begin, tree.node(from).end);
    // 2. Outwards: walking up, the subtree on the other side of each
    //    ancestor, until no point outside the subtrees searched can be better.
    while (from != 0 && search.better_may_lie_outside(tree.node(from))) {
      const Node& parent = tree.node(tree.node(from).parent);
      search.visit(parent.first_child + (parent.first_child == from ? 1 : 0));
      from = tree.node(from).parent;
    }
    if (budget_) budget_->charge(stats_.candidates);
    DEWALL_EXPENSIVE_ASSERT(brute_force_agrees(f, search.best()));
    return search.best();
  }

  /// True when no point is inside the (perturbed) circumsphere of the
  /// positively oriented simplex s: s is a Delaunay simplex. Exact.
  bool is_empty_sphere(const Simplex<D>& s) { return is_empty_sphere(s, sphere_of(s)); }
  /// As above, with the sphere of s already built.
  bool is_empty_sphere(const Simplex<D>& s, const Simplex_sphere<D>& sphere) {
    if (budget_) budget_->begin_search();
    const Ball_box<D>& ball = sphere.enclosing_box();
    stack_.assign(1, 0);
    while (!stack_.empty()) {
      const Node& n = ps_.tree.node(stack_.back());
      stack_.pop_back();
      if (!ball.may_meet(n.lo, n.hi)) continue;
      if (!n.is_leaf()) {
        stack_.push_back(n.first_child);
        stack_.push_back(n.first_child + 1);
        continue;
      }
      for (Index q = n.begin; q < n.end; ++q) {
        if (std::find(s.begin(), s.end(), q) != s.end()) continue;
        if (ball.bounded && !in_box(ball, q)) continue;
        count_candidate();
        if (inside_sphere(s, &sphere, q)) {
          if (budget_) budget_->charge(stats_.candidates);
          return false;
        }
      }
    }
    if (budget_) budget_->charge(stats_.candidates);
    return true;
  }

  /// The sphere of a positively oriented simplex, for is_empty_sphere.
  Simplex_sphere<D> sphere_of(const Simplex<D>& s) const {
    if constexpr (widened) return Simplex_sphere<D>(coords_of(s), ps_.coordinate_error);
    else return Simplex_sphere<D>(coords_of(s));
  }

  const Search_stats& stats() const { return stats_; }
  /// Whether the searches are charged to a budget (Engine::automatic).
  bool charges_budget() const { return budget_.has_value(); }
  /// Gives up DeWall for the incremental construction, as a spent budget does
  /// (unless the hand-over decision is settled: then it returns).
  /// \pre charges_budget().
  void hand_over() { budget_->spend(); }

 private:
  /// The answer of make_simplex(f) checked against every point with the exact
  /// predicates alone (no tree, no filter): no point on the outer side of f
  /// inside the apex's sphere, or none on the outer side at all without an
  /// apex. (Points on the inner side may lie inside: the first simplex searches
  /// from faces that are not Delaunay.) O(n): fuzzing only
  /// (DEWALL_EXPENSIVE_CHECKS).
  bool brute_force_agrees(const Face<D>& f, const std::optional<Index>& apex) const {
    const Simplex<D> s = with_apex<D>(f, apex.value_or(f[0]));
    if (apex && ps_.orientation(f, *apex) != kernel::POSITIVE) return false;
    for (Index q = 0; q < static_cast<Index>(ps_.size()); ++q) {
      if (is_vertex(f, q) || q == apex || ps_.orientation(f, q) != kernel::POSITIVE) continue;
      if (!apex || ps_.inside_sphere(s, q)) return false;
    }
    return true;
  }

  /// One MakeSimplex(f): the filters of the face, the best apex so far and
  /// its sphere, and the steps of the search as named functions.
  class Apex_search {
   public:
    Apex_search(Simplex_search& owner, const Face<D>& f)
        : owner_(owner), ps_(owner.ps_), f_(f), fc_(face_coords(owner.ps_, f)), side_filter_(side_filter(ps_, fc_)),
          rank_(fc_, side_filter_.normal()),
          outer_lo_(ps_.tree.lower()), outer_hi_(ps_.tree.upper()) {}

    const std::optional<Index>& best() const { return best_; }

    /// Considers the run of consecutive points [begin, end) (a leaf, or the
    /// first subtree), the one of smallest pencil rank in the current ball
    /// first: it is usually the best of the run, so the best changes at most
    /// once (each change builds a sphere), and its ball prunes the rest.
    void scan(Index begin, Index end) {
      Index lead = begin;
      double lead_rank = std::numeric_limits<double>::infinity();
      if (rank_.valid())
        for (Index q = begin; q < end; ++q) {
          if (best_ && ball_.bounded && !owner_.in_box(ball_, q)) continue;
          const double t = rank_(ps_.coords[q]);
          if (t < lead_rank && !is_vertex(f_, q)) {  // a vertex's rank is 0/0 up to rounding
            lead_rank = t;
            lead = q;
          }
        }
      consider(lead);
      refresh_sphere();
      for (Index q = begin; q < end; ++q) consider(q);
    }

    /// Depth first through the subtree at `top`, the child of smaller pencil
    /// key first while there is no best, skipping the nodes that cannot hold
    /// a better point (tested when a node is reached, so the ball found
    /// meanwhile applies).
    void visit(Index top) {
      std::vector<Index>& stack = owner_.stack_;
      stack.assign(1, top);
      while (!stack.empty()) {
        const Node& n = ps_.tree.node(stack.back());
        stack.pop_back();
        if (!may_hold_better(n)) continue;
        ++owner_.stats_.nodes_visited;
        if (n.is_leaf()) {
          scan(n.begin, n.end);
          continue;
        }
        // The nearer child first until there is a best; then its ball prunes, and
        // ranking both children costs more than it saves (docs/engines.md).
        const Index c = n.first_child;
        const bool second_first = !best_ && rank_.box_key(ps_.tree.node(c + 1).lo, ps_.tree.node(c + 1).hi) <
                                  rank_.box_key(ps_.tree.node(c).lo, ps_.tree.node(c).hi);
        stack.push_back(second_first ? c : c + 1);  // popped last
        stack.push_back(second_first ? c + 1 : c);
      }
    }

    /// Whether a point outside the subtree at n, every point of which has
    /// been considered, may still be better than the best. Any such point
    /// lies outside the open interior of n's box (at the ancestor where the
    /// two part, the median split puts the sibling's points on or beyond the
    /// side of this box): once that interior holds the closed ball of the
    /// best, none can be. Without a best, the search goes on while the part
    /// of the bounding box on the outer side of f is not empty.
    bool better_may_lie_outside(const Node& n) {
      if (!best_) return clip();
      refresh_sphere();
      if (!ball_.bounded) return true;
      for (int j = 0; j < D; ++j)
        if (!(n.lo[j] < ball_.lo[j] && ball_.hi[j] < n.hi[j])) return true;
      return false;
    }

   private:
    /// A candidate replaces the best when it is strictly on the outer side of
    /// f and inside the sphere of f and the best: exact predicates decide.
    void consider(Index q) {
      if (is_vertex(f_, q) || q == best_) return;
      if (best_ && ball_.bounded && !owner_.in_box(ball_, q)) return;
      owner_.count_candidate();
      if (!strictly_outside(q)) return;
      if (best_ && !owner_.inside_sphere(simplex_, sphere_is_current_ ? &*sphere_ : nullptr, q)) return;
      best_ = q;
      simplex_ = with_apex<D>(f_, q);
      sphere_is_current_ = false;
    }

    bool strictly_outside(Index q) const {
      std::optional<kernel::Sign> side;
      if constexpr (kernel::approximate_coordinates_are_exact<K>) side = side_filter_(ps_.coords[q]);
      if (!side) side = ps_.orientation(f_, q);
      return *side == kernel::POSITIVE;
    }

    // The sphere of the best (its proven filter and ball) is built lazily: a
    // change of best inside the first leaves is checked by the kernel's
    // predicate instead, and the older, larger ball still prunes correctly (the
    // points better than the new best lie inside it, the spheres through f
    // being nested on the outer side).
    void refresh_sphere() {
      if (sphere_is_current_ || !best_) return;
      if constexpr (widened) sphere_.emplace(owner_.coords_of(simplex_), ps_.coordinate_error);
      else sphere_.emplace(owner_.coords_of(simplex_));
      ball_ = sphere_->enclosing_box();
      sphere_is_current_ = true;
    }

    // Far searches (no outer point near the face: a hull face, or one whose
    // sphere is large) are confined to the part of the bounding box on the
    // outer side of f, computed when a scan ends without a best. A hull face
    // whose hyperplane carries other points (a lattice's side) has no such
    // part: answered without a scan.
    bool clip() {
      if (clipped_) return true;
      clipped_ = true;
      if constexpr (widened) {
        // The filter clips the box of x' (within 2w of the approximations, its
        // constructor says); the approximations lie within 2w of that.
        const double w = 2 * ps_.coordinate_error;
        outer_lo_ = Side_filter::widened_lower(outer_lo_, w);
        outer_hi_ = Side_filter::widened_upper(outer_hi_, w);
        if (!side_filter_.clip_to_outer_side(outer_lo_, outer_hi_)) return false;
        outer_lo_ = Side_filter::widened_lower(outer_lo_, w);
        outer_hi_ = Side_filter::widened_upper(outer_hi_, w);
        return true;
      } else {
        return side_filter_.clip_to_outer_side(outer_lo_, outer_hi_);
      }
    }

    bool may_hold_better(const Node& n) {
      refresh_sphere();
      if (best_ && !ball_.may_meet(n.lo, n.hi)) return false;  // the test that prunes most, first
      if (clipped_ && !boxes_meet(n.lo, n.hi, outer_lo_, outer_hi_)) return false;
      if constexpr (widened) {
        const double w = 2 * ps_.coordinate_error;
        return side_filter_.box_may_hold_outer(Side_filter::widened_lower(n.lo, w), Side_filter::widened_upper(n.hi, w));
      } else {
        return side_filter_.box_may_hold_outer(n.lo, n.hi);
      }
    }

    using Side_filter = Face_side_filter<D>;
    static Side_filter side_filter(const Point_set<K>& ps, const std::array<const Coords<D>*, D>& fc) {
      if constexpr (widened) return Side_filter(fc, ps.tree.lower(), ps.tree.upper(), ps.coordinate_error);
      else return Side_filter(fc, ps.tree.lower(), ps.tree.upper());
    }

    static std::array<const Coords<D>*, D> face_coords(const Point_set<K>& ps, const Face<D>& f) {
      std::array<const Coords<D>*, D> fc;
      for (int i = 0; i < D; ++i) fc[i] = &ps.coords[f[i]];
      return fc;
    }

    Simplex_search& owner_;
    const Point_set<K>& ps_;
    const Face<D>& f_;
    const std::array<const Coords<D>*, D> fc_;
    const Face_side_filter<D> side_filter_;
    const Pencil_rank<D> rank_;
    std::optional<Index> best_;
    Simplex<D> simplex_{};  // f and the best
    std::optional<Simplex_sphere<D>> sphere_;
    bool sphere_is_current_ = false;
    Ball_box<D> ball_;
    Coords<D> outer_lo_, outer_hi_;
    bool clipped_ = false;
  };

  /// Whether q is inside the (perturbed) sphere of s: decided by the proven
  /// filter of `sphere` (the sphere of s, when given) when the kernel's
  /// approximate coordinates are its exact ones, else (or when the filter
  /// cannot tell) by the kernel's predicate.
  bool inside_sphere(const Simplex<D>& s, const Simplex_sphere<D>* sphere, Index q) const {
    std::optional<bool> inside;
    if constexpr (kernel::approximate_coordinates_are_exact<K>)
      if (sphere)
        inside = sphere->enclosing_box().bounded ? sphere->inside_box(ps_.coords[q]) : sphere->inside(ps_.coords[q]);
    return inside ? *inside : ps_.inside_sphere(s, q);
  }

  std::array<const Coords<D>*, D + 1> coords_of(const Simplex<D>& s) const {
    std::array<const Coords<D>*, D + 1> c;
    for (int i = 0; i <= D; ++i) c[i] = &ps_.coords[s[i]];
    return c;
  }
  /// One more point examined; a long search is charged as it goes (every
  /// 512 points: a few microseconds, or a millisecond of exact tests).
  void count_candidate() {
    if ((++stats_.candidates & 511) == 0 && budget_) budget_->charge(stats_.candidates);
  }
  static bool is_vertex(const Face<D>& f, Index q) { return std::find(f.begin(), f.end(), q) != f.end(); }
  bool in_box(const Ball_box<D>& b, Index q) const {
    const auto& x = ps_.coords[q];
    for (int j = 0; j < D; ++j)
      if (x[j] < b.lo[j] || x[j] > b.hi[j]) return false;
    return true;
  }
  static bool boxes_meet(const Coords<D>& alo, const Coords<D>& ahi, const Coords<D>& blo, const Coords<D>& bhi) {
    for (int j = 0; j < D; ++j)
      if (ahi[j] < blo[j] || bhi[j] < alo[j]) return false;
    return true;
  }

  const Point_set<K>& ps_;
  std::optional<Search_budget> budget_;
  std::vector<Index> stack_;  // scratch: the nodes still to visit
  // The first subtree scanned: fewer points make the first best worse (more
  // changes of best), more make the scan longer (docs/engines.md).
  static constexpr Index near_points = 16;
  Search_stats stats_;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
