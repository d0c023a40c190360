// Options::progress: the engines report a fraction that never goes back and
// ends at 1, and a callback that returns false (or throws) stops every engine
// with dewall::Cancelled (or its exception), nothing built kept: under ASan
// the leak checker sees what the unwinding would leave behind.
#include <catch2/catch.hpp>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "dewall/dewall.hpp"
#include "dewall/error.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/point_array.hpp"

namespace {

using dewall::Engine;
using dewall::Options;

template <int D>
std::vector<dewall::kernel::Point_d<D>> uniform(std::size_t n, std::uint64_t seed) {
  return dewall::kernel::points_from_coordinates<D>(
      dewall::io::generate_points(dewall::io::Point_kind::uniform, n, D, seed).coordinates);
}

/// Engines and options that reach every poll: the incremental construction
/// (serially and in zones), DeWall's wall loop, the hybrid's regions.
std::vector<Options> every_engine() {
  std::vector<Options> all;
  for (const Engine e : {Engine::automatic, Engine::incremental, Engine::dewall, Engine::hybrid}) {
    Options o;
    o.engine = e;
    if (e == Engine::hybrid) o.region_points = 2000;
    all.push_back(o);
  }
  return all;
}

}  // namespace

TEST_CASE("progress: fractions in [0, 1] that never go back, ending at 1, the output unchanged", "[progress]") {
  const auto points = uniform<3>(20000, 57);
  const auto expected = dewall::triangulate<3>(points).simplices.size();
  for (Options o : every_engine()) {
    for (const int threads : {1, 2}) {
      CAPTURE(dewall::engine_name(o.engine), threads);
      o.threads = threads;
      std::vector<double> seen;
      o.progress = [&](double f) {
        seen.push_back(f);
        return true;
      };
      const auto t = dewall::triangulate<3>(points, o);
      CHECK(t.simplices.size() == expected);
      REQUIRE(seen.size() >= 3);  // at least two polls and the end
      CHECK(seen.back() == 1.0);
      for (std::size_t i = 0; i < seen.size(); ++i) {
        CHECK(seen[i] >= 0.0);
        CHECK(seen[i] <= 1.0);
        if (i > 0) CHECK(seen[i] >= seen[i - 1]);
      }
      CHECK(seen[seen.size() - 2] > 0.0);  // the engine counted work before the end
    }
  }
}

TEST_CASE("progress: false at the first poll or a later one throws dewall::Cancelled", "[progress]") {
  const auto points = uniform<2>(30000, 58);
  for (Options o : every_engine()) {
    for (const int stop_at : {1, 3}) {
      for (const int threads : {1, 2}) {
        CAPTURE(dewall::engine_name(o.engine), stop_at, threads);
        o.threads = threads;
        int calls = 0;
        o.progress = [&](double) { return ++calls < stop_at; };
        CHECK_THROWS_AS(dewall::triangulate<2>(points, o), dewall::Cancelled);
        CHECK(calls == stop_at);  // not called again once it said stop
      }
    }
  }
}

TEST_CASE("progress: an exception from the callback stops the work and is passed on", "[progress]") {
  const auto points = uniform<3>(20000, 59);
  struct Stop : std::runtime_error {
    Stop() : std::runtime_error("stop") {}
  };
  for (Options o : every_engine()) {
    CAPTURE(dewall::engine_name(o.engine));
    o.threads = 1;
    o.progress = [](double) -> bool { throw Stop(); };
    CHECK_THROWS_AS(dewall::triangulate<3>(points, o), Stop);
  }
}

TEST_CASE("progress: a streamed triangulation stops too, the sink keeping what it was given", "[progress]") {
  const auto points = uniform<2>(60000, 60);
  Options o;
  o.engine = Engine::hybrid;
  o.stream = true;
  o.region_points = 4000;
  int calls = 0;
  o.progress = [&](double) { return ++calls < 4; };
  std::size_t received = 0;
  CHECK_THROWS_AS(dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<2>>(
                      std::span<const dewall::kernel::Point_d<2>>(points),
                      [&](const dewall::Simplex<2>&) { ++received; }, o),
                  dewall::Cancelled);
  CHECK(received < dewall::triangulate<2>(points).simplices.size());
}

TEST_CASE("progress: 4D and up, the incremental construction polls too", "[progress]") {
  const auto points = uniform<4>(12000, 61);
  Options o;
  int calls = 0;
  o.progress = [&](double) { return ++calls < 2; };
  CHECK_THROWS_AS(dewall::triangulate<4>(points, o), dewall::Cancelled);
}
