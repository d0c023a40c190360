#include "dewall/io/simplex_writer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <memory>
#include <ostream>
#include <span>
#include <stdexcept>
#include <unistd.h>

#include "dewall/io/binary_points.hpp"
#include "dewall/io/binary_simplices.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/mesh_formats.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/quote.hpp"
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

/// Appends the plain list's lines for whole rows of k indices.
void append_plain_lines(std::string& text, std::span<const std::uint32_t> indices, std::size_t k) {
  char number[16];
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const auto r = std::to_chars(number, number + sizeof number, indices[i]);
    text.append(number, r.ptr);
    text += (i + 1) % k == 0 ? '\n' : ' ';
  }
}

}  // namespace

void write_plain(std::ostream& out, const Simplex_table& t, Progress* progress) {
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  constexpr std::size_t rows_per_write = 1 << 14;
  std::string text;
  for (std::size_t s = 0; s < t.size() && out; s += rows_per_write) {
    const std::size_t rows = std::min(rows_per_write, t.size() - s);
    text.clear();
    append_plain_lines(text, std::span(t.indices).subspan(s * k, rows * k), k);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (progress) progress->advance_to(s + rows);
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
  check_simplices_output_name(path);
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

bool can_stream_simplices(const std::string& path) {
  return !triangulation_needs_points(path) && !has_extension(path, ".ele");
}

Simplex_stream_writer::Simplex_stream_writer(const std::string& path, int vertices_per_simplex)
    : binary_(has_extension(path, ".dwsx")), k_(static_cast<std::size_t>(vertices_per_simplex)) {
  if (!can_stream_simplices(path))
    throw std::invalid_argument(shown(path) + ": .ele, .vtk and .msh files start with the count; they cannot be streamed");
  check_simplices_output_name(path);
  file_ = std::make_unique<Output_file>(path);
  if (binary_) write_binary_simplices_header(file_->stream(), vertices_per_simplex - 1, binary_simplices_unknown_count);
}

Simplex_stream_writer::~Simplex_stream_writer() = default;

void Simplex_stream_writer::write(std::span<const std::uint32_t> indices) {
  std::ostream& out = file_->stream();
  if (binary_) {
    write_binary_simplex_indices(out, indices);
  } else {
    text_.clear();
    append_plain_lines(text_, indices, k_);
    out.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  }
  count_ += indices.size() / k_;
  // Stop the triangulation at the first failed write (a full disk, a closed pipe).
  if (!out) file_->check();
}

void Simplex_stream_writer::commit() {
  if (binary_) {
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
