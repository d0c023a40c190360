// CGAL's Delaunay_triangulation_3 of a binary point file (.dwpt), the peer of
// the scale runs (bench/scale):
//
//   bench_scale_cgal POINTS.dwpt [--parallel]
//
// Sequential (CGAL's range constructor: spatial sort, then insertion), or
// parallel on all cores (Parallel_tag: CGAL's TBB construction with its lock
// grid). Prints one JSON line: points, finite cells, and seconds for the
// construction from the points in memory (reading the file is not timed).
// Peak memory is the process's; bench/scale measures it from outside. The
// heap is glibc's default, as dewall's (GLIBC_TUNABLES=glibc.malloc.hugetlb=1
// gives both transparent huge pages).
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

#include "dewall/io/point_reader.hpp"

namespace {

using K = CGAL::Epick;

template <class DT, class... Extra>
void run(const std::vector<K::Point_3>& points, const char* mode, Extra... extra) {
  const auto t0 = std::chrono::steady_clock::now();
  const DT dt(points.begin(), points.end(), extra...);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("{\"tool\": \"cgal-%s\", \"points\": %zu, \"cells\": %zu, \"seconds\": %.3f}\n", mode, points.size(),
              static_cast<std::size_t>(dt.number_of_finite_cells()), seconds);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3 || (argc == 3 && std::strcmp(argv[2], "--parallel") != 0)) {
    std::fprintf(stderr, "usage: bench_scale_cgal POINTS.dwpt [--parallel]\n");
    return 2;
  }
  const bool parallel = argc == 3;
  std::vector<K::Point_3> points;
  CGAL::Bbox_3 box;
  {
    const auto table = dewall::io::read_points_file(argv[1]);
    if (table.dimension != 3) {
      std::fprintf(stderr, "bench_scale_cgal: 3D points only\n");
      return 2;
    }
    points.reserve(table.size());
    for (std::size_t i = 0; i < table.size(); ++i) {
      points.emplace_back(table.coordinates[3 * i], table.coordinates[3 * i + 1], table.coordinates[3 * i + 2]);
      box += points.back().bbox();
    }
  }
  if (!parallel) {
    run<CGAL::Delaunay_triangulation_3<K>>(points, "sequential");
  } else {
    using Tds = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<K>,
                                                     CGAL::Delaunay_triangulation_cell_base_3<K>, CGAL::Parallel_tag>;
    using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
    typename DT::Lock_data_structure locks(box, 50);
    run<DT>(points, "parallel", &locks);
  }
  return 0;
}
