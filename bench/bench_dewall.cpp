// Side-by-side timing of dewall and CGAL on the same points, in one run.
//   bench_dewall [--points N] [--dim 2|3] [--kind K] [--seed S] [--repeat R]
// K is a kind of `dewall generate` (default uniform: the unit cube; sphere,
// grid, lattice-sphere, … are the degenerate and nearly degenerate cases).
// Prints, for each tool, the best of R runs (seconds) and the ratio to CGAL's
// sequential Delaunay_triangulation_3 (or _2), then checks (untimed) that
// dewall's simplices, serial and parallel, are CGAL's as index sets. Absolute
// seconds on a shared machine are noise; the ratios are the figure to report.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "support/cgal_delaunay.hpp"
#include "dewall/dewall.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/kernel/point_array.hpp"

namespace {

template <class F>
double best_of(int repeat, F&& f) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

template <int D>
int run(dewall::io::Point_kind kind, std::size_t n, std::uint64_t seed, int repeat) {
  const dewall::io::Point_table table = dewall::io::generate_points(kind, n, D, seed);
  const auto points = dewall::kernel::points_from_coordinates<D>(table.coordinates);

  std::size_t cgal_cells = 0;
  dewall::Triangulation<D> serial_result, parallel_result;
  const double t_cgal = best_of(repeat, [&] {
    if constexpr (D == 2) {
      std::vector<CGAL::Epick::Point_2> p;
      for (const auto& q : points) p.emplace_back(q[0], q[1]);
      CGAL::Delaunay_triangulation_2<CGAL::Epick> dt(p.begin(), p.end());
      cgal_cells = dt.number_of_faces();
    } else {
      std::vector<CGAL::Epick::Point_3> p;
      for (const auto& q : points) p.emplace_back(q[0], q[1], q[2]);
      CGAL::Delaunay_triangulation_3<CGAL::Epick> dt(p.begin(), p.end());
      cgal_cells = dt.number_of_finite_cells();
    }
  });
  // DeWall forced (the subject), then the default engine (automatic), one thread each.
  const dewall::Options serial{.parallel_depth = 0, .engine = dewall::Engine::dewall};
  const dewall::Options parallel{.engine = dewall::Engine::dewall};
  const dewall::Options automatic{.parallel_depth = 0};
  dewall::Triangulation<D> automatic_result;
  const double t_serial = best_of(repeat, [&] { serial_result = dewall::triangulate<D>(points, serial); });
  const double t_parallel = best_of(repeat, [&] { parallel_result = dewall::triangulate<D>(points, parallel); });
  const double t_automatic = best_of(repeat, [&] { automatic_result = dewall::triangulate<D>(points, automatic); });

  std::printf("%s points in E^%d, n = %zu, seed = %llu, best of %d\n", dewall::io::point_kind_name(kind), D,
              points.size(), static_cast<unsigned long long>(seed), repeat);
  std::printf("%-40s %10s %10s %12s\n", "tool", "seconds", "ratio", "simplices");
  std::printf("%-40s %10.3f %10.2f %12zu\n", D == 2 ? "CGAL Delaunay_triangulation_2" : "CGAL Delaunay_triangulation_3",
              t_cgal, 1.0, cgal_cells);
  std::printf("%-40s %10.3f %10.2f %12zu\n", "dewall (1 thread)", t_serial, t_serial / t_cgal,
              serial_result.simplices.size());
  std::printf("%-40s %10.3f %10.2f %12zu\n", "dewall (parallel recursion, TBB)", t_parallel, t_parallel / t_cgal,
              parallel_result.simplices.size());
  const std::string automatic_name = std::string("default engine, 1 thread (built by ") +
                                     dewall::engine_name(automatic_result.statistics.engine) + ")";
  std::printf("%-40s %10.3f %10.2f %12zu\n", automatic_name.c_str(), t_automatic, t_automatic / t_cgal,
              automatic_result.simplices.size());
  const auto reference = dewall::cgal::cgal_delaunay<D>(points);
  if (dewall::cgal::as_simplex_set<D>(serial_result.simplices) != reference ||
      dewall::cgal::as_simplex_set<D>(parallel_result.simplices) != reference ||
      dewall::cgal::as_simplex_set<D>(automatic_result.simplices) != reference) {
    std::fprintf(stderr, "bench_dewall: dewall's simplices differ from CGAL's\n");
    return 1;
  }
  std::printf("dewall's simplices (serial, parallel, default engine) are CGAL's\n");
  return 0;
}

int usage(const char* why) {
  std::fprintf(stderr,
               "bench_dewall: %s\nusage: bench_dewall [--points N] [--dim 2|3] [--kind K] [--seed S] [--repeat R]\n"
               "K: %s\n",
               why, dewall::io::point_kind_names().c_str());
  return 2;
}

// A whole-string unsigned decimal number, or nothing.
std::optional<std::uint64_t> parse_count(const char* text) {
  if (*text < '0' || *text > '9') return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text, &end, 10);
  if (*end != '\0' || errno == ERANGE) return std::nullopt;
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t n = 100000, dim = 3, repeat = 3, seed = 1;
  dewall::io::Point_kind kind = dewall::io::Point_kind::uniform;
  for (int i = 1; i < argc; i += 2) {
    const std::string option = argv[i];
    if (i + 1 == argc) return usage((option + " needs a value").c_str());
    const char* value = argv[i + 1];
    if (option == "--kind") {
      const auto parsed = dewall::io::parse_point_kind(value);
      if (!parsed) return usage((std::string("unknown kind ") + value).c_str());
      kind = *parsed;
      continue;
    }
    std::uint64_t* target = option == "--points" ? &n
                            : option == "--dim"  ? &dim
                            : option == "--seed" ? &seed
                            : option == "--repeat" ? &repeat
                                                   : nullptr;
    if (!target) return usage(("unknown option " + option).c_str());
    const auto parsed = parse_count(value);
    if (!parsed) return usage((option + " needs a non-negative integer, not " + value).c_str());
    *target = *parsed;
  }
  if (dim != 2 && dim != 3) return usage("--dim must be 2 or 3");
  if (repeat < 1 || repeat > 1000) return usage("--repeat must be 1 … 1000");
  try {
    return dim == 2 ? run<2>(kind, n, seed, static_cast<int>(repeat)) : run<3>(kind, n, seed, static_cast<int>(repeat));
  } catch (const std::exception& e) {  // too few points, points not spanning E^D, …
    std::fprintf(stderr, "bench_dewall: %s\n", e.what());
    return 1;
  }
}
