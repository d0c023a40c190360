// Reading point sets: plain text, Qhull's rbox format and TetGen .node.
//
// Plain text: one point per line, coordinates separated by whitespace, `#`
// starts a comment; the dimension is the number of values on the first data line.
// rbox: a line with the dimension alone, a line with the count alone (rbox may
// append a comment to either), then the points. TetGen .node (chosen by the
// file extension): "<count> <dimension> <#attributes> <boundary marker>", then
// "<index> <coordinates> [attributes] [marker]" lines.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace dewall::io {

/// Unreadable input; what() names the file and line.
class Parse_error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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
Point_table read_points(std::istream& in, const std::string& name);

/// Reads TetGen .node from `in`.
Point_table read_node(std::istream& in, const std::string& name);

/// Reads a file by path: "-" is standard input; a ".node" extension selects
/// TetGen's format, anything else plain text or rbox.
Point_table read_points_file(const std::string& path);

}  // namespace dewall::io
