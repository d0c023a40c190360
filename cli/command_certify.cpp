// dewall certify POINTS SIMPLICES [--canonical] [--all] [--json] [--threads N] [--stream] [--memory SIZE]
#include <chrono>
#include <cstdio>
#include <optional>
#include <span>
#include <vector>

#include "certify_text.hpp"
#include "cli.hpp"
#include "dewall/certify/certify.hpp"
#include "dewall/io/simplex_reader.hpp"
#include "dewall/kernel/filtered_kernel_d.hpp"

namespace dewall::cli {
namespace {

/// "512M", "4G", "65536": bytes, with K, M or G for powers of 1024.
std::size_t parse_memory(const std::string& text) {
  if (const auto bytes = memory_size(text)) return *bytes;
  throw Usage_error("--memory must be a positive size such as 512M or 4G, not " + text);
}

int command_certify(int argc, char** argv) {
  bool canonical = false, json = false;
  certify::Options options;
  const auto files = parse_arguments(
      argc, argv, 2,
      [&](const std::string& a, int& i) {
        if (a == "--canonical") canonical = true;
        else if (a == "--all") options.all = true;
        else if (a == "--json") json = true;
        else if (a == "--threads") options.threads = static_cast<unsigned>(parse_thread_count(next_arg(i, argc, argv)));
        else if (a == "--stream") options.stream = true;
        else if (a == "--memory") options.working_memory = parse_memory(next_arg(i, argc, argv));
        else return false;
        return true;
      });
  if (files.size() != 2) throw Usage_error("certify needs POINTS and SIMPLICES ('-' = standard input for one of them)");
  if (files[0] == "-" && files[1] == "-") throw Usage_error("only one of POINTS and SIMPLICES can be standard input");
  // Each file holding what the other should: say so, not only what is wrong with one.
  const auto swapped = [&](const io::Parse_error& e) {
    return io::Parse_error(std::string(e.what()) + " (the arguments look swapped: dewall certify POINTS SIMPLICES)");
  };
  io::Point_table points;
  std::optional<io::Simplex_file_reader> reader;
  try {
    points = io::read_points_file(files[0]);
    reader.emplace(files[1], points.dimension, points.first_index);
  } catch (const io::Not_points_error& e) {
    throw swapped(e);
  } catch (const io::Not_simplices_error& e) {
    throw swapped(e);
  }
  const io::Simplex_list& list = reader->list();
  if (reader->remaining() == 0)
    throw io::Parse_error(input_name(files[1]) + ": no simplices (a triangulation of " + std::to_string(points.size()) +
                          " points has at least one)");
  // Rows that would take more than a quarter of the memory (as a binary
  // file's header counts them; held, with their facet records, at about
  // three times their size) stream.
  const std::uint64_t rows = reader->remaining(), memory = physical_memory();
  if (rows != ~std::uint64_t{0} && memory > 0 &&
      rows * static_cast<std::uint64_t>(points.dimension + 1) * 4 > memory / 4)
    options.stream = true;
  const std::string sname = input_name(files[1]), pname = input_name(files[0]);

  const auto start = std::chrono::steady_clock::now();
  const certify::Report report = certify_file(points, *reader, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report.simplices == 0)
    throw io::Parse_error(sname + ": no simplices (a triangulation of " + std::to_string(points.size()) +
                          " points has at least one)");

  // Witnesses name input numbers as the files do (TetGen may count from 1).
  const Certify_names names{sname, points.first_index, [&](std::size_t r) { return list.where(sname, r); }, list.format};
  if (json) {
    const auto line = [&](std::size_t r) { return list.lines.empty() ? certify::npos : std::size_t{list.lines[r]}; };
    std::fputs(certify_json(report, names, line, seconds).c_str(), stdout);
    return report.delaunay && (report.canonical || !canonical) ? 0 : 1;
  }
  return print_certify_text(report, names, pname, canonical, options.all);
}

const bool registered = register_command({"certify", command_certify,
    "  certify POINTS SIMPLICES [--canonical] [--all] [--json] [--threads N]\n"
    "          [--stream] [--memory SIZE]\n"
    "      Decides with exact predicates whether SIMPLICES (one simplex per line,\n"
    "      zero-based indices, any order, each simplex in either orientation;\n"
    "      Qhull's 'qdelaunay Qt i' output; TetGen .ele; the binary .dwsx format;\n"
    "      a VTK or gmsh file's cells; or a CGAL triangulation written with\n"
    "      operator<<, named .cgal, given as both arguments) is a Delaunay\n"
    "      triangulation of POINTS, and whether it is the canonical one (CGAL's\n"
    "      and dewall's). Exit 0 when it is Delaunay\n"
    "      (with --canonical: only when also canonical), 1 with the first\n"
    "      violation and its witness otherwise, 2 for unreadable input.\n"
    "      --all lists every violation; --json prints a machine-readable report.\n"
    "      --threads N: at most N threads (default: the cores this process may\n"
    "      use); the report is the same for every N.\n"
    "      --stream keeps the simplices in temporary files ($TMPDIR, else /tmp)\n"
    "      instead of memory, bucketed by vertex, and matches their facets bucket\n"
    "      by bucket: memory is the points and --memory (default 512M); the same\n"
    "      report. Chosen by itself when a .dwsx file's simplices would take more\n"
    "      than a quarter of this machine's memory.\n"
    "      --memory SIZE: bytes for the facet records of one window of vertices\n"
    "      (K, M, G suffixes; default: 256K per thread, 512M streaming).\n"});

}  // namespace
}  // namespace dewall::cli
