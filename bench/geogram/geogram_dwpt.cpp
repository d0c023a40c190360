// geogram's 3D Delaunay (its Delaunay module: "BDEL", sequential, or "PDEL",
// parallel) on a .dwpt point file, timed like bench_scale_cgal and hxt_dwpt:
// the construction from the points in memory; reading the file not timed.
//
//   geogram_dwpt POINTS.dwpt [--parallel] [--threads N] [-o SIMPLICES.dwsx]
//
// Prints one JSON line: points, finite tetrahedra, seconds of set_vertices
// (geogram's BRIO order, insertion, the final compaction of its cell arrays).
// geogram keeps the input's vertex indices; of a repeated point one copy is
// inserted (-o maps it to the first occurrence).
// --parallel: "PDEL" on geogram's thread pool, --threads N of them (default
// every core). -o writes the finite tetrahedra as .dwsx (docs/formats.md) for
// `dewall certify POINTS SIMPLICES` (geogram perturbs by vertex index, not
// CGAL's scheme: on degenerate input its triangulation is Delaunay but not
// necessarily the canonical one).
//
// Built from geogram's Delaunay PSM extracted from the user's checkout
// (bench/geogram/run.sh); nothing of geogram is in this repository.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "Delaunay_psm.h"

namespace {

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "geogram_dwpt: %s\n", what.c_str());
  std::exit(1);
}

const char* const usage = "usage: geogram_dwpt POINTS.dwpt [--parallel] [--threads N] [-o SIMPLICES.dwsx]";

}  // namespace

int main(int argc, char** argv) {
  const char* input = nullptr;
  const char* output = nullptr;
  bool parallel = false;
  long threads = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--parallel")) parallel = true;
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atol(argv[++i]);
    else if (!std::strcmp(argv[i], "-o") && i + 1 < argc) output = argv[++i];
    else if (!input && argv[i][0] != '-') input = argv[i];
    else die(usage);
  }
  if (!input || threads < 0) die(usage);

  // .dwpt: 'DWPT', version 1, dimension, flags 0, count (u64), then doubles.
  std::FILE* f = std::fopen(input, "rb");
  if (!f) die("cannot open the input");
  unsigned char h[24];
  if (std::fread(h, 1, 24, f) != 24 || std::memcmp(h, "DWPT", 4) != 0) die("not a .dwpt file");
  std::uint32_t version, dim, flags;
  std::uint64_t count;
  std::memcpy(&version, h + 4, 4);
  std::memcpy(&dim, h + 8, 4);
  std::memcpy(&flags, h + 12, 4);
  std::memcpy(&count, h + 16, 8);
  if (version != 1 || flags != 0 || dim != 3) die("need a version 1, 3D .dwpt file");
  if (count < 5 || count >= UINT32_MAX) die("need 5 to 2^32-2 points");
  const auto n = static_cast<GEO::index_t>(count);
  std::vector<double> xyz(3 * static_cast<std::size_t>(n));
  if (std::fread(xyz.data(), sizeof(double), xyz.size(), f) != xyz.size()) die("truncated file");
  std::fclose(f);

  GEO::initialize(GEO::GEOGRAM_INSTALL_NONE);
  GEO::Logger::instance()->set_quiet(true);
  GEO::CmdLine::import_arg_group("standard");
  GEO::CmdLine::import_arg_group("algo");
  if (parallel) {
    if (threads > 0) GEO::Process::set_max_threads(static_cast<GEO::index_t>(threads));
  } else {
    GEO::Process::enable_multithreading(false);
  }
  GEO::Delaunay_var delaunay = GEO::Delaunay::create(3, parallel ? "PDEL" : "BDEL");

  const auto t0 = std::chrono::steady_clock::now();
  delaunay->set_vertices(n, xyz.data());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::uint64_t cells = delaunay->nb_cells();  // finite ones: keeps_infinite is off
  std::printf("{\"tool\": \"geogram\", \"mode\": \"%s\", \"threads\": %u, \"points\": %u, \"cells\": %llu, "
              "\"seconds\": %.3f}\n",
              parallel ? "PDEL" : "BDEL", parallel ? GEO::Process::maximum_concurrent_threads() : 1u, n,
              static_cast<unsigned long long>(cells), seconds);
  std::fflush(stdout);

  if (output) {
    // Each vertex as the first occurrence of its point (geogram keeps whichever
    // copy of a repeated point its order met first), as `dewall certify` expects.
    std::vector<std::uint32_t> order(n), first(n);
    for (GEO::index_t i = 0; i < n; ++i) order[i] = i;
    const auto point = [&](std::uint32_t i) {
      return std::array<double, 3>{xyz[3 * std::size_t{i}], xyz[3 * std::size_t{i} + 1], xyz[3 * std::size_t{i} + 2]};
    };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return point(a) != point(b) ? point(a) < point(b) : a < b;
    });
    for (GEO::index_t k = 0; k < n; ++k)
      first[order[k]] = k > 0 && point(order[k]) == point(order[k - 1]) ? first[order[k - 1]] : order[k];
    std::FILE* o = std::fopen(output, "wb");
    if (!o) die("cannot open the output");
    const std::uint32_t header[4] = {0x58535744u /* "DWSX" */, 1, 3, 4};
    std::fwrite(header, 4, 4, o);
    std::fwrite(&cells, 8, 1, o);
    for (std::uint64_t c = 0; c < cells; ++c) {
      std::uint32_t s[4];
      for (GEO::index_t k = 0; k < 4; ++k)
        s[k] = first[static_cast<std::uint32_t>(delaunay->cell_vertex(static_cast<GEO::index_t>(c), k))];
      std::fwrite(s, 4, 4, o);
    }
    if (std::fclose(o) != 0) die("write failed");
  }
  return 0;
}
