// Side-by-side timing of dewall and CGAL on the same points, in one run.
//   bench_dewall [--points N] [--dim 2|3] [--kind K] [--seed S] [--repeat R]
// K is a kind of `dewall generate` (default uniform: the unit cube; sphere,
// grid, lattice-sphere, … are the degenerate and nearly degenerate cases).
// Prints, for each tool, the best of R runs (seconds) and the ratio to CGAL's
// sequential Delaunay_triangulation_3 (or _2), after checking that both give
// the same simplices. Absolute seconds on a shared machine are noise; the
// ratios are the figure to report.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "dewall/dewall.hpp"
#include "dewall/io/point_generators.hpp"

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
  std::vector<dewall::kernel::Point_d<D>> points(table.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int j = 0; j < D; ++j) points[i][j] = table.coordinates[i * D + static_cast<std::size_t>(j)];

  std::size_t cgal_cells = 0, dewall_serial = 0, dewall_parallel = 0;
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
  dewall::Options serial;
  serial.parallel_depth = 0;
  const double t_serial =
      best_of(repeat, [&] { dewall_serial = dewall::triangulate<D>(points, serial).simplices.size(); });
  const double t_parallel = best_of(repeat, [&] { dewall_parallel = dewall::triangulate<D>(points).simplices.size(); });

  std::printf("%s points in E^%d, n = %zu, seed = %llu, best of %d\n", dewall::io::point_kind_name(kind), D,
              points.size(), static_cast<unsigned long long>(seed), repeat);
  std::printf("%-40s %10s %10s %12s\n", "tool", "seconds", "ratio", "simplices");
  std::printf("%-40s %10.3f %10.2f %12zu\n", D == 2 ? "CGAL Delaunay_triangulation_2" : "CGAL Delaunay_triangulation_3",
              t_cgal, 1.0, cgal_cells);
  std::printf("%-40s %10.3f %10.2f %12zu\n", "dewall (1 thread)", t_serial, t_serial / t_cgal, dewall_serial);
  std::printf("%-40s %10.3f %10.2f %12zu\n", "dewall (parallel recursion, TBB)", t_parallel, t_parallel / t_cgal,
              dewall_parallel);
  if (dewall_serial != cgal_cells || dewall_parallel != cgal_cells) {
    std::fprintf(stderr, "simplex counts differ\n");
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t n = 100000;
  int dim = 3, repeat = 3;
  std::uint64_t seed = 1;
  dewall::io::Point_kind kind = dewall::io::Point_kind::uniform;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--kind")) {
      const auto parsed = dewall::io::parse_point_kind(argv[i + 1]);
      if (!parsed) {
        std::fprintf(stderr, "bench_dewall: unknown kind %s (%s)\n", argv[i + 1], dewall::io::point_kind_names().c_str());
        return 2;
      }
      kind = *parsed;
    } else if (!std::strcmp(argv[i], "--points")) n = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--dim")) dim = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--seed")) seed = std::strtoull(argv[i + 1], nullptr, 10);
    else if (!std::strcmp(argv[i], "--repeat")) repeat = std::atoi(argv[i + 1]);
  }
  return dim == 2 ? run<2>(kind, n, seed, repeat) : run<3>(kind, n, seed, repeat);
}
