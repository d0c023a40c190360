// Writing files: simplices as the plain list (one simplex per line, zero-based
// input indices separated by single spaces), TetGen .ele, binary (.dwsx,
// binary_simplices.hpp), legacy VTK or gmsh (chosen by extension), and point
// sets as plain text, binary (.dwpt), TetGen .node or VTK. Every file
// goes through io::Output_file (output_file.hpp): a regular file is written to
// an exclusive temporary and renamed when complete; devices, FIFOs and
// standard output are written directly.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_rows.hpp"

namespace dewall::io {

class Progress;
class Output_file;

/// Simplices as rows of `vertices_per_simplex` indices, stored row after row.
struct Simplex_table {
  int vertices_per_simplex = 0;
  std::vector<std::uint32_t> indices;
  std::size_t size() const {
    return vertices_per_simplex ? indices.size() / static_cast<std::size_t>(vertices_per_simplex) : 0;
  }
};

/// `progress`, when given, receives the number of simplices written.
void write_plain(std::ostream& out, const Simplex_table& t, Progress* progress = nullptr);
/// TetGen .ele: "<count> <vertices per simplex> 0", then "<i> <v0> … <vD>", with
/// vertex numbers shifted by `first_index` (the numbering of the .node file).
void write_ele(std::ostream& out, const Simplex_table& t, std::size_t first_index);

/// Writes to `path` ("-" = standard output) through io::Output_file: the
/// binary format for ".dwsx", TetGen's for ".ele", the plain list otherwise
/// (extensions in any case).
/// \throws Write_error when the file cannot be written, or its name says a
/// format which holds no simplices (format_names.hpp), before anything is written.
void write_simplices_file(const std::string& path, const Simplex_table& t, std::size_t first_index,
                          Progress* progress = nullptr);

/// As write_simplices_file (numbered from points.first_index in .ele), and a
/// ".vtk" extension writes legacy VTK (vtk.hpp), ".msh" gmsh's format
/// (mesh_formats.hpp), which need the points too. \throws as
/// check_triangulation_output, before anything is written.
void write_triangulation_file(const std::string& path, const Point_table& points, const Simplex_table& t,
                              Progress* progress = nullptr);

/// True when the triangulation file `path` holds the points too (.vtk, .msh).
bool triangulation_needs_points(const std::string& path);

/// \throws Write_error for a name that says a format without simplices
/// (format_names.hpp), Vtk_unsupported for VTK or gmsh output of points of
/// a dimension other than 2 and 3. Commands call it before any work.
void check_triangulation_output(const std::string& path, int dimension);

/// True when `path` names a legacy VTK file (".vtk", any case).
bool is_vtk_path(const std::string& path);

/// True when simplices can be written to `path` as they come: the plain list
/// and .dwsx, not .ele, .vtk and .msh (whose headers start with the count).
bool can_stream_simplices(const std::string& path);

/// Simplices written to a file as they come (dewall triangulate --stream),
/// through io::Output_file: the plain list, or the binary format for ".dwsx",
/// whose count is written when commit() knows it; on a target that cannot
/// seek (a pipe, a device) it stays "unknown" (binary_simplices.hpp), and
/// readers take the simplices up to the end.
class Simplex_stream_writer {
 public:
  /// \throws Write_error when `path` cannot be opened; std::invalid_argument
  /// when !can_stream_simplices(path).
  Simplex_stream_writer(const std::string& path, int vertices_per_simplex);
  ~Simplex_stream_writer();
  /// Writes whole rows of vertices_per_simplex indices.
  /// \throws Write_error as soon as a write fails.
  void write(std::span<const std::uint32_t> indices);
  /// Completes the file (Output_file::commit). \throws Write_error
  void commit();
  std::size_t count() const { return count_; }

 private:
  std::unique_ptr<Output_file> file_;
  Simplex_format format_;
  std::size_t k_;
  std::uint64_t count_ = 0;
  std::string text_;
};

/// One point per line, coordinates separated by single spaces, each in the
/// shortest form that reads back to the same double (the round trip is exact).
void write_points_text(std::ostream& out, const Point_table& t, Progress* progress = nullptr);

/// TetGen .node: "<count> <dimension> 0 0", then "<i> <coordinates>", numbered
/// from t.first_index, coordinates in the shortest exact form.
void write_node(std::ostream& out, const Point_table& t);

/// Writes points to `path` ("-" = standard output) through io::Output_file: the binary format
/// for ".dwpt", TetGen's for ".node", legacy VTK for ".vtk", plain text otherwise
/// (extensions in any case). \throws Write_error for a name that says a format
/// which holds no points (format_names.hpp), before anything is written.
void write_points_file(const std::string& path, const Point_table& t, Progress* progress = nullptr);

}  // namespace dewall::io
