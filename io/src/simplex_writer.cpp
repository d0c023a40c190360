#include "dewall/io/simplex_writer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <memory>
#include <ostream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "dewall/io/binary_points.hpp"
#include "dewall/io/binary_simplices.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/mesh_formats.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/quote.hpp"
#include "dewall/io/simplex_rows.hpp"
#include "dewall/io/vtk.hpp"
#include "text_lines.hpp"

namespace dewall::io {
namespace {

/// No progress line while writing to a terminal's standard output: its carriage
/// returns would overwrite the very lines being written.
Progress* unless_terminal_output(const std::string& path, Progress* progress) {
  return path == "-" && ::isatty(STDOUT_FILENO) == 1 ? nullptr : progress;
}

/// How messages name an output path.
std::string shown(const std::string& path) { return path == "-" ? std::string("<stdout>") : file_name(path); }

}  // namespace

namespace {

/// Writes `t` in format `f`, header first, a block of rows at a time.
void write_rows(std::ostream& out, const Simplex_table& t, Simplex_format f, std::size_t first_index,
                Progress* progress) {
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  constexpr std::size_t rows_per_write = 1 << 14;
  std::string text = simplex_file_header(f, t.vertices_per_simplex - 1, t.size());
  // .ele rows are numbered, and their vertices shifted, like the .node file's points.
  const std::uint64_t shift = f == Simplex_format::ele ? first_index : 0;
  std::uint64_t row = shift;
  for (std::size_t s = 0; s < t.size() && out; s += rows_per_write) {
    const std::size_t rows = std::min(rows_per_write, t.size() - s);
    append_simplex_rows<std::uint32_t>(text, std::span(t.indices).subspan(s * k, rows * k), k, f, row, 4, shift);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    text.clear();
    if (progress) progress->advance_to(s + rows);
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));  // the header of an empty list
}

}  // namespace

Simplex_format simplex_format_named_by(std::string_view path) {
  const Named_format f = format_named_by(path);
  return f == Named_format::binary_simplices ? Simplex_format::binary
         : f == Named_format::tetgen_ele     ? Simplex_format::ele
                                             : Simplex_format::plain;
}

std::string simplex_file_header(Simplex_format f, int dimension, std::uint64_t count, int index_bytes) {
  if (f == Simplex_format::binary) {
    std::ostringstream out;
    write_binary_simplices_header(out, dimension, count, index_bytes);
    return out.str();
  }
  if (f == Simplex_format::ele) return std::to_string(count) + ' ' + std::to_string(dimension + 1) + " 0\n";
  return {};
}

void write_plain(std::ostream& out, const Simplex_table& t, Progress* progress) {
  write_rows(out, t, Simplex_format::plain, 0, progress);
}

void write_ele(std::ostream& out, const Simplex_table& t, std::size_t first_index) {
  write_rows(out, t, Simplex_format::ele, first_index, nullptr);
}

void write_binary_simplices(std::ostream& out, const Simplex_table& t, Progress* progress) {
  write_rows(out, t, Simplex_format::binary, 0, progress);
}

void write_simplices_file(const std::string& path, const Simplex_table& t, std::size_t first_index,
                          Progress* progress) {
  check_simplices_output_name(path);
  progress = unless_terminal_output(path, progress);
  const Simplex_format f = simplex_format_named_by(path);
  if (progress) progress->phase("writing " + shown(path), f == Simplex_format::ele ? 0 : t.size());
  write_output_file(path, [&](std::ostream& out) { write_rows(out, t, f, first_index, progress); });
  if (progress) progress->finish();
}

bool is_vtk_path(const std::string& path) { return has_extension(path, ".vtk"); }

bool can_stream_simplices(const std::string& path) {
  return !triangulation_needs_points(path) && !has_extension(path, ".ele");
}

Simplex_stream_writer::Simplex_stream_writer(const std::string& path, int vertices_per_simplex)
    : format_(simplex_format_named_by(path)), k_(static_cast<std::size_t>(vertices_per_simplex)) {
  if (!can_stream_simplices(path))
    throw std::invalid_argument(shown(path) + ": .ele, .vtk and .msh files start with the count; they cannot be streamed");
  check_simplices_output_name(path);
  file_ = std::make_unique<Output_file>(path);
  text_ = simplex_file_header(format_, vertices_per_simplex - 1, binary_simplices_unknown_count);
  file_->stream().write(text_.data(), static_cast<std::streamsize>(text_.size()));
}

Simplex_stream_writer::~Simplex_stream_writer() = default;

void Simplex_stream_writer::write(std::span<const std::uint32_t> indices) {
  std::ostream& out = file_->stream();
  text_.clear();
  append_simplex_rows(text_, indices, k_, format_, count_);
  out.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  // Stop the triangulation at the first failed write (a full disk, a closed pipe).
  if (!out) file_->check();
}

void Simplex_stream_writer::commit() {
  if (format_ == Simplex_format::binary) {
    unsigned char count[8];
    for (int i = 0; i < 8; ++i) count[i] = static_cast<unsigned char>(std::uint64_t{count_} >> (8 * i));
    file_->patch(binary_simplices_count_offset, count, sizeof count);  // (kept unknown on a pipe)
  }
  file_->commit();
}

bool triangulation_needs_points(const std::string& path) {
  const Named_format f = format_named_by(path);
  return f == Named_format::vtk || f == Named_format::gmsh;
}

void check_triangulation_output(const std::string& path, int dimension) {
  check_simplices_output_name(path);
  if (triangulation_needs_points(path) && dimension != 2 && dimension != 3)
    throw Vtk_unsupported(shown(path) + ": " + (is_vtk_path(path) ? "VTK" : "gmsh") +
                          " output supports 2D and 3D only; these points are in dimension " + std::to_string(dimension) +
                          " (write a plain simplex list instead)");
}

void write_triangulation_file(const std::string& path, const Point_table& points, const Simplex_table& t,
                              Progress* progress) {
  check_triangulation_output(path, points.dimension);  // refused before anything is created
  progress = unless_terminal_output(path, progress);
  if (!triangulation_needs_points(path)) return write_simplices_file(path, t, points.first_index, progress);
  if (is_vtk_path(path))
    write_output_file(path, [&](std::ostream& out) { write_vtk_triangulation(out, points, t, progress); });
  else
    write_output_file(path, [&](std::ostream& out) { write_msh_triangulation(out, points, t); });
}

void write_points_text(std::ostream& out, const Point_table& t, Progress* progress) {
  const auto d = static_cast<std::size_t>(t.dimension);
  std::string buffer;
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (std::size_t j = 0; j < d; ++j) {
      if (j) buffer += ' ';
      detail::append_shortest(buffer, t.coordinates[i * d + j]);
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

void write_node(std::ostream& out, const Point_table& t) {
  out << t.size() << ' ' << t.dimension << " 0 0\n";
  const auto d = static_cast<std::size_t>(t.dimension);
  std::string line;
  for (std::size_t i = 0; i < t.size() && out; ++i) {
    line = std::to_string(i + t.first_index);
    for (std::size_t j = 0; j < d; ++j) {
      line += ' ';
      detail::append_shortest(line, t.coordinates[i * d + j]);
    }
    line += '\n';
    out << line;
  }
}

void write_points_file(const std::string& path, const Point_table& t, Progress* progress) {
  check_points_output_name(path);
  progress = unless_terminal_output(path, progress);
  if (has_extension(path, ".node")) {
    write_output_file(path, [&](std::ostream& out) { write_node(out, t); });
  } else if (has_extension(path, ".dwpt")) {
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
