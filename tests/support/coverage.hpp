// Coverage of the convex hull, checked in rational arithmetic and independently
// of the certifier: the simplices' volumes add up exactly to the hull's, every
// facet of two simplices has them on its two sides, and every facet of one
// simplex is a hull facet (no point beyond it). With positively oriented
// simplices that is a triangulation of the hull: crossing a shared facet
// leaves the number of simplices covering a point unchanged, so it is the same
// everywhere inside the hull, and the volumes make it one.
//
// The hull's volume: CGAL's convex hull in 2D and 3D (a construction that
// shares nothing with a triangulator), CGAL's Delaunay triangulation (another
// triangulation of the same hull) in higher dimensions, compiled once in
// hull_volume.cpp. Small inputs: the hull facet test is O(facets · n).
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/point.hpp"
#include "support/gmp_reference.hpp"

namespace dewall::test {

/// D! times the volume of the simplex p_0 … p_D, signed: det[p_i − p_0].
template <int D>
mpq_class simplex_volume_times_factorial(const std::array<const kernel::Point_d<D>*, D + 1>& p) {
  std::vector<std::vector<mpq_class>> a(D, std::vector<mpq_class>(D));
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) a[i][j] = mpq_class((*p[i + 1])[j]) - mpq_class((*p[0])[j]);
  return gmp_determinant(a);
}

/// D! times the total signed volume of `simplices` (input indices).
template <int D, class Simplices>
mpq_class volume_times_factorial(const std::vector<kernel::Point_d<D>>& points, const Simplices& simplices) {
  mpq_class sum = 0;
  for (const auto& s : simplices) {
    std::array<const kernel::Point_d<D>*, D + 1> p;
    for (int i = 0; i <= D; ++i) p[static_cast<std::size_t>(i)] = &points[s[static_cast<std::size_t>(i)]];
    sum += simplex_volume_times_factorial<D>(p);
  }
  return sum;
}

/// D! times the volume of the points' convex hull (hull_volume.cpp, D = 2 … 6).
template <int D>
mpq_class hull_volume_times_factorial(const std::vector<kernel::Point_d<D>>& points);

extern template mpq_class hull_volume_times_factorial<2>(const std::vector<kernel::Point_d<2>>&);
extern template mpq_class hull_volume_times_factorial<3>(const std::vector<kernel::Point_d<3>>&);
extern template mpq_class hull_volume_times_factorial<4>(const std::vector<kernel::Point_d<4>>&);
extern template mpq_class hull_volume_times_factorial<5>(const std::vector<kernel::Point_d<5>>&);
extern template mpq_class hull_volume_times_factorial<6>(const std::vector<kernel::Point_d<6>>&);

/// The first facet that breaks the structure of a triangulation of the hull:
/// one in more than two simplices, one in two simplices on the same side of
/// it, or one in a single simplex with a point beyond it. Nothing when every
/// facet passes. \pre the simplices are positively oriented.
template <int D, class Simplices>
std::optional<std::string> facet_violation(const std::vector<kernel::Point_d<D>>& points, const Simplices& simplices) {
  using Facet = std::array<std::uint32_t, D>;
  std::map<Facet, std::vector<std::pair<std::size_t, int>>> facets;  // sorted facet -> (simplex, opposite vertex)
  for (std::size_t r = 0; r < simplices.size(); ++r)
    for (int skip = 0; skip <= D; ++skip) {
      Facet f;
      for (int i = 0, k = 0; i <= D; ++i)
        if (i != skip) f[static_cast<std::size_t>(k++)] = simplices[r][static_cast<std::size_t>(i)];
      std::sort(f.begin(), f.end());
      facets[f].emplace_back(r, skip);
    }
  // The side of q with respect to the facet of simplex r opposite `skip`, the
  // facet's vertices in the simplex's order: the apex is on the positive side.
  const auto side = [&](std::size_t r, int skip, const kernel::Point_d<D>& q) {
    std::array<const kernel::Point_d<D>*, D + 1> p;
    for (int i = 0; i <= D; ++i)
      p[static_cast<std::size_t>(i)] = i == skip ? &q : &points[simplices[r][static_cast<std::size_t>(i)]];
    return kernel::orientation_d<D>(p);
  };
  for (const auto& [f, in] : facets) {
    if (in.size() > 2) return "a facet of " + std::to_string(in.size()) + " simplices";
    if (in.size() == 2) {
      const auto& [r, skip] = in[1];
      const auto& other_apex = points[simplices[in[0].first][static_cast<std::size_t>(in[0].second)]];
      if (side(r, skip, other_apex) != kernel::NEGATIVE)
        return "simplices " + std::to_string(in[0].first) + " and " + std::to_string(r) + " on one side of a facet";
    } else {
      const auto& [r, skip] = in[0];
      for (std::size_t q = 0; q < points.size(); ++q)
        if (side(r, skip, points[q]) == kernel::NEGATIVE)
          return "point " + std::to_string(q) + " beyond the boundary facet of simplex " + std::to_string(r);
    }
  }
  return std::nullopt;
}

}  // namespace dewall::test
