// Cgal_kernel_adapter (CGAL's predicates) and Filtered_kernel_d (ours) give the
// same answers on every input family of tests/support/point_generators.hpp:
// orientation, the perturbed sphere test, the lexicographic order and the
// approximate coordinates. D = 2, 3 over CGAL::Epick, D = 4, 5 over
// CGAL::Epick_d. The adapter includes CGAL's dD kernel, which needs Eigen3 on
// the include path (CMake: CGAL::Eigen3_support); without it this file only
// says so.
#include <catch2/catch.hpp>

#if __has_include(<Eigen/Jacobi>)  // CGAL's own test for Eigen (CGAL/config.h)

#include <algorithm>
#include <array>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "dewall/kernel/cgal_kernel_adapter.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"
#include "support/point_generators.hpp"

namespace {

using namespace dewall::kernel;
using dewall::test::Rng;
template <int D>
using Point = dewall::test::Point<D>;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

template <int D>
using Cgal_kernel = std::conditional_t<(D <= 3), Epick, CGAL::Epick_d<CGAL::Dimension_tag<D>>>;
template <int D>
using Adapter = Cgal_kernel_adapter<Cgal_kernel<D>, D>;

static_assert(DelaunayKernel<Adapter<2>>);
static_assert(DelaunayKernel<Adapter<3>>);
static_assert(DelaunayKernel<Adapter<4>>);
static_assert(DelaunayKernel<Adapter<5>>);

constexpr int cases_per_family = 200;  // × 44 families × 4 dimensions

template <int D>
typename Adapter<D>::Point_d to_cgal(const Point<D>& p) {
  if constexpr (D == 2) return Epick::Point_2(p[0], p[1]);
  else if constexpr (D == 3) return Epick::Point_3(p[0], p[1], p[2]);
  else return typename Adapter<D>::Point_d(p.x.begin(), p.x.end());
}

/// Both kernels on the same points, given by index into `ours` / `theirs`.
template <int D>
struct Both {
  std::vector<Point<D>> ours;
  std::vector<typename Adapter<D>::Point_d> theirs;

  template <std::size_t N>
  std::pair<std::array<const Point<D>*, N>, std::array<const typename Adapter<D>::Point_d*, N>> refs(
      const std::array<int, N>& index) const {
    std::pair<std::array<const Point<D>*, N>, std::array<const typename Adapter<D>::Point_d*, N>> r;
    for (std::size_t i = 0; i < N; ++i) {
      r.first[i] = &ours[static_cast<std::size_t>(index[i])];
      r.second[i] = &theirs[static_cast<std::size_t>(index[i])];
    }
    return r;
  }
};

struct Tally {
  int orientation_cases = 0, sphere_cases = 0, mismatches = 0;
  std::string report;
  template <int D>
  void check(const char* what, int ours, int theirs, const std::vector<Point<D>>& points) {
    if (ours == theirs) return;
    if (++mismatches <= 3) {
      std::ostringstream out;
      out << what << ": Filtered_kernel_d " << ours << ", CGAL adapter " << theirs << " on\n"
          << dewall::test::format_points<D>(points);
      report += out.str();
    }
  }
};

template <int D>
void check_case(const std::vector<Point<D>>& points, Tally& tally) {
  const Filtered_kernel_d<D> ours;
  const Adapter<D> theirs;
  Both<D> both{points, {}};
  for (const auto& p : points) both.theirs.push_back(to_cgal<D>(p));

  // Orientation of two (D+1)-subsets: the first D+1 points and the last D+1.
  std::array<int, D + 1> simplex;
  for (int shift = 0; shift <= 1; ++shift) {
    for (int i = 0; i <= D; ++i) simplex[static_cast<std::size_t>(i)] = i + shift;
    const auto [o, t] = both.refs(simplex);
    tally.check<D>("orientation", ours.orientation_d_object()(o), theirs.orientation_d_object()(t), points);
    ++tally.orientation_cases;
  }
  // The lexicographic order and the coordinates, on every pair.
  for (std::size_t a = 0; a < points.size(); ++a)
    for (std::size_t b = 0; b < points.size(); ++b)
      tally.check<D>("compare_lexicographically",
                     ours.compare_lexicographically_d_object()(both.ours[a], both.ours[b]),
                     theirs.compare_lexicographically_d_object()(both.theirs[a], both.theirs[b]), points);
  for (std::size_t a = 0; a < points.size(); ++a)
    tally.check<D>("approximate coordinates", 1,
                   ours.approximate_coordinates_object()(both.ours[a]) ==
                       theirs.approximate_coordinates_object()(both.theirs[a]),
                   points);

  // The perturbed sphere test, under its preconditions: a positively oriented
  // simplex (swap two vertices if negative), a query that is not a vertex.
  for (int i = 0; i <= D; ++i) simplex[static_cast<std::size_t>(i)] = i;
  const Sign orientation = orientation_d<D>(both.refs(simplex).first);
  const auto q = points.back();
  if (orientation == ZERO || std::find(points.begin(), points.end() - 1, q) != points.end() - 1) return;
  std::array<int, D + 2> with_query;
  for (int i = 0; i <= D + 1; ++i) with_query[static_cast<std::size_t>(i)] = i;
  if (orientation == NEGATIVE) std::swap(with_query[0], with_query[1]);
  const auto [o, t] = both.refs(with_query);
  tally.check<D>("perturbed side_of_oriented_sphere", ours.side_of_oriented_sphere_d_object()(o),
                 theirs.side_of_oriented_sphere_d_object()(t), points);
  ++tally.sphere_cases;
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("Cgal_kernel_adapter and Filtered_kernel_d agree", "[cgal][adapter]", ((int D), D), 2, 3, 4,
                       5) {
  const auto seed = dewall::test::test_seed(0xada + D);
  INFO("seed " << seed << " (set DEWALL_TEST_SEED to reproduce)");
  const auto families = dewall::test::point_set_families<D>();
  int sphere_cases = 0;
  for (std::size_t f = 0; f < families.size(); ++f) {
    Rng rng(seed + f);
    Tally tally;
    for (int c = 0; c < cases_per_family; ++c) check_case<D>(families[f].make(rng, D + 2), tally);
    INFO("family \"" << families[f].name << "\" (index " << f << "): " << tally.orientation_cases
                     << " orientation and " << tally.sphere_cases << " sphere cases\n"
                     << tally.report);
    CHECK(tally.mismatches == 0);
    sphere_cases += tally.sphere_cases;
  }
  CHECK(sphere_cases > cases_per_family * static_cast<int>(families.size()) / 2);
}

#else

TEST_CASE("Cgal_kernel_adapter and Filtered_kernel_d agree", "[cgal][adapter]") {
  WARN("Eigen3 is not on the include path: the CGAL adapter (which includes CGAL/Epick_d.h) is not tested");
}

#endif
