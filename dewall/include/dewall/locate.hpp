// Point location in a Delaunay triangulation: which simplex contains a point.
//
// A visibility walk (O. Devillers, S. Pion, M. Teillaud, "Walking in a
// triangulation", IJFCS 13(2), 2002): from a simplex, cross any facet that the
// query point lies strictly beyond, until no facet is; the point is then in the
// closed simplex. Crossing a hull facet means the point is outside the convex
// hull. Every step is one exact orientation test (the kernel's), so the answer
// is exact: a point on a shared face gets one of the simplices that contain it,
// a point outside by any margin gets −1.
//
// Termination: in a Delaunay triangulation the "q lies beyond a facet of"
// relation between simplices is acyclic (H. Edelsbrunner, "An acyclicity
// theorem for cell complexes in d dimensions", Combinatorica 10(3), 1990; it
// holds for every regular triangulation, hence for the symbolically perturbed
// one dewall builds), so any such walk ends. A walk longer than the number of
// simplices can only come from a list that is not Delaunay; it then falls back
// to testing every simplex, so the function still answers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "dewall/kernel/concepts.hpp"
#include "dewall/kernel/floating_point.hpp"
#include "dewall/kernel/point.hpp"

namespace dewall {

/// The row of a simplex of `simplices` that contains `q` (closed), or −1 when
/// q lies outside their union (or has a non-finite coordinate). The walk starts
/// at row `start`; near the answer is fast.
/// \pre `simplices` is a Delaunay triangulation of `points` with every row
/// positively oriented (dewall's output); `neighbors` as certify::neighbors
/// computes it; start < simplices.size().
/// Complexity: one orientation test per facet looked at; O(n^(1/D)) steps on
/// average from a random start in uniform data.
template <kernel::DelaunayKernel K, class Vertex, class Index>
std::int64_t locate(const K& k, std::span<const typename K::Point_d> points,
                    std::span<const std::array<Vertex, K::dimension + 1>> simplices,
                    std::span<const std::array<Index, K::dimension + 1>> neighbors,
                    const typename K::Point_d& q, std::size_t start) {
  constexpr int D = K::dimension;
  if constexpr (kernel::approximate_coordinates_are_exact<K>) {
    for (double c : k.approximate_coordinates_object()(q))
      if (!kernel::is_finite(c)) return -1;  // outside every simplex, and outside the predicates' domain
  }
  const auto orientation = k.orientation_d_object();
  // Sign of simplex `s` with its vertex j replaced by q: NEGATIVE when q is
  // strictly beyond the facet opposite j (s is positively oriented).
  const auto side = [&](std::size_t s, int j) {
    std::array<const typename K::Point_d*, D + 1> p;
    for (int i = 0; i <= D; ++i) p[static_cast<std::size_t>(i)] = &points[simplices[s][static_cast<std::size_t>(i)]];
    p[static_cast<std::size_t>(j)] = &q;
    return orientation(p);
  };
  std::size_t s = start;
  int entered_by = -1;  // the facet we came through: q is strictly inside it, no test needed
  for (std::size_t steps = 0; steps <= simplices.size(); ++steps) {
    int beyond = -1;
    for (int j = 0; j <= D && beyond < 0; ++j)
      if (j != entered_by && side(s, j) == kernel::NEGATIVE) beyond = j;
    if (beyond < 0) return static_cast<std::int64_t>(s);
    const auto next = neighbors[s][static_cast<std::size_t>(beyond)];
    if (next < 0) return -1;  // beyond a hull facet: outside the convex hull
    entered_by = -1;
    for (int j = 0; j <= D; ++j)
      if (neighbors[static_cast<std::size_t>(next)][static_cast<std::size_t>(j)] == static_cast<Index>(s)) entered_by = j;
    s = static_cast<std::size_t>(next);
  }
  // Not reached for a Delaunay triangulation (file comment): test every simplex.
  for (std::size_t t = 0; t < simplices.size(); ++t) {
    bool inside = true;
    for (int j = 0; j <= D && inside; ++j) inside = side(t, j) != kernel::NEGATIVE;
    if (inside) return static_cast<std::int64_t>(t);
  }
  return -1;
}

/// locate() for every point of `queries`, into `out` (same size); each walk
/// starts where the previous one ended, so queries near each other are cheap.
/// Holds a kernel::Fp_environment_guard (the predicates' rounding mode).
template <kernel::DelaunayKernel K, class Vertex, class Index, class Out>
void locate_all(const K& k, std::span<const typename K::Point_d> points,
                std::span<const std::array<Vertex, K::dimension + 1>> simplices,
                std::span<const std::array<Index, K::dimension + 1>> neighbors,
                std::span<const typename K::Point_d> queries, std::span<Out> out) {
  const kernel::Fp_environment_guard guard;
  std::size_t start = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const std::int64_t s = simplices.empty() ? -1 : locate<K>(k, points, simplices, neighbors, queries[i], start);
    out[i] = static_cast<Out>(s);
    if (s >= 0) start = static_cast<std::size_t>(s);
  }
}

}  // namespace dewall
