// DeWall over CGAL's kernels: dewall::triangulate with
// Cgal_kernel_adapter<CGAL::Epick, 2/3> and <CGAL::Epick_d<4>, 4> takes CGAL's
// points directly and gives the very simplices (same tuples, same order) it
// gives with our own kernel: an independent check of our predicates inside
// the whole algorithm.
#include <catch2/catch.hpp>

#include <random>

#include "dewall/dewall.hpp"
#include "dewall/kernel/cgal_kernel_adapter.hpp"
#include "support/dewall_point_sets.hpp"

using dewall::kernel::Point_d;

namespace {

template <int D>
using Cgal_kernel = std::conditional_t<D <= 3, CGAL::Epick, CGAL::Epick_d<CGAL::Dimension_tag<D>>>;
template <int D>
using Adapter = dewall::kernel::Cgal_kernel_adapter<Cgal_kernel<D>, D>;

template <int D>
void check_same_output(const std::vector<Point_d<D>>& input) {
  INFO("D = " << D << ", n = " << input.size());
  std::vector<typename Adapter<D>::Point_d> points;
  for (const auto& p : input) {
    if constexpr (D == 2) points.emplace_back(p[0], p[1]);
    else if constexpr (D == 3) points.emplace_back(p[0], p[1], p[2]);
    else points.emplace_back(p.x.begin(), p.x.end());
  }
  const auto theirs = dewall::triangulate<Adapter<D>>(std::span<const typename Adapter<D>::Point_d>(points));
  // DeWall over both kernels (with another kernel the default engine is DeWall).
  const auto ours = dewall::triangulate<D>(input, dewall::Options{.engine = dewall::Engine::dewall});
  CHECK(theirs.simplices == ours.simplices);
  CHECK(theirs.statistics.distinct_points == ours.statistics.distinct_points);
}

template <int D>
void check_families(std::size_t n, std::uint64_t seed) {
  namespace t = dewall::test;
  std::mt19937_64 rng(seed);
  INFO("seed = " << seed);
  SECTION("uniform random") { check_same_output<D>(t::uniform<D>(n, rng)); }
  SECTION("integer lattice") { check_same_output<D>(t::lattice<D>(n)); }
  SECTION("lattice with duplicates") { check_same_output<D>(t::lattice_samples<D>(n, 3, rng)); }
  SECTION("cospherical and centre") { check_same_output<D>(t::cospherical<D>(true)); }
  SECTION("parallel planes") { check_same_output<D>(t::planes<D>(n, 3, rng)); }
}

}  // namespace

TEST_CASE("dewall::triangulate over Cgal_kernel_adapter<Epick, 2> equals our kernel", "[cgal][adapter][2d]") {
  check_families<2>(400, 20260511);
}
TEST_CASE("dewall::triangulate over Cgal_kernel_adapter<Epick, 3> equals our kernel", "[cgal][adapter][3d]") {
  check_families<3>(300, 20260512);
}
TEST_CASE("dewall::triangulate over Cgal_kernel_adapter<Epick_d<4>, 4> equals our kernel", "[cgal][adapter][4d]") {
  check_families<4>(100, 20260513);
}
