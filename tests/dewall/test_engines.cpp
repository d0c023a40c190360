// The engines (dewall/options.hpp): DeWall, the incremental construction
// compiled into the library (CGAL's), the hybrid of the two (walls, then
// regions) and the automatic choice give the same simplices; the automatic
// engine hands over on points on a sphere and not on volume data; Statistics
// says which engine built the output.
#include <catch2/catch.hpp>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <optional>
#include <span>
#include <random>
#include <stdexcept>
#include <vector>

#include "dewall/dewall.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/point_array.hpp"
#include "support/cgal_reference.hpp"
#include "support/kernel_archetype.hpp"
#include "support/rounded_kernel.hpp"

namespace {

using dewall::Engine;
using dewall::Options;

template <int D>
std::vector<dewall::kernel::Point_d<D>> generated(dewall::io::Point_kind kind, std::size_t n, std::uint64_t seed,
                                                  int planes = 0) {
  dewall::io::Generator_options shape;
  shape.planes = planes;
  return dewall::kernel::points_from_coordinates<D>(dewall::io::generate_points(kind, n, D, seed, shape).coordinates);
}

/// Every simplex positively oriented (the incremental engine reorients CGAL's cells).
template <int D>
bool positively_oriented(const std::vector<dewall::kernel::Point_d<D>>& points,
                         const std::vector<dewall::Simplex<D>>& simplices) {
  for (const auto& s : simplices) {
    std::array<const dewall::kernel::Point_d<D>*, D + 1> p;
    for (int i = 0; i <= D; ++i) p[static_cast<std::size_t>(i)] = &points[s[static_cast<std::size_t>(i)]];
    if (dewall::kernel::orientation_d<D>(p) != dewall::kernel::POSITIVE) return false;
  }
  return true;
}

/// Runs every engine on `points`: each must give CGAL's simplices, positively
/// oriented; returns the engine the automatic choice used with regions of
/// `region_points` (40 when not given; the default size, at least 16384
/// points, would make these inputs one region, which the automatic choice
/// leaves to the incremental engine, also checked). The forced hybrid runs
/// with regions of `region_points` (small: many walls and region boundaries),
/// and not at all without them.
template <int D>
Engine check_engines(const std::vector<dewall::kernel::Point_d<D>>& points,
                     std::optional<std::size_t> region_points = 40) {
  const auto expected = dewall::test::cgal_delaunay<D>(points);
  const auto forced = dewall::triangulate<D>(points, Options{.engine = Engine::dewall});
  const auto incremental = dewall::triangulate<D>(points, Options{.engine = Engine::cgal});
  const auto own = dewall::triangulate<D>(points, Options{.engine = Engine::incremental});
  const auto automatic = dewall::triangulate<D>(points, Options{.region_points = region_points.value_or(40)});
  const auto one_region = dewall::triangulate<D>(points);
  CHECK(one_region.statistics.engine == dewall::default_incremental_engine(D));
  CHECK(one_region.simplices == (dewall::default_incremental_engine(D) == Engine::cgal ? incremental : own).simplices);
  if (region_points) {
    // The same output, in the same order, on one thread.
    const auto hybrid =
        dewall::triangulate<D>(points, Options{.engine = Engine::hybrid, .region_points = *region_points});
    const auto hybrid_serial = dewall::triangulate<D>(
        points, Options{.parallel_depth = 0, .engine = Engine::hybrid, .region_points = *region_points});
    CHECK(dewall::test::as_set<D>(hybrid.simplices) == expected);
    CHECK(hybrid.simplices.size() == expected.size());
    CHECK(hybrid.simplices == hybrid_serial.simplices);
    CHECK(positively_oriented<D>(points, hybrid.simplices));
    CHECK(hybrid.statistics.engine == Engine::hybrid);
  }
  CHECK(dewall::test::as_set<D>(forced.simplices) == expected);
  CHECK(dewall::test::as_set<D>(incremental.simplices) == expected);
  CHECK(dewall::test::as_set<D>(automatic.simplices) == expected);
  CHECK(incremental.simplices.size() == expected.size());
  CHECK(automatic.simplices.size() == expected.size());
  CHECK(positively_oriented<D>(points, incremental.simplices));
  CHECK(dewall::test::as_set<D>(own.simplices) == expected);
  CHECK(own.simplices.size() == expected.size());
  CHECK(positively_oriented<D>(points, own.simplices));
  CHECK(own.statistics.engine == Engine::incremental);
  CHECK(forced.statistics.engine == Engine::dewall);
  CHECK(incremental.statistics.engine == Engine::cgal);
  CHECK(incremental.statistics.distinct_points == forced.statistics.distinct_points);
  CHECK(own.statistics.distinct_points == forced.statistics.distinct_points);  // the repeats its own order dropped
  CHECK(automatic.statistics.distinct_points == forced.statistics.distinct_points);
  return automatic.statistics.engine;
}

}  // namespace

TEST_CASE("engines: points on a sphere hand over to the incremental construction", "[engine]") {
  // Every search examines about half the points: DeWall is quadratic here,
  // and so are the hybrid's walls and region filter (checked below, smaller).
  CHECK(check_engines<3>(generated<3>(dewall::io::Point_kind::sphere, 600, 5), {}) == dewall::default_incremental_engine(3));
  CHECK(check_engines<3>(generated<3>(dewall::io::Point_kind::lattice_sphere, 600, 0), {}) == dewall::default_incremental_engine(3));
  CHECK(check_engines<2>(generated<2>(dewall::io::Point_kind::sphere, 3000, 6), {}) == dewall::default_incremental_engine(2));
  // Exactly cospherical regions: every cell's sphere is the whole sphere.
  check_engines<3>(generated<3>(dewall::io::Point_kind::lattice_sphere, 150, 0));
}

TEST_CASE("engines: volume data stays with the hybrid", "[engine]") {
  CHECK(check_engines<3>(generated<3>(dewall::io::Point_kind::uniform, 3000, 7)) == Engine::hybrid);
  CHECK(check_engines<3>(generated<3>(dewall::io::Point_kind::bubbles, 3000, 8)) == Engine::hybrid);
  CHECK(check_engines<2>(generated<2>(dewall::io::Point_kind::uniform, 3000, 9)) == Engine::hybrid);
}

TEST_CASE("engines: regions whose spheres leave them hand over, others do not", "[engine]") {
  // Two layers: most cells of a region span both layers with spheres as large
  // as the region, so the region saves no search (wall.hpp). Regions of 3000
  // points: about 10,000 cells each, above the size the rule looks at.
  const auto layers = generated<3>(dewall::io::Point_kind::planes, 12000, 17, 2);
  const auto expected = dewall::test::cgal_delaunay<3>(layers);
  const auto t = dewall::triangulate<3>(layers, Options{.region_points = 3000});
  CHECK(t.statistics.engine == dewall::default_incremental_engine(3));
  CHECK(t.statistics.searches_before_handover >= 1);
  CHECK(dewall::test::as_set<3>(t.simplices) == expected);
  CHECK(dewall::triangulate<3>(layers, Options{.engine = Engine::hybrid, .region_points = 3000}).statistics.engine ==
        Engine::hybrid);
  for (const auto kind : {dewall::io::Point_kind::uniform, dewall::io::Point_kind::bubbles})
    CHECK(dewall::triangulate<3>(generated<3>(kind, 12000, 18), Options{.region_points = 3000}).statistics.engine ==
          Engine::hybrid);
}

TEST_CASE("engines: the hybrid's regions on degenerate inputs", "[engine]") {
  // Lattices: cospherical sets everywhere, ties on every split, region
  // boundaries through lattice planes; planes: the paper's Figure 7.
  check_engines<3>(generated<3>(dewall::io::Point_kind::grid, 1000, 0));
  check_engines<3>(generated<3>(dewall::io::Point_kind::planes, 1500, 13));
  check_engines<2>(generated<2>(dewall::io::Point_kind::grid, 900, 0));
  check_engines<2>(generated<2>(dewall::io::Point_kind::bubbles, 2000, 14));
  // The regions by the other incremental construction (CGAL's; ours by
  // default): the same simplices, in that construction's order per region.
  for (const auto& lattice : {generated<3>(dewall::io::Point_kind::grid, 1000, 0)}) {
    const Engine other = dewall::default_region_engine(3) == Engine::cgal ? Engine::incremental : Engine::cgal;
    const auto t = dewall::triangulate<3>(
        lattice, Options{.engine = Engine::hybrid, .incremental_engine = other, .region_points = 40});
    CHECK(dewall::test::as_set<3>(t.simplices) == dewall::test::cgal_delaunay<3>(lattice));
    CHECK(t.simplices.size() == dewall::test::cgal_delaunay<3>(lattice).size());
  }
  // Regions of every size, including ones too small or too flat for a
  // triangulation of their own (left to DeWall).
  const auto points = generated<3>(dewall::io::Point_kind::grid, 343, 0);
  const auto expected = dewall::test::cgal_delaunay<3>(points);
  for (std::size_t region : {1, 4, 5, 9, 30, 100, 200}) {
    const auto t = dewall::triangulate<3>(points, Options{.engine = Engine::hybrid, .region_points = region});
    CHECK(dewall::test::as_set<3>(t.simplices) == expected);
    CHECK(t.simplices.size() == expected.size());
  }
}

TEST_CASE("engines: the same list for every number of threads", "[engine][threads][heavy]") {
  // Options::threads: the list, not only the set, is a function of the points.
  const std::vector<std::vector<dewall::kernel::Point_d<3>>> inputs{
      generated<3>(dewall::io::Point_kind::uniform, 20000, 15),  // 8 regions of the default size
      generated<3>(dewall::io::Point_kind::bubbles, 6000, 16), generated<3>(dewall::io::Point_kind::grid, 1000, 0)};
  for (const auto& points : inputs)
    for (Engine engine : {Engine::automatic, Engine::dewall}) {
      const auto reference = dewall::triangulate<3>(points, Options{.threads = 1, .engine = engine});
      for (int threads : {2, 3, 8, 0})
        CHECK(dewall::triangulate<3>(points, Options{.threads = threads, .engine = engine}).simplices ==
              reference.simplices);
    }
  CHECK_THROWS_AS(dewall::triangulate<3>(inputs[2], Options{.threads = -1}), std::invalid_argument);
}

namespace {

/// The simplices handed to triangulate_to's sink, checking that no two calls overlap.
template <int D>
std::vector<dewall::Simplex<D>> streamed(const std::vector<dewall::kernel::Point_d<D>>& points, Options options,
                                         dewall::Statistics* statistics = nullptr) {
  options.stream = true;
  std::vector<dewall::Simplex<D>> out;
  std::atomic<bool> inside{false};
  bool overlapped = false;
  const auto st = dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<D>>(
      std::span<const dewall::kernel::Point_d<D>>(points),
      [&](const dewall::Simplex<D>& s) {
        if (inside.exchange(true)) overlapped = true;
        out.push_back(s);
        inside = false;
      },
      options);
  CHECK(!overlapped);
  CHECK(st.simplices == out.size());
  if (statistics) *statistics = st;
  return out;
}

}  // namespace

TEST_CASE("engines: streaming gives the collected set, and the collected list on one thread", "[engine][stream][heavy]") {
  struct Case {
    std::vector<dewall::kernel::Point_d<3>> points;
    std::size_t region_points;
  };
  const std::vector<Case> cases{
      {generated<3>(dewall::io::Point_kind::uniform, 40000, 15), 0},  // regions of 16384 points
      {generated<3>(dewall::io::Point_kind::uniform, 8000, 19), 300},
      {generated<3>(dewall::io::Point_kind::bubbles, 6000, 16), 400},
      {generated<3>(dewall::io::Point_kind::grid, 1000, 0), 60},
      {generated<3>(dewall::io::Point_kind::planes, 12000, 17, 2), 3000},  // hands over at its first region
      {generated<3>(dewall::io::Point_kind::sphere, 600, 5), 40}};         // hands over in the walls
  for (const auto& c : cases)
    for (Engine engine : {Engine::automatic, Engine::hybrid, Engine::dewall, Engine::cgal}) {
      const Options options{.engine = engine, .region_points = c.region_points};
      Options one = options;
      one.threads = 1;
      dewall::Statistics collected_stats, streamed_stats;
      const auto collected = dewall::triangulate<3>(c.points, one);
      collected_stats = collected.statistics;
      const auto expected = dewall::test::as_set<3>(collected.simplices);
      CHECK(expected == dewall::test::cgal_delaunay<3>(c.points));
      // One thread: the same list, unless the collected run handed over after
      // the stream's decision was settled (then the stream kept DeWall's order).
      const auto serial = streamed<3>(c.points, one, &streamed_stats);
      if (streamed_stats.engine == collected_stats.engine) CHECK(serial == collected.simplices);
      CHECK(dewall::test::as_set<3>(serial) == expected);
      CHECK(serial.size() == expected.size());
      for (int threads : {2, 3}) {
        Options many = options;
        many.threads = threads;
        const auto parallel = streamed<3>(c.points, many);
        CHECK(dewall::test::as_set<3>(parallel) == expected);
        CHECK(parallel.size() == expected.size());  // nothing held back twice, nothing lost
      }
    }
}

TEST_CASE("engines: streaming's default regions grow with the input from 2^21 points on", "[engine][stream]") {
  const Options collecting{}, streaming{.stream = true};
  CHECK(dewall::region_points_for(streaming, 100000) == 25000);
  CHECK(dewall::region_points_for(streaming, 1000000) == dewall::largest_default_streaming_region);
  CHECK(dewall::region_points_for(streaming, std::size_t{1} << 22) == 65536);
  CHECK(dewall::region_points_for(streaming, 10000000) == 156250);
  // Rounded up: six levels of halves of 10^7 + 63 points hold at most 156251.
  CHECK(dewall::region_points_for(streaming, 10000063) == 156251);
  CHECK(dewall::region_points_for(streaming, 100000000) == dewall::largest_streaming_region_at_scale);
  std::size_t last = 0;
  for (std::size_t n = 1000; n < (std::size_t{1} << 34); n = n * 3 / 2) {
    INFO(n);
    const std::size_t region = dewall::region_points_for(streaming, n);
    CHECK(region >= last);  // never smaller for more points
    CHECK(region <= dewall::largest_streaming_region_at_scale);
    // Smaller than a collected region as long as that one is below its cap.
    if (dewall::region_points_for(collecting, n) < dewall::largest_default_region)
      CHECK(region <= dewall::region_points_for(collecting, n));
    last = region;
  }
}

TEST_CASE("engines: a stream settled at its first region never hands over", "[engine][stream][heavy]") {
  // A budget spent after the first region: uniform points in [0, 2) × [0, 1)²
  // beside points on a sphere, so the top wall cuts the uniform points (a
  // cheap wall), side 1 is uniform (built first on one thread: its regions
  // are kept) and side 2 holds the sphere, where the tests of the slabs' and
  // the regions' spheres look at every point. Collected, the run hands over;
  // streamed, the first region kept settles the decision and the run finishes
  // with the walls, passing on what it held.
  auto points = generated<3>(dewall::io::Point_kind::uniform, 4000, 20);
  for (auto& p : points) p.x[0] *= 2;
  for (auto p : generated<3>(dewall::io::Point_kind::sphere, 2000, 21)) {
    p.x[0] += 4.5;
    points.push_back(p);
  }
  // (Passes with a budget of 100 to 5000 candidates per search: a wide margin.)
  const Options options{.threads = 1, .handover_candidates_per_search = 300, .region_points = 200};
  const auto collected = dewall::triangulate<3>(points, options);
  dewall::Statistics st;
  const auto serial = streamed<3>(points, options, &st);
  CHECK(collected.statistics.engine == dewall::default_incremental_engine(3));
  CHECK(st.engine == Engine::hybrid);
  CHECK(dewall::test::as_set<3>(serial) == dewall::test::as_set<3>(collected.simplices));
  CHECK(serial.size() == collected.simplices.size());
}

TEST_CASE("engines: a streaming task keeps one block, and a held stream passes nothing on until released",
          "[engine][stream]") {
  struct Recorder final : dewall::detail::Simplex_output<3> {
    std::vector<std::size_t> block_sizes;
    std::vector<dewall::detail::Built_simplex<3>> all;
    void put(std::span<const dewall::detail::Built_simplex<3>> block) override {
      block_sizes.push_back(block.size());
      all.insert(all.end(), block.begin(), block.end());
    }
  };
  const auto simplex = [](std::uint32_t i) { return dewall::detail::Built_simplex<3>{{i, i + 1, i + 2, i + 3}, 1}; };
  Recorder open_output, held_output;
  dewall::detail::Simplex_stream<3> open(open_output, false), held(held_output, true);
  dewall::detail::Built_simplices<3> a(&open), b(&held);
  for (std::uint32_t i = 0; i < 20000; ++i) {
    a.push_back(simplex(i));
    b.push_back(simplex(i));
  }
  // Full blocks went on as they filled; the rest waits for flush().
  CHECK(open_output.block_sizes == std::vector<std::size_t>{8192, 8192});
  CHECK(held_output.block_sizes.empty());
  a.flush();
  b.flush();
  held.release();
  CHECK(open_output.all.size() == 20000);
  CHECK(held_output.all.size() == 20000);
  for (std::uint32_t i = 0; i < 20000; ++i) {
    CHECK(open_output.all[i].vertices[0] == i);
    CHECK(held_output.all[i].vertices[0] == i);
  }
  CHECK(a.size() == 20000);
}

TEST_CASE("engines: an output that fails stops the stream for every task", "[engine][stream]") {
  struct Failing final : dewall::detail::Simplex_output<3> {
    int calls = 0;
    void put(std::span<const dewall::detail::Built_simplex<3>>) override {
      ++calls;
      throw std::runtime_error("disk full");
    }
  };
  using Stream = dewall::detail::Simplex_stream<3>;
  const std::vector<dewall::detail::Built_simplex<3>> block{{{0, 1, 2, 3}, 0}};
  Failing open_output, held_output;
  Stream open(open_output, false), held(held_output, true);
  CHECK_THROWS_WITH(open.put(block), "disk full");
  // Another task's next block: stopped with the output's exception, and the
  // output is not called again.
  CHECK_THROWS_WITH(open.put(block), "disk full");
  CHECK(open_output.calls == 1);
  held.put(block);
  CHECK_THROWS_WITH(held.release(), "disk full");
  CHECK_THROWS_WITH(held.put(block), "disk full");
  held.release();  // nothing more is passed on
  CHECK(held_output.calls == 1);

  // Through the engine, on both cores: the sink's exception is the one the
  // caller sees, failing in the top wall's simplices (before the halves run
  // as tasks) or in the regions' (while both tasks stream).
  const auto points = generated<3>(dewall::io::Point_kind::uniform, 40000, 21);
  for (std::size_t fail_at : {100, 20000, 200000}) {
    std::size_t calls = 0;
    CHECK_THROWS_WITH(dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<3>>(
                          std::span<const dewall::kernel::Point_d<3>>(points),
                          [&](const dewall::Simplex<3>&) {
                            if (++calls == fail_at) throw std::runtime_error("sink failed");
                          },
                          Options{.threads = 2, .engine = Engine::hybrid, .stream = true}),
                      "sink failed");
  }
}

TEST_CASE("engines: a cancelled caller's TBB work does not cut the triangulation short", "[engine][threads]") {
  // Run from a task whose group the sink cancels at its first call (the top
  // wall's simplices, passed on before its halves start): without a context
  // of its own the recursion's parallel tasks inherited the cancellation and
  // were skipped, silently (measured: 9496 of 268024 simplices).
  const auto points = generated<3>(dewall::io::Point_kind::uniform, 40000, 22);
  const auto expected = dewall::triangulate<3>(points, Options{.threads = 1});
  tbb::task_arena arena(2);
  std::vector<dewall::Simplex<3>> inside;
  arena.execute([&] {
    tbb::task_group group;
    group.run([&] {
      dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<3>>(
          std::span<const dewall::kernel::Point_d<3>>(points),
          [&](const dewall::Simplex<3>& s) {
            if (inside.empty()) group.cancel();
            inside.push_back(s);
          },
          Options{.engine = Engine::hybrid, .stream = true});
    });
    group.wait();
  });
  CHECK(inside.size() == expected.simplices.size());
  CHECK(dewall::test::as_set<3>(inside) == dewall::test::as_set<3>(expected.simplices));
}

TEST_CASE("engines: the incremental engine in 4D and 5D, with duplicates", "[engine]") {
  std::mt19937_64 rng(10);
  std::uniform_int_distribution<int> coordinate(0, 3);
  std::vector<dewall::kernel::Point_d<4>> p4(300);
  for (auto& p : p4)
    for (int j = 0; j < 4; ++j) p[j] = coordinate(rng);  // a lattice: duplicates and ties
  check_engines<4>(p4);
  check_engines<5>(generated<5>(dewall::io::Point_kind::uniform, 200, 11));
}

TEST_CASE("engines: the budget decides, and the statistics say so", "[engine]") {
  const auto points = generated<3>(dewall::io::Point_kind::sphere, 2000, 12);
  // A budget below what any search needs hands over once the allowance is
  // spent: 4^(d-2)·n = 8000 candidates here; on points on a sphere a search
  // (the walls' or a test of a sphere's emptiness) looks at hundreds.
  const auto t = dewall::triangulate<3>(points, Options{.handover_candidates_per_search = 0.5, .region_points = 100});
  CHECK(t.statistics.engine == dewall::default_incremental_engine(3));
  CHECK(t.statistics.searches_before_handover >= 1);
  CHECK(t.statistics.searches_before_handover <= 1000);
  CHECK(dewall::test::as_set<3>(t.simplices) == dewall::test::cgal_delaunay<3>(points));
  // Wall levels come from walls: the incremental engines, which build none, refuse a sink that asks for them.
  for (const auto engine : {Engine::cgal, Engine::incremental})
    CHECK_THROWS_AS(dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<3>>(
                        std::span<const dewall::kernel::Point_d<3>>(points), [](const dewall::Simplex<3>&, int) {},
                        Options{.engine = engine}),
                    std::invalid_argument);
  // Bad input is reported the same way by every engine.
  const std::vector<dewall::kernel::Point_d<3>> flat{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{1, 1, 0}}};
  CHECK_THROWS_AS(dewall::triangulate<3>(flat, Options{.engine = Engine::cgal}), dewall::Invalid_input);
  CHECK_THROWS_AS(dewall::triangulate<3>(flat, Options{.engine = Engine::incremental}), dewall::Invalid_input);
  // The regions' construction must be an incremental one.
  CHECK_THROWS_AS(dewall::triangulate<3>(points, Options{.incremental_engine = Engine::dewall}), std::invalid_argument);
  CHECK_THROWS_AS(dewall::triangulate<3>(flat), dewall::Invalid_input);
}

TEST_CASE("engines: DeWall over the kernel archetype (the concept and nothing else) gives CGAL's simplices",
          "[engine][archetype]") {
  // The archetype's points are opaque and it has only the five functors of
  // DelaunayKernel: this compiles only while the algorithm needs nothing else.
  // Without approximate_coordinates_are_exact every decision is the kernel's.
  auto check = []<int D>(const std::vector<dewall::kernel::Point_d<D>>& points) {
    using Archetype = dewall::test::Kernel_archetype<D>;
    const auto wrapped = Archetype::points(points);
    const auto t = dewall::triangulate<Archetype>(std::span<const typename Archetype::Point_d>(wrapped));
    CHECK(t.statistics.engine == Engine::dewall);
    CHECK(dewall::test::as_set<D>(t.simplices) == dewall::test::cgal_delaunay<D>(points));
  };
  check(generated<2>(dewall::io::Point_kind::uniform, 300, 4));
  check(generated<3>(dewall::io::Point_kind::grid, 125, 4));  // cospherical: the perturbation, through the functors
  check(generated<3>(dewall::io::Point_kind::bubbles, 400, 4));
}

/// DeWall over a Rounded_kernel<D, …> against CGAL on the exact points.
template <class Rounded, int D = Rounded::dimension>
bool rounded_gives_cgal(const std::vector<dewall::kernel::Point_d<D>>& points) {
  const auto wrapped = Rounded::points(points);
  // The rounding must matter: most approximations differ from the points.
  std::size_t moved = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    moved += Rounded().approximate_coordinates_object()(wrapped[i]) != points[i].x;
  REQUIRE(moved > points.size() / 2);
  const auto t = dewall::triangulate<Rounded>(std::span<const typename Rounded::Point_d>(wrapped));
  return dewall::test::as_set<D>(t.simplices) == dewall::test::cgal_delaunay<D>(points);
}

TEST_CASE("engines: a kernel whose approximate coordinates are rounded gives CGAL's simplices",
          "[engine][archetype]") {
  // The search prunes with the approximations; with a declared error bound it
  // widens every box by it, without one it does not prune (concepts.hpp).
  using dewall::io::Point_kind;
  using dewall::test::Rounded_kernel;
  CHECK(rounded_gives_cgal<Rounded_kernel<2, 5, true>>(generated<2>(Point_kind::uniform, 600, 7)));
  CHECK(rounded_gives_cgal<Rounded_kernel<3, 4, true>>(generated<3>(Point_kind::uniform, 600, 7)));
  CHECK(rounded_gives_cgal<Rounded_kernel<3, 8, true>>(generated<3>(Point_kind::bubbles, 600, 8)));
  CHECK(rounded_gives_cgal<Rounded_kernel<4, 4, true>>(generated<4>(Point_kind::uniform, 200, 9)));
  CHECK(rounded_gives_cgal<Rounded_kernel<3, 4, false>>(generated<3>(Point_kind::uniform, 300, 10)));
}

TEST_CASE("engines: the incremental engine hands over every finite cell, after zoned rounds and on a circle",
          "[engine]") {
  // The hand-over converts every slot, finite or not, without a branch
  // (incremental_engine.cpp). 80,000 points leave more than 2^16 after the
  // sample, so zoned rounds run and leave unused slots free; on a circle every
  // other slot holds an infinite cell. The same simplices as CGAL's, each once,
  // and the same bytes on one thread and on all.
  using dewall::io::Point_kind;
  for (const auto& points : {generated<2>(Point_kind::uniform, 80000, 21), generated<2>(Point_kind::sphere, 20000, 22)}) {
    const auto expected = dewall::test::cgal_delaunay<2>(points);
    const auto all = dewall::triangulate<2>(points, Options{.engine = Engine::incremental});
    const auto one = dewall::triangulate<2>(points, Options{.threads = 1, .engine = Engine::incremental});
    CHECK(all.simplices.size() == expected.size());
    CHECK(dewall::test::as_set<2>(all.simplices) == expected);
    CHECK(positively_oriented<2>(points, all.simplices));
    CHECK(one.simplices == all.simplices);
  }
}

TEST_CASE("engines: the incremental engine needs the project's kernel", "[engine]") {
  struct User_kernel : dewall::kernel::Filtered_kernel_d<2> {};
  const std::vector<dewall::kernel::Point_d<2>> points{{{0, 0}}, {{1, 0}}, {{0, 1}}};
  for (Engine e : {Engine::cgal, Engine::incremental, Engine::hybrid})
    CHECK_THROWS_AS(
        dewall::triangulate<User_kernel>(std::span<const dewall::kernel::Point_d<2>>(points), Options{.engine = e}),
        std::invalid_argument);
  // automatic means DeWall with another kernel
  CHECK(dewall::triangulate<User_kernel>(std::span<const dewall::kernel::Point_d<2>>(points)).statistics.engine ==
        Engine::dewall);
}

TEST_CASE("engines: a sink told the input is no longer read may destroy it, and the simplices are the same",
          "[engine]") {
  // The tool frees its points when told (cli_support.cpp); here the sink
  // overwrites them with NaN instead, so that any later read would show.
  const auto with_duplicates = [] {
    auto p = generated<3>(dewall::io::Point_kind::uniform, 1500, 13);
    const std::vector<dewall::kernel::Point_d<3>> again(p.begin(), p.begin() + 200);
    p.insert(p.end(), again.begin(), again.end());  // the distinct list is then kept
    return p;
  }();
  // A lattice too: every sphere test of the walls a tie their filters leave
  // to the kernel's predicates, which then read the points.
  for (const auto& given :
       {generated<3>(dewall::io::Point_kind::uniform, 1500, 13), with_duplicates,
        generated<3>(dewall::io::Point_kind::grid, 1000, 0)}) {
    for (const Engine engine : {Engine::automatic, Engine::incremental, Engine::cgal, Engine::dewall, Engine::hybrid}) {
      Options options;
      options.engine = engine;
      const auto expected = dewall::triangulate<3>(given, options).simplices;
      std::vector<dewall::kernel::Point_d<3>> points = given;
      struct Sink {
        std::vector<dewall::kernel::Point_d<3>>& points;
        std::vector<dewall::Simplex<3>>& out;
        int told = 0;
        void input_no_longer_read() {
          ++told;
          for (auto& p : points) p.x.fill(std::numeric_limits<double>::quiet_NaN());
        }
        void operator()(const dewall::Simplex<3>& s) { out.push_back(s); }
      };
      std::vector<dewall::Simplex<3>> got;
      Sink sink{points, got};
      dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<3>>(std::span<const dewall::kernel::Point_d<3>>(points),
                                                                   sink, options);
      INFO("engine " << dewall::engine_name(engine) << ", " << given.size() << " points");
      CHECK(got == expected);
      // Told once by the project's incremental construction (the automatic
      // engine's choice for so few points) and by the walls (their point set
      // copies the points: Point_set::reads_input), never by CGAL's.
      CHECK(sink.told == (engine == Engine::cgal ? 0 : 1));
    }
  }
}

TEST_CASE("engines: after the hybrid hands over, and in 4D, the sink is told once and the simplices are the same",
          "[engine]") {
  // Points on a sphere with regions asked for: the walls start, read the
  // points, spend their budget and hand the whole input over; in 4D the
  // automatic engine leaves everything to the incremental construction.
  const auto check = []<int D>(const std::vector<dewall::kernel::Point_d<D>>& given, const Options& options,
                               Engine expected_engine) {
    const auto expected = dewall::triangulate<D>(given, options);
    CHECK(expected.statistics.engine == expected_engine);
    auto points = given;
    struct Sink {
      std::vector<dewall::kernel::Point_d<D>>& points;
      std::vector<dewall::Simplex<D>> out;
      int told = 0;
      void input_no_longer_read() {
        ++told;
        for (auto& p : points) p.x.fill(std::numeric_limits<double>::quiet_NaN());
      }
      void operator()(const dewall::Simplex<D>& s) { out.push_back(s); }
    } sink{points};
    const auto st = dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<D>>(
        std::span<const dewall::kernel::Point_d<D>>(points), sink, options);
    CHECK(st.engine == expected_engine);
    if (options.region_points) CHECK(st.searches_before_handover > 0);  // the walls ran first
    CHECK(sink.told == 1);
    CHECK(sink.out == expected.simplices);
  };
  Options regions;
  regions.region_points = 512;
  check(generated<3>(dewall::io::Point_kind::sphere, 4000, 14), regions, Engine::incremental);
  check(generated<4>(dewall::io::Point_kind::uniform, 600, 15), Options{}, Engine::incremental);
}

TEST_CASE("engines: streamed, the walls tell the sink before they build, and a hand-over builds the same simplices",
          "[engine]") {
  // Engine::automatic streamed with regions: the walls tell the sink as soon
  // as their point set holds the points; on uniform points they build
  // everything, on a sphere the budget is spent and the incremental
  // construction builds from the points the walls give back (exactly: here
  // scaled by 3·2^-602, which the point set scales back up, and with
  // duplicates). The sink overwrites its points when told.
  const auto check = [](const std::vector<dewall::kernel::Point_d<3>>& given, Engine expected_engine, int threads) {
    Options options;
    options.region_points = 512;
    options.stream = true;
    options.parallel_depth = threads > 1 ? 2 : 0;
    auto sorted = [](std::vector<dewall::Simplex<3>> s) {
      std::sort(s.begin(), s.end());
      return s;
    };
    const auto expected = dewall::triangulate<3>(given, options);
    CHECK(expected.statistics.engine == expected_engine);
    auto points = given;
    struct Sink {
      std::vector<dewall::kernel::Point_d<3>>& points;
      std::vector<dewall::Simplex<3>> out;
      int told = 0;
      std::size_t simplices_when_told = 0;
      void input_no_longer_read() {
        ++told;
        simplices_when_told = out.size();
        for (auto& p : points) p.x.fill(std::numeric_limits<double>::quiet_NaN());
      }
      void operator()(const dewall::Simplex<3>& s) { out.push_back(s); }
    } sink{points};
    tbb::task_arena arena(threads);
    const auto st = arena.execute([&] {
      return dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<3>>(
          std::span<const dewall::kernel::Point_d<3>>(points), sink, options);
    });
    CHECK(st.engine == expected_engine);
    CHECK(sink.told == 1);
    CHECK(sink.simplices_when_told == 0);
    CHECK(sorted(sink.out) == sorted(expected.simplices));
  };
  auto scaled_sphere = generated<3>(dewall::io::Point_kind::sphere, 4000, 14);
  for (auto& p : scaled_sphere)
    for (double& x : p.x) x *= 0x1.8p-601;
  const std::vector<dewall::kernel::Point_d<3>> again(scaled_sphere.begin() + 100, scaled_sphere.begin() + 400);
  scaled_sphere.insert(scaled_sphere.end(), again.begin(), again.end());
  for (const int threads : {1, 2}) {
    check(generated<3>(dewall::io::Point_kind::uniform, 5000, 16), Engine::hybrid, threads);
    check(generated<3>(dewall::io::Point_kind::sphere, 4000, 14), Engine::incremental, threads);
    check(scaled_sphere, Engine::incremental, threads);
  }
}
