#include "dewall/io/point_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string_view>

#include "dewall/io/binary_points.hpp"
#include "dewall/io/binary_simplices.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/dimensions.hpp"
#include "dewall/io/input_file.hpp"
#include "dewall/io/mesh_formats.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/vtk.hpp"
#include "tetgen_header.hpp"
#include "text_lines.hpp"

namespace dewall::io {
namespace {

using detail::where;

/// Splits a line into its numbers (comments removed). \throws Parse_error on a
/// token that is not a complete decimal number.
std::vector<double> parse_numbers(std::string_view line, const std::string& name, std::size_t line_no) {
  std::vector<double> values;
  detail::for_each_token(detail::without_comment(line),
                         [&](std::string_view token) { values.push_back(detail::parse_double(token, name, line_no)); });
  return values;
}

bool is_count(double v) { return v >= 0 && v == std::floor(v) && v < 1e15; }

/// True when a header's integer (rbox's dimension and count, a .node header
/// value) is written as one: decimal digits only, as rbox and TetGen write
/// them, not "4e0" or "0x2", which strtod would take.
bool is_integer_token(std::string_view token) {
  return !token.empty() && token.size() <= 15 &&
         std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// True when `token` is written as a whole number (decimal digits) too large
/// for a count: the value is of the right kind, and the message says so.
bool is_too_large_integer(std::string_view token) {
  return token.size() > 15 && std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// \throws Parse_error unless `d` is a whole, supported dimension; `shown` is how
/// the message writes it.
void check_dimension(double d, std::string_view shown, const std::string& name, std::size_t line_no) {
  if (!(is_supported_dimension(d) && d == std::floor(d)))
    throw Parse_error(where(name, line_no) + "dimension " + std::string(shown) + " is not supported (" +
                      dimension_range() + ")");
}

/// The next line holding data (blank and comment lines skipped), reporting
/// the bytes read to `progress` now and then; false at the end.
bool next_data_line(detail::Line_source& source, std::string& line, Progress* progress) {
  while (source.next(line)) {
    if (progress && (source.number() & 0xffff) == 0) progress->advance_to(source.bytes());
    if (!detail::is_blank(line)) return true;
  }
  return false;
}

/// True when the first data line starts rbox's header rather than a point: a
/// lone number (no point has one coordinate), or a number followed by rbox's
/// command line ("3 rbox 1000 D3", without '#'), recognised by its word "rbox"
/// or, without it, when the next line is a lone count.
bool is_rbox_header(const std::vector<std::string_view>& first, std::string_view second) {
  if (first.empty() || !detail::is_number(first[0])) return false;
  if (first.size() == 1) return true;
  if (detail::is_number(first[1])) return false;
  std::size_t second_tokens = 0;
  detail::for_each_token(detail::without_comment(second), [&](std::string_view) { ++second_tokens; });
  return first[1] == "rbox" || second_tokens == 1;
}

std::vector<std::string_view> tokens_of(std::string_view line) {
  std::vector<std::string_view> tokens;
  detail::for_each_token(detail::without_comment(line), [&](std::string_view token) { tokens.push_back(token); });
  return tokens;
}

}  // namespace

Point_table read_points(std::istream& in, const std::string& name, Progress* progress) {
  Point_table t;
  detail::Line_source source(in);
  std::string line, second;
  if (!next_data_line(source, line, progress)) throw Parse_error(name + ": no points");
  std::size_t line_no = source.number();
  const auto first = tokens_of(line);
  const bool have_second = next_data_line(source, second, progress);
  const std::size_t second_no = source.number();
  std::optional<std::size_t> expected_count;  // rbox's
  if (is_rbox_header(first, have_second ? second : std::string_view())) {
    // rbox: a dimension (maybe followed by rbox's command line), a lone count, then the rows.
    if (!is_integer_token(first[0]))
      throw Parse_error(where(name, line_no) + "invalid dimension " + quoted(first[0]) + " (a whole number, " +
                        dimension_range() + ")");
    const double dimension = detail::parse_double(first[0], name, line_no);
    check_dimension(dimension, first[0], name, line_no);
    t.dimension = static_cast<int>(dimension);
    if (!have_second)
      throw Parse_error(where(name, line_no) + "a lone dimension without rbox's count line (and no points)");
    const auto count_tokens = tokens_of(second);
    if (count_tokens.size() != 1)
      throw Parse_error(where(name, second_no) + "expected the point count alone on the line after rbox's dimension line, found " +
                        quoted(detail::without_comment(second)));
    if (is_too_large_integer(count_tokens[0]))
      throw Parse_error(where(name, second_no) + "point count " + quoted(count_tokens[0]) + " is too large (at most 10^15)");
    const double count = detail::parse_double(count_tokens[0], name, second_no);
    if (!is_count(count) || !is_integer_token(count_tokens[0]))
      throw Parse_error(where(name, second_no) + "invalid point count " + quoted(count_tokens[0]) +
                        " (a non-negative integer)");
    expected_count = static_cast<std::size_t>(count);
    if (!next_data_line(source, line, progress)) line.clear();
    // One number per line for three lines: not rbox, but a single column,
    // which no point set is (without this, "expected 5 coordinates, found 1").
    if (first.size() == 1 && !line.empty() && tokens_of(line).size() == 1)
      throw Parse_error(where(name, source.number()) + "one value per line: points need " + dimension_range() + " coordinates per line " +
                        "(read as rbox's format, lines " + std::to_string(line_no) + " and " + std::to_string(second_no) +
                        " would be the dimension and the point count)");
  } else {
    const auto values = parse_numbers(line, name, line_no);
    check_dimension(static_cast<double>(values.size()), std::to_string(values.size()), name, line_no);
    t.dimension = static_cast<int>(values.size());
    t.coordinates = values;
    if (have_second) line.swap(second);
    else line.clear();
  }
  const auto d = static_cast<std::size_t>(t.dimension);
  // `line` holds the next row (empty at the end of the input).
  while (!line.empty() && !(expected_count && t.size() == *expected_count)) {
    line_no = source.number();
    const auto values = parse_numbers(line, name, line_no);
    if (values.size() != d)
      throw Parse_error(where(name, line_no) + "expected " + std::to_string(d) + " coordinates, found " +
                        std::to_string(values.size()));
    t.coordinates.insert(t.coordinates.end(), values.begin(), values.end());
    if (!next_data_line(source, line, progress)) line.clear();
  }
  if (expected_count) {
    if (t.size() != *expected_count)
      throw Parse_error(name + ": the header announces " + std::to_string(*expected_count) + " points, the file has " +
                        std::to_string(t.size()) + " (truncated?)");
    if (!line.empty())
      throw Parse_error(where(name, source.number()) + "more rows than the header announces (" +
                        std::to_string(*expected_count) + " points)");
  }
  if (t.size() == 0) throw Parse_error(name + ": no points");
  return t;
}

Point_table read_node(std::istream& in, const std::string& name, Progress* progress) {
  Point_table t;
  detail::Line_source source(in);
  std::string line;
  std::vector<double> header;
  if (next_data_line(source, line, progress)) header = parse_numbers(line, name, source.number());
  const std::size_t header_line = std::max<std::size_t>(source.number(), 1);
  // Every header value is checked to be a count before it is converted: a
  // double outside the target type's range has no defined conversion (fuzz_parse).
  const auto header_tokens = tokens_of(line);
  const std::size_t integers = std::min<std::size_t>(header.size(), 4);
  for (std::size_t i = 0; i < std::min(integers, header_tokens.size()); ++i)
    if (is_too_large_integer(header_tokens[i]))
      throw Parse_error(where(name, header_line) + (i == 0 ? "point count " : "header value ") + quoted(header_tokens[i]) +
                        " is too large (at most 10^15)");
  if (header.size() < 2 || !std::all_of(header.begin(), header.begin() + integers, is_count) ||
      !std::all_of(header_tokens.begin(), header_tokens.begin() + integers, is_integer_token))
    throw Parse_error(where(name, header_line) + "expected a .node header '<count> <dimension> <#attributes> <markers>'");
  const auto count = static_cast<std::size_t>(header[0]);
  check_dimension(header[1], printable(tokens_of(line)[1], 40), name, header_line);
  t.dimension = static_cast<int>(header[1]);
  const std::size_t attributes = header.size() > 2 ? static_cast<std::size_t>(header[2]) : 0;
  const std::size_t markers = header.size() > 3 ? static_cast<std::size_t>(header[3]) : 0;
  const std::size_t width = 1 + static_cast<std::size_t>(t.dimension) + attributes + markers;
  std::size_t read = 0;
  while (read < count && next_data_line(source, line, progress)) {
    const std::size_t line_no = source.number();
    const auto values = parse_numbers(line, name, line_no);
    if (values.size() != width)
      throw Parse_error(where(name, line_no) + "expected " + std::to_string(width) + " values, found " +
                        std::to_string(values.size()));
    if (read == 0) {
      if (values[0] != 0 && values[0] != 1) throw Parse_error(where(name, line_no) + "the first point index must be 0 or 1");
      t.first_index = static_cast<std::size_t>(values[0]);
    } else if (values[0] != static_cast<double>(t.first_index + read)) {
      throw Parse_error(where(name, line_no) + "point index " + quoted(tokens_of(line)[0]) + " out of sequence");
    }
    t.coordinates.insert(t.coordinates.end(), values.begin() + 1, values.begin() + 1 + t.dimension);
    ++read;
  }
  if (read != count)
    throw Parse_error(name + ": the header announces " + std::to_string(count) + " points, the file has " +
                      std::to_string(read) + " (truncated?)");
  if (count == 0) throw Parse_error(name + ": no points");
  source.expect_no_more_rows(name, std::to_string(count) + " points");
  return t;
}

Point_table read_points_file(const std::string& path, Progress* progress) {
  Input_file file(path);
  const std::string& name = file.name();
  // Sniffed from the first bytes, which stay in the stream for the parser.
  const auto magic = file.prefix(4);
  if (magic == std::string_view(binary_points_magic, 4)) return read_binary_points(file.stream(), name, progress, file.size());
  if (magic == std::string_view(binary_simplices_magic, 4))
    throw Not_points_error(name + ": holds simplices (dewall's binary .dwsx format), not points");
  const auto head = file.prefix(4096);
  const bool vtk = is_vtk_header(head);
  const Named_format named = format_named_by(path);
  if (!vtk && named == Named_format::tetgen_ele)
    throw Not_points_error(name + ": the name says TetGen simplices (.ele), not points");
  const bool node = !vtk && (named == Named_format::tetgen_node ||
                             detail::looks_like_tetgen(head, head.size() < 4096, detail::Tetgen_file::node));
  // Mesh files by their key word, or by a name that says so (the reader then names what is wrong).
  const bool ply = !vtk && (is_ply_header(head) || named == Named_format::ply);
  const bool off = !vtk && !ply && (is_off_header(head) || named == Named_format::off);
  const bool obj = !vtk && !ply && !off && (named == Named_format::obj || (!node && is_obj_header(head)));
  const bool msh = !vtk && (is_msh_header(head) || named == Named_format::gmsh);
  const bool pcd = !vtk && !msh && !ply && (is_pcd_header(head) || named == Named_format::pcd);
  if (progress) progress->phase("reading " + name, file.size());
  const bool cgal = !vtk && named == Named_format::cgal;
  const Point_table t = vtk    ? read_vtk_points(file.stream(), name)
                        : cgal ? read_cgal_triangulation(file.stream(), name).points
                        : msh  ? read_msh_points(file.stream(), name)
                        : pcd  ? read_pcd_points(file.stream(), name)
                        : ply  ? read_ply_points(file.stream(), name)
                        : off  ? read_off_points(file.stream(), name)
                        : obj  ? read_obj_points(file.stream(), name)
                        : node ? read_node(file.stream(), name, progress)
                               : read_points(file.stream(), name, progress);
  if (progress) progress->finish();
  return t;
}

}  // namespace dewall::io
