// The hull volume of coverage.hpp, compiled once for D = 2 … 6 (CGAL's hulls
// and triangulations are slow to instantiate).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/convex_hull_3.h>

#include "support/cgal_delaunay.hpp"
#include "support/coverage.hpp"

namespace dewall::test {

/// D! times the volume of the points' convex hull.
template <int D>
mpq_class hull_volume_times_factorial(const std::vector<kernel::Point_d<D>>& points) {
  using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
  if constexpr (D == 2) {
    // The hull polygon, counterclockwise: twice its area is Σ x_i·y_{i+1} − x_{i+1}·y_i.
    std::vector<Epick::Point_2> in, hull;
    for (const auto& p : points) in.emplace_back(p[0], p[1]);
    CGAL::convex_hull_2(in.begin(), in.end(), std::back_inserter(hull));
    mpq_class twice = 0;
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const auto& a = hull[i];
      const auto& b = hull[(i + 1) % hull.size()];
      twice += mpq_class(a.x()) * mpq_class(b.y()) - mpq_class(b.x()) * mpq_class(a.y());
    }
    return twice;
  } else if constexpr (D == 3) {
    // Six times the volume: Σ det(a, b, c) over the outward-oriented triangles.
    std::vector<Epick::Point_3> in;
    for (const auto& p : points) in.emplace_back(p[0], p[1], p[2]);
    CGAL::Surface_mesh<Epick::Point_3> hull;
    CGAL::convex_hull_3(in.begin(), in.end(), hull);
    mpq_class six = 0;
    for (auto f : hull.faces()) {
      std::vector<std::array<mpq_class, 3>> v;
      for (auto u : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
        const auto& q = hull.point(u);
        v.push_back({mpq_class(q.x()), mpq_class(q.y()), mpq_class(q.z())});
      }
      for (std::size_t k = 1; k + 1 < v.size(); ++k) {  // a fan, should a face have more than three vertices
        const auto &a = v[0], &b = v[k], &c = v[k + 1];
        six += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
      }
    }
    return six;
  } else {
    // CGAL's cells as sorted index tuples: their orientation is lost, so each counts by its size.
    mpq_class sum = 0;
    for (const auto& s : cgal::cgal_delaunay<D>(points)) {
      std::array<const kernel::Point_d<D>*, D + 1> p;
      for (int i = 0; i <= D; ++i) p[static_cast<std::size_t>(i)] = &points[s[static_cast<std::size_t>(i)]];
      sum += abs(simplex_volume_times_factorial<D>(p));
    }
    return sum;
  }
}

template mpq_class hull_volume_times_factorial<2>(const std::vector<kernel::Point_d<2>>&);
template mpq_class hull_volume_times_factorial<3>(const std::vector<kernel::Point_d<3>>&);
template mpq_class hull_volume_times_factorial<4>(const std::vector<kernel::Point_d<4>>&);
template mpq_class hull_volume_times_factorial<5>(const std::vector<kernel::Point_d<5>>&);
template mpq_class hull_volume_times_factorial<6>(const std::vector<kernel::Point_d<6>>&);

}  // namespace dewall::test
