// dewall demo [--kind KIND] [--points N] [--dim D] [--seed S]: the default job of
// ./run: generate a point set, triangulate it, certify the result, summarize.
#include <chrono>
#include <cstdio>
#include <random>

#include "cli.hpp"
#include "dewall/certify/certify.hpp"
#include "dewall/error.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/io/quote.hpp"

namespace dewall::cli {

int command_demo(int argc, char** argv) {
  std::size_t n = 100000;
  long dim = 3;
  io::Point_kind kind = io::Point_kind::uniform;
  std::uint64_t seed = std::random_device{}();
  parse_arguments(
      argc, argv, 0,
      [&](const std::string& a, int& i) {
        if (a == "--points") n = parse_point_count(next_arg(i, argc, argv));
        else if (a == "--dim") dim = parse_long(next_arg(i, argc, argv), "--dim value");
        else if (a == "--seed") seed = parse_seed(next_arg(i, argc, argv));
        else if (a == "--kind") {
          const std::string name = next_arg(i, argc, argv);
          const auto k = io::parse_point_kind(name);
          if (!k) throw Usage_error("unknown kind " + io::quoted(name) + " (" + io::point_kind_names() + ")");
          kind = *k;
        } else return false;
        return true;
      });
  check_dim_option(dim);
  check_fits_in_memory(n, dim);
  std::printf("dewall demo: %zu %s points in E^%ld, seed %llu\n", n, io::point_kind_name(kind), dim,
              static_cast<unsigned long long>(seed));
  io::Point_table table = io::generate_points(kind, n, static_cast<int>(dim), seed);
  Run run;
  try {
    run = triangulate_any(table);
  } catch (const Invalid_input& e) {
    return report_invalid_input("demo", e, 0);
  }
  print_stats(stdout, run);
  std::printf("triangulated %zu points into %zu simplices in %.3f s\n", run.stats.distinct_points,
              run.stats.simplices, run.seconds);
  const auto start = std::chrono::steady_clock::now();
  const certify::Report report = certify_any(table, run.simplices, {});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (const auto* v = report.first_fatal()) {
    std::printf("certify: NOT a Delaunay triangulation: %s\n", certify::describe(*v).c_str());
    return 1;
  }
  std::printf("certify: %s Delaunay triangulation (checked exactly in %.3f s)\n",
              report.canonical ? "the canonical (CGAL's, perturbed)" : "a non-canonical", seconds);
  return report.canonical ? 0 : 1;
}

namespace {
const bool registered = register_command({"demo", command_demo,
    "  demo [--kind KIND] [--points N] [--dim D] [--seed S]\n"
    "      Generates N points (default 100000 uniform points in the unit cube of\n"
    "      E^3; KIND as for generate), triangulates them, certifies the result with\n"
    "      the independent exact checker and prints a summary. ./run with no\n"
    "      arguments runs this.\n"});
}  // namespace

}  // namespace dewall::cli
