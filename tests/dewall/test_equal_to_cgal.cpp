// dewall's triangulation equals CGAL's, as sets of index tuples, on random and
// degenerate inputs, also after shuffling (the output is a function of the set).
#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <random>

#include "dewall/dewall.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/point_array.hpp"
#include "support/dewall_point_sets.hpp"
#include "support/cgal_reference.hpp"

using namespace dewall;
using dewall::kernel::Point_d;

namespace {

/// Triangulates `points` and a shuffled copy; both must equal CGAL.
template <int D>
void check_equal_to_cgal(const std::vector<Point_d<D>>& points, std::uint64_t seed) {
  INFO("D = " << D << ", n = " << points.size() << ", seed = " << seed);
  const auto expected = test::cgal_delaunay<D>(points);
  const auto ours = dewall::triangulate<D>(points, dewall::Options{.engine = dewall::Engine::dewall});
  CHECK(ours.simplices.size() == expected.size());  // each simplex emitted once
  CHECK(test::as_set<D>(ours.simplices) == expected);

  // Shuffled: map back to the original indices through the first occurrence.
  std::mt19937_64 rng(seed);
  std::vector<std::size_t> perm(points.size());
  std::iota(perm.begin(), perm.end(), std::size_t{0});
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<Point_d<D>> shuffled(points.size());
  for (std::size_t i = 0; i < perm.size(); ++i) shuffled[i] = points[perm[i]];
  const auto again = dewall::triangulate<D>(shuffled, dewall::Options{.engine = dewall::Engine::dewall});
  const auto expected_shuffled = test::cgal_delaunay<D>(shuffled);
  CHECK(test::as_set<D>(again.simplices) == expected_shuffled);
}

template <int D>
std::vector<Point_d<D>> generated(io::Point_kind kind, std::size_t n, std::uint64_t seed) {
  return kernel::points_from_coordinates<D>(io::generate_points(kind, n, D, seed).coordinates);
}

template <int D>
void check_families(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  // The distributions the kd-tree adapts to: clusters, a surface, thin layers.
  SECTION("clusters (bubbles)") { check_equal_to_cgal<D>(generated<D>(io::Point_kind::bubbles, n, seed), seed); }
  SECTION("on the unit sphere") { check_equal_to_cgal<D>(generated<D>(io::Point_kind::sphere, n, seed), seed); }
  if constexpr (D == 3)
    SECTION("on a torus") { check_equal_to_cgal<D>(generated<D>(io::Point_kind::torus, 4 * n, seed), seed); }
  SECTION("uniform random") { check_equal_to_cgal<D>(test::uniform<D>(n, rng), seed); }
  SECTION("integer lattice") { check_equal_to_cgal<D>(test::lattice<D>(n), seed); }
  SECTION("lattice with duplicates, random order") { check_equal_to_cgal<D>(test::lattice_samples<D>(n, 3, rng), seed); }
  SECTION("cospherical integer points") { check_equal_to_cgal<D>(test::cospherical<D>(false), seed); }
  SECTION("cospherical integer points and the centre") { check_equal_to_cgal<D>(test::cospherical<D>(true), seed); }
  SECTION("points on a few parallel planes") { check_equal_to_cgal<D>(test::planes<D>(n, 3, rng), seed); }
  SECTION("tiny scale 2^-500") { check_equal_to_cgal<D>(test::scaled<D>(test::lattice_samples<D>(n, 3, rng), 0x1p-500, 0), seed); }
  SECTION("huge scale 2^400") { check_equal_to_cgal<D>(test::scaled<D>(test::uniform<D>(n, rng), 0x1p400, 0), seed); }
  SECTION("large offset 2^30") { check_equal_to_cgal<D>(test::scaled<D>(test::lattice_samples<D>(n, 3, rng), 1, 0x1p30), seed); }
  SECTION("large offset 2^52 with tiny differences") {
    check_equal_to_cgal<D>(test::scaled<D>(test::lattice_samples<D>(n, 3, rng), 1, 0x1p52), seed);
  }
}

}  // namespace

TEST_CASE("dewall equals CGAL in 2D", "[cgal][2d]") { check_families<2>(300, 20261121); }
TEST_CASE("dewall equals CGAL in 3D", "[cgal][3d]") { check_families<3>(250, 20261122); }
TEST_CASE("dewall equals CGAL in 4D", "[cgal][4d]") { check_families<4>(90, 20261123); }
TEST_CASE("dewall equals CGAL in 5D", "[cgal][5d]") { check_families<5>(40, 20261124); }
