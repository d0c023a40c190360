// MakeFirstSimplex: a Delaunay simplex crossed by the splitting plane.
//
// The paper's recipe (the point nearest α, its nearest neighbour across α, then
// the smallest circumsphere) does not always give a Delaunay simplex. Here a
// simplex is accepted only once it is *proven* Delaunay:
//  1. Let a be a point of side 1 nearest α. Try faces made of a and D − 1 of
//     its nearest neighbours (nearest combinations first: floating point only
//     orders the attempts). For each face f, MakeSimplex on either side gives a
//     candidate simplex S, accepted when its perturbed circumsphere is empty of
//     every input point, checked exactly (Simplex_search::is_empty_sphere). An
//     empty perturbed sphere is exactly the definition of a simplex of the
//     perturbed Delaunay triangulation, so S is CGAL's.
//     Termination: a is a vertex of the triangulation, so some Delaunay simplex
//     contains a, and the face of it through a is among the combinations once
//     the neighbourhood has grown to include its vertices (it doubles on
//     failure, up to all points); MakeSimplex on a Delaunay face returns the
//     Delaunay simplex on that side, which passes the check.
//  2. If S does not cross α, walk towards a point t of side 2 (a visibility
//     walk: cross a face that has t strictly on its outer side, building the
//     next simplex with MakeSimplex, which is exact on Delaunay faces). The first
//     simplex with vertices on both sides is returned. The visibility walk
//     terminates in a Delaunay triangulation (Edelsbrunner, "An acyclicity
//     theorem for cell complexes in d dimensions", 1990), and it reaches a
//     simplex incident to t at the latest.
#pragma once

#include <algorithm>
#include <vector>

#include "dewall/detail/common/assert.hpp"
#include "dewall/detail/walls/make_simplex.hpp"
#include "dewall/detail/walls/split.hpp"
#include "dewall/kernel/floating_point.hpp"

DEWALL_FLOATING_POINT_CODE_BEGIN
namespace dewall::detail {

template <class K>
Simplex<K::dimension> first_simplex(const Point_set<K>& ps, Simplex_search<K>& search,
                                    std::span<const Index> points, const Split<K::dimension>& split) {
  constexpr int D = K::dimension;
  const auto& x = ps.coords;
  auto side1 = [&](Index p) { return split.on_side1(x[p], p); };
  auto gap = [&](Index p) { return std::abs(x[p][split.axis] - split.value); };
  Index a = points.front(), t = points.back();
  for (Index p : points) {
    if (side1(p) && (!side1(a) || gap(p) < gap(a))) a = p;
    if (!side1(p) && (side1(t) || gap(p) < gap(t))) t = p;
  }
  auto dist2 = [&](Index p) {
    double s = 0;
    for (int j = 0; j < D; ++j) s += (x[p][j] - x[a][j]) * (x[p][j] - x[a][j]);
    return s;
  };
  // The points by distance to a, sorted only as far as the attempts reach
  // (usually 4·D suffice; a full sort is a visible part of the first wall).
  std::vector<Index> near(points.begin(), points.end());
  near.erase(std::remove(near.begin(), near.end(), a), near.end());
  std::size_t sorted = 0;
  auto sort_up_to = [&](std::size_t m) {
    std::partial_sort(near.begin() + static_cast<std::ptrdiff_t>(sorted), near.begin() + static_cast<std::ptrdiff_t>(m),
                      near.end(), [&](Index p, Index q) { return dist2(p) < dist2(q); });
    sorted = m;
  };

  // Step 1: combinations of D − 1 neighbours among the m nearest, nearest first.
  std::optional<Simplex<D>> found;
  std::size_t tried_up_to = D - 2;  // combinations whose largest member is < this were tried
  for (std::size_t m = std::min<std::size_t>(near.size(), 4 * D); !found; m = std::min(near.size(), 2 * m)) {
    sort_up_to(m);
    std::array<std::size_t, D - 1> pick;
    // Enumerate combinations by their largest member `last`, so each is tried once overall.
    for (std::size_t last = std::max<std::size_t>(tried_up_to, D - 2); last < m && !found; ++last) {
      for (int i = 0; i < D - 1; ++i) pick[i] = static_cast<std::size_t>(i);
      pick[D - 2] = last;
      for (;;) {
        Face<D> f;
        f[0] = a;
        for (int i = 0; i < D - 1; ++i) f[i + 1] = near[pick[i]];
        for (const Face<D>& g : {f, flipped<D>(f)}) {
          if (auto apex = search.make_simplex(g)) {
            const Simplex<D> s = with_apex<D>(g, *apex);
            if (search.is_empty_sphere(s)) {
              found = s;
              break;
            }
          }
        }
        if (found || D == 2) break;
        // Next combination of the first D − 2 members below `last`.
        int i = D - 3;
        while (i >= 0 && pick[i] == last - static_cast<std::size_t>(D - 2 - i)) --i;
        if (i < 0) break;
        ++pick[i];
        for (int j = i + 1; j < D - 2; ++j) pick[j] = pick[j - 1] + 1;
      }
    }
    tried_up_to = m;
    DEWALL_ASSERT(found || m < near.size());
  }

  // Step 2: walk to a simplex crossed by the split.
  Simplex<D> s = *found;
  for (;;) {
    const bool has1 = std::any_of(s.begin(), s.end(), side1);
    const bool has2 = !std::all_of(s.begin(), s.end(), side1);
    if (has1 && has2) return s;
    bool moved = false;
    for (int i = 0; i <= D && !moved; ++i) {
      const Face<D> g = opposite_face<D>(s, i);
      if (ps.orientation(g, t) != kernel::POSITIVE) continue;
      const auto apex = search.make_simplex(g);
      DEWALL_ASSERT(apex.has_value());  // t lies beyond g
      s = with_apex<D>(g, *apex);
      moved = true;
    }
    DEWALL_ASSERT(moved);  // otherwise t would be inside s without being a vertex
  }
}

}  // namespace dewall::detail
DEWALL_FLOATING_POINT_CODE_END
