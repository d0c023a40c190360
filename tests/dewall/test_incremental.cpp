// The project's own incremental engine (detail/incremental/incremental_delaunay.hpp) piece
// by piece: the Hilbert index and the BRIO order, the data structure after
// every insertion, the cavity against every cell's own conflict test, and the
// triangulation against CGAL's in 2D–6D on random, lattice, cospherical,
// flat-layered and extreme-scale points.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <span>
#include <type_traits>
#include <vector>

#include <tbb/task_arena.h>

#include "dewall/detail/incremental/testing_access.hpp"
#include "dewall/detail/incremental/brio_order.hpp"
#include "dewall/kernel/side_of_sphere.hpp"
#include "support/cgal_reference.hpp"
#include "support/dewall_point_sets.hpp"

namespace {

using dewall::detail::Incremental_delaunay;
using dewall::detail::Incremental_testing_access;
using dewall::detail::Incremental_tuning;

/// The default tuning, checking the whole structure after every insertion when `check`.
Incremental_tuning checking(bool check = true) {
  Incremental_tuning tuning;
  tuning.check_each_insertion = check;
  return tuning;
}
using dewall::detail::Incremental_statistics;
using Point3 = dewall::kernel::Point_d<3>;

/// The finite cells of a built triangulation as sorted input-index tuples.
template <int D>
dewall::test::Simplex_set<D> finite_cells(const Incremental_delaunay<D>& dt) {
  dewall::test::Simplex_set<D> cells;
  for (std::size_t c = 0; c < dt.slots(); ++c) {
    if (dt.is_free(c) || dt.is_infinite(c)) continue;
    std::array<std::uint32_t, D + 1> t;
    for (int i = 0; i <= D; ++i) t[static_cast<std::size_t>(i)] = dt.input_index(dt.cell(c)[static_cast<std::size_t>(i)]);
    std::sort(t.begin(), t.end());
    cells.insert(t);
  }
  return cells;
}

/// The engine's finite cells as sorted input-index tuples (duplicates
/// removed first, first occurrence kept, as the library does).
template <int D>
dewall::test::Simplex_set<D> incremental_delaunay(const std::vector<dewall::kernel::Point_d<D>>& points,
                                                  bool check_each_insertion = false) {
  std::set<std::array<double, D>> seen;
  std::vector<std::size_t> distinct;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (seen.insert(points[i].x).second) distinct.push_back(i);
  Incremental_delaunay<D> dt(checking(check_each_insertion));
  dewall::test::Simplex_set<D> out;
  if (!dt.build(
          distinct.size(), [&](std::size_t k) -> const std::array<double, D>& { return points[distinct[k]].x; },
          [&](std::size_t k) { return distinct[k]; }))
    return out;
  CHECK(dt.is_valid());
  std::size_t finite = 0;
  for (std::size_t c = 0; c < dt.slots(); ++c) finite += !dt.is_free(c) && !dt.is_infinite(c);
  CHECK(finite == dt.finite_cells());
  out = finite_cells(dt);
  CHECK(out.size() == finite);  // no cell twice
  return out;
}

/// The same, the repeats left to the engine (build_dropping_repeats).
template <int D>
dewall::test::Simplex_set<D> incremental_delaunay_dropping_repeats(const std::vector<dewall::kernel::Point_d<D>>& points) {
  Incremental_delaunay<D> dt;
  dewall::test::Simplex_set<D> out;
  if (!dt.build_dropping_repeats(
          points.size(), [&](std::size_t k) -> const std::array<double, D>& { return points[k].x; },
          [](std::size_t k) { return k; }, [] {}))
    return out;
  CHECK(dt.is_valid());
  std::set<std::array<double, D>> distinct;  // −0 and +0 alike, as in the engine
  for (const auto& p : points) distinct.insert(p.x);
  CHECK(dt.vertices() == distinct.size());
  return finite_cells(dt);
}

template <int D>
void check_against_cgal(const std::vector<dewall::kernel::Point_d<D>>& points, bool check_each_insertion = false) {
  const auto expected = dewall::test::cgal_delaunay<D>(points);
  const auto ours = incremental_delaunay<D>(points, check_each_insertion);
  CHECK(ours.size() == expected.size());
  CHECK(ours == expected);
  CHECK(incremental_delaunay_dropping_repeats<D>(points) == expected);
}

/// The length of the path through the points in `order` (coordinates times
/// `unit`, so that points near 2^1023 give finite steps), leaving out the
/// steps to or from an index of `end` or more.
template <int D, class Coords>
double order_path(const std::vector<std::uint32_t>& order, Coords&& coords, double unit = 1,
                  std::size_t end = std::numeric_limits<std::size_t>::max()) {
  double length = 0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (order[k] >= end || order[k - 1] >= end) continue;
    double squared = 0;
    for (std::size_t j = 0; j < static_cast<std::size_t>(D); ++j)
      squared += std::pow(coords(order[k])[j] * unit - coords(order[k - 1])[j] * unit, 2);
    length += std::sqrt(squared);
  }
  return length;
}

/// 0, 1, …, n − 1: the input order.
std::vector<std::uint32_t> input_order(std::size_t n) {
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  return order;
}

template <int D>
void check_families(std::size_t n, std::mt19937_64& rng) {
  check_against_cgal<D>(dewall::test::uniform<D>(n, rng));
  check_against_cgal<D>(dewall::test::lattice<D>(n));                 // every point ties with many
  check_against_cgal<D>(dewall::test::lattice_samples<D>(n, 4, rng)); // ties and duplicates, random order
  check_against_cgal<D>(dewall::test::cospherical<D>(false));
  check_against_cgal<D>(dewall::test::cospherical<D>(true));
  check_against_cgal<D>(dewall::test::planes<D>(n, 2, rng));
  // 2^±600: beyond the floating-point filter's domain, the scaled filter and the exact stage decide.
  check_against_cgal<D>(dewall::test::scaled<D>(dewall::test::lattice_samples<D>(n, 4, rng), 0x1p-600, 0));
  check_against_cgal<D>(dewall::test::scaled<D>(dewall::test::lattice_samples<D>(n, 4, rng), 0x1p600, 0x1p601));
}

/// Whether a and b hold the same cells with the same neighbours in the same
/// slots, and the same slots free (the output order is the slots').
template <int D>
bool same_slots(const Incremental_delaunay<D>& a, const Incremental_delaunay<D>& b) {
  if (a.slots() != b.slots()) return false;
  for (std::size_t c = 0; c < a.slots(); ++c) {
    if (a.is_free(c) != b.is_free(c)) return false;
    if (a.is_free(c)) continue;
    if (a.cell(c) != b.cell(c)) return false;
    for (int i = 0; i <= D; ++i)
      if (a.neighbor(c, i) != b.neighbor(c, i)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("incremental: the Hilbert index is a bijection between neighbouring cells", "[incremental]") {
  // 2D, 8×8 grid; 3D, 4×4×4: consecutive indices are cells sharing a facet.
  auto check = [](auto dimension, int bits) {
    constexpr int D = decltype(dimension)::value;
    const std::uint32_t side = 1u << bits;
    std::vector<std::array<std::uint32_t, D>> at(std::size_t{1} << (D * bits));
    std::vector<bool> seen(at.size(), false);
    std::array<std::uint32_t, D> x{};
    for (std::size_t cell = 0; cell < at.size(); ++cell) {
      std::size_t rest = cell;
      for (int j = 0; j < D; ++j, rest /= side) x[static_cast<std::size_t>(j)] = static_cast<std::uint32_t>(rest % side);
      const std::uint64_t h = dewall::detail::hilbert_index<D>(x, bits);
      REQUIRE(h < at.size());
      CHECK(!seen[h]);
      seen[h] = true;
      at[h] = x;
    }
    for (std::size_t h = 1; h < at.size(); ++h) {
      int distance = 0;
      for (int j = 0; j < D; ++j)
        distance += std::abs(static_cast<int>(at[h][static_cast<std::size_t>(j)]) - static_cast<int>(at[h - 1][static_cast<std::size_t>(j)]));
      CHECK(distance == 1);
    }
  };
  // 2D's table: odd and even paddings to 16 levels, and partial 4-level chunks.
  for (int bits = 1; bits <= 7; ++bits) check(std::integral_constant<int, 2>{}, bits);
  check(std::integral_constant<int, 3>{}, 2);
  check(std::integral_constant<int, 3>{}, 3);
  // 2D's table is Skilling's curve: every cell up to 2^8 per axis, random ones above.
  std::mt19937_64 rng(38);
  for (int bits = 1; bits <= 16; ++bits) {
    const std::uint32_t side = 1u << bits;
    for (std::uint32_t k = 0; k < (bits <= 8 ? side * side : 100000u); ++k) {
      const std::array<std::uint32_t, 2> x =
          bits <= 8 ? std::array<std::uint32_t, 2>{k % side, k / side}
                    : std::array<std::uint32_t, 2>{static_cast<std::uint32_t>(rng()) % side, static_cast<std::uint32_t>(rng()) % side};
      if (dewall::detail::hilbert_index<2>(x, bits) != dewall::detail::skilling_hilbert_index<2>(x, bits))
        FAIL("bits " << bits << ", cell (" << x[0] << ", " << x[1] << ")");
    }
  }
  // 3D's table is Skilling's curve too: every cell up to 2^5 per axis, random ones above.
  for (int bits = 1; bits <= 16; ++bits) {
    const std::uint32_t side = 1u << bits;
    for (std::uint32_t k = 0; k < (bits <= 5 ? side * side * side : 100000u); ++k) {
      std::array<std::uint32_t, 3> x;
      for (std::size_t i = 0; i < 3; ++i)
        x[i] = bits <= 5 ? k >> (bits * static_cast<int>(i)) & (side - 1) : static_cast<std::uint32_t>(rng()) & (side - 1);
      if (dewall::detail::hilbert_index<3>(x, bits) != dewall::detail::skilling_hilbert_index<3>(x, bits))
        FAIL("bits " << bits << ", cell (" << x[0] << ", " << x[1] << ", " << x[2] << ")");
    }
  }
  // 3D's interleaving by masks against bit by bit, at every 16-bit value.
  for (std::uint32_t v = 0; v < (1u << 16); ++v) {
    std::uint64_t spread = 0;
    for (int b = 0; b < 16; ++b) spread |= std::uint64_t{(v >> b) & 1u} << (3 * b);
    if (dewall::detail::spread_bits_3(v) != spread) FAIL("spread_bits_3(" << v << ")");
  }
  check(std::integral_constant<int, 4>{}, 2);
}

TEST_CASE("incremental: the Hilbert grid's cells are cubes on a flat box", "[incremental]") {
  // A tile 1000 × 1000 × 30 (an airborne scan's shape): its grid indexes
  // every point as the grid over the cube on the same corner whose side is
  // the tile's longest extent, in both directions.
  using dewall::detail::brio::Hilbert_grid;
  std::mt19937_64 rng(40);
  std::uniform_real_distribution<double> unit(0, 1);
  const dewall::detail::Box<3> tile{{5e5, 5e6, 250}, {5e5 + 1000, 5e6 + 1000, 280}};
  const dewall::detail::Box<3> cube{{5e5, 5e6, 250}, {5e5 + 1000, 5e6 + 1000, 1250}};
  const Hilbert_grid<3> flat(tile, 9), cubic(cube, 9);
  std::uint64_t highest_z = 0;
  for (int k = 0; k < 1000; ++k) {
    const std::array<double, 3> x{5e5 + 1000 * unit(rng), 5e6 + 1000 * unit(rng), 250 + 30 * unit(rng)};
    for (const bool backwards : {false, true}) CHECK(flat.index(x, backwards) == cubic.index(x, backwards));
    highest_z = std::max(highest_z, flat.index({5e5, 5e6, x[2]}, false));
  }
  // Along z the tile fills 30/1000 of the side's 512 cells: (lo, lo, z) lies
  // in the corner's sub-cube of side 16, which the curve, starting at the
  // corner, fills first (with a scale per axis z would reach cell 511).
  CHECK(highest_z < 16 * 16 * 16);
}

TEST_CASE("incremental: the BRIO order is a permutation, the same on every run", "[incremental]") {
  std::mt19937_64 rng(31);
  for (std::size_t n : {0, 1, 2, 999, 1000, 1001, 5000}) {
    const auto points = dewall::test::uniform<3>(n, rng);
    auto coords = [&](std::size_t i) -> const std::array<double, 3>& { return points[i].x; };
    const auto order = dewall::detail::brio_order<3>(n, coords);
    auto sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < n; ++i) CHECK(sorted[i] == i);
    CHECK(dewall::detail::brio_order<3>(n, coords) == order);
  }
  // 6D: keys of more than 32 bits (at 5,000 points 6·5 + 4), the (key, index) pairs' path.
  {
    const auto points = dewall::test::uniform<6>(5000, rng);
    auto coords = [&](std::size_t i) -> const std::array<double, 6>& { return points[i].x; };
    const auto order = dewall::detail::brio_order<6>(points.size(), coords);
    auto sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) CHECK(sorted[i] == i);
  }
  // Degenerate extents: all points on one axis line, and coordinates near ±2^1023.
  std::vector<Point3> line(100), extreme(100);
  for (std::size_t i = 0; i < 100; ++i) {
    line[i] = {{static_cast<double>(i), 0, 0}};
    extreme[i] = {{(i % 2 ? 1 : -1) * 0x1p1023, static_cast<double>(i), 0}};
  }
  for (const auto* set : {&line, &extreme}) {
    auto sorted = dewall::detail::brio_order<3>(100, [&](std::size_t i) -> const auto& { return (*set)[i].x; });
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < 100; ++i) CHECK(sorted[i] == i);
  }
}

TEST_CASE("incremental: a cluster sharing one grid cell goes along a grid of its own", "[incremental]") {
  // 6000 points in a box of 10^-6 beside two points at ±10^6: the whole
  // cluster in one cell of the order's grid (its last round, over 4096
  // points, sorted by the radix sort). Along the cluster's own grid the
  // order's steps are short; in input order (random points) each would be
  // about the cluster's size.
  std::mt19937_64 rng(39);
  const auto check = [&](auto dimension) {
    constexpr int D = decltype(dimension)::value;
    auto points = dewall::test::uniform<D>(6000, rng);
    for (auto& p : points)
      for (double& x : p.x) x *= 1e-6;
    dewall::kernel::Point_d<D> far_low, far_high;
    far_low.x.fill(-1e6);
    far_high.x.fill(1e6);
    points.push_back(far_low);
    points.push_back(far_high);
    const auto coords = [&](std::size_t i) -> const std::array<double, D>& { return points[i].x; };
    const auto order = dewall::detail::brio_order<D>(points.size(), coords);
    auto sorted = order;
    std::sort(sorted.begin(), sorted.end());
    CHECK(sorted == input_order(points.size()));
    // (the steps to and from the far points, 6000 and 6001, left out)
    CHECK(order_path<D>(order, coords, 1, 6000) < order_path<D>(input_order(points.size()), coords, 1, 6000) / 5);
    check_against_cgal<D>(points);
  };
  check(std::integral_constant<int, 2>{});
  check(std::integral_constant<int, 3>{});
  // Extents that overflow (points near ±1.7·10^308): each axis measured in
  // half units still orders them (it was one cell: input order).
  std::vector<std::array<double, 2>> huge(3000);
  std::uniform_real_distribution<double> symmetric(-1, 1);
  for (auto& p : huge) p = {1.7e308 * symmetric(rng), 1.7e308 * symmetric(rng)};
  const auto huge_coords = [&](std::size_t i) -> const std::array<double, 2>& { return huge[i]; };
  const auto huge_order = dewall::detail::brio_order<2>(huge.size(), huge_coords);
  auto sorted = huge_order;
  std::sort(sorted.begin(), sorted.end());
  CHECK(sorted == input_order(huge.size()));
  CHECK(order_path<2>(huge_order, huge_coords, 0x1p-1000) < order_path<2>(input_order(huge.size()), huge_coords, 0x1p-1000) / 5);
}

TEST_CASE("incremental: the BRIO order of the distinct points is brio_order without the repeats", "[incremental]") {
  std::mt19937_64 rng(36);
  std::uniform_int_distribution<int> value(-3, 3);
  const auto check = [](const std::vector<std::array<double, 2>>& points) {
    const auto coords = [&](std::size_t i) -> const std::array<double, 2>& { return points[i]; };
    // The first occurrences by brute force: a point repeats when an earlier one equals it.
    std::vector<std::uint32_t> first;
    for (std::size_t i = 0; i < points.size(); ++i) {
      bool repeated = false;
      for (std::size_t j = 0; j < i && !repeated; ++j) repeated = points[j] == points[i];
      if (!repeated) first.push_back(static_cast<std::uint32_t>(i));
    }
    const auto box = dewall::detail::bounding_box<2>(points.size(), coords);
    const auto distinct = dewall::detail::brio_order_of_distinct<2>(points.size(), coords, box);
    auto kept = distinct;
    std::sort(kept.begin(), kept.end());
    CHECK(kept == first);
    // In brio_order's order: the whole order with the repeats taken out.
    std::vector<std::uint32_t> expected;
    for (const std::uint32_t i : dewall::detail::brio_order<2>(points.size(), coords, box))
      if (std::binary_search(first.begin(), first.end(), i)) expected.push_back(i);
    CHECK(distinct == expected);
  };
  // Few values, −0 and +0 among them: every point repeats many times (runs of
  // one point, repeated).
  std::vector<std::array<double, 2>> repeats(3000);
  for (auto& p : repeats) {
    p = {value(rng) * 0.25, value(rng) * 0.25};
    for (double& x : p)
      if (x == 0 && rng() % 2) x = -0.0;
  }
  check(repeats);
  // A cluster in one grid cell (the box is set by two far points): runs of
  // more than 16 points, sorted by coordinates; one point many times.
  std::vector<std::array<double, 2>> cluster{{-1e6, -1e6}, {1e6, 1e6}};
  std::uniform_real_distribution<double> tiny(0, 1e-9);
  for (int i = 0; i < 2000; ++i) {
    const std::array<double, 2> p = i >= 30 && i % 3 == 0 ? cluster[2 + i % 7] : std::array<double, 2>{tiny(rng), tiny(rng)};
    cluster.push_back(p);
  }
  for (int i = 0; i < 500; ++i) cluster.push_back({0.5, 0.5});
  check(cluster);
  // Short runs (up to 16) holding different points and their repeats (A, B, A):
  // values 10^-12 apart in one grid cell of a box set by two far points.
  for (int size : {5, 9, 16}) {
    std::vector<std::array<double, 2>> mixed{{-1, -1}, {1, 1}};
    for (int i = 0; i < size - 2; ++i) mixed.push_back({(i * 7 % 3) * 1e-12, (i % 2) * 1e-12});
    check(mixed);
  }
  // Points 2^-k (k < 600), some twice: each run's grid splits off a few and
  // leaves the rest in its first cell, down to the last level of refinement.
  std::vector<std::array<double, 2>> geometric;
  for (int k = 0; k < 600; ++k) geometric.push_back({std::ldexp(1.0, -k), std::ldexp(1.0, -k)});
  for (int k = 0; k < 600; k += 7) geometric.push_back({std::ldexp(1.0, -k), std::ldexp(1.0, -k)});
  check(geometric);
  // No repeats: the whole order.
  std::vector<std::array<double, 2>> plain(1000);
  for (auto& p : plain) p = {tiny(rng), tiny(rng)};
  check(plain);
}

TEST_CASE("incremental: the radix sort is std::stable_sort, and the order the same on one and two threads",
          "[incremental]") {
  std::mt19937_64 rng(35);
  // Sizes on both sides of the chunked (parallel) passes, keys with many
  // repeats (stability shows) and keys over all 52 bits.
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{70000}, std::size_t{300001}})
    for (const int key_bits : {8, 52}) {
      std::vector<std::pair<std::uint64_t, std::uint32_t>> items(n);
      for (std::size_t i = 0; i < n; ++i)
        items[i] = {rng() & ((std::uint64_t{1} << key_bits) - 1), static_cast<std::uint32_t>(i)};
      auto expected = items;
      std::stable_sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const int threads : {1, 2}) {
        auto sorted = items;
        tbb::task_arena(threads).execute([&] {
          dewall::detail::radix_sort(sorted, 0, key_bits, [](const auto& item) { return item.first; });
        });
        CHECK(sorted == expected);
      }
      // Key and index packed in one word (brio_order's keys of up to 32 bits):
      // sorted by the key bits alone, the same order.
      if (key_bits <= 32) {
        std::vector<std::uint64_t> words(n);
        for (std::size_t i = 0; i < n; ++i) words[i] = items[i].first << 32 | items[i].second;
        for (const int threads : {1, 2}) {
          auto sorted = words;
          tbb::task_arena(threads).execute(
              [&] { dewall::detail::radix_sort(sorted, 32, 32 + key_bits, [](std::uint64_t w) { return w; }); });
          bool same = sorted.size() == expected.size();
          for (std::size_t i = 0; same && i < n; ++i)
            same = sorted[i] >> 32 == expected[i].first && static_cast<std::uint32_t>(sorted[i]) == expected[i].second;
          CHECK(same);
        }
      }
    }
  const auto points = dewall::test::uniform<3>(200000, rng);
  auto coords = [&](std::size_t i) -> const std::array<double, 3>& { return points[i].x; };
  std::vector<std::uint32_t> one, two;
  tbb::task_arena(1).execute([&] { one = dewall::detail::brio_order<3>(points.size(), coords); });
  tbb::task_arena(2).execute([&] { two = dewall::detail::brio_order<3>(points.size(), coords); });
  CHECK(one == two);
  // 2D keys of 10^5 points fit one word with the index (the packed path).
  const auto plane = dewall::test::uniform<2>(100000, rng);
  auto plane_coords = [&](std::size_t i) -> const std::array<double, 2>& { return plane[i].x; };
  tbb::task_arena(1).execute([&] { one = dewall::detail::brio_order<2>(plane.size(), plane_coords); });
  tbb::task_arena(2).execute([&] { two = dewall::detail::brio_order<2>(plane.size(), plane_coords); });
  CHECK(one == two);
  std::vector<std::uint32_t> sorted_order = one;
  std::sort(sorted_order.begin(), sorted_order.end());
  bool permutation = true;
  for (std::size_t k = 0; k < sorted_order.size(); ++k) permutation = permutation && sorted_order[k] == k;
  CHECK(permutation);
}

TEST_CASE("incremental: the structure is valid after every insertion", "[incremental]") {
  std::mt19937_64 rng(32);
  check_against_cgal<2>(dewall::test::lattice_samples<2>(300, 6, rng), true);
  check_against_cgal<3>(dewall::test::uniform<3>(300, rng), true);
  check_against_cgal<3>(dewall::test::lattice_samples<3>(300, 4, rng), true);
  check_against_cgal<4>(dewall::test::cospherical<4>(true), true);
}

TEST_CASE("incremental: the cavity is every cell in conflict, by brute force", "[incremental]") {
  std::mt19937_64 rng(33);
  // Lattice points: many queries cospherical with cells or coplanar with hull facets.
  for (const auto& points : {dewall::test::lattice_samples<3>(400, 5, rng), dewall::test::uniform<3>(400, rng)}) {
    std::set<std::array<double, 3>> distinct_set;
    std::vector<Point3> distinct;
    for (const auto& p : points)
      if (distinct_set.insert(p.x).second) distinct.push_back(p);
    Incremental_delaunay<3> dt;
    REQUIRE(dt.build(distinct));
    std::vector<Point3> queries = dewall::test::lattice_samples<3>(200, 7, rng);  // inside, on and beyond the hull
    for (auto& q : queries)
      for (int j = 0; j < 3; ++j) q[j] -= 1;
    for (const auto& q : queries) {
      if (distinct_set.count(q.x)) continue;
      // Every cell tested with the kernel's predicates, independently of the
      // engine: a finite cell's perturbed sphere; an infinite cell's hull facet
      // seen from q (orientation with q in the infinite vertex's place), and
      // when q lies in its plane the finite cell behind it (CGAL's rule too).
      auto point_of = [&](std::uint32_t v) { return &distinct[dt.input_index(v)]; };
      auto sphere_holds = [&](std::size_t c) {
        dewall::kernel::Point_refs<3, 5> refs;
        for (int i = 0; i <= 3; ++i) refs[static_cast<std::size_t>(i)] = point_of(dt.cell(c)[static_cast<std::size_t>(i)]);
        refs[4] = &q;
        return dewall::kernel::side_of_oriented_sphere_d_sos<3>(refs) == dewall::kernel::ON_POSITIVE_SIDE;
      };
      std::vector<std::size_t> brute;
      for (std::size_t c = 0; c < dt.slots(); ++c) {
        if (dt.is_free(c)) continue;
        bool conflict;
        const int at = dt.infinite_position(c);
        if (at > 3) {
          conflict = sphere_holds(c);
        } else {
          dewall::kernel::Point_refs<3, 4> refs;
          for (int i = 0; i <= 3; ++i)
            refs[static_cast<std::size_t>(i)] = i == at ? &q : point_of(dt.cell(c)[static_cast<std::size_t>(i)]);
          const auto side = dewall::kernel::orientation_d<3>(refs);
          conflict = side == dewall::kernel::POSITIVE || (side == dewall::kernel::ZERO && sphere_holds(dt.neighbor(c, at)));
        }
        if (conflict) brute.push_back(c);
      }
      CHECK(Incremental_testing_access::cavity(dt, q) == brute);
    }
  }
}

TEST_CASE("incremental: the ridge table glues stars as the directed table does", "[incremental]") {
  // In 2D and 3D only cavities of 127 boundary vertices or more take the
  // ridge table; here every star does.
  std::mt19937_64 rng(36);
  auto check = [](const auto& points) {
    constexpr int D = std::remove_cvref_t<decltype(points[0])>::dimension;
    Incremental_tuning ridge_table = checking();
    ridge_table.ridge_table_only = true;
    Incremental_delaunay<D> directed, ridges(ridge_table);
    REQUIRE(directed.build(points));
    REQUIRE(ridges.build(points));
    CHECK(ridges.statistics().ridge_table_stars == points.size() - (D + 1));
    CHECK(directed.statistics().ridge_table_stars == 0);
    CHECK(same_slots(ridges, directed));
  };
  check(dewall::test::uniform<2>(400, rng));
  check(dewall::test::uniform<3>(300, rng));
}

TEST_CASE("incremental: ridge keys that collide glue the same stars", "[incremental]") {
  // Keys cut to 3 bits match across unrelated ridges of a star: the ridge
  // check (same_ridge) alone must keep the gluing right, in every dimension,
  // serially and in zones (whose stars use each zone's own table).
  std::mt19937_64 rng(37);
  auto check = [](const auto& points, bool zoned = false) {
    constexpr int D = std::remove_cvref_t<decltype(points[0])>::dimension;
    Incremental_tuning ridge_table;
    ridge_table.ridge_table_only = true;
    if (zoned) ridge_table.zoned_insertion_threshold = 64;
    Incremental_tuning collisions = ridge_table;
    collisions.colliding_ridge_keys = true;
    collisions.check_each_insertion = true;
    Incremental_delaunay<D> plain(ridge_table), colliding(collisions);
    REQUIRE(plain.build(points));
    REQUIRE(colliding.build(points));
    INFO("D = " << D << " rounds " << colliding.statistics().zone_rounds);
    if (zoned) CHECK(colliding.statistics().zoned_points > 0);
    CHECK(same_slots(colliding, plain));
  };
  check(dewall::test::uniform<2>(300, rng));
  check(dewall::test::uniform<3>(200, rng));
  check(dewall::test::uniform<4>(100, rng));
  check(dewall::test::uniform<5>(40, rng));
  check(dewall::test::uniform<2>(3000, rng), true);
  check(dewall::test::uniform<3>(1500, rng), true);
}

TEST_CASE("incremental: CGAL's cells in 2D and 3D", "[incremental]") {
  std::mt19937_64 rng(34);
  check_families<2>(1000, rng);
  check_families<3>(600, rng);
}

TEST_CASE("incremental: CGAL's cells in 4D, 5D and 6D", "[incremental]") {
  std::mt19937_64 rng(35);
  check_families<4>(150, rng);  // small: the suite also runs under ASan at -O0
  check_families<5>(60, rng);
  check_families<6>(30, rng);
}

namespace {

/// Builds from the distinct points' first 60% after sorting them by x (the
/// later points lie outside the first ones' box, as dewall::mpi's halo
/// does), the static filter made for the box of all, then insert_more the
/// rest in two batches; the cells must be CGAL's of all points.
template <int D>
void check_insert_more(const std::vector<dewall::kernel::Point_d<D>>& points) {
  std::set<std::array<double, D>> seen;
  std::vector<std::size_t> distinct;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (seen.insert(points[i].x).second) distinct.push_back(i);
  std::stable_sort(distinct.begin(), distinct.end(),
                   [&](std::size_t a, std::size_t b) { return points[a][0] < points[b][0]; });
  const auto coords = [&](std::size_t k) -> const std::array<double, D>& { return points[distinct[k]].x; };
  const auto all_box = dewall::detail::bounding_box<D>(distinct.size(), coords);
  const std::size_t first = distinct.size() * 3 / 5, second = distinct.size() * 4 / 5;
  Incremental_delaunay<D> dt(checking(distinct.size() <= 400));
  REQUIRE(dt.build(first, coords, [&](std::size_t k) { return distinct[k]; }, &all_box));
  dt.insert_more(second - first, [&](std::size_t k) -> const auto& { return coords(first + k); },
                 [&](std::size_t k) { return distinct[first + k]; });
  dt.insert_more(distinct.size() - second, [&](std::size_t k) -> const auto& { return coords(second + k); },
                 [&](std::size_t k) { return distinct[second + k]; });
  CHECK(dt.is_valid());
  const auto ours = finite_cells(dt);
  CHECK(ours.size() == dt.finite_cells());
  CHECK(ours == dewall::test::cgal_delaunay<D>(points));
}

}  // namespace

TEST_CASE("incremental: 2D fans of every size glue as CGAL's cells", "[incremental]") {
  // A wheel: m points on a circle, then its centre (a fan of m cells: above
  // 32 the directed table glues it, below the fan scan), then points inside.
  std::mt19937_64 rng(37);
  for (const std::size_t m : {5, 31, 32, 33, 40, 126, 200}) {
    std::vector<dewall::kernel::Point_d<2>> points;
    for (std::size_t k = 0; k < m; ++k) {
      const double angle = 2 * 3.141592653589793 * static_cast<double>(k) / static_cast<double>(m);
      points.push_back({{std::cos(angle), std::sin(angle)}});
    }
    points.push_back({{0.0, 0.0}});
    for (const auto& p : dewall::test::uniform<2>(30, rng)) points.push_back({{0.5 * p[0] - 0.25, 0.5 * p[1] - 0.25}});
    const auto coords = [&](std::size_t k) -> const std::array<double, 2>& { return points[k].x; };
    const auto box = dewall::detail::bounding_box<2>(points.size(), coords);
    Incremental_delaunay<2> dt(checking());
    REQUIRE(dt.build(m, coords, [](std::size_t k) { return k; }, &box));
    const std::size_t created = dt.statistics().created_cells;
    dt.insert_more(1, [&](std::size_t) -> const auto& { return points[m].x; }, [&](std::size_t) { return m; });
    CHECK(dt.statistics().created_cells - created == m);  // the centre's fan: one cell per polygon edge
    dt.insert_more(30, [&](std::size_t k) -> const auto& { return points[m + 1 + k].x; },
                   [&](std::size_t k) { return m + 1 + k; });
    CHECK(finite_cells(dt) == dewall::test::cgal_delaunay<2>(points));
  }
}

TEST_CASE("incremental: 2D points beyond the hull start along it, with CGAL's cells", "[incremental]") {
  // Points on a circle (every one a hull vertex, every sphere test a near
  // tie): each cavity starts at a hull edge found along the hull, not by the
  // walk. Then the same circle around points inside it, and two circles:
  // hull walks that fail (the point inside) or succeed far from the start.
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<double> angle(0, 2 * 3.141592653589793);
  auto circle = [&](std::size_t n, double radius) {
    std::vector<dewall::kernel::Point_d<2>> points;
    for (std::size_t k = 0; k < n; ++k) {
      const double t = angle(rng);
      points.push_back({{radius * std::cos(t), radius * std::sin(t)}});
    }
    return points;
  };
  const auto on_circle = circle(3000, 1);
  Incremental_delaunay<2> dt;
  REQUIRE(dt.build(on_circle));
  CHECK(dt.statistics().hull_starts > on_circle.size() * 9 / 10);
  CHECK(dt.statistics().walk_steps < on_circle.size());
  check_against_cgal<2>(on_circle);
  check_against_cgal<2>(circle(300, 1), true);

  auto around = circle(1500, 1);
  for (const auto& p : dewall::test::uniform<2>(1500, rng)) around.push_back({{p[0] - 0.5, p[1] - 0.5}});
  check_against_cgal<2>(around);
  auto two = circle(1000, 1);
  for (const auto& p : circle(1000, 0.999)) two.push_back(p);
  check_against_cgal<2>(two);
}

TEST_CASE("incremental: insert_more after build gives the triangulation of all the points", "[incremental]") {
  std::mt19937_64 rng(36);
  check_insert_more<2>(dewall::test::uniform<2>(1000, rng));
  check_insert_more<2>(dewall::test::lattice<2>(400));  // every point ties
  check_insert_more<2>(dewall::test::lattice_samples<2>(600, 4, rng));
  check_insert_more<3>(dewall::test::uniform<3>(600, rng));
  check_insert_more<3>(dewall::test::lattice<3>(300));
  check_insert_more<3>(dewall::test::cospherical<3>(true));
  check_insert_more<4>(dewall::test::uniform<4>(150, rng));
}

TEST_CASE("incremental: on a small lattice the static filter decides exactly, and off it the cascade does", "[incremental]") {
  std::mt19937_64 rng(38);
  const auto distinct = [](auto points) {
    std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
    points.erase(std::unique(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.x == b.x; }),
                 points.end());
    std::shuffle(points.begin(), points.end(), std::mt19937_64(7));
    return points;
  };
  const auto check = [&]<int D>(const std::vector<dewall::kernel::Point_d<D>>& points, bool exact) {
    INFO(points.size() << " points in " << D << "D, exact " << exact);
    Incremental_delaunay<D> dt;
    REQUIRE(dt.build(points));
    CHECK(Incremental_testing_access::static_filter_exact(dt) == exact);
    CHECK(dt.is_valid());
    CHECK(finite_cells(dt) == dewall::test::cgal_delaunay<D>(points));
  };
  using dewall::test::lattice;
  using dewall::test::scaled;
  check(lattice<3>(1000), true);                                // every sphere test ties
  check(scaled<3>(lattice<3>(1000), 0x1p-30, 0.75), true);      // a lattice of unit 2^-30
  check(scaled<3>(lattice<3>(1000), 0.1, 0), false);            // 0.1·k: no small binary unit
  check(distinct(dewall::test::lattice_samples<3>(1500, 1000, rng)), false);  // extent 999: beyond the bound
  check(distinct(dewall::test::lattice_samples<3>(1500, 12, rng)), true);
  check(dewall::test::cospherical<3>(true), true);
  check(lattice<2>(2500), true);
  check(distinct(dewall::test::lattice_samples<2>(2000, 60, rng)), true);
  check(dewall::test::cospherical<2>(true), true);

  // Points off the lattice inserted later (insert_more): the filter stops deciding alone.
  auto points = lattice<3>(512);  // {0 … 7}^3
  std::uniform_int_distribution<int> cell(0, 6);
  for (int k = 0; k < 40; ++k)
    points.push_back({{cell(rng) + 0.5, cell(rng) + 0.5, static_cast<double>(cell(rng))}});
  points = distinct(points);
  const auto first = static_cast<std::size_t>(
      std::stable_partition(points.begin(), points.end(), [](const auto& p) { return p[0] == std::floor(p[0]); }) -
      points.begin());
  const auto coords = [&](std::size_t k) -> const std::array<double, 3>& { return points[k].x; };
  const auto box = dewall::detail::bounding_box<3>(points.size(), coords);
  Incremental_delaunay<3> dt(checking());
  REQUIRE(dt.build(first, coords, [](std::size_t k) { return k; }, &box));
  CHECK(Incremental_testing_access::static_filter_exact(dt));
  dt.insert_more(points.size() - first, [&](std::size_t k) -> const auto& { return coords(first + k); },
                 [&](std::size_t k) { return first + k; });
  CHECK(!Incremental_testing_access::static_filter_exact(dt));
  CHECK(finite_cells(dt) == dewall::test::cgal_delaunay<3>(points));

  // Points on a coarser lattice inserted later keep it exact: the half-integer
  // points of {0, 0.5, …, 3.5}^3 first, then its integer points.
  auto halves = dewall::test::scaled<3>(lattice<3>(512), 0.5, 0);
  const auto integral = [](const auto& p) { return p[0] == std::floor(p[0]) && p[1] == std::floor(p[1]) && p[2] == std::floor(p[2]); };
  const auto on_halves = static_cast<std::size_t>(
      std::stable_partition(halves.begin(), halves.end(), [&](const auto& p) { return !integral(p); }) - halves.begin());
  const auto half_coords = [&](std::size_t k) -> const std::array<double, 3>& { return halves[k].x; };
  const auto half_box = dewall::detail::bounding_box<3>(halves.size(), half_coords);
  Incremental_delaunay<3> coarser;
  REQUIRE(coarser.build(on_halves, half_coords, [](std::size_t k) { return k; }, &half_box));
  CHECK(Incremental_testing_access::static_filter_exact(coarser));
  coarser.insert_more(halves.size() - on_halves, [&](std::size_t k) -> const auto& { return half_coords(on_halves + k); },
                      [&](std::size_t k) { return on_halves + k; });
  CHECK(Incremental_testing_access::static_filter_exact(coarser));
  CHECK(coarser.is_valid());
  CHECK(finite_cells(coarser) == dewall::test::cgal_delaunay<3>(halves));
}

TEST_CASE("incremental: too few points or a flat set build nothing", "[incremental]") {
  Incremental_delaunay<3> dt;
  const std::vector<Point3> three{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}};
  CHECK(!dt.build(three));
  std::vector<Point3> flat;
  for (int i = 0; i < 50; ++i) flat.push_back({{static_cast<double>(i % 7), static_cast<double>(i / 7), 0}});
  CHECK(!dt.build(flat));
  flat.push_back({{0.5, 0.5, 1e-300}});  // one point off the plane makes it full-dimensional
  CHECK(dt.build(flat));
  CHECK(dt.is_valid());
}

namespace {

/// Points on a torus (ring radius 1, tube 0.3): a surface whose hole the
/// zones' planes cut, and many hull points.
std::vector<Point3> torus_points(std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  std::vector<Point3> p(n);
  for (auto& q : p) {
    const double a = angle(rng), b = angle(rng);
    q.x = {(1 + 0.3 * std::cos(b)) * std::cos(a), (1 + 0.3 * std::cos(b)) * std::sin(a), 0.3 * std::sin(b)};
  }
  return p;
}

/// Builds `points` (distinct) with zoned insertion from `threshold` points on,
/// in an arena of `threads` threads.
template <int D>
void build_zoned(Incremental_delaunay<D>& dt, const std::vector<dewall::kernel::Point_d<D>>& points,
                 std::size_t threshold, int threads, double slots_scale, std::size_t probe,
                 double near_cut_spacings = 2) {
  Incremental_tuning tuning = dt.tuning();  // (its check_each_insertion kept)
  tuning.filter_order_window = 256;  // both orders of the static filter's bounds, on few points
  tuning.zoned_insertion_threshold = threshold;
  tuning.zone_probe = probe;
  tuning.near_cut_spacings = near_cut_spacings;
  tuning.zone_slots_scale = slots_scale;
  dt = Incremental_delaunay<D>(tuning);
  tbb::task_arena arena(threads);
  arena.execute([&] { REQUIRE(dt.build(std::span<const dewall::kernel::Point_d<D>>(points))); });
}

/// Zoned insertion on one and on two threads: CGAL's cells, valid after
/// every round and serial insertion, and the same cells in the same slots
/// (the output order) on both. Returns the one-thread build's counters.
template <int D>
Incremental_statistics check_zoned(const std::vector<dewall::kernel::Point_d<D>>& given, double slots_scale = 1,
                                   std::size_t probe = 2048, double near_cut_spacings = 2) {
  std::set<std::array<double, D>> seen;
  std::vector<dewall::kernel::Point_d<D>> points;
  for (const auto& p : given)
    if (seen.insert(p.x).second) points.push_back(p);
  Incremental_delaunay<D> one(checking()), two;
  build_zoned(one, points, 64, 1, slots_scale, probe, near_cut_spacings);
  build_zoned(two, points, 64, 2, slots_scale, probe, near_cut_spacings);
  const auto cells = finite_cells(one);
  CHECK(cells == dewall::test::cgal_delaunay<D>(points));
  CHECK(one.finite_cells() == cells.size());
  CHECK(two.is_valid());
  CHECK(same_slots(one, two));
  CHECK(one.finite_cells() == two.finite_cells());
  CHECK(one.statistics().zoned_points == two.statistics().zoned_points);
  CHECK(one.statistics().zone_rounds == two.statistics().zone_rounds);
  CHECK(one.statistics().near_cut_points == two.statistics().near_cut_points);
  return one.statistics();
}

/// n points on the unit circle: in 2D every one on the hull.
std::vector<dewall::kernel::Point_d<2>> circle_points(std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(0, 2 * M_PI);
  std::vector<dewall::kernel::Point_d<2>> p(n);
  for (auto& q : p) {
    const double a = angle(rng);
    q.x = {std::cos(a), std::sin(a)};
  }
  return p;
}

}  // namespace

TEST_CASE("incremental: zoned insertion gives CGAL's cells, the same slots on one and two threads", "[incremental][heavy]") {
  std::mt19937_64 rng(41);
  // Much of a uniform set goes through the zones (on so few points many
  // cavities meet the cut); the rest waits and is inserted one by one.
  const auto uniform3 = dewall::test::uniform<3>(3000, rng);
  const Incremental_statistics with_near_cut = check_zoned<3>(uniform3);
  CHECK(with_near_cut.semi_static_first_windows == 0);  // the box's bound decides uniform points
  CHECK(with_near_cut.zoned_points > 3000 / 4);
  // Points beside the cut wait untried (near_cut), unless told not to.
  CHECK(with_near_cut.near_cut_points > 0);
  const Incremental_statistics all_tried = check_zoned<3>(uniform3, 1, 2048, 0);
  CHECK(all_tried.near_cut_points == 0);
  CHECK(all_tried.zoned_points > 3000 / 4);
  const Incremental_statistics uniform2 = check_zoned<2>(dewall::test::uniform<2>(3000, rng));
  CHECK(uniform2.zoned_points > 3000 / 8);
  CHECK(uniform2.zone_rounds > 0);
  // In 2D a point beyond the hull waits: on a circle, where every point
  // lies there, the rounds end before their zones start.
  std::mt19937_64 circle_rng(43);  // its own: the sets below stay those the test was written with
  const Incremental_statistics circle = check_zoned<2>(circle_points(3000, circle_rng));
  CHECK(circle.zone_rounds == 0);
  CHECK(circle.zoned_points == 0);
  // Ties everywhere, duplicates, cospherical and flat sets, a surface, extreme scales.
  check_zoned<3>(dewall::test::lattice<3>(2000));
  check_zoned<2>(dewall::test::lattice_samples<2>(3000, 6, rng));
  check_zoned<3>(dewall::test::lattice_samples<3>(2000, 4, rng));
  check_zoned<3>(dewall::test::planes<3>(2000, 3, rng));
  const auto torus = torus_points(2000, rng);
  const std::size_t torus_zoned = check_zoned<3>(torus).zoned_points;
  // Zones whose first tries fail too often give up, and the rest is inserted one by one.
  CHECK(check_zoned<3>(torus, 1, 64).zoned_points < torus_zoned);
  check_zoned<3>(dewall::test::scaled<3>(dewall::test::lattice_samples<3>(1500, 4, rng), 0x1p-600, 0));
  // A small torus in a wide box (its corners): the box's bound leaves most
  // sphere tests, and the semi-static bound goes first.
  std::mt19937_64 small_torus_rng(44);  // its own: the sets below stay those the test was written with
  auto small_torus = torus_points(2000, small_torus_rng);
  for (auto& p : small_torus)
    for (double& x : p.x) x *= 1e-4;
  for (int corner = 0; corner < 8; ++corner)
    small_torus.push_back({{corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0}});
  CHECK(check_zoned<3>(small_torus).semi_static_first_windows > 0);
  check_zoned<4>(dewall::test::uniform<4>(1200, rng));
  check_zoned<4>(dewall::test::lattice<4>(1000));
  // Zones that run out of slots leave their points to the next round.
  CHECK(check_zoned<3>(uniform3, 0.25).zoned_points < check_zoned<3>(uniform3).zoned_points);
}

TEST_CASE("incremental: insert_more after zoned insertion, and zones of no points", "[incremental]") {
  std::mt19937_64 rng(42);
  const auto points = dewall::test::uniform<3>(2500, rng);
  const auto more = dewall::test::uniform<3>(400, rng);
  Incremental_delaunay<3> dt;
  build_zoned(dt, points, 64, 2, 1, 2048);
  REQUIRE(dt.statistics().zoned_points > 0);
  // Inside the first points' box (the static filter was made for it).
  std::vector<Point3> inside;
  for (const auto& p : more) inside.push_back({{p.x[0] * 0.5 + 0.25, p.x[1] * 0.5 + 0.25, p.x[2] * 0.5 + 0.25}});
  dt.insert_more(inside.size(), [&](std::size_t k) -> const std::array<double, 3>& { return inside[k].x; },
                 [&](std::size_t k) { return points.size() + k; });
  std::vector<Point3> all = points;
  all.insert(all.end(), inside.begin(), inside.end());
  CHECK(dt.is_valid());
  CHECK(finite_cells(dt) == dewall::test::cgal_delaunay<3>(all));
  // Thresholds of 0: every point after the sample is zoned, rounds end when none is left.
  for (const std::size_t n : {4, 5, 20, 300}) {
    const std::vector<Point3> few(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(n));
    Incremental_delaunay<3> small(checking());
    build_zoned(small, few, 0, 2, 1, 2048);
    CHECK(finite_cells(small) == dewall::test::cgal_delaunay<3>(few));
  }
}

#if defined(DEWALL_CAN_RELEASE_PAGES) && defined(__linux__)  // (elsewhere released pages need not read as zeros)
TEST_CASE("incremental: releasing a range of slots keeps every slot outside it", "[incremental]") {
  // 50,000 points: about 335,000 slots of 32 bytes, above release_slots' 8 MB floor.
  std::mt19937_64 rng(77);
  const auto points = dewall::test::uniform<3>(50000, rng);
  Incremental_delaunay<3> dt;
  REQUIRE(dt.build(points.size(), [&](std::size_t k) -> const std::array<double, 3>& { return points[k].x; },
                   [](std::size_t k) { return k; }));
  REQUIRE(dt.slots() * 32 >= (std::size_t{8} << 20));
  std::vector<std::array<std::uint32_t, 4>> before(dt.slots());
  for (std::size_t c = 0; c < dt.slots(); ++c) before[c] = dt.cell(c);
  dt.finish_for_reading();
  // Ranges whose ends fall inside pages (a 4 KB page holds 128 records), as
  // the hand-over's blocks do where the array does not start on a page; the
  // first two meet, as neighbouring blocks do. After each release, every slot
  // outside the ranges released so far must be unchanged (the page the first
  // two share too, until both are released).
  const std::array<std::array<std::size_t, 2>, 3> ranges{{{1000 + 37, 40000 + 5}, {40000 + 5, 90000 + 101}, {150000 + 3, dt.slots()}}};
  std::size_t zeroed = 0, changed_outside = 0;
  for (std::size_t r = 0; r < ranges.size(); ++r) {
    dt.release_slots(ranges[r][0], ranges[r][1]);
    for (std::size_t c = 0; c < dt.slots(); ++c) {
      const bool released = std::any_of(ranges.begin(), ranges.begin() + static_cast<std::ptrdiff_t>(r) + 1,
                                        [&](const auto& range) { return c >= range[0] && c < range[1]; });
      changed_outside += !released && dt.cell(c) != before[c];
    }
  }
  for (const auto& [first, last] : ranges)
    for (std::size_t c = first; c < last; ++c)
      zeroed += dt.cell(c) == std::array<std::uint32_t, 4>{} && before[c] != std::array<std::uint32_t, 4>{};
  CHECK(changed_outside == 0);
  CHECK(zeroed > 100000);  // the pages went back (else the test checks nothing)
}
#endif

TEST_CASE("incremental: a tuning out of range is refused", "[incremental]") {
  const auto refused = [](auto change) {
    Incremental_tuning tuning;
    change(tuning);
    CHECK_THROWS_AS(Incremental_delaunay<3>(tuning), std::invalid_argument);
  };
  refused([](Incremental_tuning& t) { t.zone_probe = 0; });
  refused([](Incremental_tuning& t) { t.near_cut_spacings = -1; });
  refused([](Incremental_tuning& t) { t.near_cut_spacings = std::numeric_limits<double>::quiet_NaN(); });
  refused([](Incremental_tuning& t) { t.zone_slots_scale = 0; });
  refused([](Incremental_tuning& t) { t.zone_slots_scale = std::numeric_limits<double>::infinity(); });
  refused([](Incremental_tuning& t) { t.filter_order_window = 0; });
  Incremental_tuning no_zones;
  no_zones.zoned_insertion_threshold = std::numeric_limits<std::size_t>::max();
  no_zones.near_cut_spacings = 0;
  CHECK_NOTHROW(Incremental_delaunay<3>(no_zones));
}
