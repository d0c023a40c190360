// The incremental engine's counters on a point file, for profiles that do not
// depend on the machine's load (walk steps per point, the zones' share, the
// stars glued through the ridge table), and its construction time:
//
//   bench_incremental POINTS [--threads N] [--repeat R] [--sequential]
//
// Builds Incremental_delaunay<D> (D = 2 … 4) from the file's points (the
// repeats dropped, as the tool's collecting path), R times on at most N
// threads (default 1), and prints one JSON line: the counters of the last
// build (per inserted point), the best of the R build times and a hash of
// the cells in slot order (equal hashes: the same output order).
// Times: the best wall-clock and the best process CPU seconds of the R builds. --sequential
// turns the zones off (every point inserted one by one).
#include <tbb/global_control.h>

#include <chrono>
#include <ctime>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "dewall/detail/common/hashing.hpp"
#include "dewall/detail/incremental/incremental_delaunay.hpp"
#include "dewall/io/point_reader.hpp"

namespace {

struct Arguments {
  std::string path;
  int threads = 1, repeat = 1;
  bool sequential = false;
};

template <int D>
int run(const dewall::io::Point_table& table, const Arguments& a) {
  using Coords = std::array<double, D>;
  const auto* coords = reinterpret_cast<const Coords*>(table.coordinates.data());
  dewall::detail::Incremental_tuning tuning;
  if (a.sequential) tuning.zoned_insertion_threshold = std::numeric_limits<std::size_t>::max();
  // Wall-clock and process CPU seconds (on a loaded machine the CPU time
  // moves less: time spent waiting for a core is not in it).
  const auto cpu_now = [] {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  };
  double best = std::numeric_limits<double>::infinity(), best_cpu = best;
  for (int r = 0; r < a.repeat; ++r) {
    dewall::detail::Incremental_delaunay<D> dt(tuning);
    const dewall::kernel::Fp_environment_guard guard;
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = cpu_now();
    const bool built = dt.build_dropping_repeats(
        table.size(), [&](std::size_t k) -> const Coords& { return coords[k]; }, [](std::size_t k) { return k; },
        [] {});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best_cpu = std::min(best_cpu, cpu_now() - cpu0);
    if (!built) {
      std::fprintf(stderr, "bench_incremental: the points do not span E^%d\n", D);
      return 1;
    }
    best = std::min(best, seconds);
    if (r + 1 < a.repeat) continue;
    std::uint64_t hash = 0;
    for (std::size_t c = 0; c < dt.slots(); ++c)
      if (dt.holds_finite_cell(c))
        for (const auto v : dt.cell(c)) hash = dewall::detail::mix64(hash ^ dt.input_index(v));
    const auto& s = dt.statistics();
    const double n = static_cast<double>(dt.vertices());
    std::printf(
        "{\"points\": %zu, \"vertices\": %zu, \"cells\": %zu, \"walk_steps_per_point\": %.4f, "
        "\"conflict_cells_per_point\": %.4f, \"created_cells_per_point\": %.4f, \"zoned_share\": %.4f, "
        "\"zone_rounds\": %zu, \"near_cut_points\": %zu, \"zone_failures\": %zu, \"ridge_table_stars\": %zu, \"hull_starts\": %zu, "
        "\"semi_static_first_windows\": %zu, \"threads\": %d, \"seconds\": %.4f, \"cpu_seconds\": %.4f, \"hash\": \"%016llx\"}\n",
        table.size(), dt.vertices(), dt.finite_cells(), static_cast<double>(s.walk_steps) / n,
        static_cast<double>(s.conflict_cells) / n, static_cast<double>(s.created_cells) / n,
        static_cast<double>(s.zoned_points) / n, s.zone_rounds, s.near_cut_points, s.zone_failures, s.ridge_table_stars, s.hull_starts,
        s.semi_static_first_windows, a.threads, best, best_cpu, static_cast<unsigned long long>(hash));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) a.threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) a.repeat = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--sequential")) a.sequential = true;
    else if (a.path.empty() && argv[i][0] != '-') a.path = argv[i];
    else a.path.clear(), i = argc;
  }
  if (a.path.empty() || a.threads < 1 || a.repeat < 1) {
    std::fprintf(stderr, "usage: bench_incremental POINTS [--threads N] [--repeat R] [--sequential]\n");
    return 2;
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(a.threads));
  const auto table = dewall::io::read_points_file(a.path);
  switch (table.dimension) {
    case 2: return run<2>(table, a);
    case 3: return run<3>(table, a);
    case 4: return run<4>(table, a);
    default: std::fprintf(stderr, "bench_incremental: 2D to 4D points only\n"); return 2;
  }
}
