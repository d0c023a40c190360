// The command line's triangulate: its output on small inputs, its errors and
// exit statuses, --engine (the same simplices from each) and --threads (the
// same bytes for every count).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "dewall/kernel/orientation.hpp"
#include "support/cgal_reference.hpp"
#include "support/cli_runner.hpp"
#include "support/dewall_point_sets.hpp"

using namespace dewall;
using dewall::kernel::Point_d;

TEST_CASE("command line: triangulate and its errors", "[cli]") {
  const dewall::test::Cli_in_directory cli("cli_test_triangulate");
  const auto run_cli = [&](const std::string& args, const std::string& input_text = "") {
    return cli.with_stdin(args, input_text);
  };
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
  SECTION("more threads than the affinity mask allows: capped, no TBB warning") {
    REQUIRE(std::system("taskset -c 0 true > /dev/null 2>&1") == 0);  // util-linux: essential on Debian
    cli.write("grid.txt", "0 0\n1 0\n0 1\n1 1\n2 0\n2 1\n0 2\n1 2\n2 2\n");
    const auto one = cli("triangulate grid.txt --threads 1");
    const auto capped = cli("triangulate grid.txt --threads 2", "taskset -c 0 ");
    CHECK(capped.status == 0);
    CHECK(capped.err.empty());
    CHECK(capped.out == one.out);
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
    std::remove(cli.path("never.txt").c_str());
    const auto r = run_cli("triangulate - -o never.txt", "0 0\n1 1\n2 2\n3 3\n");
    CHECK(r.status == 1);
    CHECK(r.err.find("collinear") != std::string::npos);
    CHECK(!std::ifstream(cli.path("never.txt")).good());
  }
  SECTION("missing file") {
    const auto r = run_cli("triangulate /nonexistent/points.txt");
    CHECK(r.status == 2);
    CHECK(r.err.find("cannot open") != std::string::npos);
  }
  SECTION("unknown command") { CHECK(run_cli("frobnicate").status == 2); }
}

namespace {

/// A simplex list as the CLI writes it, as sorted index tuples.
template <int D>
std::set<std::array<std::uint32_t, D + 1>> simplex_set(const std::string& text) {
  std::set<std::array<std::uint32_t, D + 1>> s;
  std::istringstream in(text);
  std::array<std::uint32_t, D + 1> t;
  while (in >> t[0]) {
    for (int i = 1; i <= D; ++i) in >> t[static_cast<std::size_t>(i)];
    std::sort(t.begin(), t.end());
    s.insert(t);
  }
  return s;
}

}  // namespace

TEST_CASE("command line: triangulate --engine cgal", "[cli][cgal]") {
  const dewall::test::Cli_in_directory cli("cli_test_engine");
  SECTION("CGAL's triangulation, equal to DeWall's, positively oriented, on cospherical points with duplicates") {
    // The 3D integer points of norm^2 = 9 (cospherical), the centre, and a
    // later duplicate of each: every sphere test a tie, decided by the
    // perturbation, and duplicates mapped to their first occurrence.
    std::vector<Point_d<3>> p{{{0, 0, 0}}};
    for (int x = -3; x <= 3; ++x)
      for (int y = -3; y <= 3; ++y)
        for (int z = -3; z <= 3; ++z)
          if (x * x + y * y + z * z == 9) p.push_back({{double(x), double(y), double(z)}});
    const std::size_t distinct = p.size();
    for (std::size_t i = 0; i < distinct; i += 2) p.push_back(p[i]);
    std::string text;
    for (const auto& q : p) text += std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + "\n";
    const auto by_cgal = cli.with_stdin("triangulate - --engine cgal", text);
    const auto by_dewall = cli.with_stdin("triangulate - --engine dewall", text);
    const auto by_own = cli.with_stdin("triangulate - --engine incremental", text);
    const auto hybrid_own = cli.with_stdin("triangulate - --engine hybrid --region-points 8 --incremental-engine incremental", text);
    const auto hybrid_cgal = cli.with_stdin("triangulate - --engine hybrid --region-points 8 --incremental-engine cgal", text);
    REQUIRE(by_cgal.status == 0);
    REQUIRE(by_dewall.status == 0);
    REQUIRE(by_own.status == 0);
    REQUIRE(hybrid_own.status == 0);
    REQUIRE(hybrid_cgal.status == 0);
    const auto cells = simplex_set<3>(by_cgal.out);
    CHECK(!cells.empty());
    CHECK(cells == simplex_set<3>(by_dewall.out));
    CHECK(cells == simplex_set<3>(by_own.out));
    CHECK(cells == simplex_set<3>(hybrid_own.out));
    CHECK(cells == simplex_set<3>(hybrid_cgal.out));
    CHECK(cells == dewall::test::as_set<3>(dewall::test::cgal_delaunay<3>(p)));
    std::istringstream rows(by_cgal.out);
    std::array<std::uint32_t, 4> t;
    while (rows >> t[0] >> t[1] >> t[2] >> t[3]) {
      std::array<const Point_d<3>*, 4> s{&p[t[0]], &p[t[1]], &p[t[2]], &p[t[3]]};
      CHECK(kernel::orientation_d<3>(s) == kernel::POSITIVE);
      for (auto i : t) CHECK(i < distinct);
    }
  }
  SECTION("the same input errors as DeWall's") {
    auto r = cli.with_stdin("triangulate - --engine cgal", "0 0\n1 0\nnan 1\n1 1\n");
    CHECK(r.status == 1);
    CHECK(r.err.find("point 2") != std::string::npos);
    r = cli.with_stdin("triangulate - --engine cgal", "0 0\n1 1\n2 2\n3 3\n");
    CHECK(r.status == 1);
    CHECK(r.err.find("collinear") != std::string::npos);
    r = cli.with_stdin("triangulate - --engine cgal", "0 0\n1 0\n0 0\n");
    CHECK(r.status == 1);
    CHECK(r.err.find("at least 3 distinct points") != std::string::npos);
    CHECK(cli.with_stdin("triangulate - --engine qhull", "0 0\n1 0\n0 1\n").status == 2);
    CHECK(cli.with_stdin("triangulate - --engine", "0 0\n1 0\n0 1\n").status == 2);
    // The regions' construction must be an incremental one.
    r = cli.with_stdin("triangulate - --incremental-engine dewall", "0 0\n1 0\n0 1\n");
    CHECK(r.status == 2);
    CHECK(r.err.find("auto, incremental or cgal") != std::string::npos);
    r = cli.with_stdin("triangulate - --engine incremental", "0 0\n1 1\n2 2\n3 3\n");
    CHECK(r.status == 1);
    CHECK(r.err.find("collinear") != std::string::npos);
  }
  SECTION("--threads N: the same bytes for every N; bad counts are usage errors") {
    std::string text;
    std::mt19937_64 rng(24);
    for (const auto& q : dewall::test::uniform<3>(9000, rng))
      text += std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + "\n";
    const auto all_cores = cli.with_stdin("triangulate -", text);
    REQUIRE(all_cores.status == 0);
    CHECK(!all_cores.out.empty());
    for (const char* n : {"1", "2", "3"}) {
      const auto r = cli.with_stdin(std::string("triangulate - --threads ") + n, text);
      CHECK(r.status == 0);
      CHECK(r.out == all_cores.out);
    }
    for (const char* bad : {"0", "-2", "two", "1.5", ""}) {
      const auto r = cli.with_stdin(std::string("triangulate - --threads '") + bad + "'", text);
      CHECK(r.status == 2);
      CHECK(r.err.find("thread") != std::string::npos);
    }
  }
}

TEST_CASE("command line: triangulate --stream", "[cli][stream][heavy]") {
  const dewall::test::Cli_in_directory cli("cli_test_stream");
  using dewall::test::slurp;
  // 40,000 points: walls and regions of 16384 points (streaming takes at most 32768; collected,
  // so few points would have no walls but for --region-points).
  REQUIRE(cli("generate uniform 40000 --seed 3 -o p.dwpt").status == 0);
  SECTION("the collected bytes on one thread, the same set on all cores, certified") {
    REQUIRE(cli("triangulate p.dwpt --threads 1 --region-points 16384 -o collected.dwsx").status == 0);
    REQUIRE(cli("triangulate p.dwpt --threads 1 --stream -o streamed.dwsx").status == 0);
    CHECK(slurp(cli.path("streamed.dwsx")) == slurp(cli.path("collected.dwsx")));  // the count too
    REQUIRE(cli("triangulate p.dwpt --stream -o all_cores.dwsx --stats").status == 0);
    CHECK(slurp(cli.path("all_cores.dwsx")).size() == slurp(cli.path("collected.dwsx")).size());
    CHECK(cli("certify p.dwpt all_cores.dwsx").status == 0);
    // The same report (but its timing) on one thread and on three.
    const auto report = [&](const char* threads) {
      const auto r = cli(std::string("certify p.dwpt all_cores.dwsx --json --threads ") + threads);
      CHECK(r.status == 0);
      return std::regex_replace(r.out, std::regex("\"seconds\":[0-9.e-]+"), "");
    };
    CHECK(report("1") == report("3"));
    CHECK(report("1").find("\"canonical\":true") != std::string::npos);
    CHECK(cli("certify p.dwpt all_cores.dwsx --threads 0").status == 2);
    // The plain list on standard output, the same lines in the same order.
    const auto plain = cli("triangulate p.dwpt --threads 1 --region-points 16384");
    const auto plain_streamed = cli("triangulate p.dwpt --threads 1 --stream");
    REQUIRE(plain.status == 0);
    CHECK(!plain.out.empty());
    CHECK(plain_streamed.out == plain.out);
  }
  SECTION("to a pipe the binary count stays unknown, and certify reads what follows") {
    const std::string command = "cd " + cli.dir + " && rm -f pipe.dwsx got.dwsx && mkfifo pipe.dwsx && " +
                                "{ cat pipe.dwsx > got.dwsx & " + DEWALL_CLI_PATH +
                                " triangulate p.dwpt --stream -o pipe.dwsx; status=$?; wait; exit $status; }";
    REQUIRE(std::system(command.c_str()) == 0);
    const std::string got = slurp(cli.path("got.dwsx"));
    REQUIRE(got.size() > 24);
    CHECK(got.compare(16, 8, std::string(8, '\xff')) == 0);  // binary_simplices_unknown_count
    CHECK(cli("certify p.dwpt got.dwsx").status == 0);
  }
  SECTION("--region-points: streaming on one thread gives the collected bytes at the same region size") {
    // (By default streaming takes other regions above 131072 points, so its order differs there.)
    REQUIRE(cli("triangulate p.dwpt --threads 1 --region-points 5000 -o collected.dwsx").status == 0);
    REQUIRE(cli("triangulate p.dwpt --threads 1 --region-points 5000 --stream -o streamed.dwsx").status == 0);
    CHECK(slurp(cli.path("streamed.dwsx")) == slurp(cli.path("collected.dwsx")));
    REQUIRE(cli("triangulate p.dwpt --threads 1 -o default.dwsx").status == 0);
    CHECK(slurp(cli.path("default.dwsx")) != slurp(cli.path("collected.dwsx")));  // another order
    for (const char* bad : {"0", "-3", "x", "4294967296"}) {
      const auto r = cli(std::string("triangulate p.dwpt --region-points ") + bad);
      CHECK(r.status == 2);
      CHECK(r.err.find("--region-points") != std::string::npos);
    }
  }
  SECTION("formats that start with the count cannot be streamed") {
    for (const char* output : {"t.ele", "t.vtk"}) {
      const auto r = cli(std::string("triangulate p.dwpt --stream -o ") + output);
      CHECK(r.status == 2);
      CHECK(r.err.find("--stream") != std::string::npos);
      CHECK(!std::ifstream(cli.path(output)).good());
    }
  }
}
