// side_of_oriented_sphere_d_sos against CGAL's own perturbed predicates, on
// degenerate inputs (lattices, cube vertices, cospherical integer points, also
// scaled and shifted), and the properties the perturbation must have:
//  * never ON_ORIENTED_BOUNDARY;
//  * a function of the point set: every even permutation of a positively
//    oriented simplex gives the same answer.
// CGAL's versions:
//  2D  Triangulation_2::side_of_oriented_circle(p0, p1, p2, p, true)    (public)
//  3D  Delaunay_triangulation_3::side_of_oriented_sphere(…, p, true)    (protected)
//  dD  Delaunay_triangulation::perturbed_side_of_positive_sphere(p, cell, ori),
//      on the single finite full cell of a triangulation of the simplex, which
//      CGAL keeps positively oriented. CGAL's dD kernel needs Eigen3 on the
//      include path (CMake: CGAL::Eigen3_support); without it these comparisons
//      are compiled out and the test says so.
#include <catch2/catch.hpp>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#if __has_include(<Eigen/Jacobi>)  // CGAL's own test for Eigen (CGAL/config.h)
#define DEWALL_TEST_HAVE_EPICK_D 1
#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Epick_d.h>
#else
#define DEWALL_TEST_HAVE_EPICK_D 0
#endif

#include <algorithm>
#include <array>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "support/gmp_reference.hpp"
#include "support/point_generators.hpp"

namespace {

using namespace dewall::kernel;
using dewall::test::Rng;
template <int D>
using Point = dewall::test::Point<D>;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr int cases_per_family = 60;  // × 44 families × 5 dimensions
constexpr int sampled_even_permutations = 12;  // D ≥ 4: (D+1)!/2 is too many to try all

// CGAL's protected 3D predicate, made reachable.
struct Delaunay_3 : CGAL::Delaunay_triangulation_3<Epick> {
  using CGAL::Delaunay_triangulation_3<Epick>::side_of_oriented_sphere;
};

#if DEWALL_TEST_HAVE_EPICK_D
template <int D>
using Epick_d = CGAL::Epick_d<CGAL::Dimension_tag<D>>;

template <int D>
typename Epick_d<D>::Point_d to_cgal_d(const Point<D>& p) {
  return typename Epick_d<D>::Point_d(p.x.begin(), p.x.end());
}
template <int D>
Point<D> from_cgal_d(const typename Epick_d<D>::Point_d& p) {
  Point<D> r;
  for (int j = 0; j < D; ++j) r[j] = CGAL::to_double(p[j]);
  return r;
}
#endif

template <int D>
Oriented_side ours(const std::vector<Point<D>>& simplex, const Point<D>& q) {
  Sphere_points<D> refs;
  for (int i = 0; i <= D; ++i) refs[static_cast<std::size_t>(i)] = &simplex[static_cast<std::size_t>(i)];
  refs[D + 1] = &q;
  return side_of_oriented_sphere_d_sos<D>(refs);
}

/// CGAL's 2D or 3D perturbed test of q against the simplex (in its order).
template <int D>
Oriented_side cgal_2_3(const std::vector<Point<D>>& s, const Point<D>& q) {
  if constexpr (D == 2) {
    static const CGAL::Delaunay_triangulation_2<Epick> t;
    auto P = [](const Point<2>& p) { return Epick::Point_2(p[0], p[1]); };
    return static_cast<Oriented_side>(t.side_of_oriented_circle(P(s[0]), P(s[1]), P(s[2]), P(q), true));
  } else {
    static const Delaunay_3 t;
    auto P = [](const Point<3>& p) { return Epick::Point_3(p[0], p[1], p[2]); };
    return static_cast<Oriented_side>(t.side_of_oriented_sphere(P(s[0]), P(s[1]), P(s[2]), P(s[3]), P(q), true));
  }
}

#if DEWALL_TEST_HAVE_EPICK_D
/// CGAL's dD perturbed test: triangulates the simplex and asks about its one
/// finite full cell. `cell_order` receives the cell's vertices in CGAL's
/// (positively oriented) order.
template <int D>
Oriented_side cgal_d(const std::vector<Point<D>>& simplex, const Point<D>& q, std::vector<Point<D>>& cell_order) {
  using Triangulation = CGAL::Delaunay_triangulation<Epick_d<D>>;
  Triangulation t(D);
  std::vector<typename Epick_d<D>::Point_d> points;
  for (const auto& p : simplex) points.push_back(to_cgal_d<D>(p));
  t.insert(points.begin(), points.end());
  REQUIRE(t.current_dimension() == D);
  REQUIRE(t.number_of_finite_full_cells() == 1);
  const typename Triangulation::Full_cell_const_handle cell = std::as_const(t).finite_full_cells_begin().base();
  cell_order.clear();
  for (int i = 0; i <= D; ++i) cell_order.push_back(from_cgal_d<D>(cell->vertex(i)->point()));
  // As CGAL's Conflict_predicate does: perturb only when the plain test is zero.
  const auto cgal_q = to_cgal_d<D>(q);
  const auto side = t.geom_traits().side_of_oriented_sphere_d_object()(t.points_begin(cell),
                                                                       t.points_begin(cell) + D + 1, cgal_q);
  if (side != CGAL::ON_ORIENTED_BOUNDARY) return static_cast<Oriented_side>(side);
  return static_cast<Oriented_side>(
      t.perturbed_side_of_positive_sphere(cgal_q, cell, t.geom_traits().orientation_d_object()));
}
#endif

/// Every even permutation of 0..n−1 when there are few, else `sampled` random ones.
std::vector<std::vector<int>> even_permutations(Rng& rng, int n, int sampled) {
  std::vector<int> perm(static_cast<std::size_t>(n));
  std::iota(perm.begin(), perm.end(), 0);
  auto is_even = [](const std::vector<int>& p) {
    int inversions = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = i + 1; j < p.size(); ++j) inversions += p[i] > p[j];
    return inversions % 2 == 0;
  };
  std::vector<std::vector<int>> out;
  if (n <= 4) {
    do {
      if (is_even(perm)) out.push_back(perm);
    } while (std::next_permutation(perm.begin(), perm.end()));
  } else {
    for (int k = 0; k < sampled; ++k) {
      std::shuffle(perm.begin(), perm.end(), rng);
      if (!is_even(perm)) std::swap(perm[0], perm[1]);
      out.push_back(perm);
    }
  }
  return out;
}

struct Tally {
  int cases = 0, degenerate = 0, skipped = 0, mismatches = 0;
  std::string report;
  template <int D>
  void check(const char* what, int expected, int got, const std::vector<Point<D>>& simplex, const Point<D>& q) {
    if (expected == got) return;
    if (++mismatches <= 3) {
      std::ostringstream out;
      std::vector<Point<D>> all = simplex;
      all.push_back(q);
      out << what << ": expected " << expected << ", got " << got << " on (simplex, then q)\n"
          << dewall::test::format_points<D>(all);
      report += out.str();
    }
  }
};

template <int D>
void check_case(Rng& rng, std::vector<Point<D>> simplex, const Point<D>& q, Tally& tally) {
  // The predicate's preconditions: a positively oriented simplex, q not a vertex.
  std::array<Point<D>, D + 1> s;
  std::copy(simplex.begin(), simplex.end(), s.begin());
  const Sign orientation = dewall::test::gmp_orientation<D>(s);
  if (orientation == ZERO || std::find(simplex.begin(), simplex.end(), q) != simplex.end()) {
    ++tally.skipped;
    return;
  }
  if (orientation == NEGATIVE) std::swap(simplex[0], simplex[1]);
  ++tally.cases;
  std::copy(simplex.begin(), simplex.end(), s.begin());
  if (dewall::test::gmp_side_of_oriented_sphere<D>(s, q) == ON_ORIENTED_BOUNDARY) ++tally.degenerate;

  const Oriented_side answer = ours<D>(simplex, q);
  tally.check<D>("never ON_ORIENTED_BOUNDARY", 1, answer != ON_ORIENTED_BOUNDARY, simplex, q);
  if constexpr (D <= 3) tally.check<D>("CGAL 2D/3D perturbed", cgal_2_3<D>(simplex, q), answer, simplex, q);

#if DEWALL_TEST_HAVE_EPICK_D
  std::vector<Point<D>> cell_order;
  tally.check<D>("CGAL dD perturbed", cgal_d<D>(simplex, q, cell_order), answer, simplex, q);
  tally.check<D>("ours in CGAL's cell order", answer, ours<D>(cell_order, q), simplex, q);
#endif

  std::vector<Point<D>> permuted(simplex.size());
  for (const auto& perm : even_permutations(rng, D + 1, sampled_even_permutations)) {
    for (int i = 0; i <= D; ++i)
      permuted[static_cast<std::size_t>(i)] = simplex[static_cast<std::size_t>(perm[static_cast<std::size_t>(i)])];
    tally.check<D>("even permutation of the simplex", answer, ours<D>(permuted, q), simplex, q);
  }
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("side_of_oriented_sphere_d_sos equals CGAL's perturbed predicates", "[sos][cgal]",
                       ((int D), D), 2, 3, 4, 5, 6) {
  if (!DEWALL_TEST_HAVE_EPICK_D)
    WARN("Eigen3 is not on the include path: CGAL's dD perturbed predicate (Epick_d) is not compared");
  const auto seed = dewall::test::test_seed(0x505 + D);
  INFO("seed " << seed << " (set DEWALL_TEST_SEED to reproduce)");
  const auto families = dewall::test::point_set_families<D>();
  int cases = 0, degenerate = 0;
  for (std::size_t f = 0; f < families.size(); ++f) {
    Rng rng(seed + f);
    Tally tally;
    for (int c = 0; c < cases_per_family; ++c) {
      auto points = families[f].make(rng, D + 2);
      const Point<D> q = points.back();
      points.pop_back();
      check_case<D>(rng, points, q, tally);
    }
    INFO("family \"" << families[f].name << "\" (index " << f << "): " << tally.cases << " cases, "
                     << tally.degenerate << " cospherical, " << tally.skipped << " skipped\n"
                     << tally.report);
    CHECK(tally.mismatches == 0);
    cases += tally.cases;
    degenerate += tally.degenerate;
  }
  // Enough cases exercise the perturbation itself.
  INFO(cases << " cases, " << degenerate << " cospherical");
  CHECK(degenerate > cases / 5);
}

TEMPLATE_TEST_CASE_SIG("side_of_oriented_sphere_d_sos on small grids", "[sos][cgal]", ((int D), D), 2, 3) {
  // Every positively oriented triangle of the 4×4 grid against every other grid
  // point (2D), and a sample of the 3×3×3 grid (3D): the densest ties there are.
  const auto seed = dewall::test::test_seed(0x9e1d + D);
  INFO("seed " << seed);
  Rng rng(seed);
  const auto grid = dewall::test::grid_points<D>(D == 2 ? 4 : 3);
  Tally tally;
  const int samples = D == 2 ? 0 : 4000;
  if constexpr (D == 2) {
    for (std::size_t a = 0; a < grid.size(); ++a)
      for (std::size_t b = a + 1; b < grid.size(); ++b)
        for (std::size_t c = b + 1; c < grid.size(); ++c)
          for (const auto& q : grid) check_case<D>(rng, {grid[a], grid[b], grid[c]}, q, tally);
  }
  for (int k = 0; k < samples; ++k) {
    auto points = dewall::test::random_subset<D>(rng, grid, D + 2);
    const Point<D> q = points.back();
    points.pop_back();
    check_case<D>(rng, points, q, tally);
  }
  INFO(tally.cases << " cases, " << tally.degenerate << " cospherical\n" << tally.report);
  CHECK(tally.mismatches == 0);
  CHECK(tally.degenerate > 100);
}
