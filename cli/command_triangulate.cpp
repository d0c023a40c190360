// dewall triangulate INPUT [-o OUTPUT] [--engine auto|dewall|hybrid|incremental|cgal] [--threads N] [--stream]
//                    [--region-points N] [--incremental-engine auto|incremental|cgal] [--stats] [--quiet|-q]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "dewall/error.hpp"
#include "dewall/options.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/quote.hpp"
#include "dewall/io/vtk.hpp"

namespace dewall::cli {

namespace {

/// True when the points lie on one sphere, to within a relative 10^-6 of its
/// radius (a least-squares fit: |p|^2 = 2 c.p + k, solved by Gaussian
/// elimination on the normal equations). A warning's heuristic, never a
/// decision about the triangulation.
bool on_one_sphere(const io::Point_table& t) {
  const auto d = static_cast<std::size_t>(t.dimension), n = t.size(), m = d + 1;
  if (n <= m) return false;
  std::vector<double> low(t.coordinates.begin(), t.coordinates.begin() + static_cast<std::ptrdiff_t>(d)), high = low;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < d; ++j)
      low[j] = std::min(low[j], t.coordinates[i * d + j]), high[j] = std::max(high[j], t.coordinates[i * d + j]);
  // Centred on the box and scaled by its largest half-width (one scale for
  // every axis: a sphere stays a sphere), so that the normal equations stay well conditioned.
  double half = 0;
  for (std::size_t j = 0; j < d; ++j) half = std::max(half, high[j] / 2 - low[j] / 2);
  if (!(half > 0) || !std::isfinite(half)) return false;
  const auto x = [&](std::size_t i, std::size_t j) {
    return (t.coordinates[i * d + j] - (low[j] / 2 + high[j] / 2)) / half;
  };
  std::vector<double> a(m * (m + 1), 0.0);  // [A^T A | A^T b], rows (x_1 … x_d, 1)
  std::vector<double> row(m + 1);
  for (std::size_t i = 0; i < n; ++i) {
    double b = 0;
    for (std::size_t j = 0; j < d; ++j) row[j] = 2 * x(i, j), b += x(i, j) * x(i, j);
    row[d] = 1, row[m] = b;
    for (std::size_t r = 0; r < m; ++r)
      for (std::size_t c = 0; c <= m; ++c) a[r * (m + 1) + c] += row[r] * row[c];
  }
  for (std::size_t p = 0; p < m; ++p) {
    std::size_t best = p;
    for (std::size_t r = p + 1; r < m; ++r)
      if (std::abs(a[r * (m + 1) + p]) > std::abs(a[best * (m + 1) + p])) best = r;
    if (a[best * (m + 1) + p] == 0) return false;
    for (std::size_t c = 0; c <= m; ++c) std::swap(a[p * (m + 1) + c], a[best * (m + 1) + c]);
    for (std::size_t r = 0; r < m; ++r) {
      if (r == p) continue;
      const double f = a[r * (m + 1) + p] / a[p * (m + 1) + p];
      for (std::size_t c = p; c <= m; ++c) a[r * (m + 1) + c] -= f * a[p * (m + 1) + c];
    }
  }
  std::vector<double> centre(d);
  double r2 = a[d * (m + 1) + m] / a[d * (m + 1) + d];
  for (std::size_t j = 0; j < d; ++j) centre[j] = a[j * (m + 1) + m] / a[j * (m + 1) + j], r2 += centre[j] * centre[j];
  if (!(r2 > 0)) return false;
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0;
    for (std::size_t j = 0; j < d; ++j) s += (x(i, j) - centre[j]) * (x(i, j) - centre[j]);
    worst = std::max(worst, std::abs(s - r2));
  }
  return worst <= 2e-6 * r2;
}

}  // namespace

int command_triangulate(int argc, char** argv) {
  std::string output = "-";
  std::string engine = "auto";
  std::string incremental_engine = "auto";
  std::optional<std::string> threads;        // absent: all cores
  std::optional<std::string> region_points;  // absent: chosen by n
  bool stats = false, quiet = false, stream = false;
  const auto operands = parse_arguments(
      argc, argv, 1,
      [&](const std::string& a, int& i) {
        if (a == "-o" || a == "--output") output = next_arg(i, argc, argv);
        else if (a == "--engine") engine = next_arg(i, argc, argv);
        else if (a == "--incremental-engine") incremental_engine = next_arg(i, argc, argv);
        else if (a == "--threads") threads = next_arg(i, argc, argv);
        else if (a == "--stats") stats = true;
        else if (a == "--stream") stream = true;
        else if (a == "--region-points") region_points = next_arg(i, argc, argv);
        else if (a == "--quiet" || a == "-q") quiet = true;
        else return false;
        return true;
      });
  if (operands.empty()) throw Usage_error("triangulate needs an INPUT file ('-' for standard input)");
  const std::string& input = operands[0];
  Options options;
  if (const auto e = parse_engine(engine)) options.engine = *e;
  else throw Usage_error("unknown engine " + io::quoted(engine) + " (" + engine_choices + ")");
  if (const auto e = parse_engine(incremental_engine);
      e && (*e == Engine::automatic || *e == Engine::incremental || *e == Engine::cgal))
    options.incremental_engine = *e;
  else
    throw Usage_error("unknown incremental engine " + io::quoted(incremental_engine) + " (auto, incremental or cgal)");
  // An option the chosen engine would ignore is a mistake to point out, not to pass over.
  const bool regions = options.engine == Engine::automatic || options.engine == Engine::hybrid;
  if (region_points && !regions)
    throw Usage_error(std::string("--region-points applies to --engine auto and hybrid, not ") + engine_name(options.engine));
  if (options.incremental_engine != Engine::automatic && !regions)
    throw Usage_error(std::string("--incremental-engine applies to --engine auto and hybrid, not ") +
                      engine_name(options.engine) + (options.engine == Engine::dewall ? "" : " (itself an incremental construction)"));
  if (threads) options.threads = parse_thread_count(*threads);
  if (region_points) {
    const long n = parse_long(*region_points, "--region-points value");
    if (n < 1 || n > 0xFFFFFFFFL) throw Usage_error("--region-points must be 1 to 4294967295, not " + *region_points);
    options.region_points = static_cast<std::size_t>(n);
  }
  if (stream && !io::can_stream_simplices(output))
    throw Usage_error("--stream writes the plain simplex list or .dwsx, not " + io::quoted(output) +
                      " (.ele, .vtk and .msh files start with the count of simplices)");
  options.stream = stream;
  // Outputs that would lose data or could not be read back fail now, not after the work.
  io::check_simplices_output_name(output);
  io::check_output_is_not_input(output, input);
  io::Output_file::probe(output);
  io::Progress progress(!quiet && io::stderr_is_terminal());
  auto table = io::read_points_file(input, &progress);
  // Refuse an impossible output before the (possibly long) triangulation.
  io::check_triangulation_output(output, table.dimension);
  // Said before the work, which may take minutes: cospherical points are
  // gift wrapping's worst case (every search proves one sphere empty).
  constexpr std::size_t quadratic_warning_points = 5000;
  if (options.engine == Engine::dewall && table.size() >= quadratic_warning_points && on_one_sphere(table))
    std::fprintf(stderr,
                 "dewall: warning: the points of %s lie on one sphere, where the paper's algorithm (--engine dewall) "
                 "takes quadratic time; --engine auto hands over to the incremental construction there\n",
                 input_name(input).c_str());
  Run run;
  // Streaming: the output is open before the triangulation starts, and
  // complete (renamed into place) only once it ends.
  std::optional<io::Simplex_stream_writer> writer;
  if (stream) writer.emplace(output, table.dimension + 1);
  const Simplex_rows_sink write_rows = [&](std::span<const std::uint32_t> rows) { writer->write(rows); };
  try {
    // On a terminal, the engines' own estimate of the work done (Options::progress).
    constexpr std::uint64_t steps = 1000;
    if (progress.enabled())
      options.progress = [&progress](double fraction) {
        progress.advance_to(static_cast<std::uint64_t>(fraction * steps));
        return true;
      };
    progress.phase("triangulating " + std::to_string(table.size()) + " points", progress.enabled() ? steps : 0);
    // Only VTK and gmsh files write the points again: otherwise the table's copy
    // goes before the triangulation's peak (10^6 points: 24 MB).
    run = triangulate_any(table, options, stream ? &write_rows : nullptr, io::triangulation_needs_points(output));
    progress.finish();
  } catch (const Invalid_input& e) {
    progress.finish();
    return report_invalid_input(input_name(input), e, table.first_index);
  }
  if (writer) writer->commit();
  else io::write_triangulation_file(output, table, run.simplices, &progress);
  progress.finish();
  if (stats) print_stats(stderr, run);
  return 0;
}


namespace {
// The region sizes come from options.hpp (region_points_for), so that the help
// cannot drift from the code.
std::string count(std::size_t n) { return std::to_string(n); }
const std::string usage =
    "  triangulate INPUT [-o OUTPUT] [--engine auto|dewall|hybrid|incremental|cgal] [--threads N]\n"
    "              [--stream] [--region-points N]\n"
    "              [--incremental-engine auto|incremental|cgal] [--stats] [--quiet|-q]\n"
    "      Delaunay triangulation of the points in INPUT ('-' = standard input):\n"
    "      plain text (one point per line, '#' comments), rbox output, TetGen .node,\n"
    "      the binary .dwpt format, the POINTS of a legacy VTK file, the vertices\n"
    "      of a PLY, OFF or OBJ mesh, or a PCL .pcd point cloud (recognised by\n"
    "      their first bytes, or by name).\n"
    "      Writes one simplex per line (zero-based input indices) to OUTPUT\n"
    "      (default: standard output); TetGen .ele when OUTPUT ends in .ele, the\n"
    "      binary simplex format when it ends in .dwsx (for 10^7 points and more),\n"
    "      legacy VTK for ParaView when it ends in .vtk, gmsh's format when it ends\n"
    "      in .msh (both 2D and 3D); extensions in any case. A name that says a\n"
    "      point format (.dwpt, .node) or one dewall does not write (.ply, .stl, ...)\n"
    "      is refused, and so is OUTPUT = INPUT.\n"
    "      --engine: the construction; the simplices are the same with each.\n"
    "      hybrid builds DeWall's walls down to regions of n/4 points (" + count(smallest_default_region) + " to\n"
    "      " + count(largest_default_region) + ") and triangulates each region with an incremental construction\n"
    "      (no merge step; the regions run in parallel). auto (default) is\n"
    "      hybrid, handing over to the incremental construction alone when the\n"
    "      walls' searches prove too costly (points on or near one sphere, thin\n"
    "      surfaces); it also builds inputs of up to " + count(largest_automatic_whole_input) + " points (one\n"
    "      region's size with --stream or --region-points) and all 4D+ inputs\n"
    "      (below that size the walls do not pay on one core or two). The regions,\n"
    "      and what auto hands over, are built by dewall's own incremental\n"
    "      construction (--incremental-engine cgal chooses CGAL's).\n"
    "      dewall (walls all the way down, the paper's algorithm), incremental\n"
    "      (dewall's own Bowyer-Watson; from about 70000 points on it inserts in\n"
    "      two zones at a time, in parallel) and cgal force one.\n"
    "      --threads N: at most N threads (default: all cores); the output is the\n"
    "      same, byte for byte, for every N.\n"
    "      --stream writes each simplex as soon as it is built and keeps none\n"
    "      in memory, and takes regions of at most " + count(largest_default_streaming_region) + " points (n/" + count(streaming_region_share) + "\n"
    "      from " + count(streaming_region_share * largest_default_streaming_region) + " points on, at most " + count(largest_streaming_region_at_scale) + "; plain list or .dwsx\n"
    "      only): the same simplices; with --threads 1 in the order collecting\n"
    "      gives with the same regions (--region-points; by default they may\n"
    "      differ above " + count(4 * largest_default_streaming_region) + " points), with more threads in an order\n"
    "      that varies.\n"
    "      auto then decides once, at the first region, whether to hand over to\n"
    "      the incremental construction (whose triangulation is whole in memory).\n"
    "      To a pipe, a .dwsx stream leaves its count 'unknown' (readers take\n"
    "      what follows).\n"
    "      --region-points N: regions of at most N points instead (hybrid and\n"
    "      auto; the same simplices; the order, speed and memory change with N).\n"
    "      --incremental-engine: the incremental construction of the regions and\n"
    "      of what auto hands over: incremental (dewall's own), cgal, or auto\n"
    "      (default: the faster of the two for the job, measured; the same\n"
    "      simplices with each).\n"
    "      --stats prints on stderr the engine that built the output, how many\n"
    "      simplices each construction built, build_s=SECONDS and, when walls ran,\n"
    "      the paper's Table 1 counters.\n"
    "      A progress line is shown on stderr for long work when it is a terminal;\n"
    "      --quiet (-q) turns it off. Options may also be written --name=VALUE.\n";
const bool registered = register_command({"triangulate", command_triangulate, usage.c_str()});
}  // namespace

}  // namespace dewall::cli
