// The DeWall recursion (the paper's procedure DeWall(P, AFL)).
//
//  1. Split P by α (split.hpp) into P1 and P2.
//  2. At the top level (empty AFL): a first simplex crossed by α (first_simplex.hpp).
//  3. Sort the AFL into AFL_α (faces crossed by α), AFL_1 and AFL_2.
//  4. While AFL_α is not empty: take a face, build the simplex on its outer side
//     (make_simplex.hpp), emit it, and Update its other faces into the list of
//     their class.
//  5. Recurse on (P1, AFL_1) and (P2, AFL_2); near the top, on separate cores.
// Below the top level an empty AFL ends the recursion: every simplex lying in
// P1 shares a face with the wall or with another such simplex (the region they
// cover is bounded by wall simplices and the hull), so none is missed. The
// search for an apex uses the whole point set, and the apex of a face of AFL_1
// need not lie in P1: the simplex on the face's outer side may reach a point a
// deeper wall put on the other side (fuzz finding 165dddcd). Nothing depends on
// where the apex lies — Update closes each face once, whichever task sees it
// — but a subproblem's faces can then outlive its points; recurse() splits the
// points together with the faces' vertices in that case.
//
// Collected, the output order is the depth-first order (wall, then P1's
// part, then P2's), then the simplices finish() gift-wraps from the faces
// regions left open, whatever the number of threads: parallel subproblems
// write to their own blocks of output, appended in that order. Streamed, the
// same on one thread; with more, blocks go out as the tasks fill them.
#pragma once

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <mutex>
#include <span>
#include <vector>

#include "dewall/detail/active_face_list.hpp"
#include "dewall/detail/first_simplex.hpp"
#include "dewall/detail/region.hpp"
#include "dewall/detail/search_budget.hpp"
#include "dewall/detail/simplex_output.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

struct Wall_stats {
  std::size_t simplices = 0;
  std::size_t first_wall_simplices = 0;
  std::size_t max_depth = 0;
  std::size_t region_simplices = 0;
};

template <class K>
class Wall_builder {
  static constexpr int D = K::dimension;

 public:
  /// parallel_depth: recursion levels whose two subproblems run as parallel
  /// tasks (0: serial). budget: when given, each task's searches are charged
  /// to a copy of it (search_budget.hpp).
  /// regions: when given, a subproblem of at most region_points points is
  /// triangulated by it instead of by more walls (region.hpp).
  /// decision: when given (streaming with a budget), settled by the first
  /// region kept, which then releases the stream.
  Wall_builder(const Point_set<K>& ps, int parallel_depth, const std::optional<Search_budget>& budget = std::nullopt,
               const Region_triangulator<D>* regions = nullptr, std::size_t region_points = 0,
               Handover_decision* decision = nullptr)
      : ps_(ps), parallel_depth_(parallel_depth), budget_(budget), regions_(regions), region_points_(region_points),
        decision_(decision) {}

  /// Appends the simplices of the triangulation of `points` to `out` (and
  /// flushes it when it streams).
  /// \throws Search_budget_spent when a task's budget is spent.
  void run(std::span<Index> points, Built_simplices<D>& out) {
    Simplex_search<K> search(ps_, budget_);
    Wall_stats stats;
    std::vector<Face<D>> open_faces;
    recurse(points, Active_face_list<D>{}, Region_bounds<D>{}, 0, true, true, out, open_faces, search, stats);
    finish(open_faces, out, search, stats);
    out.flush();
    merge(search.stats(), stats);
  }

  const Wall_stats& stats() const { return stats_; }
  const Search_stats& search_stats() const { return search_stats_; }

 private:
  /// bounds: the open box the walls above leave to `points` (region.hpp);
  /// regions_apply: a region may triangulate `points`: it is exactly the set
  /// the walls above leave (not extended with faces' vertices, below), and no
  /// region above it was flat (a subset of a set that does not span E^D does
  /// not either: two planes, the paper's Figure 7, split into flat halves
  /// below the wall between them, and trying each level again cost 2× DeWall's
  /// whole time). Faces left open by a region go to open_faces.
  void recurse(std::span<Index> points, Active_face_list<D> afl, const Region_bounds<D>& bounds, std::size_t depth,
               bool top, bool regions_apply, Built_simplices<D>& out, std::vector<Face<D>>& open_faces,
               Simplex_search<K>& search, Wall_stats& stats) {
    if (!top && afl.empty()) return;
    stats.max_depth = std::max(stats.max_depth, depth);
    if (!top && regions_apply && regions_ && points.size() <= region_points_) {
      if (triangulate_region(points, afl, bounds, depth, out, open_faces, search, stats)) return;
      regions_apply = false;  // flat
    }
    std::size_t side1_size = 0;
    auto split = choose_split<D>(points, ps_.coords, static_cast<int>(depth % D), side1_size);
    // A simplex found for a face of this region may have a vertex outside it (the
    // search is global; fuzz finding 165dddcd: a region {3, 4} whose face got
    // apex 2 from the sibling region), so a region's faces can outlive its
    // points. When the points alone cannot be split, split them together with
    // the faces' vertices: any split is correct, Update still closes each face once.
    std::vector<Index> extended;
    if (!split) {
      std::vector<Face<D>> faces;
      while (!afl.empty()) faces.push_back(afl.pop());
      extended.assign(points.begin(), points.end());
      for (const auto& f : faces) extended.insert(extended.end(), f.begin(), f.end());
      std::sort(extended.begin(), extended.end());
      extended.erase(std::unique(extended.begin(), extended.end()), extended.end());
      for (const auto& f : faces) afl.update(f);
      points = std::span<Index>(extended);
      split = choose_split<D>(points, ps_.coords, static_cast<int>(depth % D), side1_size);
      regions_apply = false;
    }
    DEWALL_ASSERT(split.has_value());  // faces need two distinct points
    // A half on one axis-parallel plane has no simplex of its own: two layers
    // (the paper's Figure 7) leave them all to this wall, built at DeWall's
    // speed on one core (2.4× CGAL's time at 10^5 points). A region of any
    // size does the same work at CGAL's.
    if (!top && regions_apply && regions_ &&
        (on_one_axis_plane(points.first(side1_size)) || on_one_axis_plane(points.subspan(side1_size)))) {
      if (triangulate_region(points, afl, bounds, depth, out, open_faces, search, stats)) return;
      regions_apply = false;
    }
    Active_face_list<D> wall, afl1, afl2;
    auto classify = [&](const Face<D>& f) -> Active_face_list<D>& {
      int n1 = 0;
      for (Index v : f) n1 += split->on_side1(ps_.coords[v]);
      return n1 == D ? afl1 : n1 == 0 ? afl2 : wall;
    };
    const std::size_t before = out.size();
    auto add = [&](const Simplex<D>& s, int skip) {
      emit(out, s, depth);
      for (int i = 0; i <= D; ++i)
        if (i != skip) {
          const Face<D> g = opposite_face<D>(s, i);
          classify(g).update(g);
        }
    };
    if (top) add(first_simplex(ps_, search, points, *split), -1);
    while (!afl.empty()) {
      const Face<D> f = afl.pop();
      classify(f).update(f);
    }
    while (!wall.empty()) {
      const Face<D> f = wall.pop();
      const auto apex = search.make_simplex(f);
      if (!apex) continue;  // a convex hull face
      Simplex<D> s;
      std::copy(f.begin(), f.end(), s.begin());
      s[D] = *apex;
      add(s, D);
    }
    stats.simplices += out.size() - before;
    if (top) stats.first_wall_simplices = out.size() - before;
    const auto p1 = points.first(side1_size), p2 = points.subspan(side1_size);
    const Region_bounds<D> b1 = bounds.cut(split->axis, split->value, true);
    const Region_bounds<D> b2 = bounds.cut(split->axis, split->value, false);
    if (static_cast<int>(depth) < parallel_depth_ && !afl1.empty() && !afl2.empty()) {
      // Streaming: this task's simplices go before its subproblems'.
      out.flush();
      Built_simplices<D> out1(out.stream()), out2(out.stream());
      std::vector<Face<D>> open1, open2;
      auto task = [&](std::span<Index> p, Active_face_list<D>& a, const Region_bounds<D>& b, Built_simplices<D>& o,
                      std::vector<Face<D>>& open) {
        // A worker thread has its own floating-point environment (floating_point.hpp).
        const kernel::Fp_environment_guard guard;
        Simplex_search<K> s(ps_, budget_);
        Wall_stats st;
        recurse(p, std::move(a), b, depth + 1, false, regions_apply, o, open, s, st);
        o.flush();
        merge(s.stats(), st);
      };
      // The same tasks (and budgets) on one thread, in output order: a stream
      // then has the collected order.
      if (tbb::this_task_arena::max_concurrency() == 1) {
        task(p1, afl1, b1, out1, open1);
        task(p2, afl2, b2, out2, open2);
      } else {
        tbb::parallel_invoke([&] { task(p1, afl1, b1, out1, open1); }, [&] { task(p2, afl2, b2, out2, open2); });
      }
      out.append(std::move(out1));
      out.append(std::move(out2));
      open_faces.insert(open_faces.end(), open1.begin(), open1.end());
      open_faces.insert(open_faces.end(), open2.begin(), open2.end());
    } else {
      recurse(p1, std::move(afl1), b1, depth + 1, false, regions_apply, out, open_faces, search, stats);
      recurse(p2, std::move(afl2), b2, depth + 1, false, regions_apply, out, open_faces, search, stats);
    }
  }

  /// The simplices of DT(points) whose spheres hold no other point of the
  /// input (region.hpp), emitted in the order the triangulator lists them; the
  /// faces where they meet no other of them Update the region's AFL, and what
  /// is left open goes to open_faces. False when the points do not span E^D.
  bool triangulate_region(std::span<Index> points, Active_face_list<D>& afl, const Region_bounds<D>& bounds,
                          std::size_t depth, Built_simplices<D>& out, std::vector<Face<D>>& open_faces,
                          Simplex_search<K>& search, Wall_stats& stats) {
    // Known not to span E^D without building the triangulator's lower-dimensional one.
    if (on_one_axis_plane(points)) return false;
    // The automatic engine hands over when a region saves no search: when
    // most of its cells' spheres leave it, each of those needs the exact
    // search, and the region costs CGAL's work plus DeWall's. Measured share of
    // such cells per region (10^5 points): two layers 62 %; uniform, ball,
    // bubbles, eight layers 3–7 %; 2D 1 %. Decided as soon as the share passes
    // a quarter (the count only grows, so the decision is the same).
    struct Filter final : Region_filter<D> {
      Wall_builder& builder;
      const Region_bounds<D>& bounds;
      Active_face_list<D>& afl;
      Built_simplices<D>& out;
      Simplex_search<K>& search;
      std::size_t depth;
      std::size_t cells = 0, sphere_tests = 0;
      bool may_hand_over = false;

      Filter(Wall_builder& b, const Region_bounds<D>& bo, Active_face_list<D>& a, Built_simplices<D>& o,
             Simplex_search<K>& s, std::size_t d)
          : builder(b), bounds(bo), afl(a), out(o), search(s), depth(d) {}
      void begin(std::size_t count) override {
        cells = count;
        may_hand_over = search.charges_budget() && count >= min_cells_for_handover;
      }
      bool empty_of_others(const Simplex<D>& s) override {
        const Simplex_sphere<D> sphere = search.sphere_of(s);
        const Ball_box<D>& ball = sphere.enclosing_box();
        // A ball strictly inside the region's box holds no outside point;
        // otherwise the exact test against every point near it. (Charged like
        // a search: on cospherical input these tests look at every point, as
        // the walls' searches do.)
        if (ball.bounded && bounds.strictly_contains(ball.lo, ball.hi)) return true;
        const bool empty = search.is_empty_sphere(s, sphere);
        if (may_hand_over && 4 * ++sphere_tests > cells) search.hand_over();
        return empty;
      }
      void keep(const Simplex<D>& s, unsigned open) override {
        builder.emit(out, s, depth);
        for (int i = 0; i <= D; ++i)
          if (open >> i & 1u) afl.update(opposite_face<D>(s, i));
      }
    } filter(*this, bounds, afl, out, search, depth);
    const std::size_t before = out.size();
    if (!(*regions_)(points, ps_.coords, filter)) return false;
    while (!afl.empty()) open_faces.push_back(afl.pop());
    stats.simplices += out.size() - before;
    stats.region_simplices += out.size() - before;
    // Streaming: a region kept means the hybrid works on this input.
    if (decision_ && decision_->settle() && out.stream()) out.stream()->release();
    return true;
  }

  /// Gift-wrapping from the faces the regions left open: hull faces (no
  /// apex), and the faces of any simplex that crosses a wall but that no
  /// wall reached. Serial, after every region, in a fixed order.
  void finish(const std::vector<Face<D>>& open_faces, Built_simplices<D>& out, Simplex_search<K>& search,
              Wall_stats& stats) {
    Active_face_list<D> afl;
    for (const Face<D>& f : open_faces) afl.update(f);
    const std::size_t before = out.size();
    while (!afl.empty()) {
      const Face<D> f = afl.pop();
      const auto apex = search.make_simplex(f);
      if (!apex) continue;
      Simplex<D> s;
      std::copy(f.begin(), f.end(), s.begin());
      s[D] = *apex;
      emit(out, s, 0);
      for (int i = 0; i < D; ++i) afl.update(opposite_face<D>(s, i));
    }
    stats.simplices += out.size() - before;
  }

  /// Whether the points share one coordinate (a layer, a lattice's side); exact.
  bool on_one_axis_plane(std::span<const Index> points) const {
    for (int j = 0; j < D; ++j)
      if (std::all_of(points.begin(), points.end(),
                      [&](Index p) { return ps_.coords[p][j] == ps_.coords[points.front()][j]; }))
        return true;
    return false;
  }

  void emit(Built_simplices<D>& out, const Simplex<D>& s, std::size_t level) const {
    Simplex<D> input;
    for (int i = 0; i <= D; ++i) input[i] = static_cast<Index>(ps_.input_index[s[i]]);
    out.push_back({input, static_cast<std::uint8_t>(std::min<std::size_t>(level, 255))});
  }

  void merge(const Search_stats& s, const Wall_stats& w) {
    const std::lock_guard lock(mutex_);
    search_stats_.searches += s.searches;
    search_stats_.nodes_visited += s.nodes_visited;
    search_stats_.candidates += s.candidates;
    stats_.simplices += w.simplices;
    stats_.first_wall_simplices += w.first_wall_simplices;
    stats_.max_depth = std::max(stats_.max_depth, w.max_depth);
    stats_.region_simplices += w.region_simplices;
  }

  const Point_set<K>& ps_;
  int parallel_depth_;
  std::optional<Search_budget> budget_;
  // Regions smaller than this are never a reason to hand over (a few hull
  // cells are a large share of a small region).
  static constexpr std::size_t min_cells_for_handover = 4096;
  const Region_triangulator<D>* regions_;
  std::size_t region_points_;
  Handover_decision* decision_;
  std::mutex mutex_;
  Wall_stats stats_;
  Search_stats search_stats_;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
