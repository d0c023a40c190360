// Time to a finished CGAL::Delaunay_triangulation_3: DeWall plus direct
// assembly in the TDS (dewall::cgal::make_delaunay_triangulation_3) against
// CGAL's own construction, on the same uniform points in one run.
//
//   bench_cgal_builders [n ...]        (default: 100000 1000000)
//
// Per n, one line: CGAL's range constructor, DeWall alone, the assembly alone
// (the same steps as the builder, timed apart), the builder end to end, and the
// assembly's share of DeWall's time (the goal is ≤ 30%).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "dewall/cgal/delaunay_triangulation_3.hpp"

namespace {

using K = CGAL::Epick;
using DT = CGAL::Delaunay_triangulation_3<K>;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::stoul(argv[i]));
  if (sizes.empty()) sizes = {100000, 1000000};

  std::printf("%10s %10s %10s %10s %10s %10s %12s %12s\n", "n", "cgal_s", "dewall_s", "assembly_s", "builder_s",
              "cells", "assembly/dw", "builder/cgal");
  for (std::size_t n : sizes) {
    std::mt19937_64 rng(20260520 + n);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<K::Point_3> points(n);
    std::vector<dewall::kernel::Point_d<3>> coords(n);
    for (std::size_t i = 0; i < n; ++i) {
      coords[i] = {{u(rng), u(rng), u(rng)}};
      points[i] = K::Point_3(coords[i][0], coords[i][1], coords[i][2]);
    }

    auto t0 = std::chrono::steady_clock::now();
    DT cgal(points.begin(), points.end());
    const double cgal_s = seconds_since(t0);

    // The builder's two steps, timed apart.
    t0 = std::chrono::steady_clock::now();
    const auto simplices = dewall::triangulate<3>(coords).simplices;
    const double dewall_s = seconds_since(t0);
    double assembly_s = 0;
    t0 = std::chrono::steady_clock::now();
    {
      DT dt;
      auto& tds = dt.tds();
      tds.clear();
      dewall::cgal::detail::Tds_access<3, DT, K::Point_3, dewall::cgal::detail::Item_traits<K::Point_3>>
          access{tds, tds.create_vertex(), points};
      dt.set_infinite_vertex(access.infinite);
      tds.set_dimension(3);
      dewall::cgal::detail::assemble<3>(simplices, points.size(), access);
      assembly_s = seconds_since(t0);  // before the destructor frees the cells
      if (dt.number_of_finite_cells() != cgal.number_of_finite_cells()) std::fprintf(stderr, "cell count differs!\n");
    }

    t0 = std::chrono::steady_clock::now();
    const DT built = dewall::cgal::make_delaunay_triangulation_3<DT>(points.begin(), points.end());
    const double builder_s = seconds_since(t0);

    std::printf("%10zu %10.3f %10.3f %10.3f %10.3f %10zu %11.1f%% %12.2f\n", n, cgal_s, dewall_s, assembly_s, builder_s,
                static_cast<std::size_t>(built.number_of_finite_cells()), 100.0 * assembly_s / dewall_s,
                builder_s / cgal_s);
  }
  return 0;
}
