#include "dewall/io/point_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "dewall/io/binary_points.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/vtk.hpp"
#include "text_lines.hpp"

namespace dewall::io {
namespace {

using detail::where;

/// Splits a line into its numbers (comments removed). Throws on a token that
/// is not a complete decimal number; NaN and infinity are accepted here and
/// rejected by the triangulator with the point's index.
std::vector<double> parse_numbers(std::string_view line, const std::string& name, std::size_t line_no) {
  std::vector<double> values;
  detail::for_each_token(detail::without_comment(line), [&](std::string_view token_view) {
    const std::string token(token_view);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size())
      throw Parse_error(where(name, line_no) + "'" + token + "' is not a number");
    if (errno == ERANGE && std::isinf(v))
      throw Parse_error(where(name, line_no) + "'" + token + "' is out of the range of double");
    values.push_back(v);
  });
  return values;
}

bool is_count(double v) { return v >= 0 && v == std::floor(v) && v < 1e15; }

void check_dimension(int d, const std::string& name, std::size_t line_no) {
  if (d < 2 || d > 6)
    throw Parse_error(where(name, line_no) + "dimension " + std::to_string(d) + " is not supported (2 to 6)");
}

}  // namespace

/// The leading integer of an rbox header line ("3 rbox 1000 D3": rbox appends
/// its command line as a comment without '#'), or -1.
static long rbox_leading_integer(const std::string& line) {
  std::istringstream ss(line.substr(0, line.find('#')));
  std::string token;
  if (!(ss >> token)) return -1;
  char* end = nullptr;
  const long v = std::strtol(token.c_str(), &end, 10);
  return end == token.c_str() + token.size() && v >= 0 ? v : -1;
}

Point_table read_points(std::istream& in, const std::string& name, Progress* progress) {
  Point_table t;
  std::vector<std::pair<std::size_t, std::string>> lines;
  {
    std::string line;
    std::size_t line_no = 0;
    std::uint64_t bytes = 0;
    while (std::getline(in, line)) {
      ++line_no;
      bytes += line.size() + 1;
      if (progress && (line_no & 0xffff) == 0) progress->advance_to(bytes);
      const auto content = line.substr(0, line.find('#'));
      if (content.find_first_not_of(" \t\r\v\f") != std::string::npos) lines.emplace_back(line_no, line);
    }
  }
  if (in.bad()) throw Parse_error(name + ": read error");
  if (lines.empty()) throw Parse_error(name + ": no points");
  std::size_t first = 0;
  std::size_t expected_count = 0;
  // rbox: a dimension (maybe followed by a comment), a lone count, then the rows.
  const bool rbox = lines.size() >= 2 && rbox_leading_integer(lines[0].second) >= 0 && [&] {
    const auto second = parse_numbers(lines[1].second, name, lines[1].first);
    return second.size() == 1 && is_count(second[0]) &&
           (lines.size() == 2 || parse_numbers(lines[2].second, name, lines[2].first).size() ==
                                     static_cast<std::size_t>(rbox_leading_integer(lines[0].second)));
  }();
  if (rbox) {
    t.dimension = static_cast<int>(rbox_leading_integer(lines[0].second));
    check_dimension(t.dimension, name, lines[0].first);
    expected_count = static_cast<std::size_t>(parse_numbers(lines[1].second, name, lines[1].first)[0]);
    first = 2;
  } else {
    t.dimension = static_cast<int>(parse_numbers(lines[0].second, name, lines[0].first).size());
    check_dimension(t.dimension, name, lines[0].first);
  }
  for (std::size_t r = first; r < lines.size(); ++r) {
    const auto values = parse_numbers(lines[r].second, name, lines[r].first);
    if (values.size() != static_cast<std::size_t>(t.dimension))
      throw Parse_error(where(name, lines[r].first) + "expected " + std::to_string(t.dimension) +
                        " coordinates, found " + std::to_string(values.size()));
    t.coordinates.insert(t.coordinates.end(), values.begin(), values.end());
  }
  if (rbox && t.size() != expected_count)
    throw Parse_error(name + ": the header announces " + std::to_string(expected_count) + " points, the file has " +
                      std::to_string(t.size()) + " (truncated?)");
  if (t.size() == 0) throw Parse_error(name + ": no points");
  return t;
}

Point_table read_node(std::istream& in, const std::string& name, Progress* progress) {
  Point_table t;
  std::string line;
  std::size_t line_no = 0;
  std::uint64_t bytes = 0;
  std::vector<double> header;
  while (header.empty() && std::getline(in, line)) header = parse_numbers(line, name, ++line_no);
  // Every header value is checked to be a count before it is converted: a
  // double outside the target type's range has no defined conversion (fuzz_parse).
  if (header.size() < 2 || !std::all_of(header.begin(), header.begin() + std::min<std::size_t>(header.size(), 4), is_count))
    throw Parse_error(where(name, line_no) + "expected a .node header '<count> <dimension> <#attributes> <markers>'");
  const auto count = static_cast<std::size_t>(header[0]);
  if (header[1] > 6)
    throw Parse_error(where(name, line_no) + "dimension " + std::to_string(static_cast<long long>(header[1])) +
                      " is not supported (2 to 6)");
  t.dimension = static_cast<int>(header[1]);
  check_dimension(t.dimension, name, line_no);
  const std::size_t attributes = header.size() > 2 ? static_cast<std::size_t>(header[2]) : 0;
  const std::size_t markers = header.size() > 3 ? static_cast<std::size_t>(header[3]) : 0;
  const std::size_t width = 1 + static_cast<std::size_t>(t.dimension) + attributes + markers;
  std::size_t read = 0;
  while (read < count && std::getline(in, line)) {
    bytes += line.size() + 1;
    if (progress && (line_no & 0xffff) == 0) progress->advance_to(bytes);
    const auto values = parse_numbers(line, name, ++line_no);
    if (values.empty()) continue;
    if (values.size() != width)
      throw Parse_error(where(name, line_no) + "expected " + std::to_string(width) + " values, found " +
                        std::to_string(values.size()));
    const double expected_index = read == 0 ? values[0] : static_cast<double>(t.first_index + read);
    if (read == 0) {
      if (values[0] != 0 && values[0] != 1) throw Parse_error(where(name, line_no) + "the first point index must be 0 or 1");
      t.first_index = static_cast<std::size_t>(values[0]);
    } else if (values[0] != expected_index) {
      throw Parse_error(where(name, line_no) + "point index " + std::to_string(values[0]) + " out of sequence");
    }
    t.coordinates.insert(t.coordinates.end(), values.begin() + 1, values.begin() + 1 + t.dimension);
    ++read;
  }
  if (read != count)
    throw Parse_error(name + ": the header announces " + std::to_string(count) + " points, the file has " +
                      std::to_string(read) + " (truncated?)");
  if (count == 0) throw Parse_error(name + ": no points");
  return t;
}

Point_table read_points_file(const std::string& path, Progress* progress) {
  const bool node = path.size() > 5 && path.compare(path.size() - 5, 5, ".node") == 0;
  if (path == "-") {
    const std::string name = "<stdin>";
    if (progress) progress->phase("reading " + name);
    Point_table t;
    // A pipe cannot be rewound: the binary format is recognised by its first
    // byte ('D' never starts a text point file that parses), and a possible VTK
    // file (first byte '#') is read into memory so its first line can be examined.
    const int first = std::cin.peek();
    if (first == binary_points_magic[0]) {
      t = read_binary_points(std::cin, name, progress);
    } else if (first == '#') {
      std::ostringstream all;
      all << std::cin.rdbuf();
      std::istringstream in(all.str());
      std::string first_line;
      std::getline(in, first_line);
      in.seekg(0);
      t = is_vtk_header(first_line) ? read_vtk_points(in, name) : read_points(in, name, progress);
    } else {
      t = read_points(std::cin, name, progress);
    }
    if (progress) progress->finish();
    return t;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Parse_error(path + ": cannot open file");
  char magic[4] = {};
  in.read(magic, 4);
  const bool binary = in.gcount() == 4 && std::equal(magic, magic + 4, binary_points_magic);
  in.clear();
  in.seekg(0);
  if (binary) return read_binary_points(in, path, progress);
  std::string first_line;
  std::getline(in, first_line);
  in.clear();
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(0, in.tellg()));
  in.seekg(0);
  Point_table t;
  if (progress) progress->phase("reading " + path, size);
  if (is_vtk_header(first_line)) t = read_vtk_points(in, path);
  else t = node ? read_node(in, path, progress) : read_points(in, path, progress);
  if (progress) progress->finish();
  return t;
}

}  // namespace dewall::io
