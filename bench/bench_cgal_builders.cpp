// Time and peak memory to a finished CGAL triangulation: the drop-in builders
// (dewall/cgal/*.hpp) against CGAL's own range constructor, on the same
// uniform points, as a CGAL user would swap them (docs/cgal.md).
//
//   bench_cgal_builders [--reps R] [--only CASE[,CASE…]] [n ...]   (default: 3 reps, 100000 1000000)
//
// Cases: 3d (Delaunay_triangulation_3<Epick>), 3d_info (vertices with an
// unsigned info, built from std::pair<Point, unsigned>), 2d
// (Delaunay_triangulation_2<Epick>), 3d_parallel (Parallel_tag with a
// Spatial_lock_grid_3; CGAL's parallel construction on all cores), 4d
// (Delaunay_triangulation<Epick_d<4>>, sizes divided by 10).
//
// Each construction runs in a child process of its own (fork), so that its
// peak resident memory (getrusage of the child) is its own: the child holds
// the parent's points, as the caller would, and builds one triangulation.
// The two constructions alternate, R times each; per case and n one line:
// the best time and the lowest peak of each, and builder / CGAL ratios.
#include <CGAL/Delaunay_triangulation.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Epick_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "dewall/cgal/delaunay_triangulation_2.hpp"
#include "dewall/cgal/delaunay_triangulation_3.hpp"
#include "dewall/cgal/delaunay_triangulation_d.hpp"

namespace {

using K = CGAL::Epick;
using DT3 = CGAL::Delaunay_triangulation_3<K>;
using Vb_info = CGAL::Triangulation_vertex_base_with_info_3<unsigned, K>;
using Tds_info = CGAL::Triangulation_data_structure_3<Vb_info, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using DT3_info = CGAL::Delaunay_triangulation_3<K, Tds_info>;
using DT2 = CGAL::Delaunay_triangulation_2<K>;
using Tds_parallel = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                                          CGAL::Delaunay_triangulation_cell_base_3<K>,
                                                          CGAL::Parallel_tag>;
using DT3_parallel = CGAL::Delaunay_triangulation_3<K, Tds_parallel>;
using Kd4 = CGAL::Epick_d<CGAL::Dimension_tag<4>>;
using DT4 = CGAL::Delaunay_triangulation<Kd4>;

using Clock = std::chrono::steady_clock;

struct Run {
  double seconds = 0;
  double peak_mb = 0;
};

// Runs build() in a child process: the seconds it took (through a pipe) and
// the child's peak resident set. A failed child ends the benchmark.
Run in_child(const std::function<double()>& build) {
  int fds[2];
  if (pipe(fds) != 0) std::exit(2);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const double s = build();
    if (write(fds[1], &s, sizeof s) != static_cast<ssize_t>(sizeof s)) _exit(3);
    _exit(0);
  }
  close(fds[1]);
  Run run;
  if (read(fds[0], &run.seconds, sizeof run.seconds) != static_cast<ssize_t>(sizeof run.seconds)) run.seconds = -1;
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || run.seconds < 0) {
    std::fprintf(stderr, "bench_cgal_builders: a child failed\n");
    std::exit(1);
  }
  run.peak_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
  return run;
}

// Times make() to a finished object; a cell count from it keeps the work.
template <class Make>
double timed(Make&& make) {
  const auto t0 = Clock::now();
  const auto dt = make();
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (dt.number_of_vertices() == 0) _exit(4);
  return s;
}

struct Case {
  std::string name;
  std::function<double()> cgal, builder;
};

std::vector<double> uniform(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x(count);
  for (double& v : x) v = u(rng);
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 3;
  std::string only;
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--reps" && i + 1 < argc) reps = std::stoi(argv[++i]);
    else if (a == "--only" && i + 1 < argc) only = "," + std::string(argv[++i]) + ",";
    else sizes.push_back(std::stoul(a));
  }
  if (sizes.empty()) sizes = {100000, 1000000};

  std::printf("%-12s %9s %9s %9s %7s %9s %9s %7s\n", "case", "n", "cgal_s", "builder_s", "time", "cgal_MB",
              "builder_MB", "memory");
  for (const std::size_t n : sizes) {
    // Only the running case's points live in the parent (the children hold
    // them, as a caller would, and nothing else of the parent's).
    std::vector<K::Point_3> p3;
    std::vector<std::pair<K::Point_3, unsigned>> p3_info;
    std::vector<K::Point_2> p2;
    std::vector<Kd4::Point_d> p4;
    const std::size_t n4 = std::max<std::size_t>(n / 10, 10);
    const auto prepare = [&](const std::string& name) {
      p3 = {}, p3_info = {}, p2 = {}, p4 = {};
      if (name == "4d") {
        const std::vector<double> x = uniform(4 * n4, 20260521 + n4);
        for (std::size_t i = 0; i < n4; ++i) p4.emplace_back(x.begin() + 4 * static_cast<std::ptrdiff_t>(i),
                                                              x.begin() + 4 * static_cast<std::ptrdiff_t>(i + 1));
        return;
      }
      const std::vector<double> x = uniform(3 * n, 20260520 + n);
      for (std::size_t i = 0; i < n; ++i) {
        const K::Point_3 p(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        if (name == "3d_info") p3_info.emplace_back(p, static_cast<unsigned>(i));
        else if (name == "2d") p2.emplace_back(p.x(), p.y());
        else p3.push_back(p);
      }
    };

    const std::vector<Case> cases = {
        {"3d", [&] { return timed([&] { return DT3(p3.begin(), p3.end()); }); },
         [&] { return timed([&] { return dewall::cgal::make_delaunay_triangulation_3<DT3>(p3.begin(), p3.end()); }); }},
        {"3d_info", [&] { return timed([&] { return DT3_info(p3_info.begin(), p3_info.end()); }); },
         [&] {
           return timed([&] { return dewall::cgal::make_delaunay_triangulation_3<DT3_info>(p3_info.begin(), p3_info.end()); });
         }},
        {"2d", [&] { return timed([&] { return DT2(p2.begin(), p2.end()); }); },
         [&] { return timed([&] { return dewall::cgal::make_delaunay_triangulation_2<DT2>(p2.begin(), p2.end()); }); }},
        {"3d_parallel",
         [&] {
           DT3_parallel::Lock_data_structure locks(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 50);
           return timed([&] { return DT3_parallel(p3.begin(), p3.end(), &locks); });
         },
         [&] {
           DT3_parallel::Lock_data_structure locks(CGAL::Bbox_3(0, 0, 0, 1, 1, 1), 50);
           return timed([&] {
             return dewall::cgal::make_delaunay_triangulation_3<DT3_parallel>(p3.begin(), p3.end(), {}, {}, &locks);
           });
         }},
        {"4d",
         [&] {
           return timed([&] {
             DT4 t(4);
             t.insert(p4.begin(), p4.end());
             return t;
           });
         },
         [&] { return timed([&] { return dewall::cgal::make_delaunay_triangulation_d<DT4>(p4.begin(), p4.end()); }); }},
    };
    for (const Case& c : cases) {
      if (!only.empty() && only.find("," + c.name + ",") == std::string::npos) continue;
      prepare(c.name);
      Run cgal{1e300, 1e300}, builder{1e300, 1e300};
      for (int r = 0; r < reps; ++r) {
        const Run a = in_child(c.cgal), b = in_child(c.builder);
        cgal = {std::min(cgal.seconds, a.seconds), std::min(cgal.peak_mb, a.peak_mb)};
        builder = {std::min(builder.seconds, b.seconds), std::min(builder.peak_mb, b.peak_mb)};
      }
      std::printf("%-12s %9zu %9.3f %9.3f %6.2fx %9.0f %9.0f %6.2fx\n", c.name.c_str(), c.name == "4d" ? n4 : n,
                  cgal.seconds, builder.seconds, builder.seconds / cgal.seconds, cgal.peak_mb, builder.peak_mb,
                  builder.peak_mb / cgal.peak_mb);
      std::fflush(stdout);
    }
  }
  return 0;
}
