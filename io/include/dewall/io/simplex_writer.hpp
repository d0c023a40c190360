// Writing files: simplices as the plain list (one simplex per line, zero-based
// input indices separated by single spaces), TetGen .ele, binary (.dwsx,
// binary_simplices.hpp) or legacy VTK (chosen by extension), and point sets as plain text, binary (.dwpt) or VTK. Every file
// goes through io::Output_file (output_file.hpp): a regular file is written to
// an exclusive temporary and renamed when complete; devices, FIFOs and
// standard output are written directly.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "dewall/io/point_reader.hpp"

namespace dewall::io {

class Progress;

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
/// binary format for ".dwsx", TetGen's for ".ele", the plain list otherwise.
/// \throws Write_error when the file cannot be written.
void write_simplices_file(const std::string& path, const Simplex_table& t, std::size_t first_index,
                          Progress* progress = nullptr);

/// As write_simplices_file (numbered from points.first_index in .ele), and a
/// ".vtk" extension writes legacy VTK, which needs the points too (see vtk.hpp). \throws Vtk_unsupported for VTK in
/// dimension > 3 (before anything is written).
void write_triangulation_file(const std::string& path, const Point_table& points, const Simplex_table& t,
                              Progress* progress = nullptr);

/// True when `path` names a legacy VTK file (".vtk", any case).
bool is_vtk_path(const std::string& path);

/// One point per line, coordinates separated by single spaces, each in the
/// shortest form that reads back to the same double (the round trip is exact).
void write_points_text(std::ostream& out, const Point_table& t, Progress* progress = nullptr);

/// Writes points to `path` ("-" = standard output) through io::Output_file: the binary format
/// for ".dwpt", legacy VTK for ".vtk", plain text otherwise.
void write_points_file(const std::string& path, const Point_table& t, Progress* progress = nullptr);

}  // namespace dewall::io
