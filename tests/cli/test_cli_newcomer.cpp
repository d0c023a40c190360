// A newcomer's first hour (issue 57): no wrong answer and no data loss at the
// door. Wall levels come from walls; a TetGen file through a pipe is read as
// TetGen; an output never replaces its input; what the tool writes it reads
// back, and a name that says another format than what is written is refused;
// --stats prints the counters of the engines that ran; an option the chosen
// engine ignores is a usage error; --name=VALUE works. Each case runs the real
// executable in its own folder.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dewall/dewall.hpp"
#include "support/cli_runner.hpp"

namespace {

using dewall::test::Cli_in_directory;
using dewall::test::slurp;
namespace fs = std::filesystem;

Cli_in_directory fresh(const std::string& name) {
  fs::remove_all(name);
  return Cli_in_directory(name);
}

/// The fill colours of an SVG's triangles (polygons), each once.
std::set<std::string> triangle_fills(const std::string& svg) {
  std::set<std::string> fills;
  const std::regex polygon(R"re(<polygon[^>]*fill="([^"]+)")re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polygon); it != std::sregex_iterator(); ++it)
    fills.insert((*it)[1]);
  return fills;
}

// Five points in E^3 (a tetrahedron and a point above), as TetGen writes them.
const std::string node_file = "5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1\n";

}  // namespace

TEST_CASE("newcomer: draw --walls colours the triangles by several wall levels", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_walls");
  REQUIRE(cli("generate bubbles 300 --dim 2 --seed 42 -q -o b.txt").status == 0);
  REQUIRE(cli("draw b.txt --walls -o bw.svg").status == 0);
  const std::string svg = slurp(cli.path("bw.svg"));
  // The README's headline figure: the first wall and the levels below it.
  CHECK(triangle_fills(svg).size() >= 4);
  CHECK(svg.find(">3</text>") != std::string::npos);  // the legend reaches level 3
}

TEST_CASE("newcomer: the library's wall levels come from walls", "[dewall][newcomer]") {
  std::vector<dewall::kernel::Point_d<2>> points;
  for (int i = 0; i < 400; ++i) points.push_back({{(i * 37 % 101) / 101.0, (i * 53 % 97) / 97.0 + i * 1e-4}});
  const std::span<const dewall::kernel::Point_d<2>> view(points);
  using K = dewall::kernel::Filtered_kernel_d<2>;
  std::set<int> levels;
  std::size_t with_levels = 0;
  dewall::triangulate_to<K>(view, [&](const dewall::Simplex<2>&, int level) { levels.insert(level), ++with_levels; });
  CHECK(levels.size() >= 3);
  CHECK(with_levels == dewall::triangulate<2>(points).simplices.size());
  for (const auto engine : {dewall::Engine::incremental, dewall::Engine::cgal}) {
    dewall::Options options;
    options.engine = engine;
    CHECK_THROWS_AS(dewall::triangulate_to<K>(view, [](const dewall::Simplex<2>&, int) {}, options),
                    std::invalid_argument);
  }
}

TEST_CASE("newcomer: a TetGen file whose name does not say is read as TetGen", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_tetgen_by_content");
  cli.write("a.node", node_file);
  cli.write("a.txt", node_file);
  const auto by_name = cli("triangulate a.node");
  REQUIRE(by_name.status == 0);
  CHECK(by_name.out.find("4 2 3") == std::string::npos);  // never the header taken for a 4D point
  const auto piped = cli("triangulate -", "cat a.node | ");
  CHECK(piped.status == 0);
  CHECK(piped.out == by_name.out);
  CHECK(cli("triangulate a.txt").out == by_name.out);
  // And the .ele written from it, through a pipe, for certify.
  REQUIRE(cli("triangulate a.node -o a.ele").status == 0);
  const auto certified = cli("certify --canonical a.node -", "cat a.ele | ");
  CHECK(certified.status == 0);
  CHECK(certified.out.find("delaunay canonical") == 0);
  // A plain 4D file whose first column does not count up stays plain.
  cli.write("plain4.txt", "5 3 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n2 2 2 2\n");
  const auto plain = cli("triangulate plain4.txt --stats");
  CHECK(plain.status == 0);
  CHECK(plain.err.find("points=6 ") == 0);
}

TEST_CASE("newcomer: the output never replaces the input", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_output_is_input");
  const std::string points = "0 0\n1 0\n0 1\n1 1\n";
  cli.write("p.txt", points);
  fs::create_symlink("p.txt", cli.path("link.txt"));
  for (const std::string& run : {std::string("triangulate p.txt -o p.txt"), std::string("triangulate p.txt -o link.txt"),
                                 std::string("triangulate - -o p.txt < p.txt"),
                                 std::string("draw p.txt --walls -o p.txt")}) {
    const auto r = cli.shell("$DEWALL " + run);
    INFO(run << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("the output is the input") != std::string::npos);
    CHECK(slurp(cli.path("p.txt")) == points);
  }
  const auto appended = cli.shell("$DEWALL triangulate p.txt >> p.txt");
  CHECK(appended.status == 2);
  CHECK(slurp(cli.path("p.txt")) == points);
}

TEST_CASE("newcomer: what the tool writes it reads back, whatever the case of the name", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_round_trips");
  REQUIRE(cli("generate uniform 40 --dim 2 --seed 5 -q -o p.txt").status == 0);
  SECTION("VTK: certify and draw read the cells of a triangulation") {
    REQUIRE(cli("triangulate p.txt -o x.VTK").status == 0);
    const auto certified = cli("certify --canonical p.txt x.VTK");
    CHECK(certified.status == 0);
    CHECK(certified.out.find("delaunay canonical") == 0);
    CHECK(cli("certify --canonical x.VTK x.VTK").status == 0);  // the points from the same file
    CHECK(cli("draw p.txt x.VTK -o x.svg").status == 0);
    // A VTK file of points holds no simplices: said, not misread.
    REQUIRE(cli("generate uniform 40 --dim 2 --seed 5 -q -o points.vtk").status == 0);
    const auto no_cells = cli("certify p.txt points.vtk");
    CHECK(no_cells.status == 2);
    CHECK(no_cells.err.find("cells of 1 vertices, not simplices") != std::string::npos);
  }
  SECTION("an ASCII VTK triangulation, as other tools write it") {
    cli.write("q.txt", "0 0\n1 0\n0 1\n1 1\n");
    cli.write("q.vtk", "# vtk DataFile Version 3.0\nsquare\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                       "0 0 0 1 0 0 0 1 0 1 1 0\nCELLS 2 8\n3 0 1 3\n3 0 3 2\nCELL_TYPES 2\n5\n5\n");
    CHECK(cli("certify q.txt q.vtk").status == 0);
    cli.write("bad.vtk", "# vtk DataFile Version 3.0\nsquare\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                         "0 0 0 1 0 0 0 1 0 1 1 0\nCELLS 2 8\n3 0 1 3\n3 0 3\n");
    CHECK(cli("certify q.txt bad.vtk").status == 2);
  }
  SECTION("TetGen: generate writes .node, triangulate and certify read it") {
    REQUIRE(cli("generate uniform 30 --seed 2 -q -o G.NODE").status == 0);
    CHECK(slurp(cli.path("G.NODE")).rfind("30 3 0 0\n0 ", 0) == 0);
    REQUIRE(cli("triangulate G.NODE -o G.Ele").status == 0);
    CHECK(cli("certify --canonical G.NODE G.Ele").status == 0);
  }
  SECTION("binary: the extension in any case") {
    REQUIRE(cli("triangulate p.txt -o U.DWSX").status == 0);
    CHECK(slurp(cli.path("U.DWSX")).rfind("DWSX", 0) == 0);
    REQUIRE(cli("generate uniform 30 --seed 2 -q -o P.DwPt").status == 0);
    CHECK(slurp(cli.path("P.DwPt")).rfind("DWPT", 0) == 0);
    const auto swapped = cli("certify U.DWSX p.txt");
    CHECK(swapped.status == 2);
    CHECK(swapped.err.find("the arguments look swapped") != std::string::npos);
  }
  SECTION("a name that says another format is refused before anything is written") {
    for (const std::string& run : {std::string("triangulate p.txt -o s.dwpt"), std::string("triangulate p.txt -o s.Node"),
                                   std::string("triangulate p.txt -o s.ply"), std::string("triangulate p.txt --stream -o s.stl"),
                                   std::string("generate uniform 10 -q -o s.ele"), std::string("generate uniform 10 -q -o s.dwsx"),
                                   std::string("generate uniform 10 -q -o s.off")}) {
      const auto r = cli(run);
      INFO(run << ": " << r.err);
      CHECK(r.status == 2);
      CHECK(r.err.find("the name says") != std::string::npos);
    }
    for (const auto& entry : fs::directory_iterator(cli.dir))
      CHECK(entry.path().filename().string().rfind("s.", 0) != 0);
  }
}

TEST_CASE("newcomer: --stats prints the counters of the engines that ran", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_stats");
  REQUIRE(cli("generate bubbles 300 --dim 2 --seed 42 -q -o b.txt").status == 0);
  const auto incremental = cli("triangulate b.txt --stats -o t.txt");
  CHECK(incremental.status == 0);
  CHECK(incremental.err.find("built: dewall's incremental construction 588 simplices") != std::string::npos);
  CHECK(incremental.err.find("first_wall_simplices") == std::string::npos);
  const auto walls = cli("triangulate b.txt --engine=dewall --stats -o t.txt");
  CHECK(walls.status == 0);
  CHECK(walls.err.find("built: walls 588 simplices") != std::string::npos);
  CHECK(std::regex_search(walls.err, std::regex("first_wall_simplices=[1-9][0-9]* recursion_depth=[1-9]")));
  const auto hybrid = cli("triangulate b.txt --engine hybrid --region-points=50 --stats -o t.txt");
  CHECK(std::regex_search(hybrid.err, std::regex("built: walls [1-9][0-9]* simplices, regions \\(incremental construction\\) [1-9]")));
}

TEST_CASE("newcomer: options the engine ignores are usage errors, --name=VALUE works", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_options");
  cli.write("p.txt", "0 0\n1 0\n0 1\n1 1\n");
  CHECK(cli("triangulate p.txt --engine cgal --region-points 100").status == 2);
  CHECK(cli("triangulate p.txt --engine dewall --incremental-engine cgal").status == 2);
  CHECK(cli("triangulate p.txt --engine incremental --incremental-engine cgal").status == 2);
  const auto gnu = cli("triangulate p.txt --threads=2 --engine=cgal --stats");
  CHECK(gnu.status == 0);
  CHECK(gnu.err.find("engine=cgal") != std::string::npos);
  CHECK(gnu.out == cli("triangulate p.txt --threads 2 --engine cgal").out);
}

TEST_CASE("newcomer: certify says 'no simplices' and lists each violation once", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_certify");
  REQUIRE(cli("generate uniform 30 --dim 2 --seed 3 -q -o p.txt").status == 0);
  cli.write("empty.txt", "");
  const auto empty = cli("certify p.txt empty.txt");
  CHECK(empty.status == 2);
  CHECK(empty.err.find("no simplices") != std::string::npos);
  REQUIRE(cli("triangulate p.txt -o t.txt").status == 0);
  std::string t = slurp(cli.path("t.txt"));
  cli.write("bad.txt", t.substr(t.find('\n') + 1));  // the first triangle gone: a hole
  const auto all = cli("certify --all p.txt bad.txt");
  CHECK(all.status == 1);
  // Each violation's line once: the header names none.
  const std::string first = all.out.substr(all.out.find('\n') + 1, all.out.find('\n', all.out.find('\n') + 1) - all.out.find('\n') - 1);
  CHECK(all.out.find(first.substr(2)) == all.out.rfind(first.substr(2)));
}

TEST_CASE("newcomer: the README's example prints what the tool prints", "[cli][newcomer][docs]") {
  std::ifstream in(std::string(DEWALL_SOURCE_DIR) + "/README.md");
  const std::string readme{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::string command = "$ printf '0 0\\n1 0\\n0 1\\n1 1\\n' | dewall triangulate -\n";
  const auto at = readme.find(command);
  REQUIRE(at != std::string::npos);
  const auto from = at + command.size();
  const std::string shown = readme.substr(from, readme.find("$ ", from) - from);
  const auto cli = fresh("newcomer_test_readme");
  const auto r = cli("triangulate -", "printf '0 0\\n1 0\\n0 1\\n1 1\\n' | ");
  CHECK(r.status == 0);
  CHECK(r.out == shown);
}

TEST_CASE("newcomer: values of the right kind but too large say so", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_too_large");
  for (const std::string& run : {std::string("generate uniform 1e20"), std::string("generate uniform 1e400"),
                                 std::string("generate uniform 10 --dim 99999999999999999999")}) {
    const auto r = cli(run);
    INFO(run << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find("is too large") != std::string::npos);
  }
  const auto rbox = cli.with_stdin("triangulate -", "3\n99999999999999999\n0 0 0\n");
  CHECK(rbox.status == 2);
  CHECK(rbox.err.find("point count '99999999999999999' is too large") != std::string::npos);
  cli.write("p.node", "4 2 0 0\n0 0 0\n1 1 0\n2 0 1\n3 1 1\n");
  cli.write("big.ele", "99999999999 3 0\n");
  const auto ele = cli("certify p.node big.ele");
  CHECK(ele.status == 2);
  CHECK(ele.err.find("simplex count '99999999999' is too large") != std::string::npos);
  // Too small is out of range as too large is, never silently 0.
  const auto tiny = cli.with_stdin("triangulate -", "1e-400 0\n1 0\n0 1\n");
  CHECK(tiny.status == 2);
  CHECK(tiny.err.find("'1e-400' is out of the range of double") != std::string::npos);
}

TEST_CASE("newcomer: --engine dewall on points on one sphere warns before the work", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_sphere_warning");
  REQUIRE(cli("generate sphere 5000 --dim 2 --seed 1 -q -o circle.txt").status == 0);
  REQUIRE(cli("generate uniform 5000 --dim 2 --seed 1 -q -o square.txt").status == 0);
  const auto circle = cli("triangulate circle.txt --engine dewall -o t.txt");
  CHECK(circle.status == 0);
  CHECK(circle.err.find("lie on one sphere") != std::string::npos);
  CHECK(cli("triangulate circle.txt -o t.txt").err.empty());  // auto: nothing to warn about
  CHECK(cli("triangulate square.txt --engine dewall -o t.txt").err.empty());
}

TEST_CASE("newcomer: PLY, OFF and OBJ vertices are points, a triangulation goes out as gmsh", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_mesh_files");
  REQUIRE(cli("generate uniform 120 --seed 8 -q -o p.txt").status == 0);
  const std::string points = slurp(cli.path("p.txt"));
  const auto expected = cli("triangulate p.txt");
  REQUIRE(expected.status == 0);
  std::string ply = "ply\nformat ascii 1.0\ncomment by hand\nelement vertex 120\nproperty double x\nproperty double y\n"
                    "property double z\nproperty uchar red\nelement face 0\nproperty list uchar int vertex_indices\n"
                    "end_header\n";
  std::string off = "OFF\n120 0 0\n", obj = "# points\no cloud\n", binary = "ply\nformat binary_little_endian 1.0\n"
                                                                          "element vertex 120\nproperty double x\n"
                                                                          "property double y\nproperty double z\nend_header\n";
  for (std::size_t at = 0; at < points.size();) {
    const std::string row = points.substr(at, points.find('\n', at) - at);
    at = points.find('\n', at) + 1;
    ply += row + " 200\n", off += row + "\n", obj += "v " + row + "\n";
    std::istringstream values(row);
    for (double v; values >> v;) binary.append(reinterpret_cast<const char*>(&v), sizeof v);  // this host is little-endian
  }
  cli.write("p.ply", ply), cli.write("p.off", off), cli.write("cloud.data", obj), cli.write("b.ply", binary);
  CHECK(cli("triangulate p.ply").out == expected.out);
  CHECK(cli("triangulate b.ply").out == expected.out);
  CHECK(cli("triangulate -", "cat p.off | ").out == expected.out);  // the key word, not the name
  CHECK(cli("triangulate cloud.data").out == expected.out);        // OBJ by its statements
  // A mesh file of another kind is said to be wrong, naming what.
  cli.write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n0\n1\n");
  const auto bad = cli("triangulate bad.ply");
  CHECK(bad.status == 2);
  CHECK(bad.err.find("no x and y properties") != std::string::npos);
  const auto cut = cli("triangulate -", "head -c 700 b.ply | ");
  CHECK(cut.status == 2);
  CHECK(cut.err.find("truncated") != std::string::npos);

  // gmsh: written, read back by certify and draw, and gmsh 4.1 as gmsh writes it.
  REQUIRE(cli("triangulate p.ply -o mesh.MSH").status == 0);
  CHECK(slurp(cli.path("mesh.MSH")).rfind("$MeshFormat\n2.2 0 8\n", 0) == 0);
  CHECK(cli("certify --canonical p.txt mesh.MSH").status == 0);
  CHECK(cli("certify --canonical mesh.MSH mesh.MSH").status == 0);
  CHECK(cli("generate uniform 10 -q -o points.msh").status == 2);  // points are not written as a mesh
  cli.write("g41.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n2 4 1 4\n2 1 0 2\n1\n2\n0 0 0\n1 0 0\n"
                       "2 2 0 2\n3\n4\n0 1 0\n1 1 0\n$EndNodes\n$Elements\n2 3 1 3\n1 1 1 1\n1 1 2\n"
                       "2 1 2 2\n2 1 2 3\n3 2 4 3\n$EndElements\n");
  const auto gmsh = cli("certify --canonical g41.msh g41.msh");
  CHECK(gmsh.status == 0);
  CHECK(gmsh.out.find("(2 simplices, 4 points") != std::string::npos);
  CHECK(cli("draw g41.msh g41.msh -o g41.svg").status == 0);
}

TEST_CASE("newcomer: plain points that start like a TetGen header stay plain", "[cli][newcomer]") {
  const auto cli = fresh("newcomer_test_tetgen_lookalike");
  // A grid whose first row reads as "1 point of E^2", then rows numbered 1, 2, …: more rows than that count.
  std::string grid;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) grid += std::to_string(1 + i) + " " + std::to_string(2 + j) + " " + std::to_string(k) + "\n";
  cli.write("grid.txt", grid);
  const auto r = cli("triangulate grid.txt --stats -o t.txt");
  CHECK(r.status == 0);
  CHECK(r.err.find("points=27 ") == 0);
}
