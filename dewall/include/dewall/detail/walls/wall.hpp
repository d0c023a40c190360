// The DeWall recursion (the paper's procedure DeWall(P, AFL)), Wall_builder::recurse.
//
//  1. Split P by α (split.hpp) into P1 and P2: split_points.
//  2. At the top level (empty AFL): a first simplex crossed by α
//     (first_simplex.hpp): build_wall.
//  3. Sort the AFL into AFL_α (faces crossed by α), AFL_1 and AFL_2
//     (Face_lists): build_wall.
//  4. While AFL_α is not empty: take a face, build the simplex on its outer side
//     (make_simplex.hpp), emit it, and Update its other faces into the list of
//     their class: wall_loop.
//  5. Recurse on (P1, AFL_1) and (P2, AFL_2); near the top, on separate cores:
//     recurse_on_halves.
// With regions (Engine::hybrid, automatic), a subproblem may instead be
// triangulated as a region (region.hpp, triangulate_region), and finish
// gift-wraps, with the same wall_loop, the faces the regions left open; and
// a wall is first built from a slab around α by the regions' construction
// (wall_from_slab), the wall loop then finding only what the slab missed.
// Below the top level an empty AFL ends the recursion: every simplex lying in
// P1 shares a face with the wall or with another such simplex (the region they
// cover is bounded by wall simplices and the hull), so none is missed. The
// search for an apex uses the whole point set, and the apex of a face of AFL_1
// need not lie in P1: the simplex on the face's outer side may reach a point a
// deeper wall put on the other side (fuzz finding 165dddcd). Nothing depends on
// where the apex lies — Update closes each face once, whichever task sees it
// — but a subproblem's faces can then outlive its points; split_points splits the
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
#include <cmath>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include "dewall/detail/walls/active_face_list.hpp"
#include "dewall/detail/walls/first_simplex.hpp"
#include "dewall/detail/walls/region.hpp"
#include "dewall/detail/walls/handover_rule.hpp"
#include "dewall/detail/common/progress_meter.hpp"
#include "dewall/detail/common/simplex_output.hpp"
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
  /// to a copy of it (handover_rule.hpp).
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
    std::vector<Face<D>> open_faces;
    Task task(ps_, budget_, out, open_faces);
    recurse(Subproblem{points, {}, {}, 0, true}, task);
    finish(open_faces, task);
    out.flush();
    merge(task);
  }

  const Wall_stats& stats() const { return stats_; }
  const Search_stats& search_stats() const { return search_stats_; }

  /// Told of the points of each subproblem done (no faces left, or a region
  /// built) and polled every thousand faces a wall loop takes (Options::progress;
  /// it throws Cancelled when the caller stops the work), or null.
  Progress_meter* progress = nullptr;

 private:
  /// The paper's DeWall(P, AFL): a set of points and the active faces on them.
  struct Subproblem {
    std::span<Index> points;
    Active_face_list<D> afl;
    /// The open box the walls above leave to `points` (region.hpp).
    Region_bounds<D> bounds;
    std::size_t depth = 0;
    /// A region may triangulate `points`: it is exactly the set the walls
    /// above leave (not extended with faces' vertices, split_points), and no
    /// region above it was flat (a subset of a set that does not span E^D does
    /// not either: two planes, the paper's Figure 7, split into flat halves
    /// below the wall between them, and trying each level again costs more
    /// than DeWall's whole run).
    bool regions_apply = true;
  };

  /// What one task of the recursion owns: its search (charged to its own copy
  /// of the budget), its output block, its counters, and the faces its regions
  /// leave open (for finish).
  struct Task {
    Task(const Point_set<K>& ps, const std::optional<Search_budget>& budget, Built_simplices<D>& o,
         std::vector<Face<D>>& open)
        : search(ps, budget), out(o), open_faces(open) {}
    Simplex_search<K> search;
    Built_simplices<D>& out;
    std::vector<Face<D>>& open_faces;
    Wall_stats stats;
  };

  /// α and the partition of a subproblem's points: P1 is the first side1_size.
  struct Cut {
    Split<D> split;
    std::size_t side1_size;
  };

  /// The paper's AFL_α, AFL_1 and AFL_2 for one split; a face goes to the list
  /// of its class.
  struct Face_lists {
    const std::vector<Coords<D>>& coords;
    const Split<D>& split;
    Active_face_list<D> wall, side1, side2;
    /// How many of the vertices (a face's or a simplex's) lie on side 1.
    template <class Vertices>
    int side1_count(const Vertices& vertices) const {
      int n1 = 0;
      for (Index v : vertices) n1 += split.on_side1(coords[v], v);
      return n1;
    }
    Active_face_list<D>& operator()(const Face<D>& f) {
      const int n1 = side1_count(f);
      return n1 == D ? side1 : n1 == 0 ? side2 : wall;
    }
  };

  /// DeWall(P, AFL): a region if one applies, else the split (step 1), the
  /// wall (steps 2–4) and the two halves (step 5).
  void recurse(Subproblem p, Task& task) {
    if (p.depth > 0 && p.afl.empty()) return done(p);
    task.stats.max_depth = std::max(task.stats.max_depth, p.depth);
    if (region_may_take(p) && p.points.size() <= region_points_ && as_region(p, task)) return done(p);
    std::vector<Index> extended;  // (split_points: the points with the faces' vertices)
    const Cut cut = split_points(p, extended);
    // A half on one axis-parallel plane has no simplex of its own: two layers
    // (the paper's Figure 7) leave them all to this wall, built at DeWall's
    // speed on one core. A region of any size does the same work at the
    // incremental construction's speed.
    if (region_may_take(p) &&
        (on_one_axis_plane(p.points.first(cut.side1_size)) || on_one_axis_plane(p.points.subspan(cut.side1_size))) &&
        as_region(p, task))
      return done(p);
    auto [half1, half2] = build_wall(p, cut, task);
    recurse_on_halves(std::move(half1), std::move(half2), task);
  }
  void done(const Subproblem& p) {
    if (progress) progress->advance(p.points.size());
  }

  /// Step 1: α on axis depth mod D, P partitioned in place into P1 and P2.
  /// A simplex found for a face of this subproblem may have a vertex outside it
  /// (the search is global; fuzz finding 165dddcd: a region {3, 4} whose face
  /// got apex 2 from the sibling region), so its faces can outlive its points.
  /// When the points alone cannot be split, they are split together with the
  /// faces' vertices, kept in `extended`: any split is correct, Update still
  /// closes each face once.
  Cut split_points(Subproblem& p, std::vector<Index>& extended) const {
    const int axis = static_cast<int>(p.depth % D);
    Cut cut{};
    if (auto split = choose_split<D>(p.points, ps_.coords, axis, cut.side1_size)) {
      cut.split = *split;
      return cut;
    }
    std::vector<Face<D>> faces;
    while (!p.afl.empty()) faces.push_back(p.afl.pop());
    extended.assign(p.points.begin(), p.points.end());
    for (const auto& f : faces) extended.insert(extended.end(), f.begin(), f.end());
    std::sort(extended.begin(), extended.end());
    extended.erase(std::unique(extended.begin(), extended.end()), extended.end());
    for (const auto& f : faces) p.afl.update(f);
    p.points = std::span<Index>(extended);
    p.regions_apply = false;
    const auto split = choose_split<D>(p.points, ps_.coords, axis, cut.side1_size);
    DEWALL_ASSERT(split.has_value());  // faces need two distinct points
    cut.split = *split;
    return cut;
  }

  /// Steps 2–4: at the top the first simplex; the AFL sorted into AFL_α, AFL_1
  /// and AFL_2; the wall built from AFL_α. Returns (P1, AFL_1) and (P2, AFL_2).
  std::pair<Subproblem, Subproblem> build_wall(Subproblem& p, const Cut& cut, Task& task) {
    Face_lists lists{ps_.coords, cut.split, {}, {}, {}};
    const std::size_t before = task.out.size();
    while (!p.afl.empty()) {
      const Face<D> f = p.afl.pop();
      lists(f).update(f);
    }
    // Empty now, but its table would be held while the halves below run
    // (streaming 10^6 points on two threads: 10 of the 22 MB of active face
    // lists at the peak).
    p.afl = Active_face_list<D>();
    const bool seeded = region_may_take_wall(p) && wall_from_slab(p, cut.split, lists, task);
    if (p.depth == 0 && !seeded)
      add_simplex(first_simplex(ps_, task.search, p.points, cut.split), -1, 0, lists, task);
    wall_loop(lists.wall, p.depth, lists, task);
    task.stats.simplices += task.out.size() - before;
    if (p.depth == 0) task.stats.first_wall_simplices = task.out.size() - before;
    const Split<D>& a = cut.split;
    return {Subproblem{p.points.first(cut.side1_size), std::move(lists.side1), p.bounds.cut(a.axis, a.value, true),
                       p.depth + 1, p.regions_apply},
            Subproblem{p.points.subspan(cut.side1_size), std::move(lists.side2), p.bounds.cut(a.axis, a.value, false),
                       p.depth + 1, p.regions_apply}};
  }

  /// Whether the regions' construction may build p's wall from a slab: with
  /// regions on, and p exactly the points the walls above leave (the slab's
  /// proof, like a region's, rests on the bounds those walls draw).
  bool region_may_take_wall(const Subproblem& p) const { return p.regions_apply && regions_; }

  /// A wall's slab (slab_of): its points, and the open box they lie in and
  /// no other point of the input does.
  struct Slab {
    std::vector<Index> points;
    Region_bounds<D> bounds;
  };

  /// A slab around α: about slab_size_factor · n^((D−1)/D) of p's
  /// points nearest α (a few layers of points on each side, for points spread
  /// in volume), as the points strictly between two coordinates lo < x_a <
  /// hi (exact comparisons); its bounds are p's cut to (lo, hi), so no other
  /// point of the input lies strictly inside them.
  Slab slab_of(const Subproblem& p, const Split<D>& split) const {
    const int a = split.axis;
    const double n = static_cast<double>(p.points.size());
    const auto wanted = static_cast<std::size_t>(std::min(n, slab_size_factor * std::pow(n, (D - 1.0) / D)));
    std::vector<double> distance(p.points.size());
    for (std::size_t i = 0; i < distance.size(); ++i)
      distance[i] = std::abs(ps_.coords[p.points[i]][a] - split.value);
    const auto kth = distance.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(wanted, 1) - 1);
    std::nth_element(distance.begin(), kth, distance.end());
    // Any two doubles bound a slab: the proof needs only that the points
    // outside it are not strictly between them.
    Slab slab;
    slab.bounds = p.bounds;
    slab.bounds.lo[a] = std::max(slab.bounds.lo[a], split.value - *kth);
    slab.bounds.hi[a] = std::min(slab.bounds.hi[a], split.value + *kth);
    for (const Index q : p.points) {
      const double x = ps_.coords[q][a];
      if (slab.bounds.lo[a] < x && x < slab.bounds.hi[a]) slab.points.push_back(q);
    }
    return slab;
  }

  /// Most of a wall at an incremental construction's speed, not the gift-
  /// wrapping's (issue 25, item 3). Why it is exact: a simplex of DT(P) whose
  /// vertices all lie in the slab S is a simplex of DT(S), and a simplex of
  /// DT(S) is one of DT(P) when its sphere holds no other point (region.hpp,
  /// same argument). So the cells of DT(S) crossing α whose spheres are proven
  /// empty (inside the slab's bounds, else the exact search) are wall
  /// simplices; each is emitted and its faces not shared with another kept
  /// cell are Updated into their lists. The wall simplices with a vertex
  /// outside S are then found by the wall loop from the faces left in AFL_α
  /// (the simplices crossing α are connected through faces crossing α, as
  /// DeWall's own wall loop relies on). Returns whether a simplex was kept.
  bool wall_from_slab(const Subproblem& p, const Split<D>& split, Face_lists& lists, Task& task) {
    Slab slab = slab_of(p, split);
    if (slab.points.size() <= static_cast<std::size_t>(D)) return false;
    struct Filter final : Region_filter<D> {
      Wall_builder& builder;
      const Region_bounds<D>& bounds;
      Face_lists& lists;  // (its split is α's)
      Task& task;
      std::size_t depth;
      std::size_t kept = 0;
      Filter(Wall_builder& b, const Region_bounds<D>& bo, Face_lists& l, Task& t, std::size_t d)
          : builder(b), bounds(bo), lists(l), task(t), depth(d) {}
      void begin(std::size_t) override {}
      bool asks_every_cell() const override { return true; }
      bool empty_of_others(const Simplex<D>& s) override {
        const int n1 = lists.side1_count(s);
        if (n1 == 0 || n1 == D + 1) return false;  // not a wall simplex: the halves' own
        bool searched = false;
        return builder.empty_of_outside(s, bounds, task.search, searched);
      }
      void keep(const Simplex<D>& s, unsigned open) override {
        ++kept;
        builder.emit(task.out, s, depth);
        for (int i = 0; i <= D; ++i)
          if (open >> i & 1u) {
            const Face<D> g = opposite_face<D>(s, i);
            lists(g).update(g);
          }
      }
    } filter(*this, slab.bounds, lists, task, p.depth);
    return (*regions_)(slab.points, ps_.coords, filter) && filter.kept > 0;
  }

  /// Whether the sphere of s (positively oriented) holds no point outside the
  /// open box `bounds`, when no other point of the input lies strictly inside
  /// it: a ball strictly inside holds none; otherwise the exact test against
  /// every point near it (charged like a search: on cospherical input these
  /// tests look at every point, as the walls' searches do).
  /// `searched`: set when the exact test ran.
  bool empty_of_outside(const Simplex<D>& s, const Region_bounds<D>& bounds, Simplex_search<K>& search,
                        bool& searched) const {
    const Simplex_sphere<D> sphere = search.sphere_of(s);
    const Ball_box<D>& ball = sphere.enclosing_box();
    if (ball.bounded && bounds.strictly_contains(ball.lo, ball.hi)) return true;
    searched = true;
    return search.is_empty_sphere(s, sphere);
  }

  /// The wall loop (the paper's step 4), for a wall and for finish: while
  /// `faces` holds one, the simplex on its outer side (none for a hull face)
  /// is emitted at wall level `level` and its other faces are Updated into
  /// the list `list_of(face)` names.
  template <class List_of>
  void wall_loop(Active_face_list<D>& faces, std::size_t level, List_of& list_of, Task& task) {
    for (std::size_t taken = 1; !faces.empty(); ++taken) {
      const Face<D> f = faces.pop();
      if (const auto apex = task.search.make_simplex(f)) add_simplex(with_apex<D>(f, *apex), D, level, list_of, task);
      if (progress && taken % 1024 == 0) progress->advance();
    }
  }

  /// Emits s and Updates its faces other than the one opposite vertex
  /// `known` (the face it was built on; −1: none) into their lists.
  template <class List_of>
  void add_simplex(const Simplex<D>& s, int known, std::size_t level, List_of& list_of, Task& task) {
    emit(task.out, s, level);
    for (int i = 0; i <= D; ++i)
      if (i != known) {
        const Face<D> g = opposite_face<D>(s, i);
        list_of(g).update(g);
      }
  }

  /// Step 5: (P1, AFL_1), then (P2, AFL_2); near the top, while both have
  /// faces, as two parallel tasks with their own output blocks, appended in
  /// that order.
  void recurse_on_halves(Subproblem half1, Subproblem half2, Task& task) {
    // (the halves' parent is parallel when its depth, half1.depth − 1, is below parallel_depth)
    if (static_cast<int>(half1.depth) > parallel_depth_ || half1.afl.empty() || half2.afl.empty()) {
      recurse(std::move(half1), task);
      recurse(std::move(half2), task);
      return;
    }
    // Streaming: this task's simplices go before its subproblems'.
    task.out.flush();
    Built_simplices<D> out1(task.out.stream()), out2(task.out.stream());
    std::vector<Face<D>> open1, open2;
    auto run_task = [&](Subproblem& half, Built_simplices<D>& out, std::vector<Face<D>>& open) {
      // A worker thread has its own floating-point environment (floating_point.hpp).
      const kernel::Fp_environment_guard guard;
      Task t(ps_, budget_, out, open);
      recurse(std::move(half), t);
      out.flush();
      merge(t);
    };
    // The same tasks (and budgets) on one thread, in output order: a stream
    // then has the collected order.
    if (tbb::this_task_arena::max_concurrency() == 1) {
      run_task(half1, out1, open1);
      run_task(half2, out2, open2);
    } else {
      tbb::parallel_invoke([&] { run_task(half1, out1, open1); }, [&] { run_task(half2, out2, open2); });
    }
    task.out.append(std::move(out1));
    task.out.append(std::move(out2));
    task.open_faces.insert(task.open_faces.end(), open1.begin(), open1.end());
    task.open_faces.insert(task.open_faces.end(), open2.begin(), open2.end());
  }

  /// Whether a region may take p instead of more walls: below the top, with
  /// regions on (Engine::hybrid, automatic), and allowed there.
  bool region_may_take(const Subproblem& p) const { return p.depth > 0 && p.regions_apply && regions_; }

  /// p as a region (triangulate_region); when its points do not span E^D,
  /// false, and no region applies below it.
  bool as_region(Subproblem& p, Task& task) {
    if (triangulate_region(p, task)) return true;
    p.regions_apply = false;
    return false;
  }

  /// The simplices of DT(points) whose spheres hold no other point of the
  /// input (region.hpp), emitted in the order the triangulator lists them; the
  /// faces where they meet no other of them Update the region's AFL, and what
  /// is left open goes to open_faces. False when the points do not span E^D.
  bool triangulate_region(Subproblem& p, Task& task) {
    // Known not to span E^D without building the triangulator's lower-dimensional one.
    if (on_one_axis_plane(p.points)) return false;
    // With a budget, the automatic engine hands over when a region saves no
    // search (handover_rule.hpp, Region_handover).
    struct Filter final : Region_filter<D> {
      Wall_builder& builder;
      const Region_bounds<D>& bounds;
      Active_face_list<D>& afl;
      Built_simplices<D>& out;
      Simplex_search<K>& search;
      std::size_t depth;
      Region_handover handover;

      Filter(Wall_builder& b, const Region_bounds<D>& bo, Active_face_list<D>& a, Built_simplices<D>& o,
             Simplex_search<K>& s, std::size_t d)
          : builder(b), bounds(bo), afl(a), out(o), search(s), depth(d) {}
      void begin(std::size_t count) override {
        handover = Region_handover(search.charges_budget(), count);
      }
      bool empty_of_others(const Simplex<D>& s) override {
        bool searched = false;
        const bool empty = builder.empty_of_outside(s, bounds, search, searched);
        if (searched && handover.searched_one()) search.hand_over();
        return empty;
      }
      void keep(const Simplex<D>& s, unsigned open) override {
        builder.emit(out, s, depth);
        for (int i = 0; i <= D; ++i)
          if (open >> i & 1u) afl.update(opposite_face<D>(s, i));
      }
    } filter(*this, p.bounds, p.afl, task.out, task.search, p.depth);
    const std::size_t before = task.out.size();
    if (!(*regions_)(p.points, ps_.coords, filter)) return false;
    while (!p.afl.empty()) task.open_faces.push_back(p.afl.pop());
    task.stats.simplices += task.out.size() - before;
    task.stats.region_simplices += task.out.size() - before;
    // Streaming: a region kept means the hybrid works on this input.
    if (decision_ && decision_->settle() && task.out.stream()) task.out.stream()->release();
    return true;
  }

  /// Gift-wrapping from the faces the regions left open: hull faces (no
  /// apex), and the faces of any simplex that crosses a wall but that no
  /// wall reached. Serial, after every region, in a fixed order.
  void finish(const std::vector<Face<D>>& open_faces, Task& task) {
    Active_face_list<D> afl;
    for (const Face<D>& f : open_faces) afl.update(f);
    auto same_list = [&](const Face<D>&) -> Active_face_list<D>& { return afl; };
    const std::size_t before = task.out.size();
    wall_loop(afl, 0, same_list, task);
    task.stats.simplices += task.out.size() - before;
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

  void merge(const Task& task) {
    const Search_stats& s = task.search.stats();
    const Wall_stats& w = task.stats;
    const std::lock_guard lock(mutex_);
    search_stats_.searches += s.searches;
    search_stats_.nodes_visited += s.nodes_visited;
    search_stats_.candidates += s.candidates;
    stats_.simplices += w.simplices;
    stats_.first_wall_simplices += w.first_wall_simplices;
    stats_.max_depth = std::max(stats_.max_depth, w.max_depth);
    stats_.region_simplices += w.region_simplices;
  }

  /// A wall's slab holds about this many times n^((D−1)/D) points (slab_of):
  /// for points spread in volume, a layer and a half on each side of α, enough
  /// that most wall simplices lie in it with their spheres (the fastest of the
  /// factors measured: docs/engines.md).
  static constexpr double slab_size_factor = 3;

  const Point_set<K>& ps_;
  int parallel_depth_;
  std::optional<Search_budget> budget_;
  const Region_triangulator<D>* regions_;
  std::size_t region_points_;
  Handover_decision* decision_;
  std::mutex mutex_;
  Wall_stats stats_;
  Search_stats search_stats_;
};

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
