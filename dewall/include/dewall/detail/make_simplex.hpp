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
// closed ball of sphere(f, b) (ball_enclosure.hpp) can hold a better point; the
// box only shrinks, as each new sphere's outer part lies inside the previous
// one. The search stops when a ring lies wholly outside that box. Points in a
// visited cell but outside the box are skipped by the same proof. Floating
// point thus only orders the visit and prunes; every choice is exact.
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include "dewall/detail/ball_enclosure.hpp"
#include "dewall/detail/face_side_filter.hpp"
#include "dewall/kernel/concepts.hpp"
#include "dewall/detail/point_set.hpp"

namespace dewall::detail {

/// Counters for the paper's Table 1.
struct Search_stats {
  std::size_t searches = 0;
  std::size_t cells_visited = 0;
  std::size_t candidates = 0;
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
    std::optional<Face_side_filter<D>> side_filter;
    if constexpr (kernel::approximate_coordinates_are_exact<K>) {
      std::array<const Coords<D>*, D> fc;
      for (int i = 0; i < D; ++i) fc[i] = &ps_.coords[f[i]];
      side_filter.emplace(fc);
    }
    visit_rings(centroid_cell(f), [&](Index q) {
      if (is_vertex(f, q)) return;
      if (best && ball.bounded && !in_box(ball, q)) return;
      ++stats_.candidates;
      std::optional<kernel::Sign> side;
      if (side_filter) side = (*side_filter)(ps_.coords[q]);
      if (!side) side = ps_.orientation(f, q);
      if (*side != kernel::POSITIVE) return;
      if (best) {
        s[D] = *best;
        if (!ps_.inside_sphere(s, q)) return;
      }
      best = q;
      s[D] = q;
      ball = circumball_box<D>(coords_of(s));
    }, [&](Cell_box<D>& box) {
      if (best && ball.bounded) box = ps_.grid.cells_meeting(ball.lo, ball.hi);
    });
    return best;
  }

  /// True when no point is inside the (perturbed) circumsphere of the
  /// positively oriented simplex s: s is a Delaunay simplex. Exact.
  bool is_empty_sphere(const Simplex<D>& s) {
    const Ball_box<D> ball = circumball_box<D>(coords_of(s));
    bool empty = true;
    Coords<D> centre;
    for (int j = 0; j < D; ++j) centre[j] = ball.bounded ? 0.5 * (ball.lo[j] + ball.hi[j]) : ps_.coords[s[0]][j];
    visit_rings(ps_.grid.cell_of_point(centre), [&](Index q) {
      if (!empty || std::find(s.begin(), s.end(), q) != s.end()) return;
      if (ball.bounded && !in_box(ball, q)) return;
      if (ps_.inside_sphere(s, q)) empty = false;
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
  /// `start`, restricted to the search box, which `bound(box)` may shrink after
  /// each point (an empty box stops the search). Stops once every cell of the
  /// box has been visited. Cost: the cells of the rings met, each once.
  template <class Visit, class Bound>
  void visit_rings(const std::array<int, D>& start, Visit&& visit, Bound&& bound) {
    Cell_box<D> box = ps_.grid.all_cells();
    bound(box);
    for (int r = 0; !is_empty(box) && !inside_cube(box, start, r - 1); ++r) {
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
        for (const Index* q = grid.begin(cell); q != grid.end(cell); ++q) {
          visit(*q);
          bound(box);
        }
        if (is_empty(box)) return false;
      }
      int i = 0;
      for (; i < D && c[i] == cells.hi[i]; ++i) c[i] = cells.lo[i];
      if (i == D) return true;
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
  Search_stats stats_;
};

}  // namespace dewall::detail
