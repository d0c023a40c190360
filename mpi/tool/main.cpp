// dewall-mpi: the Delaunay triangulation of a binary point file (.dwpt) on the
// ranks of an MPI job.
//
//   mpirun -n R dewall-mpi triangulate POINTS.dwpt -o OUT [--stats] [--sorted | --per-rank]
//                                          [--stream | --region-points N] [--index-bytes 4|8]
//
// Reading: every rank checks the header and the file size itself, then reads
// its share (points [n·r/R, n·(r+1)/R)) through MPI-IO (MPI_File_read_at_all):
// no rank holds all points. Triangulating: dewall::mpi::triangulate_into,
// whose sink writes; --stream: each rank's block in regions, whose simplices
// are written as each region is done. Writing, by
// default: rank 0 opens OUT through io::Output_file (a temporary renamed over
// OUT once complete, so a failure, or a rank dying, leaves an old OUT
// untouched), every rank writes its simplices into that temporary through
// MPI-IO at the offset of the ranks (and regions) before it (no rank holds more than its
// own), and rank 0 renames it once every rank has closed it. The order is the
// ranks' (with regions: region by region, each's ranks in order; the same
// bytes on every run with R ranks). .dwsx indices are 4 bytes, 8 beyond
// 2^32 − 2 points (or with --index-bytes 8). --sorted: rank 0 gathers
// the sorted lists, merges and writes them (the same bytes for every R). A
// target written in place (a pipe, standard output) is gathered and written
// by rank 0 too, in the ranks' order unless --sorted.
// --per-rank: one file per rank. Errors: every rank learns the lowest failing
// rank's error and ends with it; rank 0 prints it. Exit 1: the points cannot
// be triangulated (a non-finite coordinate, too few distinct points, not
// spanning E^D); 2: usage, reading or writing; 0: success.
//
//   mpirun -n R dewall-mpi certify POINTS SIMPLICES [--canonical] [--all] [--json] [--per-rank] [--threads N]
//                                                   [--stream] [--memory SIZE]
//
// `dewall certify` split over the ranks (certify_share, merge_shares): every
// rank reads both files (--per-rank: triangulate --per-rank's files, in rank order), checks its share of the vertices' facets, rows and
// points, and sends its findings to rank 0, which merges them and prints what
// `dewall certify` prints; every rank exits with its status.
#include <fcntl.h>
#include <mpi.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <exception>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "certify_text.hpp"
#include "dewall/certify/certify.hpp"
#include "dewall/io/binary_points.hpp"
#include "dewall/io/binary_simplices.hpp"
#include "dewall/io/dimensions.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/point_reader.hpp"
#include "dewall/io/quote.hpp"
#include "dewall/io/simplex_reader.hpp"
#include "dewall/io/simplex_rows.hpp"
#include "dewall/io/simplex_writer.hpp"
#include "dewall/mpi/collective_error.hpp"
#include "dewall/kernel/dimension.hpp"
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
    "usage: mpirun -n R dewall-mpi triangulate POINTS.dwpt -o OUT [--stats] [--sorted | --per-rank]\n"
    "                                          [--stream | --region-points N] [--seed-spacings X]\n"
    "                                          [--index-bytes 4|8]\n"
    "\n"
    "The Delaunay triangulation of POINTS.dwpt (the binary point format, docs/formats.md)\n"
    "computed by R ranks, each reading its share of the file; the same simplices as\n"
    "`dewall triangulate` and CGAL for every R. OUT: .dwsx (binary), .ele, or a plain\n"
    "list (one simplex per line, 0-based point indices), written by every rank at once\n"
    "(MPI-IO): rank 0's simplices first, then rank 1's, ... (the same bytes on every run\n"
    "with R ranks).\n"
    "  --sorted  the simplices sorted (the same bytes for every R): rank 0 gathers and\n"
    "            merges them, and writes the file alone\n"
    "  --per-rank  each rank writes its own simplices (global point indices) to its own\n"
    "            file, OUT with .r<rank> before the extension (out.r3.dwsx)\n"
    "  --stream  each rank builds its block in regions of at most 2^21 points, one after\n"
    "            another, and writes each region's simplices as soon as it is done: a\n"
    "            rank holds its block's points and one region's triangulation (about\n"
    "            0.9 GB in 3D) instead of its whole block's; the output's order is then\n"
    "            region by region (--sorted and --per-rank keep theirs)\n"
    "  --region-points N   as --stream, with regions of at most N points\n"
    "  --index-bytes W   .dwsx indices of W bytes (default: 4, or 8 beyond 2^32 - 2 points)\n"
    "  --stats   per-rank figures on standard error (points, halo, rounds, seconds, CPU\n"
    "            seconds, peak memory)\n"
    "  --seed-spacings X   the first halo: the points within X mean spacings of a\n"
    "            rank's block (default 1; 0: none); only the time changes\n"
    "\n"
    "usage: mpirun -n R dewall-mpi certify POINTS SIMPLICES [--canonical] [--all] [--json]\n"
    "                                      [--per-rank] [--threads N] [--stream] [--memory SIZE]\n"
    "                                      [--stats]\n"
    "\n"
    "`dewall certify` on R ranks: the same verdict, witness, words and exit status (0:\n"
    "Delaunay, and canonical with --canonical; 1: not; 2: unreadable input). Every rank\n"
    "reads POINTS and SIMPLICES (any format dewall certify reads) and checks the facets,\n"
    "rows and points of its share of the vertices; rank 0 merges the shares' findings\n"
    "and prints the verdict. --all, --json, --stream and --memory as dewall certify's\n"
    "(--memory: per rank).\n"
    "  --stats   per-rank figures on standard error: seconds (reading, its share,\n"
    "            merging), CPU seconds (reading and its share) and peak memory\n"
    "  --per-rank  SIMPLICES is the OUT of `triangulate --per-rank`: the files\n"
    "            OUT.r0.ext, OUT.r1.ext, ... up to the first missing one, their rows\n"
    "            numbered one after another\n"
    "  --threads N   at most N threads per rank (default: this node's cores shared\n"
    "            among its ranks)\n";

struct Arguments {
  bool certify = false;
  std::string simplices;  // certify's
  bool canonical = false, all = false, json = false, stream = false;
  std::size_t working_memory = 0;  // certify's --memory (0: the default)
  unsigned threads = 0;
  std::string input, output;
  bool stats = false, sorted = false, per_rank = false;
  int index_bytes = 0;  // 0: 4, or 8 when the points need it
  dewall::mpi::Options options;
};

Arguments parse_certify(const std::vector<std::string>& a) {
  Arguments r;
  r.certify = true;
  for (std::size_t i = 1; i < a.size(); ++i) {
    if (a[i] == "--help" || a[i] == "-h") throw Usage_error("");
    if (a[i] == "--canonical") r.canonical = true;
    else if (a[i] == "--all") r.all = true;
    else if (a[i] == "--json") r.json = true;
    else if (a[i] == "--stream") r.stream = true;
    else if (a[i] == "--memory") {
      const std::string v = i + 1 < a.size() ? a[i + 1] : std::string();
      const auto bytes = dewall::cli::memory_size(v);
      if (!bytes) throw Usage_error("--memory must be a positive size such as 512M or 4G, not " + v);
      r.working_memory = *bytes;
      ++i;
    }
    else if (a[i] == "--per-rank") r.per_rank = true;
    else if (a[i] == "--stats") r.stats = true;
    else if (a[i] == "--threads") {
      std::uint64_t x = 0;
      const std::string v = i + 1 < a.size() ? a[i + 1] : std::string();
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
      if (v.empty() || ec != std::errc() || end != v.data() + v.size() || x == 0 || x > 4096)
        throw Usage_error("--threads takes a whole number from 1 to 4096");
      r.threads = static_cast<unsigned>(x);
      ++i;
    } else if (a[i] == "-") throw Usage_error("certify: every rank reads the files: name them, not '-'");
    else if (!a[i].empty() && a[i][0] == '-') throw Usage_error("unknown option '" + a[i] + "'");
    else if (r.input.empty()) r.input = a[i];
    else if (r.simplices.empty()) r.simplices = a[i];
    else throw Usage_error("certify takes two files, POINTS and SIMPLICES");
  }
  if (r.simplices.empty()) throw Usage_error("certify needs POINTS and SIMPLICES");
  return r;
}

Arguments parse(int argc, char** argv) {
  std::vector<std::string> a(argv + 1, argv + argc);
  if (a.empty()) throw Usage_error("missing command");
  if (a[0] == "--help" || a[0] == "-h") throw Usage_error("");
  if (a[0] == "help") {  // dewall-mpi help [triangulate], as dewall's
    if (a.size() > 2) throw Usage_error("unexpected argument '" + a[2] + "'");
    if (a.size() == 2 && a[1] != "triangulate" && a[1] != "certify")
      throw Usage_error("unknown command '" + a[1] + "' (the commands: triangulate, certify)");
    throw Usage_error("");
  }
  if (a[0] == "certify") return parse_certify(a);
  if (a[0] != "triangulate") throw Usage_error("unknown command '" + a[0] + "' (the commands: triangulate, certify)");
  Arguments r;
  for (std::size_t i = 1; i < a.size(); ++i) {
    if (a[i] == "--help" || a[i] == "-h") throw Usage_error("");
    if (a[i] == "--stats") r.stats = true;
    else if (a[i] == "--sorted") r.sorted = true;
    else if (a[i] == "--per-rank") r.per_rank = true;
    else if (a[i] == "--stream") r.options.region_points = std::uint64_t{1} << 21;
    else if (a[i] == "--region-points" || a[i] == "--index-bytes") {
      if (i + 1 >= a.size()) throw Usage_error(a[i] + " needs a number");
      std::uint64_t x = 0;
      const std::string& v = a[i + 1];
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
      if (ec != std::errc() || end != v.data() + v.size() || x == 0)
        throw Usage_error(a[i] + " takes a positive whole number");
      if (a[i] == "--region-points") r.options.region_points = x;
      else if (x == 4 || x == 8) r.index_bytes = static_cast<int>(x);
      else throw Usage_error("--index-bytes takes 4 or 8");
      ++i;
    } else if (a[i] == "--seed-spacings") {
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
  if (r.sorted && r.per_rank) throw Usage_error("--sorted and --per-rank exclude each other");
  if (r.per_rank && r.output == "-") throw Usage_error("--per-rank writes one file per rank: -o names them, not '-'");
  return r;
}

std::uint64_t load_le(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | p[i];
  return v;
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

/// This rank's share of the file: its dimension, first global index, coordinates.
struct Share {
  int dimension = 0;
  std::uint64_t count = 0, first = 0;
  std::vector<double> coordinates;
  double seconds = 0;  // reading it
};

std::string mpi_error_text(int code) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  return std::string(text, static_cast<std::size_t>(length));
}

/// Collective: reads `size` bytes at `offset` into `to` with MPI_File_read_at_all
/// (every rank calls it equally often: as many times as the rank with the
/// most to read needs). \throws File_error, on every rank alike
void read_all_at(MPI_Comm comm, MPI_File fh, const std::string& name, unsigned char* to, std::uint64_t size,
                 std::uint64_t offset) {
  constexpr std::uint64_t chunk = std::uint64_t{1} << 30;  // MPI's int counts
  std::uint64_t calls = (size + chunk - 1) / chunk, most = 0;
  MPI_Allreduce(&calls, &most, 1, MPI_UINT64_T, MPI_MAX, comm);
  std::string error;
  for (std::uint64_t k = 0; k < most; ++k) {
    const std::uint64_t at = std::min(size, k * chunk), n = std::min(chunk, size - at);
    MPI_Status status;
    const int rc = MPI_File_read_at_all(fh, static_cast<MPI_Offset>(offset + at), to + at, static_cast<int>(n),
                                        MPI_BYTE, &status);
    int got = 0;
    if (rc == MPI_SUCCESS) MPI_Get_count(&status, MPI_BYTE, &got);
    if (error.empty() && rc != MPI_SUCCESS) error = name + ": cannot read: " + mpi_error_text(rc);
    else if (error.empty() && static_cast<std::uint64_t>(got) != n) error = name + ": truncated while reading";
  }
  step(comm, [&] {
    if (!error.empty()) throw File_error(error);
  });
}

/// Collective: this rank's share of the file, points [n·r/R, n·(r+1)/R), read
/// through MPI-IO (no rank reads more than its share and the header).
/// \throws File_error, Invalid_input..., on every rank alike (step)
Share read_share(MPI_Comm comm, const std::string& name, int rank, int size) {
  step(comm, [&] {
    struct stat st {};
    if (::stat(name.c_str(), &st) != 0) throw File_error(name + ": cannot open file: " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw File_error(name + ": not a regular file (each rank reads its share by offset)");
  });
  MPI_File fh = MPI_FILE_NULL;
  const int opened = MPI_File_open(comm, name.c_str(), MPI_MODE_RDONLY, MPI_INFO_NULL, &fh);
  step(comm, [&] {
    if (opened != MPI_SUCCESS) throw File_error(name + ": cannot open file: " + mpi_error_text(opened));
  });
  struct Closer {  // collective: every rank leaves together (each error below is agreed on)
    MPI_File& fh;
    ~Closer() { MPI_File_close(&fh); }
  } closer{fh};
  Share s;
  std::uint64_t offset = 0, bytes = 0;
  step(comm, [&] {
    MPI_Offset length = 0;
    const int rc = MPI_File_get_size(fh, &length);
    if (rc != MPI_SUCCESS) throw File_error(name + ": cannot stat: " + mpi_error_text(rc));
    const auto file_size = static_cast<std::uint64_t>(length);
    unsigned char h[dewall::io::binary_points_header_size];
    if (file_size == 0) throw File_error(name + ": no points");  // dewall's message for an empty input
    if (file_size < sizeof h)
      throw File_error(name + ": truncated: the header needs 24 bytes, the file has " + std::to_string(file_size));
    MPI_Status status;
    const int read = MPI_File_read_at(fh, 0, h, static_cast<int>(sizeof h), MPI_BYTE, &status);
    int got = 0;
    if (read == MPI_SUCCESS) MPI_Get_count(&status, MPI_BYTE, &got);
    if (read != MPI_SUCCESS) throw File_error(name + ": cannot read: " + mpi_error_text(read));
    if (got != static_cast<int>(sizeof h)) throw File_error(name + ": truncated while reading");
    if (std::memcmp(h, dewall::io::binary_points_magic, 4) != 0)
      throw File_error(name + ": not a binary point file (the first bytes are not 'DWPT')");
    const std::uint64_t version = load_le(h + 4, 4), dimension = load_le(h + 8, 4), flags = load_le(h + 12, 4);
    const std::uint64_t count = load_le(h + 16, 8);
    if (version != dewall::io::binary_points_version)
      throw File_error(name + ": unsupported binary point format version " + std::to_string(version));
    if (!dewall::io::is_supported_dimension(dimension))
      throw File_error(name + ": dimension " + std::to_string(dimension) + " is outside " +
                       dewall::io::dimension_range());
    if (flags != 0) throw File_error(name + ": unknown flags " + std::to_string(flags));
    if (count > (std::uint64_t{1} << 58) / dimension) throw File_error(name + ": impossible point count");
    if (count == 0 && file_size == sizeof h) throw File_error(name + ": no points");  // dewall's message
    const std::uint64_t expected = dewall::io::binary_points_file_size(count, static_cast<int>(dimension));
    const std::string announced = std::to_string(count) + " points of dimension " + std::to_string(dimension);
    if (file_size < expected)
      throw File_error(name + ": truncated: " + announced + " need " + std::to_string(expected) +
                       " bytes, the file has " + std::to_string(file_size));
    if (file_size > expected)
      throw File_error(name + ": " + std::to_string(file_size - expected) + " bytes after the last point");
    s.dimension = static_cast<int>(dimension);
    s.count = count;
    s.first = static_cast<std::uint64_t>(static_cast<U128>(count) * static_cast<unsigned>(rank) /
                                          static_cast<unsigned>(size));
    const auto last = static_cast<std::uint64_t>(static_cast<U128>(count) * static_cast<unsigned>(rank + 1) /
                                                 static_cast<unsigned>(size));
    s.coordinates.resize((last - s.first) * dimension);
    offset = dewall::io::binary_points_header_size + s.first * dimension * 8;
    bytes = s.coordinates.size() * 8;
  });
  read_all_at(comm, fh, name, reinterpret_cast<unsigned char*>(s.coordinates.data()), bytes, offset);
  if constexpr (std::endian::native == std::endian::big)
    for (double& x : s.coordinates) x = std::bit_cast<double>(__builtin_bswap64(std::bit_cast<std::uint64_t>(x)));
  return s;
}

using Format = dewall::io::Simplex_format;

/// Appends the file's bytes for `batch` (io/simplex_rows.hpp: the formatting
/// every writer shares), .ele rows numbered from `row`.
template <int D>
void append_rows(std::string& out, std::span<const dewall::mpi::Global_simplex<D>> batch, Format f,
                 std::uint64_t& row, int index_bytes) {
  // A Global_simplex is D + 1 indices and nothing else: the batch is their flat sequence.
  static_assert(sizeof(dewall::mpi::Global_simplex<D>) == sizeof(std::uint64_t) * (D + 1));
  const std::span<const std::uint64_t> indices(batch.empty() ? nullptr : batch.front().data(), batch.size() * (D + 1));
  dewall::io::append_simplex_rows(out, indices, D + 1, f, row, index_bytes);
}

/// The output written by every rank at once through MPI-IO into the
/// temporary that rank 0's io::Output_file created (rank 0 renames it into
/// place once every rank has written and closed it). The simplices come in
/// parts (one per region, Simplex_sink); each rank's simplices of a part go
/// at the offset the parts before and the ranks before it in this part fill
/// (MPI_Exscan of the counts, in start): .dwsx streamed as the simplices
/// come (4 MiB at a time), its header, whose count is known last, written by
/// rank 0 at the end; the text formats formatted in memory, then written
/// (their lengths vary, and .ele's header leads). Without regions: rank 0's
/// simplices, then rank 1's, ... Write failures are recorded, not thrown (the
/// sink runs inside dewall::mpi; the ranks agree afterwards).
template <int D>
class Collective_writer {
 public:
  Collective_writer(MPI_Comm comm, MPI_File fh, Format f, std::string name, int index_bytes)
      : comm_(comm), fh_(fh), format_(f), name_(std::move(name)), index_bytes_(index_bytes) {
    MPI_Comm_rank(comm, &rank_);
  }
  /// Collective (every rank is called, dewall::mpi's contract): a part begins.
  void start(std::uint64_t count) {
    if (format_ == Format::binary) flush();  // the previous part's rest, at its offset
    std::uint64_t before = 0, total = 0;
    MPI_Exscan(&count, &before, 1, MPI_UINT64_T, MPI_SUM, comm_);
    if (rank_ == 0) before = 0;  // MPI_Exscan leaves rank 0's undefined
    MPI_Allreduce(&count, &total, 1, MPI_UINT64_T, MPI_SUM, comm_);
    row_ = written_ + before;
    written_ += total;
    try {  // this rank's alone, after the collective calls: recorded
      if (format_ == Format::binary) {
        buffer_.reserve(flush_bytes + 4096 * sizeof(dewall::mpi::Global_simplex<D>));
        offset_ = dewall::io::simplex_file_header(format_, D, 0, index_bytes_).size() + row_ * (D + 1) * static_cast<std::uint64_t>(index_bytes_);
      } else {
        part_begin_.push_back(buffer_.size());
      }
    } catch (const std::exception& e) {
      if (error_.empty()) error_ = name_ + ": " + e.what();
    }
  }
  void take(std::span<const dewall::mpi::Global_simplex<D>> batch) {
    append_rows<D>(buffer_, batch, format_, row_, index_bytes_);
    if (format_ == Format::binary && buffer_.size() >= flush_bytes) flush();
  }
  /// Collective: writes what is left (the text formats: everything) and the header.
  void finish() {
    const std::string header = dewall::io::simplex_file_header(format_, D, written_, index_bytes_);
    if (format_ == Format::binary) {
      flush();
      if (rank_ == 0) write(header.data(), header.size(), 0);
      return;
    }
    // Each part's text goes after the header, the earlier parts' text (all
    // ranks') and this part's text of the ranks before this one.
    const std::size_t parts = part_begin_.size();  // the same on every rank
    std::vector<std::uint64_t> bytes(parts), before(parts, 0), total(parts, 0);
    for (std::size_t p = 0; p < parts; ++p)
      bytes[p] = (p + 1 < parts ? part_begin_[p + 1] : buffer_.size()) - part_begin_[p];
    MPI_Exscan(bytes.data(), before.data(), static_cast<int>(parts), MPI_UINT64_T, MPI_SUM, comm_);
    if (rank_ == 0) std::fill(before.begin(), before.end(), 0);
    MPI_Allreduce(bytes.data(), total.data(), static_cast<int>(parts), MPI_UINT64_T, MPI_SUM, comm_);
    if (rank_ == 0) write(header.data(), header.size(), 0);
    std::uint64_t at = header.size();
    for (std::size_t p = 0; p < parts; ++p) {
      write(buffer_.data() + part_begin_[p], bytes[p], at + before[p]);
      at += total[p];
    }
    std::string().swap(buffer_);
  }
  /// The first write error on this rank, or empty.
  const std::string& error() const { return error_; }

 private:
  static constexpr std::size_t flush_bytes = std::size_t{1} << 22;  // .dwsx: written 4 MiB at a time
  void flush() {
    write(buffer_.data(), buffer_.size(), offset_);
    offset_ += buffer_.size();
    buffer_.clear();
  }
  void write(const char* data, std::size_t size, std::uint64_t offset) {
    for (std::size_t at = 0; at < size && error_.empty();) {
      const int n = static_cast<int>(std::min<std::size_t>(size - at, std::size_t{1} << 30));
      MPI_Status status;
      const int rc = MPI_File_write_at(fh_, static_cast<MPI_Offset>(offset + at), data + at, n, MPI_BYTE, &status);
      int written = 0;
      if (rc == MPI_SUCCESS) MPI_Get_count(&status, MPI_BYTE, &written);
      if (rc != MPI_SUCCESS) error_ = name_ + ": write error: " + mpi_error_text(rc);
      else if (written != n) error_ = name_ + ": write error: short write";
      at += static_cast<std::size_t>(n);
    }
  }
  MPI_Comm comm_;
  MPI_File fh_;
  Format format_;
  std::string name_, buffer_, error_;
  int index_bytes_;
  int rank_ = 0;
  std::uint64_t offset_ = 0, row_ = 0, written_ = 0;  // written_: the simplices of the parts begun, all ranks
  std::vector<std::size_t> part_begin_;               // text formats: where each part's text begins in buffer_
};

/// The statistics line of every rank, printed by rank 0.
void print_statistics(MPI_Comm comm, const dewall::mpi::Statistics& st, double read, double total, double write,
                      int rank, int size) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const std::array<double, 19> mine = {static_cast<double>(st.local_points), static_cast<double>(st.block_points),
                                       static_cast<double>(st.halo_points),  static_cast<double>(st.rounds),
                                       static_cast<double>(st.builds),       static_cast<double>(st.queries_sent),
                                       static_cast<double>(st.simplices),    st.decompose_seconds,
                                       st.build_seconds,                     st.verify_seconds,
                                       st.halo_seconds,                      st.finish_seconds,
                                       write,                                total,
                                       static_cast<double>(usage.ru_maxrss) / 1024.0,
                                       static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                                           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec),
                                       st.index_seconds, read, static_cast<double>(st.regions)};
  std::vector<double> every(rank == 0 ? mine.size() * static_cast<std::size_t>(size) : 0);
  MPI_Gather(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, every.data(), static_cast<int>(mine.size()),
             MPI_DOUBLE, 0, comm);
  if (rank != 0) return;
  std::fprintf(stderr,
               "rank   points    block    halo  halo%% regions rounds builds queries simplices | seconds:   read decompose"
               "  index  build verify   halo finish  write |  total    cpu | peak MB\n");
  for (int q = 0; q < size; ++q) {
    const double* e = &every[static_cast<std::size_t>(q) * mine.size()];
    std::fprintf(stderr,
                 "%4d %8.0f %8.0f %7.0f %6.1f %7.0f %6.0f %6.0f %7.0f %9.0f |          %6.3f %9.3f %6.3f %6.3f %6.3f %6.3f %6.3f %6.3f "
                 "| %6.3f %6.3f | %7.0f\n",
                 q, e[0], e[1], e[2], e[1] > 0 ? 100.0 * e[2] / e[1] : 0.0, e[18], e[3], e[4], e[5], e[6], e[17], e[7], e[16], e[8], e[9],
                 e[10], e[11], e[12], e[13], e[15], e[14]);
  }
}

/// Runs f, keeping its exception (the first) in `failed` instead of throwing:
/// a sink runs inside dewall::mpi, and a rank leaving it early would leave the
/// others waiting in the next collective call.
template <class F>
void guarded(std::exception_ptr& failed, F&& f) {
  if (failed) return;
  try {
    f();
  } catch (...) {
    failed = std::current_exception();
  }
}

/// OUT with ".r<rank>" before its extension (the per-rank files).
std::string per_rank_name(const std::string& out, const std::string& rank) {
  const std::size_t slash = out.find_last_of('/');
  const std::size_t dot = out.find_last_of('.');
  const std::string tag = ".r" + rank;
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) || dot == slash + 1)
    return out + tag;
  return out.substr(0, dot) + tag + out.substr(dot);
}

template <int D>
int triangulate(MPI_Comm comm, const Arguments& args, Share share, int rank, int size) {
  const double t0 = MPI_Wtime();
  using S = dewall::mpi::Global_simplex<D>;
  std::vector<dewall::kernel::Point_d<D>> points(share.coordinates.size() / D);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int j = 0; j < D; ++j) points[i][j] = share.coordinates[i * D + static_cast<std::size_t>(j)];
  std::vector<double>().swap(share.coordinates);
  const Format format = dewall::io::simplex_format_named_by(args.output);
  // 8-byte .dwsx indices when 4 cannot hold them (an index up to n − 1; 2^32 − 1 is no index in dewall's files).
  const int index_bytes = args.index_bytes ? args.index_bytes : share.count > (std::uint64_t{1} << 32) - 2 ? 8 : 4;
  dewall::mpi::Statistics st;
  double write_seconds = 0;
  const auto report_invalid = [&](const dewall::Invalid_input& e) {
    if (rank == 0) std::fprintf(stderr, "dewall-mpi: %s: %s\n", args.input.c_str(), e.what());
    return 1;
  };

  if (args.per_rank) {
    // Each rank its own file, committed once every rank has written its own.
    const std::string name = per_rank_name(args.output, std::to_string(rank));
    std::unique_ptr<dewall::io::Output_file> file;
    step(comm, [&] { file = std::make_unique<dewall::io::Output_file>(name); });
    // The simplices come in parts (one per region): .dwsx's count is patched
    // in at the end, .ele's rows are kept until their count is known.
    struct Sink {
      dewall::io::Output_file& file;
      Format format;
      int index_bytes;
      std::string text, kept;
      std::uint64_t row = 0, count = 0;
      bool begun = false;
      void start(std::uint64_t n) {
        count += n;
        if (!begun && format == Format::binary) {
          text = dewall::io::simplex_file_header(format, D, dewall::io::binary_simplices_unknown_count, index_bytes);
          file.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
        }
        begun = true;
      }
      void take(std::span<const S> batch) {
        if (format == Format::ele) return append_rows<D>(kept, batch, format, row, index_bytes);
        text.clear();
        append_rows<D>(text, batch, format, row, index_bytes);
        file.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
      }
      void end() {
        if (format == Format::binary) {
          unsigned char le[8];
          for (int k = 0; k < 8; ++k) le[k] = static_cast<unsigned char>(count >> (8 * k));
          file.patch(dewall::io::binary_simplices_count_offset, le, sizeof le);  // false (a device): kept unknown
        } else if (format == Format::ele) {
          text = dewall::io::simplex_file_header(format, D, count, index_bytes);
          file.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
          file.stream().write(kept.data(), static_cast<std::streamsize>(kept.size()));
        }
      }
    } sink{*file, format, index_bytes, {}, {}};
    std::exception_ptr failed;  // the sink's (this rank's alone): the ranks agree below
    dewall::mpi::Simplex_sink<D> s;
    s.start = [&](std::uint64_t n) { guarded(failed, [&] { sink.start(n); }); };
    s.take = [&](std::span<const S> b) { guarded(failed, [&] { sink.take(b); }); };
    try {
      st = dewall::mpi::triangulate_into<D>(comm, std::move(points), share.first, s, args.options);
    } catch (const dewall::Invalid_input& e) {
      return report_invalid(e);
    }
    const double t1 = MPI_Wtime();
    step(comm, [&] {
      if (failed) std::rethrow_exception(failed);
      file->stream().flush();
      sink.end();
      file->check();
    });
    step(comm, [&] { file->commit(); });
    // An earlier run on more ranks left OUT.r<R>, …: removed, so that the set
    // `certify --per-rank` reads (up to the first missing file) is this run's.
    if (rank == 0) {
      int stale = size;
      while (::unlink(per_rank_name(args.output, std::to_string(stale)).c_str()) == 0) ++stale;
    }
    write_seconds = MPI_Wtime() - t1;
  } else {
    // Rank 0 opens the output: a temporary, which every rank then writes
    // through MPI-IO, or, for a target written in place (standard output, a
    // pipe) and for --sorted, the file rank 0 writes alone after gathering.
    std::unique_ptr<dewall::io::Output_file> file;
    int gather = args.sorted ? 1 : 0;
    std::string temporary;
    step(comm, [&] {
      if (rank != 0) return;
      file = std::make_unique<dewall::io::Output_file>(args.output);
      if (file->direct()) gather = 1;
      temporary = file->temporary_path();
    });
    MPI_Bcast(&gather, 1, MPI_INT, 0, comm);
    if (!gather) {
      std::uint64_t length = temporary.size();
      MPI_Bcast(&length, 1, MPI_UINT64_T, 0, comm);
      temporary.resize(length);
      MPI_Bcast(temporary.data(), static_cast<int>(length), MPI_CHAR, 0, comm);
      MPI_File fh = MPI_FILE_NULL;
      const int rc = MPI_File_open(comm, temporary.c_str(), MPI_MODE_WRONLY, MPI_INFO_NULL, &fh);
      step(comm, [&] {
        if (rc != MPI_SUCCESS) throw File_error(args.output + ": cannot open its temporary for MPI-IO: " + mpi_error_text(rc));
      });
      Collective_writer<D> writer(comm, fh, format, args.output, index_bytes);
      std::exception_ptr failed;  // the sink's (this rank's alone): the ranks agree below
      dewall::mpi::Simplex_sink<D> s;
      s.start = [&](std::uint64_t n) { writer.start(n); };  // collective: must not be skipped
      s.take = [&](std::span<const S> b) { guarded(failed, [&] { writer.take(b); }); };
      try {
        st = dewall::mpi::triangulate_into<D>(comm, std::move(points), share.first, s, args.options);
      } catch (...) {
        MPI_File_close(&fh);  // every rank is here (the library's errors are collective); rank 0's file removes the temporary
        try {
          throw;
        } catch (const dewall::Invalid_input& e) {
          return report_invalid(e);
        }
      }
      const double t1 = MPI_Wtime();
      writer.finish();
      const int closed = MPI_File_close(&fh);
      step(comm, [&] {
        if (failed) std::rethrow_exception(failed);
        if (!writer.error().empty()) throw File_error(writer.error());
        if (closed != MPI_SUCCESS) throw File_error(args.output + ": write error: " + mpi_error_text(closed));
      });
      step(comm, [&] {
        if (rank == 0) file->commit();
      });
      write_seconds = MPI_Wtime() - t1;
    } else {
      dewall::mpi::Result<D> r;
      try {
        r = dewall::mpi::triangulate<D>(comm, std::span<const dewall::kernel::Point_d<D>>(points), share.first,
                                        args.options);
      } catch (const dewall::Invalid_input& e) {
        return report_invalid(e);
      }
      st = r.statistics;
      const double t1 = MPI_Wtime();
      if (args.sorted) std::sort(r.simplices.begin(), r.simplices.end());
      // Gather on rank 0 in rank order, in chunks (no 2^31 limit on the
      // total); --sorted merges the ranks' sorted lists as they arrive.
      constexpr std::size_t chunk = std::size_t{1} << 24;  // simplices per message
      std::vector<S> all;
      if (rank == 0) {
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
          if (args.sorted) std::inplace_merge(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(at), all.end());
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
        std::string text = dewall::io::simplex_file_header(format, D, all.size(), index_bytes);
        std::uint64_t row = 0;
        std::ostream& out = file->stream();
        for (std::size_t k = 0; k < all.size() && out; k += 4096) {
          append_rows<D>(text, std::span<const S>(all).subspan(k, std::min<std::size_t>(4096, all.size() - k)), format,
                         row, index_bytes);
          out.write(text.data(), static_cast<std::streamsize>(text.size()));
          text.clear();
        }
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        std::vector<S>().swap(all);
        file->commit();
      });
      write_seconds = MPI_Wtime() - t1;
    }
  }
  if (args.stats) print_statistics(comm, st, share.seconds, MPI_Wtime() - t0, write_seconds, rank, size);
  return 0;
}

/// Simplex files as the certifier reads them: rows straight into its blocks,
/// one file after another.
template <int D>
class Files_source final : public dewall::certify::Simplex_source<D> {
 public:
  explicit Files_source(std::span<const std::unique_ptr<dewall::io::Simplex_file_reader>> readers) : readers_(readers) {}
  std::size_t read(std::span<dewall::certify::Simplex_indices<D>> rows) override {
    for (; next_ < readers_.size(); ++next_)
      if (const std::size_t k = readers_[next_]->read(
              std::span<std::uint32_t>(reinterpret_cast<std::uint32_t*>(rows.data()), rows.size() * (D + 1))))
        return k;
    return 0;
  }
  std::size_t remaining() const override {
    std::size_t sum = 0;
    for (std::size_t f = next_; f < readers_.size(); ++f) {
      const std::uint64_t m = readers_[f]->remaining();
      if (m == ~std::uint64_t{0}) return dewall::certify::npos;
      sum += static_cast<std::size_t>(m);
    }
    return sum;
  }

 private:
  std::span<const std::unique_ptr<dewall::io::Simplex_file_reader>> readers_;
  std::size_t next_ = 0;
};

/// The simplex files: SIMPLICES, or with --per-rank OUT.r0.ext, OUT.r1.ext, …
/// (dewall-mpi triangulate --per-rank's names) up to the first missing one.
struct Simplex_files {
  std::vector<std::string> paths;
  std::vector<std::unique_ptr<dewall::io::Simplex_file_reader>> readers;
  std::vector<std::uint64_t> first_row;  // of each file, then the total
  std::string name;                      // as messages give it

  /// "FILE:LINE" of row r.
  std::string where(std::size_t r) const {
    const std::size_t f = file_of(r);
    return readers[f]->list().where(dewall::io::file_name(paths[f]), r - first_row[f]);
  }
  /// The line of row r in its text file (dewall::certify::npos: binary).
  std::size_t line(std::size_t r) const {
    const std::size_t f = file_of(r);
    const auto& lines = readers[f]->list().lines;
    return lines.empty() ? dewall::certify::npos : lines[r - first_row[f]];
  }
  std::size_t file_of(std::size_t r) const {
    return static_cast<std::size_t>(std::upper_bound(first_row.begin(), first_row.end(), r) - first_row.begin()) - 1;
  }
};

/// A share's findings as words of 64 bits, and back (rank 0 merges them).
template <int D>
std::vector<std::uint64_t> serialize(const dewall::certify::Share_report<D>& s) {
  const auto& r = s.report;
  std::vector<std::uint64_t> w = {r.distinct_points, r.simplices, r.interior_facets, r.boundary_facets,
                                  r.cospherical_facets, s.first_row, r.violations.size(), s.boundary.size(),
                                  s.share.part, s.share.parts, s.point_count, s.input_numbering ? 1u : 0u};
  w.insert(w.end(), s.first_cell.begin(), s.first_cell.end());
  for (const auto& v : r.violations) {
    w.insert(w.end(), {static_cast<std::uint64_t>(v.rule), v.simplex, v.other_simplex, v.point, v.face.size()});
    w.insert(w.end(), v.face.begin(), v.face.end());
  }
  for (const auto& b : s.boundary) {
    w.insert(w.end(), b.facet.begin(), b.facet.end());
    w.insert(w.end(), {b.apex, b.positive ? 1u : 0u, b.row});
  }
  return w;
}

template <int D>
dewall::certify::Share_report<D> deserialize(std::span<const std::uint64_t> w) {
  dewall::certify::Share_report<D> s;
  std::size_t at = 0;
  const auto next = [&] { return w[at++]; };
  auto& r = s.report;
  r.dimension = D;
  r.distinct_points = next();
  r.simplices = next();
  r.interior_facets = next();
  r.boundary_facets = next();
  r.cospherical_facets = next();
  s.first_row = next();
  r.violations.resize(next());
  s.boundary.resize(next());
  s.share.part = next();
  s.share.parts = next();
  s.point_count = next();
  s.input_numbering = next() != 0;
  for (auto& v : s.first_cell) v = static_cast<std::uint32_t>(next());
  for (auto& v : r.violations) {
    v.rule = static_cast<dewall::certify::Rule>(next());
    v.simplex = next();
    v.other_simplex = next();
    v.point = next();
    v.face.resize(next());
    for (auto& f : v.face) f = static_cast<std::uint32_t>(next());
  }
  for (auto& b : s.boundary) {
    for (auto& f : b.facet) f = static_cast<std::uint32_t>(next());
    b.apex = static_cast<std::uint32_t>(next());
    b.positive = next() != 0;
    b.row = next();
  }
  return s;
}

/// The CPU seconds of this process (all of its threads) so far.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// This node's cores shared among its ranks (at least one each).
unsigned threads_per_rank(MPI_Comm comm, int rank) {
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
  int local = 1;
  MPI_Comm_size(node, &local);
  MPI_Comm_free(&node);
  cpu_set_t set;
  const unsigned cores = sched_getaffinity(0, sizeof set, &set) == 0 ? static_cast<unsigned>(CPU_COUNT(&set)) : 1u;
  return std::max(1u, cores / static_cast<unsigned>(std::max(local, 1)));
}

template <int D>
int certify(MPI_Comm comm, const Arguments& args, const dewall::io::Point_table& points, const Simplex_files& files, int rank,
            int size, double read_seconds, double cpu0) {
  const double t0 = MPI_Wtime();
  namespace certify = dewall::certify;
  using K = dewall::kernel::Filtered_kernel_d<D>;
  static_assert(sizeof(dewall::kernel::Point_d<D>) == D * sizeof(double) && alignof(dewall::kernel::Point_d<D>) == alignof(double));
  const std::span<const dewall::kernel::Point_d<D>> p(reinterpret_cast<const dewall::kernel::Point_d<D>*>(points.coordinates.data()),
                                                      points.coordinates.size() / D);
  certify::Options options{.all = args.all, .threads = args.threads ? args.threads : threads_per_rank(comm, rank),
                           .working_memory = args.working_memory};
  // As dewall certify: rows that would take more than a quarter of the memory stream.
  const std::uint64_t rows = files.first_row.back();
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  const std::uint64_t memory = pages > 0 && page_size > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size) : 0;
  int stream = args.stream || (rows != ~std::uint64_t{0} && memory > 0 && rows * (D + 1) * 4 > memory / 4);
  // Every share must be made the same way (a streaming share numbers its
  // vertices as the input does, an in-memory one in Z order): one rank on a
  // smaller node makes them all stream.
  MPI_Allreduce(MPI_IN_PLACE, &stream, 1, MPI_INT, MPI_LOR, comm);
  options.stream = stream != 0;

  std::vector<std::uint64_t> mine;
  double cpu = 0;  // reading and the share, before any waiting for the other ranks
  step(comm, [&] {
    Files_source<D> source(files.readers);
    mine = serialize<D>(certify::certify_share<K>(p, source, {static_cast<std::size_t>(rank), static_cast<std::size_t>(size)}, options));
    cpu = cpu_seconds() - cpu0;
  });
  const double t1 = MPI_Wtime();
  // Rank 0 gathers the shares, in chunks (no 2^31 limit on a share).
  constexpr std::size_t chunk = std::size_t{1} << 24;
  std::vector<std::vector<std::uint64_t>> all;
  if (rank == 0) {
    all.resize(static_cast<std::size_t>(size));
    all[0] = std::move(mine);
    for (int q = 1; q < size; ++q) {
      std::uint64_t n = 0;
      MPI_Recv(&n, 1, MPI_UINT64_T, q, 2, comm, MPI_STATUS_IGNORE);
      auto& w = all[static_cast<std::size_t>(q)];
      w.resize(n);
      for (std::size_t k = 0; k < n; k += chunk)
        MPI_Recv(w.data() + k, static_cast<int>(std::min<std::size_t>(chunk, n - k)), MPI_UINT64_T, q, 3, comm, MPI_STATUS_IGNORE);
    }
  } else {
    const std::uint64_t n = mine.size();
    MPI_Send(&n, 1, MPI_UINT64_T, 0, 2, comm);
    for (std::size_t k = 0; k < n; k += chunk)
      MPI_Send(mine.data() + k, static_cast<int>(std::min<std::size_t>(chunk, n - k)), MPI_UINT64_T, 0, 3, comm);
  }
  int status = 0;
  step(comm, [&] {
    if (rank != 0) return;
    std::vector<certify::Share_report<D>> shares;
    for (const auto& w : all) shares.push_back(deserialize<D>(w));
    std::vector<std::vector<std::uint64_t>>().swap(all);
    const certify::Report report = certify::merge_shares<K>(p, std::span<const certify::Share_report<D>>(shares), options);
    if (report.simplices == 0)
      throw File_error(files.name + ": no simplices (a triangulation of " + std::to_string(points.size()) + " points has at least one)");
    const dewall::cli::Certify_names names{files.name, points.first_index, [&](std::size_t r) { return files.where(r); },
                                           files.readers[0]->list().format};
    if (args.json) {
      const auto line = [&](std::size_t r) { return files.line(r); };
      std::fputs(dewall::cli::certify_json(report, names, line, MPI_Wtime() - t0).c_str(), stdout);
      status = report.delaunay && (report.canonical || !args.canonical) ? 0 : 1;
    } else {
      status = dewall::cli::print_certify_text(report, names, dewall::io::file_name(args.input), args.canonical, args.all);
    }
    std::fflush(stdout);
  });
  MPI_Bcast(&status, 1, MPI_INT, 0, comm);
  if (args.stats) {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    constexpr std::size_t k = 5;
    const std::array<double, k> mine_figures = {read_seconds, t1 - t0, MPI_Wtime() - t1, cpu, static_cast<double>(usage.ru_maxrss) / 1024.0};
    std::vector<double> every(rank == 0 ? k * static_cast<std::size_t>(size) : 0);
    MPI_Gather(mine_figures.data(), k, MPI_DOUBLE, every.data(), k, MPI_DOUBLE, 0, comm);
    if (rank == 0) {
      std::fprintf(stderr, "rank | seconds:   read  share  merge |    cpu | peak MB\n");
      for (int q = 0; q < size; ++q) {
        const double* e = &every[k * static_cast<std::size_t>(q)];
        std::fprintf(stderr, "%4d |          %6.3f %6.3f %6.3f | %6.3f | %7.0f\n", q, e[0], e[1], e[2], e[3], e[4]);
      }
    }
  }
  return status;
}

int certify_command(const Arguments& args, int rank, int size) {
  dewall::io::Point_table points;
  Simplex_files files;
  const double t0 = MPI_Wtime(), cpu0 = cpu_seconds();
  step(MPI_COMM_WORLD, [&] {
    points = dewall::io::read_points_file(args.input);
    if (!args.per_rank) {
      files.paths = {args.simplices};
      files.name = dewall::io::file_name(args.simplices);
    } else {
      for (int r = 0; ::access(per_rank_name(args.simplices, std::to_string(r)).c_str(), F_OK) == 0; ++r)
        files.paths.push_back(per_rank_name(args.simplices, std::to_string(r)));
      files.name = dewall::io::file_name(per_rank_name(args.simplices, "*"));
      if (files.paths.empty()) throw File_error(per_rank_name(args.simplices, "0") + ": cannot open file: no per-rank files");
    }
    files.first_row = {0};
    for (const std::string& path : files.paths) {
      files.readers.push_back(std::make_unique<dewall::io::Simplex_file_reader>(path, points.dimension, points.first_index));
      const std::uint64_t m = files.readers.back()->remaining();
      if (m == ~std::uint64_t{0} && files.paths.size() > 1) throw File_error(path + ": the number of simplices is not in its header");
      files.first_row.push_back(m == ~std::uint64_t{0} ? m : files.first_row.back() + m);
    }
    if (files.first_row.back() == 0)
      throw File_error(files.name + ": no simplices (a triangulation of " + std::to_string(points.size()) +
                       " points has at least one)");
  });
  return dewall::kernel::with_dimension(points.dimension, [&](auto d) {
    return certify<decltype(d)::value>(MPI_COMM_WORLD, args, points, files, rank, size, MPI_Wtime() - t0, cpu0);
  });
}

int run(int argc, char** argv, int rank, int size) {
  Arguments args;
  try {
    args = parse(argc, argv);  // every rank parses the same arguments: the same outcome, no communication
  } catch (const Usage_error& e) {
    // A usage error is one line and where the help is, as dewall's; the help itself goes to stdout.
    if (rank == 0) {
      if (*e.what()) std::fprintf(stderr, "dewall-mpi: %s\nrun 'dewall-mpi help' for the usage\n", e.what());
      else std::fputs(usage_text, stdout);
    }
    return *e.what() ? 2 : 0;
  }
  if (args.certify) {
    try {
      return certify_command(args, rank, size);
    } catch (const std::exception& e) {
      if (rank == 0) std::fprintf(stderr, "dewall-mpi: %s\n", e.what());
      return 2;
    }
  }
  try {
    // Checked before any work, as dewall checks them: a name that says a
    // point format, and an output that would replace the input.
    if (args.output != "-") {
      dewall::io::check_simplices_output_name(args.output);
      dewall::io::check_output_is_not_input(args.output, args.input);
    }
    Share share;
    const double t = MPI_Wtime();
    share = read_share(MPI_COMM_WORLD, args.input, rank, size);
    share.seconds = MPI_Wtime() - t;
    return dewall::kernel::with_dimension(share.dimension, [&](auto d) {
      return triangulate<decltype(d)::value>(MPI_COMM_WORLD, args, std::move(share), rank, size);
    });
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
