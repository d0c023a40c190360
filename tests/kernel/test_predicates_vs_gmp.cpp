// Every stage of both predicates against the GMP rational reference
// (tests/support/gmp_reference.hpp), D = 2..6, on every family of
// tests/support/point_generators.hpp: random, exactly degenerate,
// near-degenerate, extreme magnitudes and large offsets.
//
// A stage that returns a value (the filter, the interval stage) must return the
// exact sign; the exact stage and the full cascade must always do so.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dewall/kernel/orientation.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "dewall/kernel/static_filter.hpp"
#include "support/gmp_reference.hpp"
#include "support/point_generators.hpp"

namespace {

using namespace dewall::kernel;
using dewall::test::Degeneracy;
using dewall::test::Rng;
template <int D>
using Point = dewall::test::Point<D>;

constexpr int cases_per_family = 150;  // × 44 families × 5 dimensions
constexpr int mismatches_shown = 3;

/// Counts per family: disagreements (with the first few inputs kept) and how
/// far down the cascade the inputs went.
struct Tally {
  int cases = 0, mismatches = 0, filter_undecided = 0, interval_undecided = 0, scaled_undecided = 0, exact_zero = 0,
      static_undecided = 0;
  std::string report;

  template <int D>
  void check(const char* what, int expected, int got, const std::vector<Point<D>>& points) {
    if (expected == got) return;
    if (++mismatches <= mismatches_shown) {
      std::ostringstream out;
      out << what << ": expected " << expected << ", got " << got << " on\n"
          << dewall::test::format_points<D>(points);
      report += out.str();
    }
  }
  template <int D>
  void check_stage(const char* what, int expected, std::optional<Sign> got, int& undecided,
                   const std::vector<Point<D>>& points) {
    if (got) check<D>(what, expected, *got, points);
    else ++undecided;
  }
};

/// The static filter (static_filter.hpp) with the bound of the points' own
/// box, or (`wide`) of that box joined with [-1, 1]^D: the calls of an
/// incremental construction see a few close points in a large box.
template <int D>
Static_filter_d<D> static_filter_of(const std::vector<Point<D>>& points, bool wide = false) {
  std::array<double, D> lo = points[0].x, hi = points[0].x;
  if (wide) {
    for (int j = 0; j < D; ++j) {
      lo[static_cast<std::size_t>(j)] = std::min(lo[static_cast<std::size_t>(j)], -1.0);
      hi[static_cast<std::size_t>(j)] = std::max(hi[static_cast<std::size_t>(j)], 1.0);
    }
  }
  for (const auto& p : points)
    for (int j = 0; j < D; ++j) {
      lo[static_cast<std::size_t>(j)] = std::min(lo[static_cast<std::size_t>(j)], p[j]);
      hi[static_cast<std::size_t>(j)] = std::max(hi[static_cast<std::size_t>(j)], p[j]);
    }
  return Static_filter_d<D>(lo, hi);
}

template <int D>
void check_orientation(const std::vector<Point<D>>& points, Degeneracy degeneracy, Tally& tally) {
  std::array<Point<D>, D + 1> simplex;
  Orientation_points<D> refs;
  for (int i = 0; i <= D; ++i) {
    simplex[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(i)];
    refs[static_cast<std::size_t>(i)] = &points[static_cast<std::size_t>(i)];
  }
  const int expected = dewall::test::gmp_orientation<D>(simplex);
  if (degeneracy == Degeneracy::flat || degeneracy == Degeneracy::flat_but_last)
    tally.check<D>("generator: orientation of a flat set", 0, expected, points);
  if (expected == 0) ++tally.exact_zero;
  tally.check<D>("orientation_d", expected, orientation_d<D>(refs), points);
  tally.check<D>("orientation_d_exact", expected, orientation_d_exact<D>(refs), points);
  tally.check_stage<D>("orientation_d_filter", expected, orientation_d_filter<D>(refs), tally.filter_undecided,
                       points);
  tally.check_stage<D>("orientation_d_interval", expected, orientation_d_interval<D>(refs),
                       tally.interval_undecided, points);
  double ignored;
  tally.check_stage<D>("orientation filter on points scaled by 2^s", expected,
                       stages::filter_scaled<Orientation_recipe<D>, D>(refs, &ignored), tally.scaled_undecided, points);
  int unused_undecided = 0;
  tally.check_stage<D>("orientation exact in double", expected, stages::exact_in_double<Orientation_recipe<D>, D>(refs),
                       unused_undecided, points);
  tally.check_stage<D>("orientation static filter", expected, static_filter_of<D>(points).orientation(refs),
                       tally.static_undecided, points);
  tally.check_stage<D>("orientation static filter, wide box", expected,
                       static_filter_of<D>(points, true).orientation(refs), tally.static_undecided, points);
  std::swap(refs[0], refs[1]);  // an odd permutation flips the sign
  tally.check<D>("orientation_d, p_0 and p_1 swapped", -expected, orientation_d<D>(refs), points);
}

template <int D>
void check_side_of_sphere(const std::vector<Point<D>>& points, Degeneracy degeneracy, Tally& tally) {
  std::array<Point<D>, D + 1> simplex;
  Sphere_points<D> refs;
  for (int i = 0; i <= D + 1; ++i) {
    if (i <= D) simplex[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(i)];
    refs[static_cast<std::size_t>(i)] = &points[static_cast<std::size_t>(i)];
  }
  const int expected = dewall::test::gmp_side_of_oriented_sphere<D>(simplex, points[D + 1]);
  if (degeneracy == Degeneracy::flat || degeneracy == Degeneracy::cospherical)
    tally.check<D>("generator: sphere test of a cospherical set", 0, expected, points);
  if (expected == 0) ++tally.exact_zero;
  tally.check<D>("side_of_oriented_sphere_d", expected, side_of_oriented_sphere_d<D>(refs), points);
  tally.check<D>("side_of_oriented_sphere_d_exact", expected, side_of_oriented_sphere_d_exact<D>(refs), points);
  tally.check_stage<D>("side_of_oriented_sphere_d_filter", expected, side_of_oriented_sphere_d_filter<D>(refs),
                       tally.filter_undecided, points);
  tally.check_stage<D>("side_of_oriented_sphere_d_interval", expected,
                       side_of_oriented_sphere_d_interval<D>(refs), tally.interval_undecided, points);
  double ignored;
  tally.check_stage<D>("sphere filter on points scaled by 2^s", expected,
                       stages::filter_scaled<Side_of_sphere_recipe<D>, D>(refs, &ignored), tally.scaled_undecided,
                       points);
  int unused_undecided = 0;
  tally.check_stage<D>("sphere exact in double", expected,
                       stages::exact_in_double<Side_of_sphere_recipe<D>, D>(refs), unused_undecided, points);
  tally.check_stage<D>("sphere static filter", expected, static_filter_of<D>(points).side_of_oriented_sphere(refs),
                       tally.static_undecided, points);
  tally.check_stage<D>("sphere static filter, wide box", expected,
                       static_filter_of<D>(points, true).side_of_oriented_sphere(refs), tally.static_undecided, points);
  std::swap(refs[0], refs[D]);  // an odd permutation of the simplex flips the sign
  tally.check<D>("side_of_oriented_sphere_d, p_0 and p_D swapped", -expected, side_of_oriented_sphere_d<D>(refs),
                 points);
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("GMP reference: sign conventions on the unit simplex", "[gmp]", ((int D), D), 2, 3, 4, 5,
                       6) {
  // p_0 = 0, p_i = e_i: positively oriented (det of the identity). Its
  // circumsphere has centre (½, …, ½) and squared radius D/4.
  std::array<Point<D>, D + 1> simplex{};
  for (int i = 0; i < D; ++i) simplex[static_cast<std::size_t>(i + 1)][i] = 1;
  Point<D> centroid, far, on_sphere{};
  for (int j = 0; j < D; ++j) {
    centroid[j] = 1.0 / (D + 1);
    far[j] = 2;
  }
  on_sphere[0] = on_sphere[1] = 1;  // |(½, ½, −½, …)|² = D/4

  CHECK(dewall::test::gmp_orientation<D>(simplex) == POSITIVE);
  CHECK(dewall::test::gmp_side_of_oriented_sphere<D>(simplex, centroid) == ON_POSITIVE_SIDE);
  CHECK(dewall::test::gmp_side_of_oriented_sphere<D>(simplex, far) == ON_NEGATIVE_SIDE);
  CHECK(dewall::test::gmp_side_of_oriented_sphere<D>(simplex, on_sphere) == ON_ORIENTED_BOUNDARY);
  // The kernel agrees on the same convention.
  const auto refs = [&](const Point<D>& q) {
    Sphere_points<D> r;
    for (int i = 0; i <= D; ++i) r[static_cast<std::size_t>(i)] = &simplex[static_cast<std::size_t>(i)];
    r[D + 1] = &q;
    return r;
  };
  CHECK(side_of_oriented_sphere_d<D>(refs(centroid)) == ON_POSITIVE_SIDE);
  CHECK(side_of_oriented_sphere_d<D>(refs(far)) == ON_NEGATIVE_SIDE);

  // An odd permutation flips the orientation and the sphere test.
  std::swap(simplex[1], simplex[2]);
  CHECK(dewall::test::gmp_orientation<D>(simplex) == NEGATIVE);
  CHECK(dewall::test::gmp_side_of_oriented_sphere<D>(simplex, centroid) == ON_NEGATIVE_SIDE);
  CHECK(dewall::test::gmp_side_of_oriented_sphere<D>(simplex, far) == ON_POSITIVE_SIDE);
}

TEMPLATE_TEST_CASE_SIG("every predicate stage agrees with GMP rationals", "[gmp][predicates]", ((int D), D), 2, 3,
                       4, 5, 6) {
  const auto seed = dewall::test::test_seed(0xde3a11 + D);
  INFO("seed " << seed << " (set DEWALL_TEST_SEED to reproduce)");
  const auto families = dewall::test::point_set_families<D>();
  long total_cases = 0, filter_undecided = 0, interval_undecided = 0, exact_zero = 0;
  for (std::size_t f = 0; f < families.size(); ++f) {
    const auto& family = families[f];
    Rng rng(seed + f);
    Tally tally;
    for (int c = 0; c < cases_per_family; ++c) {
      const auto points = family.make(rng, D + 2);
      REQUIRE(points.size() == D + 2);
      check_orientation<D>(points, family.degeneracy, tally);
      check_side_of_sphere<D>(points, family.degeneracy, tally);
      ++tally.cases;
    }
    INFO("family \"" << family.name << "\" (index " << f << "), " << tally.mismatches << " mismatches\n"
                     << tally.report);
    CHECK(tally.mismatches == 0);
    total_cases += tally.cases;
    filter_undecided += tally.filter_undecided;
    interval_undecided += tally.interval_undecided;
    exact_zero += tally.exact_zero;
  }
  // The families reach every stage: the filter fails on many inputs, the
  // interval stage on some, and many answers are exactly zero.
  CHECK(total_cases == cases_per_family * static_cast<long>(families.size()));
  CHECK(filter_undecided > total_cases / 4);
  CHECK(exact_zero > total_cases / 4);
}

TEMPLATE_TEST_CASE_SIG("far from 1: the filter decides on the points scaled by a power of two", "[predicates]",
                       ((int D), D), 2, 3, 4, 5, 6) {
  Rng rng(20261122 + D);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (const int exponent : {600, -600, 900, -900}) {
    for (int trial = 0; trial < 50; ++trial) {
      std::array<Point<D>, D + 2> p;
      for (auto& q : p)
        for (int j = 0; j < D; ++j) q[j] = std::ldexp(unit(rng), exponent);
      Sphere_points<D> sphere;
      Orientation_points<D> simplex;
      for (int i = 0; i <= D + 1; ++i) sphere[static_cast<std::size_t>(i)] = &p[static_cast<std::size_t>(i)];
      for (int i = 0; i <= D; ++i) simplex[static_cast<std::size_t>(i)] = &p[static_cast<std::size_t>(i)];
      std::array<Point<D>, D + 1> first;
      std::copy_n(p.begin(), D + 1, first.begin());
      // Outside the plain filter's domain (its products would overflow or underflow) …
      CHECK(!side_of_oriented_sphere_d_filter<D>(sphere));
      // … but exactly scaled into it, decided, and right.
      double computed;
      const auto o = stages::filter_scaled<Orientation_recipe<D>, D>(simplex, &computed);
      const auto s = stages::filter_scaled<Side_of_sphere_recipe<D>, D>(sphere, &computed);
      REQUIRE(o);
      REQUIRE(s);
      CHECK(*o == dewall::test::gmp_orientation<D>(first));
      CHECK(*s == dewall::test::gmp_side_of_oriented_sphere<D>(first, p[D + 1]));
    }
  }
  // Magnitudes 2^1100 apart in one call: no power of two scales both exactly.
  std::array<Point<D>, D + 1> mixed{};
  for (int i = 1; i <= D; ++i) mixed[static_cast<std::size_t>(i)][i - 1] = 0x1p500;
  mixed[0][0] = 0x1p-600;
  Orientation_points<D> refs;
  for (int i = 0; i <= D; ++i) refs[static_cast<std::size_t>(i)] = &mixed[static_cast<std::size_t>(i)];
  double computed;
  CHECK(!stages::filter_scaled<Orientation_recipe<D>, D>(refs, &computed));
  CHECK(orientation_d<D>(refs) == dewall::test::gmp_orientation<D>(mixed));
}

TEST_CASE("predicate stats count the deciding stage", "[stats]") {
  if constexpr (!predicate_stats_enabled) {
    SUCCEED("DEWALL_PREDICATE_STATS is not defined: counters are compiled out");
  } else {
    auto& o = predicate_stats().orientation[3];
    auto& s = predicate_stats().side_of_sphere[3];
    o.reset();
    s.reset();
    const Point<3> a{{0, 0, 0}}, b{{1, 0, 0}}, c{{0, 1, 0}}, d{{0, 0, 1}}, e{{1, 1, 0}}, g{{0.25, 0.25, 0.25}};
    CHECK(orientation_d(a, b, c, d) == POSITIVE);  // decided by the filter
    CHECK(o.filter == 1);
    // Coplanar (z = x + y) with no zero column: only the exact stage proves ZERO.
    const Point<3> b1{{1, 0, 1}}, c1{{0, 1, 1}}, e1{{1, 1, 2}};
    CHECK(orientation_d(a, b1, c1, e1) == ZERO);
    CHECK(o.exact == 1);
    CHECK(o.calls() == 2);
    CHECK(side_of_oriented_sphere_d(a, b, c, d, g) == ON_POSITIVE_SIDE);
    CHECK(s.filter == 1);
    CHECK(side_of_oriented_sphere_d_sos(a, b, c, d, e) == ON_NEGATIVE_SIDE);  // cospherical
    CHECK(s.exact == 1);
    CHECK(s.perturbed == 1);
    CHECK(s.calls() == 2);
  }
}

TEMPLATE_TEST_CASE_SIG("small integers: the double determinant is exact, zero included", "[predicates]",
                       ((int D), D), 2, 3, 4, 5, 6) {
  Rng rng(0xe8ac7 + D);
  int decided = 0, zeros = 0;
  for (int c = 0; c < 1000; ++c) {
    // Cospherical and flat integer sets tie; random small integers mostly do not.
    auto points = c % 3 == 0 ? dewall::test::cospherical_integer_points<D>(rng, D + 2)
                             : c % 3 == 1 ? dewall::test::flat_integer_points<D>(rng, D + 2, D - 1)
                                          : dewall::test::lattice_points<D>(rng, D + 2, -6, 6);
    Sphere_points<D> refs;
    Orientation_points<D> simplex;
    for (int i = 0; i <= D + 1; ++i) refs[static_cast<std::size_t>(i)] = &points[static_cast<std::size_t>(i)];
    for (int i = 0; i <= D; ++i) simplex[static_cast<std::size_t>(i)] = &points[static_cast<std::size_t>(i)];
    std::array<Point<D>, D + 1> first;
    for (int i = 0; i <= D; ++i) first[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(i)];
    const auto o = stages::exact_in_double<Orientation_recipe<D>, D>(simplex);
    const auto s = stages::exact_in_double<Side_of_sphere_recipe<D>, D>(refs);
    if (o) CHECK(*o == dewall::test::gmp_orientation<D>(first));
    if (s) CHECK(*s == dewall::test::gmp_side_of_oriented_sphere<D>(first, points[D + 1]));
    if (o && s) ++decided;
    if (s && *s == ZERO) ++zeros;
  }
  CHECK(decided > 600);  // small integers (in 6D some sets exceed the 2^52 bound)
  CHECK(zeros > 100);
  // Not integers, or too large: never decides.
  std::array<Point<D>, D + 1> half;
  Orientation_points<D> h;
  for (int i = 0; i <= D; ++i) {
    half[static_cast<std::size_t>(i)][i % D] = i == D ? 0.5 : 1;
    h[static_cast<std::size_t>(i)] = &half[static_cast<std::size_t>(i)];
  }
  CHECK(!stages::exact_in_double<Orientation_recipe<D>, D>(h));
  half[0][0] = 0x1p21;
  half[D][0] = 0;
  CHECK(!stages::exact_in_double<Orientation_recipe<D>, D>(h));
}

TEMPLATE_TEST_CASE_SIG("the static filter decides most calls on spread points, and never wrongly", "[predicates]",
                       ((int D), D), 2, 3) {
  Rng rng(0x57a71c + D);
  std::array<double, D> lo, hi;
  lo.fill(-1);
  hi.fill(1);
  const Static_filter_d<D> filter(lo, hi);
  REQUIRE(filter.valid());
  int decided = 0, cases = 2000;
  for (int c = 0; c < cases; ++c) {
    const auto points = dewall::test::uniform_points<D>(rng, D + 2);
    Sphere_points<D> refs;
    Orientation_points<D> simplex;
    for (int i = 0; i <= D + 1; ++i) refs[static_cast<std::size_t>(i)] = &points[static_cast<std::size_t>(i)];
    for (int i = 0; i <= D; ++i) simplex[static_cast<std::size_t>(i)] = &points[static_cast<std::size_t>(i)];
    const auto o = filter.orientation(simplex);
    const auto s = filter.side_of_oriented_sphere(refs);
    if (o && s) ++decided;
    if (o) CHECK(*o == orientation_d<D>(simplex));
    if (s) CHECK(*s == side_of_oriented_sphere_d<D>(refs));
  }
  CHECK(decided > cases * 9 / 10);
  // Outside the domain (a box wider than 2^100) it never decides.
  hi[0] = 0x1p101;
  CHECK(!Static_filter_d<D>(lo, hi).valid());
}
