// The Voronoi diagram's topology from a Delaunay triangulation (dewall.Voronoi,
// python/dewall/_hull.py): its ridges (the duals of the Delaunay edges) and
// regions (the duals of the vertices), over Voronoi vertices given as one
// group index per simplex (neighbouring simplices with one circumsphere share
// a group, hence a vertex). Topology only: no coordinates, no predicates.
//
// 1. Edges: every simplex's vertex pairs (lo < hi), bucketed by lo, each bucket
//    ordered by (hi, simplex) (counting sorts, stable, of incidences made in
//    simplex order): the simplices around an edge side by side in ascending
//    order, with what the walk needs of each, and the edges in scipy's ridge
//    order (lo, then hi).
// 2. A ridge's vertices: in 3-D the walk around the edge across the facets
//    through it, always turning the same way (a cycle inside, opened at its
//    smallest simplex; a chain from one hull facet to the other on the hull,
//    then −1 first); in 4-D and up the groups by ascending simplex (a ridge is
//    a polytope there, no cyclic order), −1 first on the hull; in 2-D the
//    triangle across the edge's first one, then that one. Repeated groups are
//    one vertex; an edge is a ridge when at least D distinct vertices remain.
// 3. Regions: in 2-D the walk counterclockwise around each point (−1 last on
//    the hull); from 3-D up each point's groups, ascending, −1 first on the hull.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

namespace dewall_python {

/// Ridges and regions as compressed rows: row r of `ridges` is
/// ridge_vertices[ridge_start[r] .. ridge_start[r + 1]), likewise regions.
struct Voronoi_topology {
  std::vector<std::array<std::int32_t, 2>> ridge_points;
  std::vector<std::size_t> ridge_start{0};
  std::vector<std::int32_t> ridge_vertices;
  std::vector<std::size_t> region_start{0};
  std::vector<std::int32_t> region_vertices;
};

namespace detail {

/// An edge (lo, hi) of simplex t, sorted by key = hi << 32 | t in lo's bucket (in 2-D also a
/// vertex of t, key t, in the vertex's bucket); `next`: in 2-D and 3-D the simplex after t
/// around the edge or vertex (−1 across the hull), in 4-D and up 1 when a facet of t through
/// the edge is on the hull; `group`: t's Voronoi vertex.
struct Edge_incidence {
  std::uint64_t key;
  std::int32_t next;
  std::int32_t group;
  std::uint32_t simplex() const { return static_cast<std::uint32_t>(key & 0xffffffffu); }
};

/// In 3-D, leave[a][b]: the facet (opposite vertex position) through which the walk around the
/// edge from position a (lo) to position b (hi) leaves a tetrahedron: the first of the other
/// two positions k < l when (a, b, k, l) is an even permutation, else the second. Every
/// tetrahedron then turns the same way around the directed edge lo → hi.
constexpr std::array<std::array<int, 4>, 4> leave_3d() {
  std::array<std::array<int, 4>, 4> out{};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      if (a == b) continue;
      std::array<int, 4> p{a, b, 0, 0};
      for (int i = 0, k = 2; i < 4; ++i)
        if (i != a && i != b) p[static_cast<std::size_t>(k++)] = i;
      int inversions = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += p[static_cast<std::size_t>(i)] > p[static_cast<std::size_t>(j)];
      out[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = p[inversions % 2 == 0 ? 2 : 3];
    }
  return out;
}

/// Appends `g` to `out` unless it repeats the last one after position `start`.
inline void push_distinct_from_last(std::vector<std::int32_t>& out, std::size_t start, std::int32_t g) {
  if (out.size() == start || out.back() != g) out.push_back(g);
}

/// The groups of the simplices around an edge (3-D) or a vertex (2-D), in walk order, onto
/// `out`, repeats merged: a cycle from its smallest simplex, a chain from its first, with −1
/// (the vertex at infinity) first or last. `run`: the incidences, sorted by key, all with the
/// key's high half; `next` leads to the following simplex. \returns whether it was a chain.
inline bool walk(std::span<const Edge_incidence> run, bool infinity_first, std::vector<std::int32_t>& out,
                 std::vector<char>& reached) {
  const std::uint64_t hi = run.front().key & ~std::uint64_t{0xffffffffu};
  const auto find = [&](std::int32_t t) -> std::size_t {
    const std::uint64_t key = hi | static_cast<std::uint32_t>(t);
    const auto it = std::lower_bound(run.begin(), run.end(), key,
                                     [](const Edge_incidence& e, std::uint64_t k) { return e.key < k; });
    if (it == run.end() || it->key != key)
      throw std::invalid_argument("not a triangulation: the walk around an edge leaves its tetrahedra");
    return static_cast<std::size_t>(it - run.begin());
  };
  std::size_t at = 0;
  const bool chain = std::any_of(run.begin(), run.end(), [](const Edge_incidence& e) { return e.next < 0; });
  if (chain) {  // the chain's first tetrahedron: the one no other leads to
    reached.assign(run.size(), 0);
    for (const auto& e : run)
      if (e.next >= 0) reached[find(e.next)] = 1;
    at = static_cast<std::size_t>(std::find(reached.begin(), reached.end(), 0) - reached.begin());
    if (infinity_first) out.push_back(-1);
  }
  const std::size_t groups = out.size();
  for (std::size_t steps = 0; steps < run.size(); ++steps) {
    if (at >= run.size()) throw std::invalid_argument("not a triangulation: the walk around an edge ends early");
    push_distinct_from_last(out, groups, run[at].group);
    const std::int32_t next = run[at].next;
    at = next < 0 ? run.size() : find(next);
  }
  if (chain ? at != run.size() : at != 0)
    throw std::invalid_argument("not a triangulation: the walk around an edge does not close");
  if (chain && !infinity_first) out.push_back(-1);
  if (!chain && out.size() - groups > 1 && out[groups] == out.back()) out.pop_back();
  return chain;
}

}  // namespace detail

/// The ridges and regions of the Voronoi diagram dual to `simplices`.
/// \pre neighbors[i][j] is the simplex across the facet of i opposite its
/// vertex j (−1 on the hull); group.size() == simplices.size(); every vertex
/// index < vertex_count. \throws std::invalid_argument when the walk around
/// an edge does not close (not a triangulation).
/// Complexity: O(m·D²) for m simplices, plus sorting each vertex's neighbours
/// and a binary search per walk step; a walk reads only its edge's incidences,
/// side by side, not the simplices. poll() is called every few thousand
/// vertices; what it throws stops the work (and is passed on).
template <int D, class Poll>
Voronoi_topology voronoi_topology(std::size_t vertex_count, std::span<const std::array<std::uint32_t, D + 1>> simplices,
                                  std::span<const std::array<std::int32_t, D + 1>> neighbors,
                                  std::span<const std::int32_t> group, Poll&& poll) {
  constexpr std::size_t poll_every = 4096;  // vertices
  Voronoi_topology out;
  const std::size_t m = simplices.size();

  // 1. Each edge incidence in lo's bucket, with what the walk needs from its simplex.
  std::vector<std::size_t> start(vertex_count + 1, 0);
  for (const auto& s : simplices)
    for (int i = 0; i <= D; ++i)
      for (int j = i + 1; j <= D; ++j) ++start[std::min(s[static_cast<std::size_t>(i)], s[static_cast<std::size_t>(j)]) + 1];
  for (std::size_t v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
  std::vector<detail::Edge_incidence> incidence(start[vertex_count]);
  {
    constexpr auto leave = detail::leave_3d();
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < m; ++t) {
      const auto& s = simplices[t];
      const auto& n = neighbors[t];
      for (int i = 0; i <= D; ++i)
        for (int j = i + 1; j <= D; ++j) {
          const bool ordered = s[static_cast<std::size_t>(i)] < s[static_cast<std::size_t>(j)];
          const int a = ordered ? i : j, b = ordered ? j : i;  // positions of lo and hi
          std::int32_t next = 0;
          if constexpr (D == 3) {
            next = n[static_cast<std::size_t>(leave[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)])];
          } else if constexpr (D > 3) {
            for (int k = 0; k <= D; ++k)
              if (k != i && k != j && n[static_cast<std::size_t>(k)] < 0) next = 1;
          }
          const std::uint32_t lo = s[static_cast<std::size_t>(a)], hi = s[static_cast<std::size_t>(b)];
          incidence[fill[lo]++] = {(std::uint64_t{hi} << 32) | t, next, group[t]};
        }
    }
  }

  // 2. One ridge per edge with enough distinct vertices. A bucket is in simplex order (filled
  // so); a counting sort by hi, stable, puts each edge's incidences side by side, in simplex
  // order, and the edges in ascending hi, in O(bucket + distinct hi · log).
  std::vector<char> reached;
  std::vector<std::uint32_t> at_hi(vertex_count, 0), his;
  std::vector<detail::Edge_incidence> sorted;
  for (std::size_t lo = 0; lo < vertex_count; ++lo) {
    if (lo % poll_every == 0) poll();
    const std::span<const detail::Edge_incidence> bucket(incidence.data() + start[lo], start[lo + 1] - start[lo]);
    his.clear();
    for (const auto& e : bucket)
      if (at_hi[e.key >> 32]++ == 0) his.push_back(static_cast<std::uint32_t>(e.key >> 32));
    std::sort(his.begin(), his.end());
    std::uint32_t offset = 0;
    for (const std::uint32_t h : his) offset += std::exchange(at_hi[h], offset);
    sorted.resize(bucket.size());
    for (const auto& e : bucket) sorted[at_hi[e.key >> 32]++] = e;
    for (const std::uint32_t h : his) at_hi[h] = 0;
    const auto first = sorted.begin(), last = sorted.end();
    for (auto run = first; run != last;) {
      const std::uint64_t hi = run->key >> 32;
      auto end = run;
      while (end != last && (end->key >> 32) == hi) ++end;
      const std::size_t begin = out.ridge_vertices.size();
      auto& v = out.ridge_vertices;
      if constexpr (D == 2) {  // the triangle across the edge (or −1), then the edge's first triangle
        v.push_back(end - run == 2 ? (run + 1)->group : -1);
        detail::push_distinct_from_last(v, begin, run->group);
      } else if constexpr (D == 3) {
        detail::walk(std::span<const detail::Edge_incidence>(&*run, static_cast<std::size_t>(end - run)), true, v,
                     reached);
      } else {
        if (std::any_of(run, end, [](const detail::Edge_incidence& e) { return e.next != 0; })) v.push_back(-1);
        const std::size_t groups = v.size();
        for (auto it = run; it != end; ++it)
          if (std::find(v.begin() + static_cast<std::ptrdiff_t>(groups), v.end(), it->group) == v.end())
            v.push_back(it->group);
      }
      if (v.size() - begin >= static_cast<std::size_t>(D)) {
        out.ridge_points.push_back({static_cast<std::int32_t>(lo), static_cast<std::int32_t>(hi)});
        out.ridge_start.push_back(v.size());
      } else {
        v.resize(begin);
      }
      run = end;
    }
  }

  // 3. Regions. 2-D: the walk counterclockwise around each point, across the edge from it to
  // the vertex before it in the triangle (−1 last on the hull).
  if constexpr (D == 2) {
    std::vector<detail::Edge_incidence> around(3 * m);
    std::fill(start.begin(), start.end(), 0);
    for (const auto& s : simplices)
      for (const std::uint32_t v : s) ++start[v + 1];
    for (std::size_t v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < m; ++t)
      for (std::size_t j = 0; j < 3; ++j) around[fill[simplices[t][j]]++] = {t, neighbors[t][(j + 1) % 3], group[t]};
    for (std::size_t p = 0; p < vertex_count; ++p) {
      if (p % poll_every == 0) poll();
      if (start[p + 1] > start[p])
        detail::walk(std::span<const detail::Edge_incidence>(around.data() + start[p], start[p + 1] - start[p]), false,
                     out.region_vertices, reached);
      out.region_start.push_back(out.region_vertices.size());
    }
    return out;
  }
  // 3-D and up: each point's groups, ascending, −1 first on the hull.
  std::vector<char> on_hull(vertex_count, 0);
  std::fill(start.begin(), start.end(), 0);
  for (std::size_t t = 0; t < m; ++t)
    for (int j = 0; j <= D; ++j) {
      ++start[simplices[t][static_cast<std::size_t>(j)] + 1];
      if (neighbors[t][static_cast<std::size_t>(j)] < 0)
        for (int k = 0; k <= D; ++k)
          if (k != j) on_hull[simplices[t][static_cast<std::size_t>(k)]] = 1;
    }
  for (std::size_t v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
  std::vector<std::int32_t> around(start[vertex_count]);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < m; ++t)
      for (int j = 0; j <= D; ++j) around[fill[simplices[t][static_cast<std::size_t>(j)]]++] = group[t];
  }
  out.region_vertices.reserve(around.size() / 2 + vertex_count);
  for (std::size_t p = 0; p < vertex_count; ++p) {
    if (p % poll_every == 0) poll();
    const auto first = around.begin() + static_cast<std::ptrdiff_t>(start[p]);
    const auto last = around.begin() + static_cast<std::ptrdiff_t>(start[p + 1]);
    if (first != last) {
      std::sort(first, last);
      if (on_hull[p]) out.region_vertices.push_back(-1);
      out.region_vertices.insert(out.region_vertices.end(), first, std::unique(first, last));
    }
    out.region_start.push_back(out.region_vertices.size());
  }
  return out;
}

/// Groups of simplices joined by `pairs` (neighbours with one circumsphere), each simplex's
/// group numbered in the order of the groups' first simplices: union-find, every root the
/// smallest simplex of its group.
/// \pre every index < count. Complexity: O((count + pairs) α(count)).
inline std::vector<std::int32_t> merge_groups(std::size_t count, std::span<const std::array<std::int32_t, 2>> pairs) {
  std::vector<std::int32_t> parent(count);
  for (std::size_t i = 0; i < count; ++i) parent[i] = static_cast<std::int32_t>(i);
  const auto root = [&](std::int32_t i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      i = parent[static_cast<std::size_t>(i)];
    }
    return i;
  };
  for (const auto& [a, b] : pairs) {
    const std::int32_t ra = root(a), rb = root(b);
    if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }
  std::vector<std::int32_t> group(count);
  std::int32_t groups = 0;
  for (std::size_t i = 0; i < count; ++i) {  // a root comes before the rest of its group
    const std::int32_t r = root(static_cast<std::int32_t>(i));
    group[i] = r == static_cast<std::int32_t>(i) ? groups++ : group[static_cast<std::size_t>(r)];
  }
  return group;
}

/// The circumcentre of each simplex: c solving 2 (v_j − v_0)·(c − v_0) = |v_j − v_0|²,
/// j = 1 … D, by Gaussian elimination with partial pivoting, relative to v_0 for
/// accuracy. A flat simplex (no pivot) gets NaN.
template <int D>
void circumcentres(const double* points, std::span<const std::array<std::uint32_t, D + 1>> simplices, double* out) {
  for (const auto& s : simplices) {
    const double* v0 = points + std::size_t{s[0]} * D;
    double a[D][D + 1];
    for (int j = 0; j < D; ++j) {
      const double* vj = points + std::size_t{s[static_cast<std::size_t>(j + 1)]} * D;
      double rhs = 0;
      for (int k = 0; k < D; ++k) {
        a[j][k] = vj[k] - v0[k];
        rhs += a[j][k] * a[j][k];
      }
      a[j][D] = 0.5 * rhs;
    }
    for (int col = 0; col < D; ++col) {
      int pivot = col;
      for (int r = col + 1; r < D; ++r)
        if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
      if (pivot != col)
        for (int k = col; k <= D; ++k) std::swap(a[col][k], a[pivot][k]);
      for (int r = col + 1; r < D; ++r) {
        const double f = a[r][col] / a[col][col];
        for (int k = col; k <= D; ++k) a[r][k] -= f * a[col][k];
      }
    }
    double c[D];
    for (int r = D - 1; r >= 0; --r) {
      double x = a[r][D];
      for (int k = r + 1; k < D; ++k) x -= a[r][k] * c[k];
      c[r] = x / a[r][r];
    }
    for (int k = 0; k < D; ++k) out[k] = v0[k] + c[k];
    out += D;
  }
}

}  // namespace dewall_python
