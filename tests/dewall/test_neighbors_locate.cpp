// The queries the Python bindings build on: certify::neighbors (the simplex
// across each facet), locate (exact point location by a visibility walk),
// kernel::first_occurrences (duplicates) and parse_engine. Checked against
// brute force on lattices (every point ties) and random points.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <thread>
#include <vector>

#include "dewall/certify/neighbors.hpp"
#include "dewall/dewall.hpp"
#include "dewall/kernel/first_occurrence.hpp"
#include "dewall/locate.hpp"
#include "support/dewall_point_sets.hpp"

using dewall::kernel::Point_d;
namespace kernel = dewall::kernel;

namespace {

template <int D>
std::vector<std::array<std::int32_t, D + 1>> neighbors_of(std::size_t n, const std::vector<dewall::Simplex<D>>& s) {
  std::vector<std::array<std::int32_t, D + 1>> out(s.size());
  dewall::certify::neighbors<D, std::int32_t>(n, std::span<const dewall::Simplex<D>>(s),
                                              std::span<std::array<std::int32_t, D + 1>>(out));
  return out;
}

/// The facet of simplex s opposite position j, sorted.
template <int D>
std::array<std::uint32_t, D> facet(const dewall::Simplex<D>& s, int j) {
  std::array<std::uint32_t, D> f;
  for (int i = 0, k = 0; i <= D; ++i)
    if (i != j) f[static_cast<std::size_t>(k++)] = s[static_cast<std::size_t>(i)];
  std::sort(f.begin(), f.end());
  return f;
}

/// Brute force: does closed simplex s contain q (exact orientations)?
template <int D>
bool contains(const std::vector<Point_d<D>>& p, const dewall::Simplex<D>& s, const Point_d<D>& q) {
  for (int j = 0; j <= D; ++j) {
    std::array<const Point_d<D>*, D + 1> r;
    for (int i = 0; i <= D; ++i) r[static_cast<std::size_t>(i)] = &p[s[static_cast<std::size_t>(i)]];
    r[static_cast<std::size_t>(j)] = &q;
    if (kernel::orientation_d<D>(r) == kernel::NEGATIVE) return false;
  }
  return true;
}

template <int D>
void check(const std::vector<Point_d<D>>& p, std::mt19937_64& rng) {
  const auto s = dewall::triangulate<D>(p).simplices;
  const auto nb = neighbors_of<D>(p.size(), s);
  // Neighbours: symmetric, across the same facet; −1 exactly on the hull
  // (every facet is in one or two simplices).
  std::size_t hull = 0;
  for (std::size_t r = 0; r < s.size(); ++r)
    for (int j = 0; j <= D; ++j) {
      const auto n = nb[r][static_cast<std::size_t>(j)];
      if (n < 0) {
        ++hull;
        continue;
      }
      const auto& other = nb[static_cast<std::size_t>(n)];
      const auto back = std::find(other.begin(), other.end(), static_cast<std::int32_t>(r));
      REQUIRE(back != other.end());
      REQUIRE(facet<D>(s[static_cast<std::size_t>(n)], static_cast<int>(back - other.begin())) == facet<D>(s[r], j));
    }
  CHECK(hull > 0);
  // Locate: lattice-aligned and random queries, inside, on faces, outside.
  std::vector<Point_d<D>> queries;
  std::uniform_int_distribution<int> coordinate(-2, 12);
  std::uniform_real_distribution<double> real(-0.5, 4.5);
  for (int i = 0; i < 200; ++i) {
    Point_d<D> q;
    for (int j = 0; j < D; ++j) q[j] = i % 2 ? coordinate(rng) * 0.5 : real(rng);
    queries.push_back(q);
  }
  queries.insert(queries.end(), p.begin(), p.end());
  std::vector<std::int64_t> found(queries.size());
  dewall::locate_all<kernel::Filtered_kernel_d<D>>(
      {}, std::span<const Point_d<D>>(p), std::span<const dewall::Simplex<D>>(s),
      std::span<const std::array<std::int32_t, D + 1>>(nb), std::span<const Point_d<D>>(queries),
      std::span<std::int64_t>(found));
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const bool anywhere = std::any_of(s.begin(), s.end(), [&](const auto& t) { return contains<D>(p, t, queries[i]); });
    REQUIRE((found[i] >= 0) == anywhere);
    if (found[i] >= 0) REQUIRE(contains<D>(p, s[static_cast<std::size_t>(found[i])], queries[i]));
  }
}

}  // namespace

TEST_CASE("neighbors and locate agree with brute force on lattices and random points", "[python][locate]") {
  std::mt19937_64 rng(14);
  check<2>(dewall::test::lattice<2>(25), rng);
  check<3>(dewall::test::lattice<3>(64), rng);
  auto random3 = dewall::test::uniform<3>(200, rng);
  for (auto& q : random3)
    for (int j = 0; j < 3; ++j) q[j] *= 4;
  check<3>(random3, rng);
  check<4>(dewall::test::lattice<4>(81), rng);
}

TEST_CASE("neighbors refuses a facet of three simplices", "[python]") {
  const std::vector<dewall::Simplex<2>> s = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};
  std::vector<std::array<std::int32_t, 3>> out(s.size());
  CHECK_THROWS_AS((dewall::certify::neighbors<2, std::int32_t>(5, std::span<const dewall::Simplex<2>>(s),
                                                               std::span<std::array<std::int32_t, 3>>(out))),
                  std::invalid_argument);
}

TEST_CASE("first_occurrences: each point maps to the earliest equal point, -0 == +0", "[python]") {
  const std::vector<Point_d<2>> p = {{{1, 2}}, {{0, 0}}, {{1, 2}}, {{-0.0, 0}}, {{3, 3}}, {{1, 2}}};
  const kernel::Filtered_kernel_d<2> k;
  const auto first = kernel::first_occurrences(std::span<const Point_d<2>>(p), k.compare_lexicographically_d_object(),
                                               k.approximate_coordinates_object());
  CHECK(first == std::vector<std::uint32_t>{0, 1, 0, 1, 4, 0});
}

TEST_CASE("first_occurrences agrees with a quadratic scan on many duplicates, in one pass or many, on two threads", "[python]") {
  // Coordinates from a small set (0, ±0, 1, 2^-1074, a NaN-free mix), so most
  // points repeat an earlier one and the hash table's probe chains are long.
  const double values[] = {0.0, -0.0, 1.0, 0x1p-1074, -1.0, 3.5};
  std::mt19937_64 rng(5);
  // Two threads, each taking every other part: the passes run at once.
  const auto two_threads = [](std::size_t count, auto&& f) {
    std::thread other([&] {
      for (std::size_t i = 1; i < count; i += 2) f(i, 1u);
    });
    for (std::size_t i = 0; i < count; i += 2) f(i, 0u);
    other.join();
  };
  for (std::size_t n : {1u, 2u, 50u, 3000u, 9000u}) {
    std::vector<Point_d<3>> p(n);
    for (auto& q : p)
      for (double& c : q.x) c = values[rng() % 6];
    const kernel::Filtered_kernel_d<3> k;
    std::vector<std::uint32_t> expected(n);
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t j = 0;
      while (!(p[j].x[0] == p[i].x[0] && p[j].x[1] == p[i].x[1] && p[j].x[2] == p[i].x[2])) ++j;
      expected[i] = static_cast<std::uint32_t>(j);
    }
    // One table, and tables so small that the points take many passes.
    for (std::size_t max_table_bytes : {std::size_t{0}, std::size_t{64}, std::size_t{1024}}) {
      INFO("n = " << n << ", table at most " << max_table_bytes << " bytes");
      const auto first = kernel::first_occurrences(std::span<const Point_d<3>>(p), k.compare_lexicographically_d_object(),
                                                   k.approximate_coordinates_object(), [](std::size_t) { return false; },
                                                   max_table_bytes);
      CHECK(first == expected);
      INFO("on two threads");
      CHECK(kernel::first_occurrences(std::span<const Point_d<3>>(p), k.compare_lexicographically_d_object(),
                                      k.approximate_coordinates_object(), [](std::size_t) { return false; },
                                      max_table_bytes, two_threads, 2) == expected);
    }
    // Excluded points map to themselves and stand for no later point.
    const auto excluded = [](std::size_t i) { return i % 3 == 0; };
    std::vector<std::uint32_t> expected_excluding(n);
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t j = i;
      if (!excluded(i))
        for (j = 0; j < i; ++j)
          if (!excluded(j) && p[j].x[0] == p[i].x[0] && p[j].x[1] == p[i].x[1] && p[j].x[2] == p[i].x[2]) break;
      expected_excluding[i] = static_cast<std::uint32_t>(j);
    }
    for (std::size_t max_table_bytes : {std::size_t{0}, std::size_t{64}}) {
      INFO("n = " << n << ", every third point excluded, table at most " << max_table_bytes << " bytes");
      CHECK(kernel::first_occurrences(std::span<const Point_d<3>>(p), k.compare_lexicographically_d_object(),
                                      k.approximate_coordinates_object(), excluded, max_table_bytes) == expected_excluding);
      CHECK(kernel::first_occurrences(std::span<const Point_d<3>>(p), k.compare_lexicographically_d_object(),
                                      k.approximate_coordinates_object(), excluded, max_table_bytes, two_threads,
                                      2) == expected_excluding);
    }
  }
}

TEST_CASE("parse_engine names the engines the CLI and Python accept", "[python]") {
  CHECK(dewall::parse_engine("auto") == dewall::Engine::automatic);
  CHECK(dewall::parse_engine("dewall") == dewall::Engine::dewall);
  CHECK(dewall::parse_engine("cgal") == dewall::Engine::cgal);
  CHECK(dewall::parse_engine("incremental") == dewall::Engine::incremental);
  CHECK(!dewall::parse_engine("automatic"));
}
