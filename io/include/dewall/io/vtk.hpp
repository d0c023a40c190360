// Legacy VTK files (".vtk"), the format ParaView and VisIt open directly.
//
// Written: an UNSTRUCTURED_GRID whose POINTS are the input points (z = 0 in
// 2D) and whose cells are the simplices — VTK_TRIANGLE (5) in 2D, VTK_TETRA (10)
// in 3D, in our positive orientation, which is VTK's (a tetrahedron's fourth
// point lies on the side its first three define by the right-hand rule) — or, for
// a point file, one VTK_VERTEX (1) cell per point so that the points render.
// BINARY by default (big-endian doubles and 32-bit ints, as the legacy format
// prescribes: a quarter of the size of ASCII, and the doubles' bits kept);
// ASCII on request, with coordinates in the shortest form that reads back to
// the same double. Either way a round trip through VTK is exact. VTK is a 3D
// format: dimensions above 3 are refused, and so are counts beyond its 32-bit
// ints (2^31 − 1 points; cells × (vertices + 1) likewise).
//
// Read: the POINTS section of any legacy file (ASCII or BINARY, float or
// double; POLYDATA, UNSTRUCTURED_GRID, STRUCTURED_GRID). VTK points always have
// three coordinates; the point set is taken as 2D when every z is 0, else 3D.
// And the simplices of an UNSTRUCTURED_GRID: its CELLS section, right after
// the POINTS, each cell of D + 1 vertices (what write_vtk_triangulation
// writes, and ParaView or meshio save), so that every file the tool writes
// can be certified and drawn.
#pragma once

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_writer.hpp"

namespace dewall::io {

class Progress;

/// Thrown when a point set or triangulation cannot be written as VTK (dimension > 3).
class Vtk_unsupported : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Vtk_encoding { binary, ascii };

/// Writes `points` and the simplices `t` (indices into `points`) as a legacy
/// UNSTRUCTURED_GRID. \throws Vtk_unsupported when the dimension is not 2 or 3
/// or the counts exceed 32-bit ints. `progress`, when given, receives the
/// number of points plus simplices written.
void write_vtk_triangulation(std::ostream& out, const Point_table& points, const Simplex_table& t,
                             Progress* progress = nullptr, Vtk_encoding encoding = Vtk_encoding::binary);

/// Writes `points` alone, one VTK_VERTEX cell each. \throws Vtk_unsupported
/// as write_vtk_triangulation.
void write_vtk_points(std::ostream& out, const Point_table& points, Progress* progress = nullptr,
                      Vtk_encoding encoding = Vtk_encoding::binary);

/// Reads the POINTS section of a legacy VTK file; `name` is used in messages.
/// \throws Parse_error (with the file and line) on a missing or malformed header
/// or POINTS section, non-numbers, or a truncated section.
Point_table read_vtk_points(std::istream& in, const std::string& name);

/// Reads the CELLS section of a legacy VTK file as simplices of `dimension`
/// (the dimension of its points: 2 when every z is 0). \throws Parse_error
/// when there is none, or a cell is not a simplex of D + 1 vertices, or the
/// section is truncated or malformed.
Simplex_table read_vtk_simplices(std::istream& in, const std::string& name, int dimension);

/// True when `head` (a first line, or the first bytes of an input) starts as a
/// legacy VTK file ("# vtk DataFile …").
bool is_vtk_header(std::string_view head);

}  // namespace dewall::io
