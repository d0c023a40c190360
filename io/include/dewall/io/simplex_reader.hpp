// Reading simplex lists: the plain list, TetGen .ele, Qhull's `qdelaunay i`,
// the binary format (binary_simplices.hpp, recognised by its magic bytes) and
// the cells of legacy VTK files (vtk.hpp, recognised by their first line) and
// the triangles or tetrahedra of gmsh meshes (mesh_formats.hpp).
//
// Plain list: one simplex per line, its D + 1 zero-based point indices
// separated by whitespace, any vertex order, any line order; `#` starts a
// comment, blank lines are skipped. Qhull (`qdelaunay i`, `qdelaunay Qt i`):
// a first line with the number of facets alone, then one facet per line as
// zero-based indices; recognised by that lone count. A facet with more than
// D + 1 vertices is a non-simplicial Delaunay region: Qhull writes those
// without `Qt`, and they are rejected (run qdelaunay with Qt). TetGen .ele
// (chosen by the extension, or by its header and rows when the name does not
// say): "<count> <vertices per simplex> <#attributes>", then
// "<index> <v_0> … <v_D> [attributes]", numbered like the .node file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_writer.hpp"

namespace dewall::io {

/// An input that holds points, not simplices (a .dwpt file, a name ending in
/// .node), e.g. the two files of `certify` swapped.
class Not_simplices_error : public Parse_error {
 public:
  using Parse_error::Parse_error;
};

/// A simplex list as read: the rows (zero-based indices) and the line of the
/// file each row came from, for messages.
struct Simplex_list {
  Simplex_table table;
  std::vector<std::size_t> lines;  // lines[r]: the 1-based line of row r; empty for binary
  std::string format;              // "plain", "qhull", "tetgen", "binary", "vtk" or "gmsh"

  /// Where row r is, for messages: "NAME:LINE", or "NAME" for a binary file.
  std::string where(const std::string& name, std::size_t r) const {
    return lines.empty() ? name : name + ":" + std::to_string(lines[r]);
  }
};

/// Reads the plain list or Qhull's output (recognised by its lone count line)
/// of simplices of `dimension` (D + 1 indices per row).
/// \throws Parse_error (naming file and line) on a token that is not a
/// non-negative integer below 2^32, a row of the wrong length, or a Qhull count
/// that does not match the rows.
Simplex_list read_simplices(std::istream& in, const std::string& name, int dimension);

/// Reads TetGen .ele; vertex numbers are shifted down by `first_index` (the
/// first point number of the matching .node file: 0 or 1).
/// \throws Parse_error as read_simplices, and on a vertex number below first_index.
Simplex_list read_ele(std::istream& in, const std::string& name, int dimension, std::size_t first_index);

/// Reads a file by path ("-" = standard input), choosing the format by its
/// content first: the magic bytes 'DWSX' select the binary format, a first
/// line "# vtk DataFile …" VTK's cells, "$MeshFormat" (or the extension ".msh")
/// a gmsh mesh's triangles or tetrahedra; then the extension ".ele" (any case) or
/// an .ele header recognised in the first bytes TetGen's; anything else is the
/// plain list or Qhull's. \throws Not_simplices_error for a file of points
/// (magic 'DWPT', a name ending in .node); Parse_error for anything unreadable.
Simplex_list read_simplices_file(const std::string& path, int dimension, std::size_t first_index);

class Input_file;
class Binary_simplex_reader;

/// A simplex file read a block of rows at a time: the binary format straight
/// from the file (never held whole), the other formats read whole first (as
/// read_simplices_file) and then handed out.
class Simplex_file_reader {
 public:
  /// Opens `path` ("-" = standard input) and reads the binary header, or the
  /// whole file of another format. \throws as read_simplices_file.
  Simplex_file_reader(const std::string& path, int dimension, std::size_t first_index);
  ~Simplex_file_reader();
  /// Copies the next whole rows into `indices` (at most indices.size() / (D + 1));
  /// returns how many, 0 at the end. \throws Parse_error as read_simplices_file.
  std::size_t read(std::span<std::uint32_t> indices);
  /// The rows still to come, 2^64 − 1 when unknown (a binary stream of unknown count).
  std::uint64_t remaining() const;
  /// The format and the rows' lines, as Simplex_list's (no lines for binary).
  const Simplex_list& list() const { return list_; }

 private:
  std::unique_ptr<Input_file> file_;
  std::unique_ptr<Binary_simplex_reader> binary_;
  Simplex_list list_;  // the rows of a format read whole; format and lines of any
  std::size_t k_, next_ = 0;
};

}  // namespace dewall::io
