// dewall-mpi: the Delaunay triangulation of a binary point file (.dwpt) on the
// ranks of an MPI job.
//
//   mpirun -n R dewall-mpi triangulate POINTS.dwpt -o OUT [--stats]
//
// Reading: every rank checks the header and the file size itself, then reads
// its share (points [n·r/R, n·(r+1)/R)) with pread: no rank holds all points.
// Triangulating: dewall::mpi::triangulate. Writing: rank 0 gathers the
// simplices (point-to-point, in chunks), each rank's list sorted, and merges
// them (sorted: the same bytes for every R) and writes them through io::Output_file: a temporary renamed over OUT
// once complete, so a failure, or a rank dying, leaves an old OUT untouched.
// Errors: every rank learns the lowest failing rank's error and ends with it;
// rank 0 prints it. Exit 1: the points cannot be triangulated (a non-finite
// coordinate, too few distinct points, not spanning E^D); 2: usage, reading or
// writing; 0: success.
#include <fcntl.h>
#include <mpi.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "dewall/io/binary_points.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/simplex_writer.hpp"
#include "dewall/mpi/collective_error.hpp"
#include "dewall/mpi/triangulate.hpp"

namespace {

using dewall::mpi::Error_kind;
using dewall::mpi::Rank_error;

__extension__ using U128 = unsigned __int128;  // n·r / R without overflow

struct Usage_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct File_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const char* const usage_text =
    "usage: mpirun -n R dewall-mpi triangulate POINTS.dwpt -o OUT [--stats] [--seed-spacings X]\n"
    "\n"
    "The Delaunay triangulation of POINTS.dwpt (the binary point format, docs/formats.md)\n"
    "computed by R ranks, each reading its share of the file; the same simplices as\n"
    "`dewall triangulate` and CGAL for every R. OUT: .dwsx (binary), .ele, or a plain\n"
    "list (one simplex per line, 0-based point indices); rank 0 writes it, sorted.\n"
    "  --stats   per-rank figures on standard error (points, halo, rounds, seconds)\n"
    "  --seed-spacings X   the first halo: the points within X mean spacings of a\n"
    "            rank's block (default 1; 0: none); only the time changes\n";

struct Arguments {
  std::string input, output;
  bool stats = false;
  dewall::mpi::Options options;
};

Arguments parse(int argc, char** argv) {
  std::vector<std::string> a(argv + 1, argv + argc);
  if (a.empty()) throw Usage_error("missing command");
  if (a[0] == "--help" || a[0] == "-h") throw Usage_error("");
  if (a[0] != "triangulate") throw Usage_error("unknown command '" + a[0] + "' (the one command: triangulate)");
  Arguments r;
  for (std::size_t i = 1; i < a.size(); ++i) {
    if (a[i] == "--help" || a[i] == "-h") throw Usage_error("");
    if (a[i] == "--stats") r.stats = true;
    else if (a[i] == "--seed-spacings") {
      if (i + 1 >= a.size()) throw Usage_error("--seed-spacings needs a number");
      std::size_t used = 0;
      double x = -1;
      try {
        x = std::stod(a[i + 1], &used);
      } catch (const std::exception&) {
      }
      if (used != a[i + 1].size() || !(x >= 0 && x <= 1000)) throw Usage_error("--seed-spacings takes a number in [0, 1000]");
      r.options.seed_spacings = x;
      ++i;
    }
    else if (a[i] == "-o" || a[i] == "--output") {
      if (i + 1 >= a.size()) throw Usage_error(a[i] + " needs a file name");
      r.output = a[++i];
    } else if (!a[i].empty() && a[i][0] == '-') throw Usage_error("unknown option '" + a[i] + "'");
    else if (r.input.empty()) r.input = a[i];
    else throw Usage_error("more than one input file");
  }
  if (r.input.empty()) throw Usage_error("missing input file");
  if (r.output.empty()) throw Usage_error("missing -o OUT");
  if (dewall::io::is_vtk_path(r.output)) throw Usage_error("VTK output needs every point on one rank; write .dwsx");
  return r;
}

std::uint64_t load_le(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

/// Reads `size` bytes at `offset`. \throws File_error
void read_at(int fd, const std::string& name, unsigned char* to, std::uint64_t size, std::uint64_t offset) {
  while (size > 0) {
    const ssize_t got = ::pread(fd, to, std::min<std::uint64_t>(size, 1u << 30), static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw File_error(name + ": cannot read: " + std::strerror(errno));
    if (got == 0) throw File_error(name + ": truncated while reading");
    to += got;
    size -= static_cast<std::uint64_t>(got);
    offset += static_cast<std::uint64_t>(got);
  }
}

/// This rank's share of the file: its dimension, first global index, coordinates.
struct Share {
  int dimension = 0;
  std::uint64_t count = 0, first = 0;
  std::vector<double> coordinates;
};

Share read_share(const std::string& name, int rank, int size) {
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw File_error(name + ": cannot open file: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw File_error(name + ": cannot stat: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw File_error(name + ": not a regular file (each rank reads its share by offset)");
  const auto file_size = static_cast<std::uint64_t>(st.st_size);
  unsigned char h[dewall::io::binary_points_header_size];
  if (file_size < sizeof h)
    throw File_error(name + ": truncated: the header needs 24 bytes, the file has " + std::to_string(file_size));
  read_at(fd, name, h, sizeof h, 0);
  if (std::memcmp(h, dewall::io::binary_points_magic, 4) != 0)
    throw File_error(name + ": not a binary point file (the first bytes are not 'DWPT')");
  const std::uint64_t version = load_le(h + 4, 4), dimension = load_le(h + 8, 4), flags = load_le(h + 12, 4);
  const std::uint64_t count = load_le(h + 16, 8);
  if (version != dewall::io::binary_points_version)
    throw File_error(name + ": unsupported binary point format version " + std::to_string(version));
  if (dimension < 2 || dimension > 6)
    throw File_error(name + ": dimension " + std::to_string(dimension) + " is outside 2 … 6");
  if (flags != 0) throw File_error(name + ": unknown flags " + std::to_string(flags));
  if (count > (std::uint64_t{1} << 58) / dimension) throw File_error(name + ": impossible point count");
  const std::uint64_t expected = dewall::io::binary_points_file_size(count, static_cast<int>(dimension));
  const std::string announced = std::to_string(count) + " points of dimension " + std::to_string(dimension);
  if (file_size < expected)
    throw File_error(name + ": truncated: " + announced + " need " + std::to_string(expected) + " bytes, the file has " +
                     std::to_string(file_size));
  if (file_size > expected)
    throw File_error(name + ": " + std::to_string(file_size - expected) + " bytes after the last point");
  if (count >= (std::uint64_t{1} << 32) - 1)
    throw File_error(name + ": " + announced + ": the simplex formats hold 32-bit indices (at most 2^32 - 2 points)");
  Share s;
  s.dimension = static_cast<int>(dimension);
  s.count = count;
  s.first = static_cast<std::uint64_t>(static_cast<U128>(count) * static_cast<unsigned>(rank) /
                                        static_cast<unsigned>(size));
  const auto last = static_cast<std::uint64_t>(static_cast<U128>(count) * static_cast<unsigned>(rank + 1) /
                                               static_cast<unsigned>(size));
  s.coordinates.resize((last - s.first) * dimension);
  read_at(fd, name, reinterpret_cast<unsigned char*>(s.coordinates.data()), s.coordinates.size() * 8,
          dewall::io::binary_points_header_size + s.first * dimension * 8);
  if constexpr (std::endian::native == std::endian::big)
    for (double& x : s.coordinates) x = std::bit_cast<double>(__builtin_bswap64(std::bit_cast<std::uint64_t>(x)));
  return s;
}

/// Collective: runs f on this rank; on any rank's failure every rank throws
/// the lowest failing rank's error, its kind kept (File_error counts as file).
template <class F>
void step(MPI_Comm comm, F&& f) {
  Rank_error mine;
  try {
    f();
  } catch (const File_error& e) {
    mine = {Error_kind::file, e.what()};
  } catch (const dewall::io::Write_error& e) {
    mine = {Error_kind::file, e.what()};
  } catch (...) {
    mine = dewall::mpi::error_of(std::current_exception());
  }
  const Rank_error agreed = dewall::mpi::agree_on_error(comm, mine);
  if (agreed.kind == Error_kind::file) throw File_error(agreed.message);
  if (agreed.kind != Error_kind::none) dewall::mpi::throw_error(agreed);
}

template <int D>
int triangulate(MPI_Comm comm, const Arguments& args, const Share& share, int rank, int size) {
  const double t0 = MPI_Wtime();
  std::vector<dewall::kernel::Point_d<D>> points(share.coordinates.size() / D);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int j = 0; j < D; ++j) points[i][j] = share.coordinates[i * D + static_cast<std::size_t>(j)];
  dewall::mpi::Result<D> r;
  try {
    r = dewall::mpi::triangulate<D>(comm, points, share.first, args.options);
  } catch (const dewall::Invalid_input& e) {
    if (rank == 0) std::fprintf(stderr, "dewall-mpi: %s: %s\n", args.input.c_str(), e.what());
    return 1;
  }
  const double t1 = MPI_Wtime();
  // Gather on rank 0, in chunks (no 2^31 limit on the total).
  constexpr std::size_t chunk = std::size_t{1} << 24;  // simplices per message
  using S = dewall::mpi::Global_simplex<D>;
  std::vector<S> all;
  if (rank == 0) {
    // Each rank's list comes sorted: merge them as they arrive.
    all = std::move(r.simplices);
    for (int q = 1; q < size; ++q) {
      std::uint64_t n = 0;
      MPI_Recv(&n, 1, MPI_UINT64_T, q, 0, comm, MPI_STATUS_IGNORE);
      const std::size_t at = all.size();
      all.resize(at + n);
      for (std::size_t k = 0; k < n; k += chunk) {
        const std::size_t m = std::min<std::size_t>(chunk, n - k);
        MPI_Recv(all.data() + at + k, static_cast<int>(m * sizeof(S)), MPI_BYTE, q, 1, comm, MPI_STATUS_IGNORE);
      }
      std::inplace_merge(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(at), all.end());
    }
  } else {
    const std::uint64_t n = r.simplices.size();
    MPI_Send(&n, 1, MPI_UINT64_T, 0, 0, comm);
    for (std::size_t k = 0; k < n; k += chunk) {
      const std::size_t m = std::min<std::size_t>(chunk, n - k);
      MPI_Send(r.simplices.data() + k, static_cast<int>(m * sizeof(S)), MPI_BYTE, 0, 1, comm);
    }
    std::vector<S>().swap(r.simplices);
  }
  step(comm, [&] {
    if (rank != 0) return;
    dewall::io::Simplex_table table;
    table.vertices_per_simplex = D + 1;
    table.indices.reserve(all.size() * (D + 1));
    for (const S& s : all)
      for (const std::uint64_t v : s) table.indices.push_back(static_cast<std::uint32_t>(v));
    std::vector<S>().swap(all);
    dewall::io::write_simplices_file(args.output, table, 0);
  });
  const double t2 = MPI_Wtime();
  if (args.stats) {
    const dewall::mpi::Statistics& st = r.statistics;
    const std::array<double, 14> mine = {static_cast<double>(st.local_points), static_cast<double>(st.block_points),
                                         static_cast<double>(st.halo_points),  static_cast<double>(st.rounds),
                                         static_cast<double>(st.builds),       static_cast<double>(st.queries_sent),
                                         static_cast<double>(st.simplices),    st.decompose_seconds,
                                         st.build_seconds,                     st.verify_seconds,
                                         st.halo_seconds,                      st.finish_seconds,
                                         t1 - t0,                              t2 - t1};
    std::vector<double> every(rank == 0 ? mine.size() * static_cast<std::size_t>(size) : 0);
    MPI_Gather(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, every.data(), static_cast<int>(mine.size()),
               MPI_DOUBLE, 0, comm);
    if (rank == 0) {
      std::fprintf(stderr,
                   "rank   points    block    halo  halo%%  rounds builds queries simplices | seconds: decompose"
                   "  build verify   halo finish | triangulate gather+write\n");
      for (int q = 0; q < size; ++q) {
        const double* e = &every[static_cast<std::size_t>(q) * mine.size()];
        std::fprintf(stderr, "%4d %8.0f %8.0f %7.0f %6.1f %6.0f %6.0f %7.0f %9.0f |          %9.3f %6.3f %6.3f %6.3f %6.3f | %11.3f %12.3f\n",
                     q, e[0], e[1], e[2], e[1] > 0 ? 100.0 * e[2] / e[1] : 0.0, e[3], e[4], e[5], e[6], e[7], e[8],
                     e[9], e[10], e[11], e[12], e[13]);
      }
    }
  }
  return 0;
}

int run(int argc, char** argv, int rank, int size) {
  Arguments args;
  try {
    args = parse(argc, argv);  // every rank parses the same arguments: the same outcome, no communication
  } catch (const Usage_error& e) {
    if (rank == 0) {
      if (*e.what()) std::fprintf(stderr, "dewall-mpi: %s\n\n", e.what());
      std::fputs(usage_text, *e.what() ? stderr : stdout);
    }
    return *e.what() ? 2 : 0;
  }
  try {
    Share share;
    step(MPI_COMM_WORLD, [&] { share = read_share(args.input, rank, size); });
    switch (share.dimension) {
      case 2: return triangulate<2>(MPI_COMM_WORLD, args, share, rank, size);
      case 3: return triangulate<3>(MPI_COMM_WORLD, args, share, rank, size);
      case 4: return triangulate<4>(MPI_COMM_WORLD, args, share, rank, size);
      case 5: return triangulate<5>(MPI_COMM_WORLD, args, share, rank, size);
      default: return triangulate<6>(MPI_COMM_WORLD, args, share, rank, size);
    }
  } catch (const dewall::Invalid_input& e) {
    if (rank == 0) std::fprintf(stderr, "dewall-mpi: %s: %s\n", args.input.c_str(), e.what());
    return 1;
  } catch (const std::exception& e) {
    if (rank == 0) std::fprintf(stderr, "dewall-mpi: %s\n", e.what());
    return 2;
  }
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const int status = run(argc, argv, rank, size);
  MPI_Finalize();
  return status;
}
