// dewall: the command-line front end.
//   dewall triangulate INPUT [-o OUTPUT] [--stats]
//   dewall demo [--points N] [--dim D] [--seed S]
// Exit status: 0 on success, 1 when the points cannot be triangulated, 2 for
// usage errors and unreadable input.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "dewall/dewall.hpp"
#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_writer.hpp"

namespace {

constexpr const char* usage =
    "usage: dewall <command> [options]\n"
    "\n"
    "commands:\n"
    "  triangulate INPUT [-o OUTPUT] [--stats]\n"
    "      Delaunay triangulation of the points in INPUT ('-' = standard input):\n"
    "      plain text (one point per line, '#' comments), rbox output, or TetGen .node.\n"
    "      Writes one simplex per line (zero-based input indices) to OUTPUT\n"
    "      (default: standard output); TetGen .ele when OUTPUT ends in .ele.\n"
    "      --stats prints the paper's Table 1 counters and build_s=SECONDS on stderr.\n"
    "  demo [--points N] [--dim D] [--seed S]\n"
    "      Generates N uniform random points in the unit cube of E^D (default\n"
    "      100000 points, D = 3), triangulates them and prints a summary.\n"
    "  help\n";

struct Usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Run {
  dewall::io::Simplex_table simplices;
  dewall::Statistics stats;
  double seconds = 0;
};

template <int D>
Run triangulate_table(const dewall::io::Point_table& table) {
  std::vector<dewall::kernel::Point_d<D>> points(table.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int j = 0; j < D; ++j) points[i][j] = table.coordinates[i * D + static_cast<std::size_t>(j)];
  Run run;
  run.simplices.vertices_per_simplex = D + 1;
  const auto start = std::chrono::steady_clock::now();
  run.stats = dewall::triangulate_to<dewall::kernel::Filtered_kernel_d<D>>(
      std::span<const dewall::kernel::Point_d<D>>(points),
      [&](const dewall::Simplex<D>& s) { run.simplices.indices.insert(run.simplices.indices.end(), s.begin(), s.end()); });
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

Run triangulate_any(const dewall::io::Point_table& table) {
  switch (table.dimension) {
    case 2: return triangulate_table<2>(table);
    case 3: return triangulate_table<3>(table);
    case 4: return triangulate_table<4>(table);
    case 5: return triangulate_table<5>(table);
    case 6: return triangulate_table<6>(table);
  }
  throw Usage_error("dimension " + std::to_string(table.dimension) + " is not supported (2 to 6)");
}

void print_stats(std::FILE* out, const Run& run) {
  const auto& s = run.stats;
  std::fprintf(out,
               "points=%zu distinct=%zu simplices=%zu first_wall_simplices=%zu recursion_depth=%zu\n"
               "grid_cells=%zu max_points_in_cell=%zu mean_cells_per_simplex=%.2f candidates_per_search=%.2f\n"
               "build_s=%.6f\n",
               s.input_points, s.distinct_points, s.simplices, s.first_wall_simplices, s.recursion_depth,
               s.grid_cells, s.max_points_in_cell, s.mean_cells_per_simplex(),
               s.simplex_searches ? double(s.candidates_tested) / double(s.simplex_searches) : 0.0, run.seconds);
}

std::string next_arg(int& i, int argc, char** argv) {
  if (i + 1 >= argc) throw Usage_error(std::string("option ") + argv[i] + " needs a value");
  return argv[++i];
}

long parse_long(const std::string& s, const char* what) {
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < 0) throw Usage_error(std::string("invalid ") + what + ": '" + s + "'");
  return v;
}

int command_triangulate(int argc, char** argv) {
  std::string input, output = "-";
  bool stats = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-o" || a == "--output") output = next_arg(i, argc, argv);
    else if (a == "--stats") stats = true;
    else if (a == "-h" || a == "--help") { std::fputs(usage, stdout); return 0; }
    else if (a.size() > 1 && a[0] == '-') throw Usage_error("unknown option '" + a + "'");
    else if (input.empty()) input = a;
    else throw Usage_error("unexpected argument '" + a + "'");
  }
  if (input.empty()) throw Usage_error("triangulate needs an INPUT file ('-' for standard input)");
  const auto table = dewall::io::read_points_file(input);
  Run run;
  try {
    run = triangulate_any(table);
  } catch (const dewall::Invalid_input& e) {
    const auto index = e.point_index();
    if (index != dewall::Invalid_input::npos)
      std::fprintf(stderr, "dewall: %s: point %zu: %s\n", input.c_str(), index + table.first_index, e.what());
    else
      std::fprintf(stderr, "dewall: %s: %s\n", input.c_str(), e.what());
    return 1;
  }
  dewall::io::write_simplices_file(output, run.simplices, table.first_index);
  if (stats) print_stats(stderr, run);
  return 0;
}

int command_demo(int argc, char** argv) {
  long n = 100000, dim = 3;
  unsigned long long seed = std::random_device{}();
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points") n = parse_long(next_arg(i, argc, argv), "point count");
    else if (a == "--dim") dim = parse_long(next_arg(i, argc, argv), "dimension");
    else if (a == "--seed") seed = static_cast<unsigned long long>(parse_long(next_arg(i, argc, argv), "seed"));
    else if (a == "-h" || a == "--help") { std::fputs(usage, stdout); return 0; }
    else throw Usage_error("unknown option '" + a + "'");
  }
  if (dim < 2 || dim > 6) throw Usage_error("--dim must be 2 to 6");
  std::printf("dewall demo: %ld uniform random points in the unit cube of E^%ld, seed %llu\n", n, dim, seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  dewall::io::Point_table table;
  table.dimension = static_cast<int>(dim);
  table.coordinates.resize(static_cast<std::size_t>(n * dim));
  for (double& c : table.coordinates) c = uniform(rng);
  Run run;
  try {
    run = triangulate_any(table);
  } catch (const dewall::Invalid_input& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 1;
  }
  print_stats(stdout, run);
  std::printf("triangulated %zu points into %zu simplices in %.3f s\n", run.stats.distinct_points,
              run.stats.simplices, run.seconds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string command = argc > 1 ? argv[1] : "help";
    if (command == "triangulate") return command_triangulate(argc, argv);
    if (command == "demo") return command_demo(argc, argv);
    if (command == "help" || command == "-h" || command == "--help") {
      std::fputs(usage, stdout);
      return 0;
    }
    throw Usage_error("unknown command '" + command + "'");
  } catch (const Usage_error& e) {
    std::fprintf(stderr, "dewall: %s\n\n%s", e.what(), usage);
    return 2;
  } catch (const dewall::io::Parse_error& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 2;
  }
}
