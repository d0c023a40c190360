// The DeWall recursion (the paper's procedure DeWall(P, AFL)).
//
//  1. Split P by α (split.hpp) into P1 and P2.
//  2. At the top level (empty AFL): a first simplex crossed by α (first_simplex.hpp).
//  3. Sort the AFL into AFL_α (faces crossed by α), AFL_1 and AFL_2.
//  4. While AFL_α is not empty: take a face, build the simplex on its outer side
//     (make_simplex.hpp), emit it, and Update its other faces into the list of
//     their class.
//  5. Recurse on (P1, AFL_1) and (P2, AFL_2).
// Below the top level an empty AFL ends the recursion: every simplex lying in
// P1 shares a face with the wall or with another such simplex (the region they
// cover is bounded by wall simplices and the hull), so none is missed. The
// search for an apex uses the whole point set; the apex of a face of AFL_1 lies
// in P1 anyway, since a simplex with vertices on both sides is a wall simplex
// and was built with the wall.
#pragma once

#include <span>
#include <vector>

#include "dewall/detail/active_face_list.hpp"
#include "dewall/detail/first_simplex.hpp"

namespace dewall::detail {

struct Wall_stats {
  std::size_t simplices = 0;
  std::size_t first_wall_simplices = 0;
  std::size_t max_depth = 0;
};

template <class K, class Emit>
class Wall_builder {
  static constexpr int D = K::dimension;

 public:
  Wall_builder(const Point_set<K>& ps, Emit& emit) : ps_(ps), search_(ps), emit_(emit) {}

  void run(std::span<Index> points) { recurse(points, Active_face_list<D>{}, 0, true); }

  const Wall_stats& stats() const { return stats_; }
  const Search_stats& search_stats() const { return search_.stats(); }

 private:
  void recurse(std::span<Index> points, Active_face_list<D> afl, std::size_t depth, bool top) {
    if (!top && afl.empty()) return;
    stats_.max_depth = std::max(stats_.max_depth, depth);
    std::size_t side1_size = 0;
    const auto split = choose_split<D>(points, ps_.coords, static_cast<int>(depth % D), side1_size);
    DEWALL_ASSERT(split.has_value());  // faces need two distinct points
    Active_face_list<D> wall, afl1, afl2;
    auto classify = [&](const Face<D>& f) -> Active_face_list<D>& {
      int n1 = 0;
      for (Index v : f) n1 += split->on_side1(ps_.coords[v]);
      return n1 == D ? afl1 : n1 == 0 ? afl2 : wall;
    };
    const std::size_t before = stats_.simplices;
    auto add = [&](const Simplex<D>& s, int skip) {
      emit_(s);
      ++stats_.simplices;
      for (int i = 0; i <= D; ++i)
        if (i != skip) {
          const Face<D> g = opposite_face<D>(s, i);
          classify(g).update(g);
        }
    };
    if (top) add(first_simplex(ps_, search_, points, *split), -1);
    while (!afl.empty()) {
      const Face<D> f = afl.pop();
      classify(f).update(f);
    }
    while (!wall.empty()) {
      const Face<D> f = wall.pop();
      const auto apex = search_.make_simplex(f);
      if (!apex) continue;  // a convex hull face
      Simplex<D> s;
      std::copy(f.begin(), f.end(), s.begin());
      s[D] = *apex;
      add(s, D);
    }
    if (top) stats_.first_wall_simplices = stats_.simplices - before;
    recurse(points.first(side1_size), std::move(afl1), depth + 1, false);
    recurse(points.subspan(side1_size), std::move(afl2), depth + 1, false);
  }

  const Point_set<K>& ps_;
  Simplex_search<K> search_;
  Emit& emit_;
  Wall_stats stats_;
};

}  // namespace dewall::detail
