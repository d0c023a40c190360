// dewall demo [--points N] [--dim D] [--seed S]
#include <cstdio>
#include <random>

#include "cli.hpp"
#include "dewall/error.hpp"

namespace dewall::cli {

int command_demo(int argc, char** argv) {
  long n = 100000, dim = 3;
  unsigned long long seed = std::random_device{}();
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points") n = parse_long(next_arg(i, argc, argv), "point count");
    else if (a == "--dim") dim = parse_long(next_arg(i, argc, argv), "dimension");
    else if (a == "--seed") seed = static_cast<unsigned long long>(parse_long(next_arg(i, argc, argv), "seed"));
    else throw Usage_error("unknown option '" + a + "'");
  }
  if (dim < 2 || dim > 6) throw Usage_error("--dim must be 2 to 6");
  std::printf("dewall demo: %ld uniform random points in the unit cube of E^%ld, seed %llu\n", n, dim, seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  io::Point_table table;
  table.dimension = static_cast<int>(dim);
  table.coordinates.resize(static_cast<std::size_t>(n * dim));
  for (double& c : table.coordinates) c = uniform(rng);
  Run run;
  try {
    run = triangulate_any(table);
  } catch (const Invalid_input& e) {
    std::fprintf(stderr, "dewall: %s\n", e.what());
    return 1;
  }
  print_stats(stdout, run);
  std::printf("triangulated %zu points into %zu simplices in %.3f s\n", run.stats.distinct_points,
              run.stats.simplices, run.seconds);
  return 0;
}


namespace {
const bool registered = register_command({"demo", command_demo,
    "  demo [--points N] [--dim D] [--seed S]\n"
    "      Generates N uniform random points in the unit cube of E^D (default\n"
    "      100000 points, D = 3), triangulates them and prints a summary.\n"});
}  // namespace

}  // namespace dewall::cli
