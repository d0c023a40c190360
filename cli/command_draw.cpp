// dewall draw POINTS [SIMPLICES] [-o picture.svg] [--walls] [--width PX] [--quiet|-q]
//
// An SVG picture of a 2D triangulation. With --walls each triangle is coloured
// by the recursion level of the wall that built it, as in the paper's Figures
// 2, 4 and 5: level 0 is the first wall (the triangles crossed by the first
// splitting line), level 1 the two walls of the halves, and so on. The levels
// are not stored in any file, so --walls triangulates POINTS again (the result
// is the same canonical triangulation `dewall triangulate` writes).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <span>
#include <stdexcept>
#include <vector>

#include "cli.hpp"
#include "dewall/dewall.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/quote.hpp"
#include "dewall/io/simplex_reader.hpp"

namespace dewall::cli {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

/// The triangles of SIMPLICES (plain list, Qhull's `qdelaunay Qt i` or TetGen
/// .ele: io/simplex_reader.hpp), each index checked against the point count.
std::vector<Triangle> read_triangles(const std::string& path, const io::Point_table& table) {
  const auto list = io::read_simplices_file(path, 2, table.first_index);
  const std::string name = input_name(path);
  std::vector<Triangle> triangles(list.table.size());
  for (std::size_t r = 0; r < triangles.size(); ++r)
    for (std::size_t i = 0; i < 3; ++i) {
      const auto v = list.table.indices[3 * r + i];
      if (v >= table.size())
        throw io::Parse_error(list.where(name, r) + ": point index " +
                              std::to_string(v + table.first_index) + " out of range (" +
                              std::to_string(table.size()) + " points)");
      triangles[r][i] = v;
    }
  return triangles;
}

/// The triangulation of `table` with the wall level of each triangle.
std::vector<std::pair<Triangle, int>> triangulate_with_levels(const io::Point_table& table) {
  std::vector<kernel::Point_d<2>> points(table.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {{table.coordinates[2 * i], table.coordinates[2 * i + 1]}};
  std::vector<std::pair<Triangle, int>> out;
  triangulate_to<kernel::Filtered_kernel_d<2>>(std::span<const kernel::Point_d<2>>(points),
                                               [&](const Simplex<2>& s, int level) { out.emplace_back(s, level); });
  return out;
}

/// Fill colours by wall level: ten well-separated hues, repeated beyond.
constexpr std::array<const char*, 10> palette = {"#e15759", "#4e79a7", "#f28e2b", "#76b7b2", "#59a14f",
                                                 "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
const char* unmatched_colour = "#dddddd";

void write_svg(std::ostream& out, const io::Point_table& table, const std::vector<Triangle>& triangles,
               const std::vector<int>& levels, int width, bool walls) {
  const auto& c = table.coordinates;
  double x0 = c[0], x1 = c[0], y0 = c[1], y1 = c[1];
  for (std::size_t i = 0; i < table.size(); ++i) {
    x0 = std::min(x0, c[2 * i]), x1 = std::max(x1, c[2 * i]);
    y0 = std::min(y0, c[2 * i + 1]), y1 = std::max(y1, c[2 * i + 1]);
  }
  // Differences are taken between halves: x1 - x0 overflows to infinity for
  // coordinates near ±1e308 (and infinity · 0 is NaN), x1/2 - x0/2 never does.
  const auto half_offset = [](double v, double low) { return v * 0.5 - low * 0.5; };
  const double margin = 10, legend = walls ? 24 : 0;
  const double half_span = std::max({half_offset(x1, x0), half_offset(y1, y0), 1e-300});
  const double scale = (width - 2 * margin) / half_span;  // pixels per half unit
  const double height = std::ceil(half_offset(y1, y0) * scale + 2 * margin + legend);
  // SVG's y axis points down: flip so the picture is the usual way up.
  auto px = [&](std::uint32_t i) { return margin + half_offset(c[2 * i], x0) * scale; };
  auto py = [&](std::uint32_t i) { return height - margin - half_offset(c[2 * i + 1], y0) * scale; };
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%.0f\" viewBox=\"0 0 %d %.0f\">\n",
                width, height, width, height);
  out << buffer;
  out << "<title>Delaunay triangulation of " << table.size() << " points, " << triangles.size()
      << " triangles (dewall)</title>\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const double stroke = triangles.size() > 20000 ? 0.2 : 0.6;
  std::snprintf(buffer, sizeof buffer, "<g stroke=\"#333333\" stroke-width=\"%.1f\" stroke-linejoin=\"round\">\n",
                stroke);
  out << buffer;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& s = triangles[t];
    const char* fill = !walls ? "#dce6f2"
                       : levels[t] < 0 ? unmatched_colour
                                       : palette[static_cast<std::size_t>(levels[t]) % palette.size()];
    std::snprintf(buffer, sizeof buffer, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n",
                  px(s[0]), py(s[0]), px(s[1]), py(s[1]), px(s[2]), py(s[2]), fill);
    out << buffer;
  }
  out << "</g>\n";
  if (table.size() <= 20000) {
    out << "<g fill=\"#111111\">\n";
    for (std::uint32_t i = 0; i < table.size(); ++i) {
      std::snprintf(buffer, sizeof buffer, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"1.5\"/>\n", px(i), py(i));
      out << buffer;
    }
    out << "</g>\n";
  }
  if (walls) {
    const int top = levels.empty() ? 0 : *std::max_element(levels.begin(), levels.end());
    out << "<g font-family=\"sans-serif\" font-size=\"12\">\n<text x=\"" << margin << "\" y=\"" << margin + 12
        << "\">wall level</text>\n";
    for (int l = 0; l <= top; ++l) {
      const double x = margin + 70 + 26 * l;
      std::snprintf(buffer, sizeof buffer,
                    "<rect x=\"%.0f\" y=\"%.0f\" width=\"22\" height=\"14\" fill=\"%s\" stroke=\"#333333\"/>"
                    "<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"middle\">%d</text>\n",
                    x, margin + 1, palette[static_cast<std::size_t>(l) % palette.size()], x + 11, margin + 12, l);
      out << buffer;
    }
    out << "</g>\n";
  }
  out << "</svg>\n";
}

}  // namespace

int command_draw(int argc, char** argv) {
  std::string output = "-";
  bool walls = false, quiet = false;
  long width = 800;
  const auto operands = parse_arguments(
      argc, argv, 2,
      [&](const std::string& a, int& i) {
        if (a == "-o" || a == "--output") output = next_arg(i, argc, argv);
        else if (a == "--walls") walls = true;
        else if (a == "--width") width = parse_long(next_arg(i, argc, argv), "--width value");
        else if (a == "--quiet" || a == "-q") quiet = true;
        else return false;
        return true;
      });
  if (operands.empty()) throw Usage_error("draw needs a POINTS file");
  const std::string points_path = operands[0], simplices_path = operands.size() > 1 ? operands[1] : "";
  if (!walls && simplices_path.empty()) throw Usage_error("draw needs a SIMPLICES file (or --walls)");
  if (width < 100 || width > 100000) throw Usage_error("--width must be 100 to 100000 pixels");
  if (points_path == "-" && simplices_path == "-" && !walls)
    throw Usage_error("POINTS and SIMPLICES cannot both be standard input");

  // A target that cannot be written, or is an input, fails now, not after the work.
  io::check_output_is_not_input(output, points_path);
  if (!simplices_path.empty()) io::check_output_is_not_input(output, simplices_path);
  io::Output_file::probe(output);
  io::Progress progress(!quiet && io::stderr_is_terminal());
  const auto table = io::read_points_file(points_path, &progress);
  if (table.dimension != 2)
    throw std::runtime_error("draw pictures 2D triangulations only; " + input_name(points_path) +
                             " holds points of dimension " + std::to_string(table.dimension));
  // A picture needs finite coordinates (with --walls the triangulator would refuse them too).
  for (std::size_t i = 0; i < table.coordinates.size(); ++i)
    if (!std::isfinite(table.coordinates[i]))
      return report_invalid_input(input_name(points_path),
                                  Invalid_input(i / 2, "has a non-finite coordinate (NaN or infinity)"),
                                  table.first_index);

  std::vector<Triangle> triangles;
  std::vector<int> levels;
  if (walls) {
    std::vector<std::pair<Triangle, int>> built;
    try {
      progress.phase("triangulating " + std::to_string(table.size()) + " points");
      built = triangulate_with_levels(table);
      progress.finish();
    } catch (const Invalid_input& e) {
      progress.finish();
      return report_invalid_input(input_name(points_path), e, table.first_index);
    }
    if (simplices_path.empty() || simplices_path == "-") {
      for (const auto& [t, level] : built) triangles.push_back(t), levels.push_back(level);
    } else {
      // Draw the given triangles, each with the level of the same triangle
      // (same vertex set) in the canonical triangulation; the others in grey.
      std::map<Triangle, int> level_of;
      for (auto [t, level] : built) std::sort(t.begin(), t.end()), level_of[t] = level;
      triangles = read_triangles(simplices_path, table);
      std::size_t unmatched = 0;
      for (auto t : triangles) {
        std::sort(t.begin(), t.end());
        const auto it = level_of.find(t);
        levels.push_back(it == level_of.end() ? -1 : it->second);
        unmatched += it == level_of.end();
      }
      if (unmatched)
        std::fprintf(stderr,
                     "dewall draw: %zu of %zu triangles of %s are not in the canonical triangulation (drawn grey)\n",
                     unmatched, triangles.size(), input_name(simplices_path).c_str());
    }
  } else {
    triangles = read_triangles(simplices_path, table);
  }
  if (output != "-") progress.phase("writing " + io::file_name(output));  // no progress line inside the SVG on a terminal
  io::write_output_file(output, [&](std::ostream& out) {
    write_svg(out, table, triangles, levels, static_cast<int>(width), walls);
  });
  progress.finish();
  return 0;
}

namespace {
const bool registered = register_command({"draw", command_draw,
    "  draw POINTS [SIMPLICES] [-o PICTURE.svg] [--walls] [--width PX] [--quiet|-q]\n"
    "      SVG picture of a 2D triangulation (default: standard output). SIMPLICES is\n"
    "      a simplex list as certify reads it ('-' = standard input). --walls colours each triangle\n"
    "      by the recursion level of the DeWall wall that built it (0: the first\n"
    "      wall), as in the paper's figures; it triangulates POINTS again to learn\n"
    "      the levels, so SIMPLICES may then be omitted (or '-'); when given, its\n"
    "      triangles are drawn and those not in the canonical triangulation are grey.\n"});
}  // namespace

}  // namespace dewall::cli
