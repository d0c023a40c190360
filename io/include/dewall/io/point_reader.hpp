// Reading point sets: plain text, Qhull's rbox format, TetGen .node, the binary
// format (binary_points.hpp), the POINTS of legacy VTK files (vtk.hpp) and the
// vertices of PLY, OFF and OBJ meshes (mesh_formats.hpp).
//
// Plain text: one point per line, coordinates separated by whitespace, `#`
// starts a comment; the dimension is the number of values on the first data line.
// rbox: a line with the dimension alone, a line with the count alone (rbox may
// append a comment to either), then the points. TetGen .node (chosen by the
// file extension, or by its header and rows when the name does not say):
// "<count> <dimension> <#attributes> <boundary marker>", then
// "<index> <coordinates> [attributes] [marker]" lines.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace dewall::io {

class Progress;

/// Unreadable input; what() names the file and line.
class Parse_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An input that holds something else than points (simplices: a .dwsx file,
/// or a name ending in .ele), e.g. the two files of `certify` swapped.
class Not_points_error : public Parse_error {
 public:
  using Parse_error::Parse_error;
};

/// Points of one dimension, coordinates stored point after point.
struct Point_table {
  int dimension = 0;
  std::vector<double> coordinates;
  /// Index of the first point in the source numbering (TetGen may start at 1).
  std::size_t first_index = 0;
  std::size_t size() const { return dimension ? coordinates.size() / static_cast<std::size_t>(dimension) : 0; }
};

/// Reads plain text or rbox format from `in`; `name` is used in messages.
/// \throws Parse_error on non-numbers, ragged rows, a dimension outside 2…6,
/// a wrong count in rbox format, or no points.
/// `progress`, when given, receives the number of bytes read so far.
Point_table read_points(std::istream& in, const std::string& name, Progress* progress = nullptr);

/// Reads TetGen .node from `in`.
Point_table read_node(std::istream& in, const std::string& name, Progress* progress = nullptr);

/// Reads a file by path ("-" is standard input), choosing the format by its
/// content first: the magic bytes "DWPT" select the binary format, a first line
/// "# vtk DataFile …" legacy VTK; then by extension (any case): ".node" selects
/// TetGen's format; then a TetGen .node header and rows recognised in the first
/// bytes (through a pipe, or under another name) select it too; PLY, OFF and
/// OBJ meshes are read for their vertices and gmsh meshes for their nodes
/// (mesh_formats.hpp), recognised by their key word or their extension;
/// anything else is plain text or rbox. `progress`, when given, shows a
/// "reading" phase (a percentage for files, elapsed time for standard input).
/// \throws Not_points_error for a file of simplices (magic "DWSX", or a name
/// ending in .ele); Parse_error for anything unreadable.
Point_table read_points_file(const std::string& path, Progress* progress = nullptr);

}  // namespace dewall::io
