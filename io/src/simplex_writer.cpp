#include "dewall/io/simplex_writer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <ostream>
#include <unistd.h>

#include "dewall/io/binary_points.hpp"
#include "dewall/io/binary_simplices.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/quote.hpp"
#include "dewall/io/vtk.hpp"

namespace dewall::io {
namespace {

bool has_extension(const std::string& path, const std::string& ext) {
  if (path.size() <= ext.size()) return false;
  return std::equal(ext.begin(), ext.end(), path.end() - static_cast<std::ptrdiff_t>(ext.size()),
                    [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

/// No progress line while writing to a terminal's standard output: its carriage
/// returns would overwrite the very lines being written.
Progress* unless_terminal_output(const std::string& path, Progress* progress) {
  return path == "-" && ::isatty(STDOUT_FILENO) == 1 ? nullptr : progress;
}

/// How messages name an output path.
std::string shown(const std::string& path) { return path == "-" ? std::string("<stdout>") : printable(path); }

}  // namespace

void write_plain(std::ostream& out, const Simplex_table& t, Progress* progress) {
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  std::string line;
  for (std::size_t s = 0; s < t.size(); ++s) {
    line.clear();
    for (std::size_t i = 0; i < k; ++i) {
      if (i) line += ' ';
      line += std::to_string(t.indices[s * k + i]);
    }
    line += '\n';
    out << line;
    if (progress && (s & 0xffff) == 0) progress->advance_to(s);
  }
}

void write_ele(std::ostream& out, const Simplex_table& t, std::size_t first_index) {
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  out << t.size() << ' ' << k << " 0\n";
  for (std::size_t s = 0; s < t.size(); ++s) {
    out << s + first_index;
    for (std::size_t i = 0; i < k; ++i) out << ' ' << t.indices[s * k + i] + first_index;
    out << '\n';
  }
}

void write_simplices_file(const std::string& path, const Simplex_table& t, std::size_t first_index,
                          Progress* progress) {
  progress = unless_terminal_output(path, progress);
  const bool ele = has_extension(path, ".ele"), binary = has_extension(path, ".dwsx");
  if (progress) progress->phase("writing " + shown(path), ele ? 0 : t.size());
  write_output_file(path, [&](std::ostream& out) {
    if (binary) write_binary_simplices(out, t, progress);
    else if (ele) write_ele(out, t, first_index);
    else write_plain(out, t, progress);
  });
  if (progress) progress->finish();
}

bool is_vtk_path(const std::string& path) { return has_extension(path, ".vtk"); }

void write_triangulation_file(const std::string& path, const Point_table& points, const Simplex_table& t,
                              Progress* progress) {
  progress = unless_terminal_output(path, progress);
  if (!is_vtk_path(path)) return write_simplices_file(path, t, points.first_index, progress);
  if (points.dimension != 2 && points.dimension != 3)  // refuse before creating anything
    throw Vtk_unsupported(shown(path) + ": VTK output supports 2D and 3D only; these points are in dimension " +
                          std::to_string(points.dimension) + " (write a plain simplex list instead)");
  write_output_file(path, [&](std::ostream& out) { write_vtk_triangulation(out, points, t, progress); });
}

void write_points_text(std::ostream& out, const Point_table& t, Progress* progress) {
  const auto d = static_cast<std::size_t>(t.dimension);
  std::string buffer;
  char number[32];
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (std::size_t j = 0; j < d; ++j) {
      if (j) buffer += ' ';
      // Shortest representation that reads back to the same double.
      const auto r = std::to_chars(number, number + sizeof number, t.coordinates[i * d + j]);
      buffer.append(number, r.ptr);
    }
    buffer += '\n';
    if (buffer.size() > (1u << 16)) {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
      if (progress) progress->advance_to(i);
    }
  }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

void write_points_file(const std::string& path, const Point_table& t, Progress* progress) {
  progress = unless_terminal_output(path, progress);
  if (has_extension(path, ".dwpt")) {
    if (progress) progress->phase("writing " + shown(path), binary_points_file_size(t.size(), t.dimension));
    write_output_file(path, [&](std::ostream& out) { write_binary_points(out, t, progress); });
  } else if (is_vtk_path(path)) {
    if (t.dimension != 2 && t.dimension != 3)
      throw Vtk_unsupported(shown(path) + ": VTK output supports 2D and 3D only; these points are in dimension " +
                            std::to_string(t.dimension));
    write_output_file(path, [&](std::ostream& out) { write_vtk_points(out, t, progress); });
  } else {
    if (progress) progress->phase("writing " + shown(path), t.size());
    write_output_file(path, [&](std::ostream& out) { write_points_text(out, t, progress); });
  }
  if (progress) progress->finish();
}

}  // namespace dewall::io
