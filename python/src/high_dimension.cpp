// The dimension known at run time, by CGAL's dD code (high_dimension.hpp says
// why). One translation unit: CGAL's dD templates are compiled here once.
//
// 1. triangulate: duplicates removed first (a lexicographic sort of the input
//    indices, stable, so each run of equal points starts with its first
//    occurrence), the distinct points inserted into CGAL's
//    Delaunay_triangulation (it sorts them along a space-filling curve), then
//    each finite full cell written out with its vertices' input indices (found
//    by binary search in the sorted run heads: CGAL stores the doubles given),
//    swapped to positive orientation where needed, and its neighbours. In 7
//    and 8 dimensions over Epick_d of that static dimension (faster), else of
//    the dynamic one.
// 2. predicate_signs: CGAL's filtered exact Orientation_d and
//    Side_of_oriented_sphere_d; the perturbed sphere test is written out here
//    from its definition (below), so the tests can hold it against the
//    library's kernel in 2 … 6 dimensions and against CGAL's triangulation in
//    7 and up.
// 3. locate: a visibility walk (Devillers, Pion, Teillaud, "Walking in a
//    triangulation", 2002): from the current simplex, cross a facet whose
//    hyperplane separates it from the query, until none does. It ends in a
//    Delaunay triangulation (the simplices crossed descend in the lifted
//    order); a bound on the steps and a scan of all simplices guard the rest.
#include "high_dimension.hpp"

#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Epick_d.h>
#include <CGAL/spatial_sort.h>
#include <boost/iterator/indirect_iterator.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <unordered_map>

#include "dewall/error.hpp"

namespace dewall_python::high_dimension {
namespace {

using K = CGAL::Epick_d<CGAL::Dynamic_dimension_tag>;
using Point = K::Point_d;

std::vector<Point> as_points(const double* x, std::size_t n, int d) {
  std::vector<Point> p;
  p.reserve(n);
  for (std::size_t i = 0; i < n; ++i) p.emplace_back(x + i * d, x + (i + 1) * d);
  return p;
}

/// Lexicographic order of two rows of d doubles (−0 equals 0, as CGAL's and the library's comparison).
bool row_less(const double* a, const double* b, int d) {
  return std::lexicographical_compare(a, a + d, b, b + d);
}

/// The positive sign of the sphere test (+1: inside) from CGAL's oriented side.
std::int8_t sign_of(CGAL::Oriented_side s) { return static_cast<std::int8_t>(s); }

/// side_of_oriented_sphere under CGAL's symbolic perturbation, for a positively
/// oriented simplex s (d + 1 points) and a query q that is not one of them.
///
/// The perturbation lifts point p to |p|² + ε^(rank of p), the lexicographically
/// larger points by the larger powers of ε (CGAL's Compare_points_for_perturbation
/// order in Delaunay_triangulation::perturbed_side_of_positive_sphere). When the
/// unperturbed determinant is zero, the sign is that of the first non-zero ε
/// term, taken from the largest point down. Expanding the lifted (d+2)×(d+2)
/// determinant along the lifted column, the term of a vertex s_i is the
/// orientation of s with s_i replaced by q (with the sign that makes it the
/// side "inside" for +), and the term of q itself is the orientation of s,
/// positive, which the expansion turns into "outside". Orientations of
/// replaced simplices may be zero (q in the hyperplane of a facet): then the
/// next point down decides; q is reached at the latest, so the loop ends.
std::int8_t perturbed_side(const K& k, const std::vector<const Point*>& s, const Point& q) {
  const auto side = k.side_of_oriented_sphere_d_object()(
      boost::make_indirect_iterator(s.begin()), boost::make_indirect_iterator(s.end()), q);
  if (side != CGAL::ON_ORIENTED_BOUNDARY) return sign_of(side);
  const auto compare = k.compare_lexicographically_d_object();
  std::vector<std::size_t> order(s.size() + 1);  // s.size() stands for q
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto at = [&](std::size_t i) -> const Point& { return i == s.size() ? q : *s[i]; };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return compare(at(a), at(b)) == CGAL::SMALLER; });
  const auto orientation = k.orientation_d_object();
  std::vector<const Point*> replaced(s);
  for (auto i = order.rbegin(); i != order.rend(); ++i) {
    if (*i == s.size()) return -1;  // q is the largest left: outside
    replaced[*i] = &q;
    const CGAL::Orientation o = orientation(boost::make_indirect_iterator(replaced.begin()),
                                            boost::make_indirect_iterator(replaced.end()));
    replaced[*i] = s[*i];
    if (o != CGAL::ZERO) return static_cast<std::int8_t>(o);
  }
  return -1;  // not reached: q is in `order`
}

/// triangulate() over the kernel Kd: Epick_d of a static dimension (7 and 8, scipy's
/// tests reach 8: its points and predicates allocate nothing, 1.65× faster on 200 points in
/// 7-D) or of the dynamic one (every other dimension).
template <class Kd>
Cells triangulate_with(const double* x, std::size_t n, int d, const std::function<void(double)>& progress) {
  using Kd_point = typename Kd::Point_d;
  using Triangulation = CGAL::Delaunay_triangulation<Kd>;
  for (std::size_t i = 0; i < n; ++i)
    for (int j = 0; j < d; ++j)
      if (!std::isfinite(x[i * d + j])) throw dewall::Invalid_input(i, "has a non-finite coordinate (NaN or infinity)");
  // 1. distinct points: heads of the runs of equal rows, in lexicographic order
  std::vector<std::uint32_t> sorted(n);
  std::iota(sorted.begin(), sorted.end(), 0u);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return row_less(x + a * std::size_t(d), x + b * std::size_t(d), d); });
  std::vector<std::uint32_t> heads;
  for (std::size_t r = 0; r < n; ++r)
    if (r == 0 || row_less(x + sorted[r - 1] * std::size_t(d), x + sorted[r] * std::size_t(d), d))
      heads.push_back(sorted[r]);
  if (heads.size() < static_cast<std::size_t>(d) + 1)
    throw dewall::Invalid_input("need at least " + std::to_string(d + 1) + " distinct points in dimension " +
                                std::to_string(d) + ", got " + std::to_string(heads.size()));
  std::vector<Kd_point> points;
  points.reserve(heads.size());
  for (const std::uint32_t h : heads) points.emplace_back(x + h * std::size_t(d), x + (h + 1) * std::size_t(d));

  // As CGAL's insert(begin, end): a spatial sort, then each point from the
  // cell of the last; here with a report every few points (7-D and up: each
  // insertion touches hundreds of cells).
  Triangulation dt(d);
  CGAL::spatial_sort(points.begin(), points.end(), dt.geom_traits());
  typename Triangulation::Full_cell_handle hint;
  for (std::size_t i = 0; i < points.size(); ++i) {
    hint = dt.insert(points[i], hint)->full_cell();
    if (i % 64 == 63) progress(static_cast<double>(i + 1) / static_cast<double>(points.size()));
  }
  if (dt.current_dimension() < d)
    throw dewall::Invalid_input("the points do not span E^" + std::to_string(d) + ": all " +
                                std::to_string(heads.size()) + " distinct points are in one " +
                                std::to_string(dt.current_dimension()) + "-flat (affine dimension " +
                                std::to_string(dt.current_dimension()) + ")");

  // 2. the finite full cells, numbered; input indices of their vertices
  const auto index_of = [&](const Kd_point& p) {
    std::vector<double> c(p.cartesian_begin(), p.cartesian_end());
    const auto it = std::lower_bound(heads.begin(), heads.end(), c.data(), [&](std::uint32_t h, const double* v) {
      return row_less(x + h * std::size_t(d), v, d);
    });
    return static_cast<std::int32_t>(*it);  // present: CGAL keeps the doubles it was given
  };
  std::unordered_map<const void*, std::int32_t> number;
  Cells cells;
  for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c)
    number.emplace(&*c, static_cast<std::int32_t>(cells.count++));
  const std::size_t width = static_cast<std::size_t>(d) + 1;
  cells.simplices.resize(cells.count * width);
  cells.neighbors.resize(cells.count * width);
  const auto orientation = dt.geom_traits().orientation_d_object();
  std::vector<const Kd_point*> corners(width);
  for (auto c = dt.finite_full_cells_begin(); c != dt.finite_full_cells_end(); ++c) {
    const std::size_t i = static_cast<std::size_t>(number.at(&*c));
    std::int32_t* row = &cells.simplices[i * width];
    std::int32_t* next = &cells.neighbors[i * width];
    for (std::size_t j = 0; j < width; ++j) {
      corners[j] = &c->vertex(static_cast<int>(j))->point();
      row[j] = index_of(*corners[j]);
      const auto neighbor = c->neighbor(static_cast<int>(j));
      next[j] = dt.is_infinite(neighbor) ? -1 : number.at(&*neighbor);
    }
    if (orientation(boost::make_indirect_iterator(corners.begin()), boost::make_indirect_iterator(corners.end())) ==
        CGAL::NEGATIVE) {
      std::swap(row[0], row[1]);
      std::swap(next[0], next[1]);
    }
  }
  return cells;
}

}  // namespace

Cells triangulate(const double* x, std::size_t n, int d, const std::function<void(double)>& progress) {
  if (d == 7) return triangulate_with<CGAL::Epick_d<CGAL::Dimension_tag<7>>>(x, n, d, progress);
  if (d == 8) return triangulate_with<CGAL::Epick_d<CGAL::Dimension_tag<8>>>(x, n, d, progress);
  return triangulate_with<K>(x, n, d, progress);
}

void predicate_signs(const double* x, std::size_t n, int d, const std::uint32_t* rows, std::size_t count, int kind,
                     std::int8_t* out) {
  const K k;
  const std::vector<Point> p = as_points(x, n, d);
  const std::size_t width = static_cast<std::size_t>(d) + (kind == 0 ? 1 : 2);
  std::vector<const Point*> s(static_cast<std::size_t>(d) + 1);
  const auto orientation = k.orientation_d_object();
  const auto sphere = k.side_of_oriented_sphere_d_object();
  for (std::size_t r = 0; r < count; ++r) {
    const std::uint32_t* row = rows + r * width;
    for (std::size_t j = 0; j < s.size(); ++j) s[j] = &p[row[j]];
    const auto first = boost::make_indirect_iterator(s.begin());
    const auto last = boost::make_indirect_iterator(s.end());
    if (kind == 0)
      out[r] = static_cast<std::int8_t>(orientation(first, last));
    else if (kind == 1)
      out[r] = sign_of(sphere(first, last, p[row[d + 1]]));
    else
      out[r] = perturbed_side(k, s, p[row[d + 1]]);
  }
}

void locate(const double* x, std::size_t n, int d, const std::int32_t* simplices, const std::int32_t* neighbors,
            std::size_t count, const double* queries, std::size_t query_count, std::int32_t* out) {
  const K k;
  const auto orientation = k.orientation_d_object();
  const std::vector<Point> p = as_points(x, n, d);
  const std::size_t width = static_cast<std::size_t>(d) + 1;
  std::vector<const Point*> s(width);
  // The sign of simplex i with vertex j replaced by q (j = width: none replaced).
  const auto side = [&](std::size_t i, std::size_t j, const Point& q) {
    for (std::size_t v = 0; v < width; ++v) s[v] = v == j ? &q : &p[static_cast<std::size_t>(simplices[i * width + v])];
    return orientation(boost::make_indirect_iterator(s.begin()), boost::make_indirect_iterator(s.end()));
  };
  const auto contains = [&](std::size_t i, const Point& q) {
    for (std::size_t j = 0; j < width; ++j)
      if (side(i, j, q) == CGAL::NEGATIVE) return false;
    return true;
  };
  std::size_t current = 0;
  for (std::size_t t = 0; t < query_count; ++t) {
    out[t] = -1;
    if (count == 0) continue;
    const double* qx = queries + t * static_cast<std::size_t>(d);
    if (!std::all_of(qx, qx + d, [](double v) { return std::isfinite(v); })) continue;
    const Point q(qx, qx + d);
    std::int64_t found = -2;  // −2: not decided by the walk
    const std::size_t step_limit = 4 * count + 64;
    for (std::size_t step = 0; step < step_limit && found == -2; ++step) {
      std::size_t crossed = width;
      // facets tried from a rotating start, so that a walk cannot cycle on a fixed choice
      for (std::size_t m = 0; m < width && crossed == width; ++m) {
        const std::size_t j = (m + step) % width;
        if (side(current, j, q) == CGAL::NEGATIVE) crossed = j;
      }
      if (crossed == width) {
        found = static_cast<std::int64_t>(current);
      } else {
        const std::int32_t next = neighbors[current * width + crossed];
        // a hull facet separating q from the hull's inside: q is outside the (convex) hull
        if (next < 0) found = -1;
        else current = static_cast<std::size_t>(next);
      }
    }
    if (found == -2)
      for (std::size_t i = 0; i < count && found == -2; ++i)
        if (contains(i, q)) found = static_cast<std::int64_t>(i);
    out[t] = static_cast<std::int32_t>(found == -2 ? -1 : found);
  }
}

}  // namespace dewall_python::high_dimension
