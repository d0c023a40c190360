// The files people already have: the vertices of PLY, OFF and Wavefront OBJ
// meshes and point clouds (what scanners, MeshLab, CloudCompare and PCL write)
// read as points, and a triangulation written as a gmsh mesh for
// finite-element users.
//
// Only the vertices are read: faces, normals, colours and other elements are
// skipped. Coordinates keep the value the file declares: a PLY property of
// type float is the float its text or bytes say (then widened exactly), a
// double the double, and OFF and OBJ text is read as doubles. These are 3D
// formats: a set whose every z is 0 (or a PLY vertex without z) is read as 2D,
// as VTK's points are. PCD (the Point Cloud Library's) holds points only:
// the fields x, y and z of each, in text or little-endian binary (not the
// LZF-compressed binary, which is refused with a word on converting it).
// Hand-written rather than CGAL's readers (CGAL::IO::
// read_PLY, read_OFF, read_OBJ), which report failure as a bool: these name
// the file, the line and what is wrong, as every other reader here does, and
// read forward only (pipes work).
//
// PLY: "ply", a format line (ascii 1.0, binary_little_endian 1.0 or
// binary_big_endian 1.0), elements with scalar and list properties of the
// types char … double (or int8 … float64), "end_header", then the data; the
// points are the "vertex" element's x, y and z. OFF: an optional "OFF" key
// line (also COFF, NOFF, STOFF: their extra per-vertex values are skipped),
// "<vertices> <faces> <edges>", then the vertices. OBJ: the "v x y z [w]"
// lines (w and vertex colours skipped).
//
// Written: gmsh's MSH 2.2 ASCII format, which gmsh, hxt and most solvers
// read: $Nodes (numbered from 1, z = 0 in 2D), $Elements (triangles, type 2,
// or tetrahedra, type 4, each with the two tags 0 and 1). Read back, and what
// gmsh and hxt write (MSH 4.1 ASCII too): the nodes as points, the triangles or
// tetrahedra as simplices, so that certify and draw take a mesh file as it is.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/simplex_writer.hpp"

namespace dewall::io {

/// The vertices of a PLY file. \throws Parse_error naming the file (and the
/// line, in text) for a malformed header, a missing vertex element or x/y
/// property, a non-number, or data that ends early.
Point_table read_ply_points(std::istream& in, const std::string& name);

/// The vertices of an OFF file. \throws Parse_error as read_ply_points.
Point_table read_off_points(std::istream& in, const std::string& name);

/// The vertices ("v" lines) of a Wavefront OBJ file. \throws Parse_error as
/// read_ply_points, and when there is no vertex.
Point_table read_obj_points(std::istream& in, const std::string& name);

/// True when `head`, a file's first bytes, starts as a PLY, OFF or OBJ file
/// (PLY and OFF by their key word, OBJ by a first statement that is one of
/// OBJ's: v, vt, vn, f, o, g, s, mtllib, usemtl).
bool is_ply_header(std::string_view head);
bool is_off_header(std::string_view head);
bool is_obj_header(std::string_view head);

/// The points of a Point Cloud Library PCD file (DATA ascii or binary; the
/// fields x and y, z when present, each of COUNT 1, of any TYPE and SIZE:
/// floats read as the float or double stored, integers exactly; the other
/// fields skipped). \throws Parse_error naming the file (and the line, in
/// text) for a malformed header, DATA binary_compressed (refused: convert the
/// file), a missing x or y field, a non-number, an integer coordinate beyond
/// 2^53, or data that ends early or goes on after the points.
Point_table read_pcd_points(std::istream& in, const std::string& name);

/// True when `head` starts as a PCD file: PCL's "# .PCD" comment, or a first
/// statement VERSION.
bool is_pcd_header(std::string_view head);

/// A triangulation as CGAL's operator<< writes it in ASCII mode (no header or
/// magic word: recognised by the name `.cgal`): CGAL::Delaunay_triangulation_2
/// ("n m 2", the n − 1 finite points, m faces, m neighbour rows),
/// Delaunay_triangulation_3 ("3", n, the n points, m, m cells, m neighbour
/// rows) or the dD Delaunay_triangulation ("d", n, the infinite vertex, the n
/// points each after its dimension, m, m full cells, m neighbour rows); vertex
/// 0 is the infinite vertex, 1 … the finite points in the order written.
/// Coordinates are read as written: CGAL writes them with the stream's
/// precision, so a file written without `std::setprecision(17)` holds rounded
/// points (certified as such). Vertex and cell bases that write more (an
/// info) are refused by the count of values on a line.
struct Cgal_triangulation {
  Point_table points;
  Simplex_table cells;  ///< the finite cells, 0-based indices into points
};
/// \throws Parse_error naming the file and line: a triangulation that is not
/// full-dimensional (its dimension below its points'), binary files (a
/// non-number), wrong counts, an index out of range, or a truncated file.
Cgal_triangulation read_cgal_triangulation(std::istream& in, const std::string& name);

/// True when `head` starts as a gmsh mesh ("$MeshFormat").
bool is_msh_header(std::string_view head);

/// The nodes of a gmsh mesh (MSH 2.2 or 4.1, ASCII), in file order, as points.
/// \throws Parse_error for binary files, parametric nodes, malformed or truncated sections.
Point_table read_msh_points(std::istream& in, const std::string& name);

/// The triangles (dimension 2) or tetrahedra (3) of a gmsh mesh, as indices
/// of its nodes in file order (what read_msh_points numbers); other elements
/// (boundary triangles, lines, points) are skipped. \throws Parse_error as
/// read_msh_points, and when there is no such element.
Simplex_table read_msh_simplices(std::istream& in, const std::string& name, int dimension);

/// Writes `points` and the simplices `t` (dimension 2 or 3) as gmsh MSH 2.2
/// ASCII, coordinates in the shortest form that reads back to the same double.
/// \pre points.dimension is 2 or 3 (write_triangulation_file checks it).
void write_msh_triangulation(std::ostream& out, const Point_table& points, const Simplex_table& t);

}  // namespace dewall::io
