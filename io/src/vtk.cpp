#include "dewall/io/vtk.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <string>
#include <istream>
#include <iterator>
#include <ostream>
#include <vector>

#include "dewall/io/progress.hpp"
#include "text_lines.hpp"
#include "xyz_table.hpp"

namespace dewall::io {
namespace {

using detail::where;

void check_writable(int dimension) {
  if (dimension != 2 && dimension != 3)
    throw Vtk_unsupported("VTK output supports points in 2D and 3D only; these are in dimension " +
                          std::to_string(dimension) + " (write a plain simplex list instead)");
}

/// Legacy VTK's binary sections: big-endian values, whatever the host,
/// buffered and written a chunk at a time.
class Big_endian_writer {
 public:
  explicit Big_endian_writer(std::ostream& out) : out_(out) {}
  ~Big_endian_writer() { flush(); }
  void put(std::uint64_t bits, int bytes) {
    for (int shift = 8 * (bytes - 1); shift >= 0; shift -= 8) buffer_.push_back(static_cast<char>(bits >> shift));
    if (buffer_.size() >= (std::size_t{1} << 16)) flush();
  }
  void put_double(double v) { put(std::bit_cast<std::uint64_t>(v), 8); }
  void put_int(std::uint32_t v) { put(v, 4); }
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  std::ostream& out_;
  std::string buffer_;
};

/// A cell list of `cells` cells of `k` vertices each must fit VTK's 32-bit
/// ints (legacy files, version 3.0), and so must every point index.
void check_legacy_ints(std::size_t points, std::size_t cells, std::size_t k) {
  constexpr std::size_t largest = 2147483647;
  if (points > largest || cells * (k + 1) > largest)
    throw Vtk_unsupported("VTK output: " + std::to_string(cells) + " cells of " + std::to_string(points) +
                          " points exceed legacy VTK's 32-bit ints (write .dwsx instead)");
}

void write_header_and_points(std::ostream& out, const Point_table& p, const char* title, Vtk_encoding encoding,
                             Progress* progress) {
  const bool binary = encoding == Vtk_encoding::binary;
  out << "# vtk DataFile Version 3.0\n" << title << (binary ? "\nBINARY" : "\nASCII") << "\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << p.size() << " double\n";
  const auto d = static_cast<std::size_t>(p.dimension);
  if (binary) {
    Big_endian_writer w(out);
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (std::size_t j = 0; j < d; ++j) w.put_double(p.coordinates[i * d + j]);
      if (d == 2) w.put_double(0);
      if (progress && (i & 0xffff) == 0) progress->advance_to(i);
    }
    w.flush();
    out << '\n';
    return;
  }
  std::string line;
  for (std::size_t i = 0; i < p.size(); ++i) {
    line.clear();
    for (std::size_t j = 0; j < d; ++j) {
      if (j) line += ' ';
      detail::append_shortest(line, p.coordinates[i * d + j]);
    }
    if (d == 2) line += " 0";
    line += '\n';
    out << line;
    if (progress && (i & 0xffff) == 0) progress->advance_to(i);
  }
}

/// The CELLS and CELL_TYPES sections: `count` cells of `k` vertices, the
/// vertices of cell c from `vertex(c, i)`, all of VTK type `type`;
/// `progress_base` + c is reported.
template <class Vertex>
void write_cells(std::ostream& out, std::size_t count, std::size_t k, Vertex&& vertex, std::uint32_t type,
                 Vtk_encoding encoding, Progress* progress, std::size_t progress_base) {
  out << "CELLS " << count << ' ' << count * (k + 1) << '\n';
  if (encoding == Vtk_encoding::binary) {
    Big_endian_writer w(out);
    for (std::size_t c = 0; c < count; ++c) {
      w.put_int(static_cast<std::uint32_t>(k));
      for (std::size_t i = 0; i < k; ++i) w.put_int(vertex(c, i));
      if (progress && (c & 0xffff) == 0) progress->advance_to(progress_base + c);
    }
    w.flush();
    out << "\nCELL_TYPES " << count << '\n';
    for (std::size_t c = 0; c < count; ++c) w.put_int(type);
    w.flush();
    out << '\n';
    return;
  }
  std::string line;
  for (std::size_t c = 0; c < count; ++c) {
    line.assign(std::to_string(k));
    for (std::size_t i = 0; i < k; ++i) {
      line += ' ';
      line += std::to_string(vertex(c, i));
    }
    line += '\n';
    out << line;
    if (progress && (c & 0xffff) == 0) progress->advance_to(progress_base + c);
  }
  out << "CELL_TYPES " << count << '\n';
  const std::string type_line = std::to_string(type) + '\n';
  for (std::size_t c = 0; c < count; ++c) out << type_line;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> tokens;
  detail::for_each_token(line, [&](std::string_view token) { tokens.emplace_back(token); });
  return tokens;
}

/// Reads `n` big-endian values of `Stored` (VTK's binary legacy files are
/// big-endian whatever the host) into `out`, converted to Value; `section`
/// says in messages what announced them ("the POINTS section announces 5 points").
template <class Stored, class Value>
void read_big_endian(std::istream& in, std::size_t n, std::vector<Value>& out, const std::string& name,
                     const std::string& section) {
  // Read in bounded chunks: the header's count is not trusted with an allocation
  // before the bytes are there (a 100-byte file may announce 2^40 points: fuzz
  // finding f2e10cdf).
  constexpr std::size_t chunk_values = std::size_t{1} << 16;
  std::vector<unsigned char> bytes;
  out.clear();
  while (out.size() < n) {
    bytes.resize(std::min(chunk_values, n - out.size()) * sizeof(Stored));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (static_cast<std::size_t>(in.gcount()) != bytes.size())
      throw Parse_error(name + ": truncated: " + section + " (" + std::to_string(n * sizeof(Stored)) +
                        " bytes of binary data), the file has " +
                        std::to_string(out.size() * sizeof(Stored) + static_cast<std::size_t>(in.gcount())));
    for (std::size_t i = 0; i < bytes.size(); i += sizeof(Stored)) {
      unsigned char b[sizeof(Stored)];
      std::memcpy(b, &bytes[i], sizeof(Stored));
      if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + sizeof(Stored));
      Stored v;
      std::memcpy(&v, b, sizeof(Stored));
      out.push_back(static_cast<Value>(v));
    }
  }
}

/// True when `token` is a keyword that may start the section after POINTS in
/// a legacy file (VTK's "File Formats": the dataset's cells, then its
/// attributes), in any case, as VTK's reader compares them.
bool is_section_keyword(const std::string& token) {
  static constexpr const char* keywords[] = {"cells",           "cell_types", "vertices",  "lines", "polygons",
                                             "triangle_strips", "point_data", "cell_data", "field", "metadata"};
  const std::string t = lower(token);
  return std::any_of(std::begin(keywords), std::end(keywords), [&](const char* k) { return t == k; });
}

/// "N points (M coordinates)", what a POINTS header announces.
std::string announced(unsigned long long count) {
  return std::to_string(count) + " points (" + std::to_string(count * 3) + " coordinates)";
}

/// After the binary data of the POINTS section: blanks, then the end of the
/// file or the next section's keyword. Binary data carries no separators, so
/// this is where a wrong count shows: with fewer points announced than stored
/// the next bytes are coordinates; with more, the reading ran on into the next
/// section and stops in its middle (or at the end of the file: truncated).
/// Returns the keyword found ("" at the end of the file).
std::string expect_end_of_binary_points(std::istream& in, const std::string& name, std::size_t points_line,
                                        unsigned long long count) {
  using traits = std::char_traits<char>;
  auto c = in.peek();
  while (c != traits::eof() && std::isspace(c)) {
    in.get();
    c = in.peek();
  }
  if (c == traits::eof()) return {};
  std::string token;
  while (token.size() < 32 && (c = in.peek()) != traits::eof() && !std::isspace(c)) token += static_cast<char>(in.get());
  if (is_section_keyword(token)) return token;
  // (The bytes found are binary: not quoted.)
  throw Parse_error(where(name, points_line) + "count mismatch: the POINTS section announces " + announced(count) +
                    ", but its binary data is followed by neither the end of the file nor a section keyword "
                    "(CELLS, POINT_DATA, …): the file holds more or fewer points than announced");
}

}  // namespace

bool is_vtk_header(std::string_view head) {
  const std::string first_line(head.substr(0, head.find_first_of("\r\n")));
  return lower(first_line).rfind("# vtk datafile", 0) == 0;
}

void write_vtk_triangulation(std::ostream& out, const Point_table& points, const Simplex_table& t,
                             Progress* progress, Vtk_encoding encoding) {
  check_writable(points.dimension);
  if (t.vertices_per_simplex != points.dimension + 1)
    throw Vtk_unsupported("VTK output: simplices of " + std::to_string(t.vertices_per_simplex) +
                          " vertices do not match points of dimension " + std::to_string(points.dimension));
  const auto k = static_cast<std::size_t>(t.vertices_per_simplex);
  check_legacy_ints(points.size(), t.size(), k);
  if (progress) progress->phase("writing VTK", points.size() + t.size());
  write_header_and_points(out, points, "dewall Delaunay triangulation", encoding, progress);
  const std::uint32_t type = points.dimension == 2 ? 5 : 10;  // VTK_TRIANGLE, VTK_TETRA
  write_cells(out, t.size(), k, [&](std::size_t c, std::size_t i) { return t.indices[c * k + i]; }, type, encoding,
              progress, points.size());
  if (progress) progress->finish();
}

void write_vtk_points(std::ostream& out, const Point_table& points, Progress* progress, Vtk_encoding encoding) {
  check_writable(points.dimension);
  check_legacy_ints(points.size(), points.size(), 1);
  if (progress) progress->phase("writing VTK", 2 * points.size());
  write_header_and_points(out, points, "dewall points", encoding, progress);
  // One VTK_VERTEX (1) per point.
  write_cells(out, points.size(), 1, [](std::size_t c, std::size_t) { return static_cast<std::uint32_t>(c); }, 1,
              encoding, progress, points.size());
  if (progress) progress->finish();
}

namespace {

/// The POINTS section of a legacy file, read from its first line on: three
/// coordinates a point, and the header line of the section after it (its
/// tokens; none at the end of the file).
struct Points_section {
  std::vector<double> xyz;
  bool binary = false;
  std::vector<std::string> next_header;
};

Points_section read_points_section(std::istream& in, detail::Line_source& source, const std::string& name) {
  std::string line;
  std::size_t line_no = 0;
  auto next_line = [&] {
    if (!source.next(line)) return false;
    line_no = source.number();
    return true;
  };
  if (!next_line() || !is_vtk_header(line))
    throw Parse_error(where(name, 1) + "not a legacy VTK file (expected '# vtk DataFile Version …')");
  if (!next_line()) throw Parse_error(name + ": truncated VTK header (no title line)");
  if (!next_line()) throw Parse_error(name + ": truncated VTK header (no ASCII/BINARY line)");
  const auto encoding = split(line);
  const std::string mode = encoding.empty() ? "" : lower(encoding[0]);
  if (mode != "ascii" && mode != "binary")
    throw Parse_error(where(name, line_no) + "expected ASCII or BINARY, found " + quoted(line));

  std::vector<std::string> tokens;
  bool found = false;
  while (!found && next_line()) {
    tokens = split(line);
    found = !tokens.empty() && lower(tokens[0]) == "points";
  }
  if (!found) throw Parse_error(name + ": no POINTS section (only datasets with explicit points can be read)");
  const std::size_t points_line = line_no;
  if (tokens.size() != 3) throw Parse_error(where(name, line_no) + "expected 'POINTS <count> <type>'");
  char* end = nullptr;
  errno = 0;
  const unsigned long long count = std::strtoull(tokens[1].c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE || tokens[1][0] == '-' || count > (1ull << 40))
    throw Parse_error(where(name, line_no) + "invalid point count " + quoted(tokens[1]));
  if (count == 0) throw Parse_error(where(name, line_no) + "no points");
  const std::string type = lower(tokens[2]);
  const std::size_t n = static_cast<std::size_t>(count) * 3;

  Points_section section;
  auto& xyz = section.xyz;
  section.binary = mode == "binary";
  if (section.binary) {
    const std::string announces = "the POINTS section announces " + announced(count);
    if (type == "double") read_big_endian<double>(in, n, xyz, name, announces);
    else if (type == "float") read_big_endian<float>(in, n, xyz, name, announces);
    else throw Parse_error(where(name, line_no) + "binary POINTS of type " + quoted(tokens[2]) + " are not supported (float, double)");
    const std::string keyword = expect_end_of_binary_points(in, name, points_line, count);
    if (!keyword.empty()) {
      std::string rest;
      std::getline(in, rest);
      section.next_header = split(keyword + " " + rest);
    }
  } else {
    xyz.reserve(std::min<std::size_t>(n, std::size_t{1} << 16));  // not trusting the count (f2e10cdf)
    // The section ends with its last coordinate: more on that line, or a
    // further line of numbers, means more points than the header announces.
    const auto too_many = [&] {
      return Parse_error(where(name, line_no) + "more coordinates than the POINTS header announces (" +
                         std::to_string(count) + " points)");
    };
    // A section keyword before the last coordinate: fewer points than announced.
    const auto too_few = [&](const std::string& keyword) {
      return Parse_error(where(name, points_line) + "truncated: the POINTS section announces " + announced(count) +
                         ", the file has " + std::to_string(xyz.size()) + " before " + quoted(keyword) + " on line " +
                         std::to_string(line_no));
    };
    while (xyz.size() < n && next_line()) {
      for (const auto& token : split(line)) {
        if (xyz.size() == n) throw too_many();
        if (is_section_keyword(token)) throw too_few(token);
        xyz.push_back(detail::parse_double(token, name, line_no));
      }
    }
    if (xyz.size() == n) {
      bool more = next_line();
      while (more && split(line).empty()) more = next_line();
      if (more && detail::is_number(split(line).front())) throw too_many();
      if (more) section.next_header = split(line);
    }
    if (xyz.size() != n)
      throw Parse_error(where(name, points_line) + "truncated: the POINTS section announces " + announced(count) +
                        ", the file has " + std::to_string(xyz.size()));
  }
  return section;
}

/// A count of a section header ("CELLS <count> <size>"), at most 2^40.
std::size_t section_count(const std::string& token, const std::string& name, const char* what) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(token.c_str(), &end, 10);
  if (token.empty() || *end != '\0' || errno == ERANGE || token[0] == '-' || v > (1ull << 40))
    throw Parse_error(name + ": invalid " + what + " " + quoted(token) + " in the CELLS header");
  return static_cast<std::size_t>(v);
}

}  // namespace

Point_table read_vtk_points(std::istream& in, const std::string& name) {
  detail::Line_source source(in);
  return detail::table_from_xyz(read_points_section(in, source, name).xyz);
}

Simplex_table read_vtk_simplices(std::istream& in, const std::string& name, int dimension) {
  detail::Line_source source(in);
  const Points_section points = read_points_section(in, source, name);
  const auto& header = points.next_header;
  if (header.empty() || lower(header[0]) != "cells")
    throw Parse_error(name + ": no CELLS section after the POINTS: the file holds points, not simplices");
  if (header.size() != 3) throw Parse_error(name + ": expected 'CELLS <count> <size>' after the POINTS");
  const std::size_t count = section_count(header[1], name, "cell count");
  const std::size_t size = section_count(header[2], name, "size");
  const auto k = static_cast<std::size_t>(dimension + 1);
  // Each cell is its vertex count and its vertices: simplices of E^D all take k + 1 values.
  if (size != count * (k + 1)) {
    const std::string kind = count && size % count == 0 && size / count >= 1
                                 ? "cells of " + std::to_string(size / count - 1) + " vertices"
                                 : "cells of mixed sizes";
    throw Parse_error(name + ": the CELLS section holds " + kind + ", not simplices of dimension " +
                      std::to_string(dimension) + " (" + std::to_string(k) + " vertices each)");
  }
  std::vector<std::uint32_t> values;
  if (points.binary) {
    read_big_endian<std::uint32_t>(in, size, values, name,
                                   "the CELLS section announces " + std::to_string(count) + " cells");
  } else {
    values.reserve(std::min<std::size_t>(size, std::size_t{1} << 16));  // not trusting the count
    std::string line;
    while (values.size() < size && source.next(line))
      detail::for_each_token(line, [&](std::string_view token) {
        if (values.size() == size || is_section_keyword(std::string(token)))
          throw Parse_error(where(name, source.number()) + "the CELLS section does not hold the " + std::to_string(size) +
                            " values its header announces");
        const double v = detail::parse_double(token, name, source.number());
        if (!(v >= 0 && v <= 4294967295.0 && v == std::floor(v)))
          throw Parse_error(where(name, source.number()) + quoted(token) + " is not a vertex index (a non-negative integer)");
        values.push_back(static_cast<std::uint32_t>(v));
      });
    if (values.size() != size)
      throw Parse_error(name + ": truncated: the CELLS section announces " + std::to_string(size) + " values, the file has " +
                        std::to_string(values.size()));
  }
  Simplex_table t;
  t.vertices_per_simplex = dimension + 1;
  t.indices.reserve(count * k);
  for (std::size_t c = 0; c < count; ++c) {
    const std::uint32_t* cell = &values[c * (k + 1)];
    if (cell[0] != k)
      throw Parse_error(name + ": cell " + std::to_string(c) + " has " + std::to_string(cell[0]) +
                        " vertices, not the " + std::to_string(k) + " of a simplex of dimension " + std::to_string(dimension));
    t.indices.insert(t.indices.end(), cell + 1, cell + 1 + k);
  }
  return t;
}

}  // namespace dewall::io
