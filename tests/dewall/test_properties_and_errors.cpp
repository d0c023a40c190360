// The empty-sphere property checked directly with the exact perturbed
// predicate, the facet structure, and bad input through the library and the CLI.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>

#include "dewall/dewall.hpp"
#include "dewall_point_sets.hpp"

using namespace dewall;
using dewall::kernel::Point_d;

namespace {

/// Every simplex positively oriented with an empty perturbed sphere (brute
/// force over all points), every facet shared by at most two simplices, and
/// every point a vertex unless it duplicates an earlier one.
template <int D>
void check_delaunay_properties(const std::vector<Point_d<D>>& points) {
  const auto t = dewall::triangulate<D>(points);
  REQUIRE(!t.simplices.empty());
  std::map<std::array<std::uint32_t, D>, int> facet_count;
  std::vector<bool> used(points.size(), false);
  for (const auto& s : t.simplices) {
    std::array<const Point_d<D>*, D + 1> p;
    for (int i = 0; i <= D; ++i) p[i] = &points[s[i]], used[s[i]] = true;
    REQUIRE(kernel::orientation_d<D>(p) == kernel::POSITIVE);
    for (std::size_t q = 0; q < points.size(); ++q) {
      if (std::find(s.begin(), s.end(), q) != s.end()) continue;
      std::array<const Point_d<D>*, D + 2> ps;
      std::copy(p.begin(), p.end(), ps.begin());
      ps[D + 1] = &points[q];
      if (kernel::compare_lexicographically(points[q], *p[0]) == kernel::EQUAL) continue;  // duplicate
      bool duplicate = false;
      for (int i = 0; i <= D; ++i) duplicate |= points[q] == *p[i];
      if (duplicate) continue;
      INFO("point " << q << " inside the sphere of a simplex");
      REQUIRE(kernel::side_of_oriented_sphere_d_sos<D>(ps) == kernel::ON_NEGATIVE_SIDE);
    }
    for (int i = 0; i <= D; ++i) {
      std::array<std::uint32_t, D> f;
      for (int j = 0, k = 0; j <= D; ++j)
        if (j != i) f[k++] = s[j];
      std::sort(f.begin(), f.end());
      ++facet_count[f];
    }
  }
  for (const auto& [f, count] : facet_count) REQUIRE(count <= 2);
  std::map<std::array<double, D>, std::size_t> first;
  for (std::size_t i = points.size(); i-- > 0;) first[points[i].x] = i;
  for (std::size_t i = 0; i < points.size(); ++i) REQUIRE(used[i] == (first[points[i].x] == i));
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
      CHECK(std::string(e.what()).find("non-finite") != std::string::npos);
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

namespace {

struct Cli_result {
  int status;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs the dewall CLI built with the tests (DEWALL_CLI_PATH, set by CMake).
Cli_result run_cli(const std::string& args, const std::string& input_text = "") {
  const char* cli = DEWALL_CLI_PATH;
  const std::string dir = "cli_test_tmp";
  std::system(("mkdir -p " + dir).c_str());
  std::ofstream(dir + "/stdin.txt") << input_text;
  const std::string cmd = std::string(cli) + " " + args + " < " + dir + "/stdin.txt > " + dir + "/out.txt 2> " + dir +
                          "/err.txt";
  const int raw = std::system(cmd.c_str());
  return {WEXITSTATUS(raw), slurp(dir + "/out.txt"), slurp(dir + "/err.txt")};
}

}  // namespace

TEST_CASE("command line: triangulate and its errors", "[cli]") {
  SECTION("a square from standard input, with --stats") {
    const auto r = run_cli("triangulate - --stats", "# unit square\n0 0\n1 0\n0 1\n1 1\n");
    CHECK(r.status == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 2);
    CHECK(r.err.find("build_s=") != std::string::npos);
    CHECK(r.err.find("simplices=2") != std::string::npos);
  }
  SECTION("rbox format") {
    const auto r = run_cli("triangulate -", "3 rbox 5 D3\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n");
    CHECK(r.status == 0);
    CHECK(!r.out.empty());
  }
  SECTION("truncated rbox file") {
    const auto r = run_cli("triangulate -", "3 rbox 5 D3\n5\n0 0 0\n1 0 0\n0 1 0\n");
    CHECK(r.status == 2);
    CHECK(r.err.find("truncated") != std::string::npos);
  }
  SECTION("not a number, with file and line") {
    const auto r = run_cli("triangulate -", "0 0\n1 0\n0 x\n1 1\n");
    CHECK(r.status == 2);
    CHECK(r.err.find("<stdin>:3") != std::string::npos);
  }
  SECTION("ragged rows") {
    const auto r = run_cli("triangulate -", "0 0\n1 0 3\n0 1\n");
    CHECK(r.status == 2);
    CHECK(r.err.find("expected 2 coordinates") != std::string::npos);
  }
  SECTION("NaN names the point") {
    const auto r = run_cli("triangulate -", "0 0\n1 0\nnan 1\n1 1\n");
    CHECK(r.status == 1);
    CHECK(r.err.find("point 2") != std::string::npos);
  }
  SECTION("collinear points, and no partial output file") {
    std::remove("cli_test_tmp/never.txt");
    const auto r = run_cli("triangulate - -o cli_test_tmp/never.txt", "0 0\n1 1\n2 2\n3 3\n");
    CHECK(r.status == 1);
    CHECK(r.err.find("collinear") != std::string::npos);
    CHECK(!std::ifstream("cli_test_tmp/never.txt").good());
  }
  SECTION("missing file") {
    const auto r = run_cli("triangulate /nonexistent/points.txt");
    CHECK(r.status == 2);
    CHECK(r.err.find("cannot open") != std::string::npos);
  }
  SECTION("unknown command") { CHECK(run_cli("frobnicate").status == 2); }
}
