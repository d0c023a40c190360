#include "dewall/io/simplex_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string_view>

#include "dewall/io/binary_points.hpp"
#include "dewall/io/binary_simplices.hpp"
#include "dewall/io/format_names.hpp"
#include "dewall/io/mesh_formats.hpp"
#include "dewall/io/vtk.hpp"
#include "dewall/io/dimensions.hpp"
#include "dewall/io/input_file.hpp"
#include "tetgen_header.hpp"
#include "text_lines.hpp"

namespace dewall::io {
namespace {

using detail::where;

/// The non-negative integers of one line (comment removed). Indices must fit in
/// 32 bits, the width simplices are stored in; anything else is a Parse_error.
std::vector<std::uint64_t> parse_indices(std::string_view line, const std::string& name, std::size_t line_no) {
  std::vector<std::uint64_t> values;
  detail::for_each_token(detail::without_comment(line), [&](std::string_view token) {
    std::uint64_t v = 0;
    for (char c : token) {
      if (!std::isdigit(static_cast<unsigned char>(c)))
        throw Parse_error(where(name, line_no) + quoted(token) + " is not a vertex index (a non-negative integer)");
      v = v * 10 + static_cast<std::uint64_t>(c - '0');
      if (v > UINT32_MAX) throw Parse_error(where(name, line_no) + quoted(token) + " is too large for a vertex index");
    }
    values.push_back(v);
  });
  return values;
}

/// The whole numbers of an .ele header: a count, the vertices per simplex,
/// the attributes; messages call them what they are, not vertex indices.
std::vector<std::uint64_t> parse_header(std::string_view line, const std::string& name, std::size_t line_no) {
  std::vector<std::uint64_t> values;
  detail::for_each_token(detail::without_comment(line), [&](std::string_view token) {
    const char* what = values.empty() ? "simplex count " : values.size() == 1 ? "vertices per simplex " : "header value ";
    std::uint64_t v = 0;
    for (char c : token) {
      if (!std::isdigit(static_cast<unsigned char>(c)))
        throw Parse_error(where(name, line_no) + what + quoted(token) + " is not a non-negative integer");
      v = v * 10 + static_cast<std::uint64_t>(c - '0');
      if (v > UINT32_MAX) throw Parse_error(where(name, line_no) + what + quoted(token) + " is too large (at most 2^32 - 1)");
    }
    values.push_back(v);
  });
  return values;
}

void check_dimension(int dimension, const std::string& name) {
  if (!is_supported_dimension(dimension))
    throw Parse_error(name + ": dimension " + std::to_string(dimension) + " is not supported (" + dimension_range() + ")");
}

void add_row(Simplex_list& list, const std::vector<std::uint64_t>& v, std::size_t from, std::size_t shift,
             const std::string& name, std::size_t line_no) {
  const auto k = static_cast<std::size_t>(list.table.vertices_per_simplex);
  for (std::size_t i = from; i < from + k; ++i) {
    if (v[i] < shift)
      throw Parse_error(where(name, line_no) + "vertex number " + std::to_string(v[i]) + " is below the first point number " +
                        std::to_string(shift));
    list.table.indices.push_back(static_cast<std::uint32_t>(v[i] - shift));
  }
  list.lines.push_back(line_no);
}

}  // namespace

Simplex_list read_simplices(std::istream& in, const std::string& name, int dimension) {
  check_dimension(dimension, name);
  Simplex_list list;
  list.format = "plain";
  list.table.vertices_per_simplex = dimension + 1;
  const auto k = static_cast<std::size_t>(dimension + 1);
  detail::Line_source source(in);
  std::string line;
  std::size_t expected = 0;
  bool first = true;
  while (source.next(line)) {
    const std::size_t line_no = source.number();
    const auto v = parse_indices(line, name, line_no);
    if (v.empty()) continue;
    if (first && v.size() == 1) {  // a lone count: Qhull's header (a plain row has D + 1 ≥ 3 values)
      list.format = "qhull";
      expected = static_cast<std::size_t>(v[0]);
      first = false;
      continue;
    }
    first = false;
    if (v.size() != k) {
      if (list.format == "qhull" && v.size() > k)
        throw Parse_error(where(name, line_no) + "a non-simplicial facet with " + std::to_string(v.size()) +
                          " vertices (cospherical points; run qdelaunay with the Qt option)");
      throw Parse_error(where(name, line_no) + "expected " + std::to_string(k) + " vertex indices, found " +
                        std::to_string(v.size()));
    }
    add_row(list, v, 0, 0, name, line_no);
  }
  if (list.format == "qhull" && list.table.size() > expected)
    throw Parse_error(where(name, list.lines[expected]) + "more rows than the header announces (" +
                      std::to_string(expected) + " facets)");
  if (list.format == "qhull" && list.table.size() != expected)
    throw Parse_error(name + ": the Qhull header announces " + std::to_string(expected) + " facets, the file has " +
                      std::to_string(list.table.size()) + " (truncated?)");
  return list;
}

Simplex_list read_ele(std::istream& in, const std::string& name, int dimension, std::size_t first_index) {
  check_dimension(dimension, name);
  Simplex_list list;
  list.format = "tetgen";
  list.table.vertices_per_simplex = dimension + 1;
  const auto k = static_cast<std::size_t>(dimension + 1);
  detail::Line_source source(in);
  std::string line;
  std::vector<std::uint64_t> header;
  while (header.empty() && source.next(line)) header = parse_header(line, name, source.number());
  const std::size_t line_no = source.number();
  if (header.size() < 2)
    throw Parse_error(where(name, line_no) + "expected an .ele header '<count> <vertices per simplex> <#attributes>'");
  if (header[1] != k)
    throw Parse_error(where(name, line_no) + "the header says " + std::to_string(header[1]) +
                      " vertices per simplex; the points need " + std::to_string(k));
  const std::size_t count = static_cast<std::size_t>(header[0]);
  const std::size_t width = 1 + k + (header.size() > 2 ? static_cast<std::size_t>(header[2]) : 0);
  while (list.table.size() < count && source.next(line)) {
    const std::size_t row_no = source.number();
    // Attributes may be real numbers: parse only the index and the vertices strictly.
    std::string prefix;
    std::size_t tokens = 0;
    detail::for_each_token(detail::without_comment(line), [&](std::string_view token) {
      if (tokens < 1 + k) prefix += std::string(token) + " ";
      ++tokens;
    });
    if (tokens == 0) continue;
    if (tokens != width)
      throw Parse_error(where(name, row_no) + "expected " + std::to_string(width) + " values, found " + std::to_string(tokens));
    const auto v = parse_indices(prefix, name, row_no);
    add_row(list, v, 1, first_index, name, row_no);
  }
  if (list.table.size() != count)
    throw Parse_error(name + ": the header announces " + std::to_string(count) + " simplices, the file has " +
                      std::to_string(list.table.size()) + " (truncated?)");
  source.expect_no_more_rows(name, std::to_string(count) + " simplices");
  return list;
}

namespace {

Simplex_list read_simplices_from(Input_file& file, const std::string& path, int dimension, std::size_t first_index) {
  const std::string& name = file.name();
  const auto magic = file.prefix(4);
  if (magic == std::string_view(binary_simplices_magic, 4)) return read_binary_simplices(file.stream(), name, dimension, file.size());
  if (magic == std::string_view(binary_points_magic, 4))
    throw Not_simplices_error(name + ": holds points (dewall's binary .dwpt format), not simplices");
  const auto head = file.prefix(4096);
  if (is_vtk_header(head)) {
    Simplex_list list;
    list.format = "vtk";
    list.table = read_vtk_simplices(file.stream(), name, dimension);
    return list;
  }
  const Named_format named = format_named_by(path);
  if (is_msh_header(head) || named == Named_format::gmsh) {
    Simplex_list list;
    list.format = "gmsh";
    list.table = read_msh_simplices(file.stream(), name, dimension);
    return list;
  }
  if (named == Named_format::cgal) {
    Simplex_list list;
    list.format = "cgal";
    list.table = read_cgal_triangulation(file.stream(), name).cells;
    if (list.table.vertices_per_simplex != dimension + 1)
      throw Parse_error(name + ": a CGAL triangulation of dimension " + std::to_string(list.table.vertices_per_simplex - 1) +
                        ", the points are of dimension " + std::to_string(dimension));
    return list;
  }
  if (named == Named_format::tetgen_node)
    throw Not_simplices_error(name + ": the name says TetGen points (.node), not simplices");
  const bool ele = named == Named_format::tetgen_ele ||
                   detail::looks_like_tetgen(head, head.size() < 4096, detail::Tetgen_file::ele);
  return ele ? read_ele(file.stream(), name, dimension, first_index) : read_simplices(file.stream(), name, dimension);
}

}  // namespace

Simplex_list read_simplices_file(const std::string& path, int dimension, std::size_t first_index) {
  Input_file file(path);
  return read_simplices_from(file, path, dimension, first_index);
}

Simplex_file_reader::Simplex_file_reader(const std::string& path, int dimension, std::size_t first_index)
    : file_(std::make_unique<Input_file>(path)), k_(static_cast<std::size_t>(dimension + 1)) {
  if (file_->prefix(4) == std::string_view(binary_simplices_magic, 4)) {
    binary_ = std::make_unique<Binary_simplex_reader>(file_->stream(), file_->name(), dimension, file_->size());
    list_.format = "binary";
  } else {
    list_ = read_simplices_from(*file_, path, dimension, first_index);
    file_.reset();
  }
}

Simplex_file_reader::~Simplex_file_reader() = default;

std::size_t Simplex_file_reader::read(std::span<std::uint32_t> indices) {
  if (binary_) return binary_->read(indices);
  const std::size_t rows = std::min(indices.size() / k_, list_.table.size() - next_);
  std::copy_n(list_.table.indices.begin() + static_cast<std::ptrdiff_t>(next_ * k_), rows * k_, indices.begin());
  next_ += rows;
  return rows;
}

std::uint64_t Simplex_file_reader::remaining() const {
  if (binary_) return binary_->sized() ? binary_->count() - binary_->rows_read() : binary_simplices_unknown_count;
  return list_.table.size() - next_;
}

}  // namespace dewall::io
