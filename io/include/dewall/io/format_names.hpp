// What a file's name says about its format: the one table of extensions that
// every reader and writer consults (compared in any case: ".VTK" is ".vtk").
//
// Readers trust a file's content first (magic bytes, a VTK or TetGen header)
// and its name after; writers choose by the name alone, so a name that says
// one format must never receive another: an output whose extension names a
// format that does not hold what is written (points into ".dwsx", simplices
// into ".dwpt" or ".node") or a format dewall does not write (".ply", ".stl")
// is refused before anything is computed or created.
#pragma once

#include <string>
#include <string_view>

namespace dewall::io {

/// The formats an extension names.
enum class Named_format {
  unnamed,           ///< no extension dewall knows: the plain text formats
  binary_points,     ///< .dwpt
  binary_simplices,  ///< .dwsx
  tetgen_node,       ///< .node (points)
  tetgen_ele,        ///< .ele (simplices)
  vtk,               ///< .vtk (points, or points and simplices)
  gmsh,              ///< .msh (a triangulation; written, not read)
  ply,               ///< .ply (points; read, not written)
  off,               ///< .off (points; read, not written)
  obj,               ///< .obj (points; read, not written)
  pcd,               ///< .pcd (points; read, not written)
  cgal,              ///< .cgal (CGAL's operator<< of a triangulation; read, not written)
  foreign,           ///< a known format dewall neither reads nor writes (.stl, .vtu, …)
};

/// True when `path` ends in `extension` (".vtk"), compared in any case.
bool has_extension(std::string_view path, std::string_view extension);

/// The format the extension of `path` names ("-" and unknown extensions: unnamed).
Named_format format_named_by(std::string_view path);

/// \throws Write_error (output_file.hpp) when `path` names a format that
/// dewall does not write points in: .dwsx, .ele, .msh, .ply, .off, .obj, .pcd, or a
/// foreign one. "-" is always accepted.
void check_points_output_name(const std::string& path);

/// \throws Write_error when `path` names a format that dewall does not write
/// simplices in: .dwpt, .node, .ply, .off, .obj, .pcd, or a foreign one. "-" is
/// always accepted.
void check_simplices_output_name(const std::string& path);

/// \throws Write_error when writing `output` would replace the file `input`
/// (the same device and inode, through any name, link or redirection of
/// standard input or output): the points would be lost. Paths that do not
/// exist yet, and "-" that is not a regular file, never conflict.
void check_output_is_not_input(const std::string& output, const std::string& input);

}  // namespace dewall::io
