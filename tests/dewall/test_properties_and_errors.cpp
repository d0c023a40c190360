// The empty-sphere property checked by brute force with the exact perturbed
// predicate and by the certifier, and bad input through the library (through the
// command line: tests/cli).
#include <catch2/catch.hpp>

#include <limits>
#include <random>
#include <string>

#include "dewall/certify/certify.hpp"
#include "dewall/dewall.hpp"
#include "support/dewall_point_sets.hpp"
#include "support/brute_force_delaunay.hpp"
#include "support/coverage.hpp"
#include "support/cgal_reference.hpp"

using namespace dewall;
using dewall::kernel::Point_d;

namespace {

/// Every simplex positively oriented with an empty perturbed sphere (by brute
/// force over all points, independent of the certifier), the hull covered
/// exactly once (coverage.hpp, also independent of it), and the certifier's
/// verdict: a triangulation of the hull, the canonical one, every distinct
/// point a vertex.
template <int D>
void check_delaunay_properties(const std::vector<Point_d<D>>& points) {
  const auto t = dewall::triangulate<D>(points, dewall::Options{.engine = dewall::Engine::dewall});
  REQUIRE(!t.simplices.empty());
  const auto violation = test::brute_force_violation<D>(points, t.simplices);
  INFO("simplex " << (violation ? violation->first : 0) << ", point " << (violation ? violation->second : 0));
  CHECK(!violation);
  // Coverage, in rational arithmetic: the hull's volume exactly, and each
  // facet in two simplices on its two sides or on the hull.
  CHECK(test::volume_times_factorial<D>(points, t.simplices) == test::hull_volume_times_factorial<D>(points));
  const auto facet_problem = test::facet_violation<D>(points, t.simplices);
  INFO(facet_problem.value_or("facets fine"));
  CHECK(!facet_problem);
  const auto report = certify::certify<kernel::Filtered_kernel_d<D>>(points, t.simplices);
  CHECK(report.delaunay);
  CHECK(report.canonical);
  CHECK(report.distinct_points == test::first_occurrences_by_brute_force<D>(points).size());
}

}  // namespace

TEST_CASE("empty spheres and facet structure", "[properties]") {
  const std::uint64_t seed = 77;
  INFO("seed = " << seed);
  std::mt19937_64 rng(seed);
  check_delaunay_properties<2>(test::uniform<2>(200, rng));
  check_delaunay_properties<2>(test::lattice_samples<2>(200, 6, rng));
  check_delaunay_properties<3>(test::uniform<3>(150, rng));
  check_delaunay_properties<3>(test::lattice_samples<3>(150, 4, rng));
  check_delaunay_properties<4>(test::lattice_samples<4>(60, 3, rng));
  check_delaunay_properties<6>(test::uniform<6>(20, rng));
  // The coverage checks fail where they should: a simplex missing, one twice.
  const auto points = test::uniform<3>(100, rng);
  auto simplices = dewall::triangulate<3>(points).simplices;
  const auto hull = test::hull_volume_times_factorial<3>(points);
  CHECK(test::volume_times_factorial<3>(points, simplices) == hull);
  CHECK(!test::facet_violation<3>(points, simplices));
  const auto missing = simplices.back();
  simplices.pop_back();
  CHECK(test::volume_times_factorial<3>(points, simplices) < hull);
  CHECK(test::facet_violation<3>(points, simplices));  // its neighbours' facets are not on the hull
  simplices.push_back(missing);
  simplices.push_back(missing);
  CHECK(test::facet_violation<3>(points, simplices));
}

TEST_CASE("bad input through the library", "[errors]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  SECTION("NaN names the point") {
    std::vector<Point_d<2>> p{{{0, 0}}, {{1, 0}}, {{0, 1}}, {{nan, 1}}};
    try {
      dewall::triangulate<2>(p);
      FAIL("no exception");
    } catch (const Invalid_input& e) {
      CHECK(e.point_index() == 3);
      CHECK(std::string(e.what()) == "point 3 has a non-finite coordinate (NaN or infinity)");
      CHECK(e.reason() == "has a non-finite coordinate (NaN or infinity)");  // for callers that number points otherwise
    }
  }
  SECTION("infinity") {
    std::vector<Point_d<3>> p{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, inf}}};
    CHECK_THROWS_AS(dewall::triangulate<3>(p), Invalid_input);
  }
  SECTION("too few distinct points (duplicates do not count)") {
    std::vector<Point_d<3>> p{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{1, 0, 0}}, {{0, 0, 0}}};
    CHECK_THROWS_WITH(dewall::triangulate<3>(p), Catch::Contains("at least 4 distinct points"));
  }
  SECTION("collinear in 2D") {
    std::vector<Point_d<2>> p;
    for (int i = 0; i < 50; ++i) p.push_back({{double(i), 2.0 * i + 1}});
    CHECK_THROWS_WITH(dewall::triangulate<2>(p), Catch::Contains("collinear"));
  }
  SECTION("coplanar in 3D") {
    std::vector<Point_d<3>> p;
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j) p.push_back({{double(i), double(j), double(i + j)}});
    CHECK_THROWS_WITH(dewall::triangulate<3>(p), Catch::Contains("coplanar"));
  }
  SECTION("no points") { CHECK_THROWS_AS(dewall::triangulate<2>(std::vector<Point_d<2>>{}), Invalid_input); }
}

TEMPLATE_TEST_CASE_SIG("far from 1: scaling the input by 2^±600 changes nothing, not even the work done", "[dewall][scale]",
                       ((int D), D), 2, 3, 4) {
  // DeWall's own double arithmetic (kd-tree boxes, ball boxes, filters) runs on
  // coordinates scaled exactly to near 1, and the kernel's filter scales too:
  // the same simplices, and the same counters, as the unscaled input. Before,
  // a 4D lattice scaled by 2^600 collapsed the search structure (then a uniform
  // grid) to one cell and every predicate went to the exact stage (minutes
  // instead of milliseconds).
  std::mt19937_64 rng(20261122);
  for (const auto& base : {dewall::test::lattice<D>(D == 4 ? 300 : 500), dewall::test::uniform<D>(400, rng)}) {
    const auto reference = dewall::triangulate<D>(base, dewall::Options{.engine = dewall::Engine::dewall});
    for (const double factor : {0x1p600, 0x1p-600}) {
      auto points = base;
      for (auto& p : points)
        for (int j = 0; j < D; ++j) p[j] *= factor;
      const auto t = dewall::triangulate<D>(points, dewall::Options{.engine = dewall::Engine::dewall});
      CHECK(t.simplices == reference.simplices);
      CHECK(t.statistics.tree_leaves == reference.statistics.tree_leaves);
      CHECK(t.statistics.nodes_visited == reference.statistics.nodes_visited);
      CHECK(t.statistics.candidates_tested == reference.statistics.candidates_tested);
      CHECK(dewall::test::as_set<D>(t.simplices) == dewall::test::cgal_delaunay<D>(points));
    }
  }
}
