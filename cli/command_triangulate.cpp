// dewall triangulate INPUT [-o OUTPUT] [--stats]
#include <cstdio>

#include "cli.hpp"
#include "dewall/error.hpp"

namespace dewall::cli {

int command_triangulate(int argc, char** argv) {
  std::string input, output = "-";
  bool stats = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-o" || a == "--output") output = next_arg(i, argc, argv);
    else if (a == "--stats") stats = true;
    else if (a.size() > 1 && a[0] == '-') throw Usage_error("unknown option '" + a + "'");
    else if (input.empty()) input = a;
    else throw Usage_error("unexpected argument '" + a + "'");
  }
  if (input.empty()) throw Usage_error("triangulate needs an INPUT file ('-' for standard input)");
  const auto table = io::read_points_file(input);
  Run run;
  try {
    run = triangulate_any(table);
  } catch (const Invalid_input& e) {
    const auto index = e.point_index();
    if (index != Invalid_input::npos)
      std::fprintf(stderr, "dewall: %s: point %zu: %s\n", input.c_str(), index + table.first_index, e.what());
    else
      std::fprintf(stderr, "dewall: %s: %s\n", input.c_str(), e.what());
    return 1;
  }
  io::write_simplices_file(output, run.simplices, table.first_index);
  if (stats) print_stats(stderr, run);
  return 0;
}


namespace {
const bool registered = register_command({"triangulate", command_triangulate,
    "  triangulate INPUT [-o OUTPUT] [--stats]\n"
    "      Delaunay triangulation of the points in INPUT ('-' = standard input):\n"
    "      plain text (one point per line, '#' comments), rbox output, or TetGen .node.\n"
    "      Writes one simplex per line (zero-based input indices) to OUTPUT\n"
    "      (default: standard output); TetGen .ele when OUTPUT ends in .ele.\n"
    "      --stats prints the paper's Table 1 counters and build_s=SECONDS on stderr.\n"});
}  // namespace

}  // namespace dewall::cli
