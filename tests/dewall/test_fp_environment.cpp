// The caller's floating-point environment cannot change an answer: with
// flush-to-zero and denormals-are-zero on (what linking with -ffast-math or
// -Ofast does to a whole process, through crtfastmath.o) and rounding upward,
// the predicates still give GMP's sign, triangulate still gives CGAL's cells,
// certify still says canonical, and the caller gets its environment back
// (kernel/include/dewall/kernel/floating_point.hpp). The compile-flag side is
// tested through the installed package by the fp_flags_* tests (examples/).
#include <catch2/catch.hpp>

#include <array>
#include <cfenv>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "dewall/certify/certify.hpp"
#include "dewall/detail/incremental/brio_order.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "dewall/kernel/static_filter.hpp"
#include "support/cgal_reference.hpp"
#include "support/gmp_reference.hpp"

#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace {

using dewall::kernel::Point_d;

/// Sets FTZ and DAZ (x86-64) and upward rounding for its lifetime.
class Hostile_environment {
 public:
  Hostile_environment() {
#if defined(__x86_64__)
    saved_csr_ = _mm_getcsr();
    _mm_setcsr(saved_csr_ | 0x8040u);  // FTZ (bit 15) and DAZ (bit 6)
#endif
    saved_rounding_ = std::fegetround();
    std::fesetround(FE_UPWARD);
  }
  ~Hostile_environment() {
    std::fesetround(saved_rounding_);
#if defined(__x86_64__)
    _mm_setcsr(saved_csr_);
#endif
  }
  /// True while the environment is still the hostile one (the library put it back).
  static bool in_force() {
    bool ok = std::fegetround() == FE_UPWARD;
#if defined(__x86_64__)
    ok = ok && (_mm_getcsr() & 0x8040u) == 0x8040u;
#endif
    return ok;
  }

 private:
  unsigned saved_csr_ = 0;
  int saved_rounding_ = FE_TONEAREST;
};

/// An n^D lattice in which every fifth point has one coordinate moved up by one
/// ulp: 0 becomes 2^-1074, the smallest subnormal, which DAZ reads as 0.
template <int D>
std::vector<Point_d<D>> nudged_lattice(int n) {
  std::vector<Point_d<D>> points;
  std::array<int, D> c{};
  for (int k = 0;; ++k) {
    Point_d<D> p;
    for (int j = 0; j < D; ++j) p[j] = c[j];
    if (k % 5 == 0) p[k % D] = std::nextafter(p[k % D], 1e300);
    points.push_back(p);
    int j = 0;
    for (; j < D && ++c[j] == n; ++j) c[j] = 0;
    if (j == D) return points;
  }
}

}  // namespace

TEST_CASE("predicates are exact under flush-to-zero and upward rounding", "[kernel][fp-environment]") {
  using P = Point_d<3>;
  // Through a volatile: a constant would let the compiler fold the comparisons
  // at compile time, where DAZ does not apply.
  volatile double smallest_subnormal = 0x1p-1074;
  const double t = smallest_subnormal;
  const P o{{0, 0, 0}}, x{{t, 0, 0}}, y{{0, 1, 0}}, z{{0, 0, 1}}, q{{t, t, 0}};
  const std::array<P, 4> simplex{o, x, y, z};
  // The references first: GMP's conversion from double is floating-point code too.
  const auto orientation = dewall::test::gmp_orientation<3>(simplex);
  const auto side = dewall::test::gmp_side_of_oriented_sphere<3>(simplex, q);
  REQUIRE(orientation == dewall::kernel::POSITIVE);
  const Hostile_environment hostile;
  // Under DAZ the subnormal difference reads as 0 and the answer would be ZERO.
  CHECK(dewall::kernel::orientation_d<3>(o, x, y, z) == orientation);
  CHECK(dewall::kernel::orientation_d_exact<3>({&o, &x, &y, &z}) == orientation);
  CHECK(dewall::kernel::side_of_oriented_sphere_d<3>(o, x, y, z, q) == side);
  // The exact order of coordinates: DAZ makes the hardware say 2^-1074 == 0.
  CHECK(dewall::kernel::compare_lexicographically(x, o) == dewall::kernel::LARGER);
  CHECK(dewall::kernel::compare_lexicographically(P{{-0.0, 0, 0}}, o) == dewall::kernel::EQUAL);
  CHECK(Hostile_environment::in_force());  // the caller's environment is back
}

TEST_CASE("the static filters hold in any rounding mode and with flush-to-zero", "[kernel][fp-environment]") {
  // Near-degenerate inputs, where a filter's bound is tight: points on a plane,
  // then moved by a few ulps, at several scales (some entries subnormal).
  std::mt19937_64 rng(20261123);
  std::uniform_int_distribution<int> coordinate(-8, 8), nudge(-3, 3), scale(-1060, 40);
  using P = Point_d<3>;
  std::vector<std::array<P, 5>> cases;
  for (int k = 0; k < 3000; ++k) {
    std::array<P, 5> c;
    const int s = scale(rng);
    for (auto& p : c) {
      for (int j = 0; j < 2; ++j) p[j] = std::ldexp(coordinate(rng), s);
      p[2] = p[0] + p[1] - std::ldexp(1.0, s);  // the plane z = x + y − 2^s (exact)
      for (int j = 0; j < 3; ++j)
        for (int n = nudge(rng); n != 0; n += n > 0 ? -1 : 1) p[j] = std::nextafter(p[j], n > 0 ? 1e300 : -1e300);
    }
    cases.push_back(c);
  }
  // Inside the filter's domain but with products that underflow: two points
  // differ from the first by 2^-600 or 2^-530 in x and y and not in z, so the
  // determinant is a product of two such differences (2^-1200: flushed to 0 by
  // FTZ; 2^-1060: subnormal), while every column's largest entry is about 1.
  for (int k = 0; k < 1000; ++k) {
    const double e = k % 2 ? 0x1p-600 : 0x1p-530;
    std::array<P, 5> c;
    c[0] = P{{0, 0, 0}};
    for (int i = 1; i <= 2; ++i) c[i] = P{{e * coordinate(rng), e * coordinate(rng), 0}};
    for (int i = 3; i <= 4; ++i) c[i] = P{{double(coordinate(rng)), double(coordinate(rng)), double(coordinate(rng))}};
    cases.push_back(c);
  }
  // The x column tiny for every point (at most 2^-556, below the per-call
  // filter's domain) in a box whose extents are in it: the static filter's
  // semi-static bound decides these with its underflow floor (static_filter.hpp).
  const std::size_t first_tiny_column = cases.size();
  for (int k = 0; k < 1000; ++k) {
    std::array<P, 5> c;
    for (auto& p : c) p = P{{0x1p-560 * coordinate(rng), double(coordinate(rng)), double(coordinate(rng))}};
    cases.push_back(c);
  }
  std::vector<std::pair<int, int>> expected;
  for (const auto& c : cases)
    expected.emplace_back(dewall::test::gmp_orientation<3>({c[0], c[1], c[2], c[3]}),
                          dewall::test::gmp_side_of_oriented_sphere<3>({c[0], c[1], c[2], c[3]}, c[4]));
  const Hostile_environment hostile;
  int decided = 0, semi_static_decided = 0, tiny_column_decided = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto& c = cases[k];
    const dewall::kernel::Orientation_points<3> o{&c[0], &c[1], &c[2], &c[3]};
    const dewall::kernel::Sphere_points<3> s{&c[0], &c[1], &c[2], &c[3], &c[4]};
    INFO("case " << k);
    // The static filter of a box around the case (at least [-1, 1]^3, so
    // that a tiny column's extent stays in the domain), then its semi-static bound.
    std::array<double, 3> lo, hi;
    lo.fill(-1);
    hi.fill(1);
    for (const auto& p : c)
      for (int j = 0; j < 3; ++j) lo[j] = std::min(lo[j], p[j]), hi[j] = std::max(hi[j], p[j]);
    const dewall::kernel::Static_filter_d<3> box_filter(lo, hi);
    const auto by_box = box_filter.side_of_oriented_sphere(s);
    if (const auto f = box_filter.side_of_oriented_sphere_filtered(s)) {
      CHECK(*f == expected[k].second);
      semi_static_decided += !by_box;
      tiny_column_decided += !by_box && k >= first_tiny_column;
    }
    if (box_filter.valid()) {
      CHECK(box_filter.side_of_oriented_sphere_sign(s) == expected[k].second);
      std::uint32_t box_bound_left = 0;  // and the semi-static bound first
      CHECK(box_filter.side_of_oriented_sphere_sign<true>(s, box_bound_left) == expected[k].second);
    }
    if (const auto f = dewall::kernel::orientation_d_filter<3>(o)) {
      ++decided;
      CHECK(*f == expected[k].first);
    }
    if (const auto f = dewall::kernel::side_of_oriented_sphere_d_filter<3>(s)) CHECK(*f == expected[k].second);
    CHECK(dewall::kernel::orientation_d<3>(o) == expected[k].first);
    CHECK(dewall::kernel::side_of_oriented_sphere_d<3>(s) == expected[k].second);
  }
  CHECK(decided > 0);  // the filter was exercised, not only the later stages
  CHECK(semi_static_decided > 0);  // and the static filter's semi-static bound,
  CHECK(tiny_column_decided > 0);  // below the per-call filter's domain too
  CHECK(Hostile_environment::in_force());
}

TEST_CASE("the permanent stage holds on the filter's own entries in every rounding mode", "[kernel][fp-environment]") {
  // filtered_after_static runs stage 2a inline on the 2D sphere test's matrix
  // as the caller's environment computed it, without a guard. Near ties: four
  // points on a circle or on a short arc of it (rounded, half of them moved by
  // an ulp or two) at scales 2^-90 … 2^90. Underflow inside the filter's
  // domain: the query at the origin, one point 2^-530 from it (its lifted
  // entry 2^-1060, subnormal: flushed by FTZ) or 2^-1065 (its coordinates
  // subnormal: read as 0 by DAZ), the other two at integer coordinates, so
  // that every column's largest entry is about 1 and the determinant, about
  // 2^-530 in the first case, is above the stage's floor.
  using P = Point_d<2>;
  using Recipe = dewall::kernel::Side_of_sphere_recipe<2>;
  namespace stages = dewall::kernel::stages;
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586);
  std::uniform_int_distribution<int> scale(-90, 90), nudge(-2, 2), coordinate(-8, 8);
  std::vector<std::array<P, 4>> cases;
  for (int k = 0; k < 4000; ++k) {
    const int s = scale(rng);
    std::array<P, 4> c;
    const double base = angle(rng), spread = k % 4 < 2 ? 1.0 : 0x1p-8;  // half of them on a short arc
    for (auto& p : c) {
      const double a = base + spread * angle(rng);
      p = P{{std::ldexp(std::cos(a), s), std::ldexp(std::sin(a), s)}};
      for (int j = 0; j < 2 && k % 2; ++j)
        for (int n = nudge(rng); n != 0; n += n > 0 ? -1 : 1) p[j] = std::nextafter(p[j], n > 0 ? 1e300 : -1e300);
    }
    cases.push_back(c);
  }
  const std::size_t tiny_first = cases.size();
  for (int k = 0; k < 1000; ++k) {
    const double e = k % 2 ? 0x1p-1065 : 0x1p-530;
    std::array<P, 4> c;
    for (const int i : {0, 2}) c[static_cast<std::size_t>(i)] = P{{double(coordinate(rng)), double(coordinate(rng))}};
    c[1] = P{{e * coordinate(rng), e * coordinate(rng)}};
    c[3] = P{{0, 0}};  // the query
    cases.push_back(c);
  }
  std::vector<int> expected;
  for (const auto& c : cases) expected.push_back(dewall::test::gmp_side_of_oriented_sphere<2>({c[0], c[1], c[2]}, c[3]));
  const Hostile_environment hostile;  // FTZ and DAZ; the rounding mode set below
  for (const int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO, FE_TONEAREST}) {
    std::fesetround(mode);
    int decided = 0, undecided = 0, decided_with_underflow = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const auto& c = cases[k];
      const dewall::kernel::Sphere_points<2> refs{&c[0], &c[1], &c[2], &c[3]};
      double computed = std::numeric_limits<double>::quiet_NaN();
      if (stages::filter<Recipe, 2>(refs, &computed) || std::isnan(computed)) continue;  // not stage 2a's call
      const auto m = Recipe::matrix<double>([&](int i, int j) { return (*refs[static_cast<std::size_t>(i)])[j]; });
      INFO("mode " << mode << ", case " << k);
      if (const auto s = stages::permanent_decision<Recipe, 2>(m, computed)) {
        ++(k < tiny_first ? decided : decided_with_underflow);
        CHECK(*s == expected[k]);
      } else if (k < tiny_first) {
        ++undecided;
      }
    }
    CHECK(decided > 500);    // the stage was exercised on near ties
    CHECK(undecided > 100);  // and they were near enough to leave some
    CHECK(decided_with_underflow > 50);
    CHECK(std::fegetround() == mode);  // the stage changed nothing in the environment
  }
  std::fesetround(FE_UPWARD);
}

TEMPLATE_TEST_CASE_SIG("triangulate and certify are exact under flush-to-zero and upward rounding",
                       "[dewall][fp-environment]", ((int D), D), 2, 3) {
  const auto points = nudged_lattice<D>(D == 2 ? 12 : 6);
  const auto expected = dewall::test::cgal_delaunay<D>(points);  // in the default environment
  const Hostile_environment hostile;
  for (int depth : {0, 6}) {  // serial, and parallel (worker threads have their own environment)
    const auto t = dewall::triangulate<D>(points, dewall::Options{.parallel_depth = depth, .engine = dewall::Engine::dewall});
    CHECK(dewall::test::as_set<D>(t.simplices) == expected);
    const auto report = dewall::certify::certify<dewall::kernel::Filtered_kernel_d<D>>(points, t.simplices);
    CHECK(report.canonical);
  }
  CHECK(Hostile_environment::in_force());
}

TEST_CASE("the incremental engine tells a subnormal from 0 under denormals-are-zero, and drops the repeats",
          "[dewall][fp-environment]") {
  // (0, 0), (0, 2^-1074) and (0, −0) share a grid cell of the BRIO order (the
  // corners set the box) and a round (one round below 250 points), so they
  // are compared in one run, where DAZ makes the hardware call all three equal.
  const std::vector<Point_d<2>> points{{{-1, -1}}, {{1, 1}}, {{1, -1}}, {{0, 0}}, {{0, 0x1p-1074}}, {{0, -0.0}}, {{-1, 1}}};
  const auto expected = dewall::test::cgal_delaunay<2>(points);  // in the default environment
  const Hostile_environment hostile;
  const auto coords = [&](std::size_t i) -> const std::array<double, 2>& { return points[i].x; };
  const auto order = dewall::detail::brio_order_of_distinct<2>(points.size(), coords,
                                                               dewall::detail::bounding_box<2>(points.size(), coords));
  CHECK(order.size() == 6);  // (0, −0) repeats (0, 0); (0, 2^-1074) does not
  for (const dewall::Engine engine : {dewall::Engine::incremental, dewall::Engine::automatic}) {
    const auto t = dewall::triangulate<2>(points, dewall::Options{.parallel_depth = 0, .engine = engine});
    CHECK(dewall::test::as_set<2>(t.simplices) == expected);
    CHECK(t.statistics.distinct_points == 6);
  }
  CHECK(Hostile_environment::in_force());
}

TEST_CASE("the BRIO order is the same under denormals-are-zero and upward rounding", "[dewall][fp-environment]") {
  // Clusters whose runs get grids of their own (refined), among points with
  // subnormal coordinates and a box whose scale rounds, beside far points.
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<std::array<double, 2>> points{{-3e6, -1e6}, {3e6, 7e5}};
  for (int i = 0; i < 3000; ++i) points.push_back({unit(rng) * 1e-6 / 3, unit(rng) * 0x1p-1060});
  for (int i = 0; i < 1000; ++i) points.push_back({unit(rng) * 3 / 511, unit(rng) * 1e-300});
  const auto coords = [&](std::size_t i) -> const std::array<double, 2>& { return points[i]; };
  const auto box = dewall::detail::bounding_box<2>(points.size(), coords);
  const auto plain = dewall::detail::brio_order<2>(points.size(), coords, box);
  const auto distinct = dewall::detail::brio_order_of_distinct<2>(points.size(), coords, box);
  const auto whole = dewall::detail::brio_order<2>(points.size(), coords);
  const Hostile_environment hostile;
  CHECK(dewall::detail::brio_order<2>(points.size(), coords, box) == plain);
  CHECK(dewall::detail::brio_order_of_distinct<2>(points.size(), coords, box) == distinct);
  CHECK(dewall::detail::brio_order<2>(points.size(), coords) == whole);  // the box computed inside too
  CHECK(Hostile_environment::in_force());
}
