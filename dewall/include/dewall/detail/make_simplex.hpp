// MakeSimplex: the Delaunay simplex on the outer side of a face (the paper's
// "dd-nearest" point), found through the uniform grid.
//
// Exactness. Among the points strictly on the outer side of f (exact
// orientation), the apex is the one whose sphere with f contains no other such
// point — decided by the exact perturbed sphere predicate: a candidate q
// replaces the current best b when q is inside sphere(f, b). Under the
// perturbation this is a strict total order on the outer points (the spheres
// through f form a pencil), so the result is unique and equals CGAL's.
//
// Search. Cells are visited in rings of growing Chebyshev distance around the
// cell of the face's centroid, so a good candidate is usually found first. Once
// there is a best b, only cells meeting a box that provably contains the
// closed ball of sphere(f, b) (simplex_sphere.hpp) can hold a better point; the
// box only shrinks, as each new sphere's outer part lies inside the previous
// one. The search stops when a ring lies wholly outside that box. Points in a
// visited cell but outside the box are skipped by the same proof. Floating
// point thus only orders the visit and prunes; every choice is exact.
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "dewall/detail/face_side_filter.hpp"
#include "dewall/detail/pencil_rank.hpp"
#include "dewall/detail/simplex_sphere.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/detail/point_set.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

/// Counters for the paper's Table 1.
struct Search_stats {
  std::size_t searches = 0;
  std::size_t cells_visited = 0;
  std::size_t candidates = 0;
  std::size_t best_changes = 0;
  std::size_t unbounded = 0;
  std::size_t in_sphere_tests = 0;
};

template <class K>
class Simplex_search {
  static constexpr int D = K::dimension;

 public:
  explicit Simplex_search(const Point_set<K>& ps) : ps_(ps) {}

  /// The apex of the Delaunay simplex on the outer side of f, or nothing when
  /// f is on the convex hull (no point strictly outside).
  /// \pre f is a face of the Delaunay triangulation.
  std::optional<Index> make_simplex(const Face<D>& f) {
    ++stats_.searches;
    std::optional<Index> best;
    Simplex<D> s;
    std::copy(f.begin(), f.end(), s.begin());
    Ball_box<D> ball;
    std::array<const Coords<D>*, D> fc;
    for (int i = 0; i < D; ++i) fc[i] = &ps_.coords[f[i]];
    const Face_side_filter<D> side_filter(fc, ps_.grid.lower(), ps_.grid.upper());
    std::optional<Simplex_sphere<D>> sphere;
    auto consider = [&](Index q) {
      if (is_vertex(f, q) || q == best) return false;  // the seed is met again in the rings
      if (best && ball.bounded && !in_box(ball, q)) return false;
      ++stats_.candidates;
      std::optional<kernel::Sign> side;
      if constexpr (kernel::approximate_coordinates_are_exact<K>) side = side_filter(ps_.coords[q]);
      if (!side) side = ps_.orientation(f, q);
      if (*side != kernel::POSITIVE) return false;
      if (best) {
        s[D] = *best;
        ++stats_.in_sphere_tests;
        std::optional<bool> inside;
        if constexpr (kernel::approximate_coordinates_are_exact<K>)
          inside = ball.bounded ? sphere->inside_box(ps_.coords[q]) : sphere->inside(ps_.coords[q]);
        if (!inside) inside = ps_.inside_sphere(s, q);
        if (!*inside) return false;
      }
      best = q;
      s[D] = q;
      ++stats_.best_changes;
      sphere.emplace(coords_of(s));
      ball = sphere->enclosing_box();
      return true;
    };
    const auto start = centroid_cell(f);
    // Rings 0 and 1 first, the candidate of smallest pencil parameter leading:
    // it is usually the apex, so the search box is small from the start. Every
    // point of these cells still goes through the exact `consider`.
    {
      const Pencil_rank<D> rank(fc, side_filter.normal());
      Cell_box<D> near;
      for (int i = 0; i < D; ++i) {
        near.lo[i] = std::max(start[i] - 1, 0);
        near.hi[i] = std::min(start[i] + 1, ps_.grid.dims()[i] - 1);
      }
      near_.clear();
      std::size_t lead = 0;
      for_each_cell(near, [&](std::size_t cell) {
        stats_.cells_visited += 1;
        for (const Index* q = ps_.grid.begin(cell); q != ps_.grid.end(cell); ++q) {
          const double t = rank.valid() ? rank(ps_.coords[*q]) : 0.0;
          if (near_.empty() || t < near_[lead].first) lead = near_.size();
          near_.push_back({t, *q});
        }
      });
      if (!near_.empty()) std::swap(near_[0], near_[lead]);
      for (const auto& [t, q] : near_) consider(q);
    }
    // Far searches (no candidate next to the face: near the hull; or a large
    // sphere) are confined to the part of the grid on the outer side of f. A
    // face with no room there is a hull face, answered without a scan.
    Cell_box<D> limit = ps_.grid.all_cells();
    bool clipped = false;
    auto clip = [&] {
      clipped = true;
      ++stats_.unbounded;
      Coords<D> lo = ps_.grid.lower(), hi = ps_.grid.upper();
      if (!side_filter.clip_to_outer_side(lo, hi)) return false;
      limit = ps_.grid.cells_meeting(lo, hi);
      return true;
    };
    if (!best && !clip()) return std::nullopt;
    visit_rings(start, 2, consider, [&](Cell_box<D>& box) {
      if (best && ball.bounded) box = ps_.grid.cells_meeting(ball.lo, ball.hi);
      if (!clipped && wide(box)) clip();
      for (int i = 0; i < D; ++i) {
        box.lo[i] = std::max(box.lo[i], limit.lo[i]);
        box.hi[i] = std::min(box.hi[i], limit.hi[i]);
      }
    });
    return best;
  }

  /// True when no point is inside the (perturbed) circumsphere of the
  /// positively oriented simplex s: s is a Delaunay simplex. Exact.
  bool is_empty_sphere(const Simplex<D>& s) {
    const Simplex_sphere<D> sphere(coords_of(s));
    const Ball_box<D> ball = sphere.enclosing_box();
    bool empty = true;
    Coords<D> centre;
    for (int j = 0; j < D; ++j) centre[j] = ball.bounded ? 0.5 * (ball.lo[j] + ball.hi[j]) : ps_.coords[s[0]][j];
    visit_rings(ps_.grid.cell_of_point(centre), 0, [&](Index q) {
      if (!empty || std::find(s.begin(), s.end(), q) != s.end()) return false;
      if (ball.bounded && !in_box(ball, q)) return false;
      if (ps_.inside_sphere(s, q)) empty = false;
      return !empty;
    }, [&](Cell_box<D>& box) {
      if (ball.bounded) box = ps_.grid.cells_meeting(ball.lo, ball.hi);
      if (!empty) box.hi[0] = box.lo[0] - 1;  // found one: stop
    });
    return empty;
  }

  const Search_stats& stats() const { return stats_; }

 private:
  std::array<const Coords<D>*, D + 1> coords_of(const Simplex<D>& s) const {
    std::array<const Coords<D>*, D + 1> c;
    for (int i = 0; i <= D; ++i) c[i] = &ps_.coords[s[i]];
    return c;
  }
  static bool is_vertex(const Face<D>& f, Index q) { return std::find(f.begin(), f.end(), q) != f.end(); }
  bool in_box(const Ball_box<D>& b, Index q) const {
    const auto& x = ps_.coords[q];
    for (int j = 0; j < D; ++j)
      if (x[j] < b.lo[j] || x[j] > b.hi[j]) return false;
    return true;
  }
  std::array<int, D> centroid_cell(const Face<D>& f) const {
    Coords<D> c{};
    for (Index v : f)
      for (int j = 0; j < D; ++j) c[j] += ps_.coords[v][j] / D;
    return ps_.grid.cell_of_point(c);
  }

  /// Visits the points of the cells in rings of growing Chebyshev radius around
  /// `start`, from `first_ring` on (the caller has visited the inner ones), restricted to the search box, which `bound(box)` may shrink after
  /// a point whose visit returned true (an empty box stops the search). Stops once every cell of the
  /// box has been visited. Cost: the cells of the rings met, each once.
  template <class Visit, class Bound>
  void visit_rings(const std::array<int, D>& start, int first_ring, Visit&& visit, Bound&& bound) {
    Cell_box<D> box = ps_.grid.all_cells();
    bound(box);
    for (int r = first_ring; !is_empty(box) && !inside_cube(box, start, r - 1); ++r) {
      // The shell of radius r: for each axis k and side, the slab c[k] = start[k] ± r,
      // with axes before k restricted to the open range (so no cell repeats).
      for (int k = 0; k < D; ++k) {
        for (int side : {-1, 1}) {
          if (r == 0 && side == 1) break;
          Cell_box<D> slab;
          bool empty = false;
          for (int i = 0; i < D; ++i) {
            const int reach = i < k ? r - 1 : r;
            slab.lo[i] = i == k ? start[i] + side * r : std::max(start[i] - reach, box.lo[i]);
            slab.hi[i] = i == k ? start[i] + side * r : std::min(start[i] + reach, box.hi[i]);
            if (i == k && (slab.lo[i] < box.lo[i] || slab.lo[i] > box.hi[i])) empty = true;
            if (slab.lo[i] > slab.hi[i]) empty = true;
          }
          if (!empty && !visit_cells(slab, box, visit, bound)) return;
          if (r == 0) break;
        }
        if (r == 0) break;
      }
    }
  }

  /// Visits every cell of `cells`; false when `bound` emptied the box.
  template <class Visit, class Bound>
  bool visit_cells(const Cell_box<D>& cells, Cell_box<D>& box, Visit& visit, Bound& bound) {
    const auto& grid = ps_.grid;
    std::array<int, D> c = cells.lo;
    for (;;) {
      if (contains(box, c)) {
        const std::size_t cell = grid.linear(c);
        ++stats_.cells_visited;
        bool changed = false;
        for (const Index* q = grid.begin(cell); q != grid.end(cell); ++q) changed |= visit(*q);
        if (changed) {
          bound(box);
          if (is_empty(box)) return false;
        }
      }
      int i = 0;
      for (; i < D && c[i] == cells.hi[i]; ++i) c[i] = cells.lo[i];
      if (i == D) return true;
      ++c[i];
    }
  }

  static bool wide(const Cell_box<D>& b) {
    for (int i = 0; i < D; ++i)
      if (b.hi[i] - b.lo[i] > 3) return true;
    return false;
  }

  template <class Fn>
  void for_each_cell(const Cell_box<D>& cells, Fn&& fn) const {
    std::array<int, D> c = cells.lo;
    for (;;) {
      fn(ps_.grid.linear(c));
      int i = 0;
      for (; i < D && c[i] == cells.hi[i]; ++i) c[i] = cells.lo[i];
      if (i == D) return;
      ++c[i];
    }
  }

  static bool is_empty(const Cell_box<D>& b) {
    for (int i = 0; i < D; ++i)
      if (b.lo[i] > b.hi[i]) return true;
    return false;
  }
  static bool contains(const Cell_box<D>& b, const std::array<int, D>& c) {
    for (int i = 0; i < D; ++i)
      if (c[i] < b.lo[i] || c[i] > b.hi[i]) return false;
    return true;
  }
  static bool inside_cube(const Cell_box<D>& b, const std::array<int, D>& start, int r) {
    if (r < 0) return false;
    for (int i = 0; i < D; ++i)
      if (b.lo[i] < start[i] - r || b.hi[i] > start[i] + r) return false;
    return true;
  }

  const Point_set<K>& ps_;
  std::vector<std::pair<double, Index>> near_;  // scratch: the points of rings 0 and 1, ranked
  Search_stats stats_;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
