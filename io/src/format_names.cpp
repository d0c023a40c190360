#include "dewall/io/format_names.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>

#include <sys/stat.h>
#include <unistd.h>

#include "dewall/io/output_file.hpp"
#include "dewall/io/quote.hpp"

namespace dewall::io {
namespace {

struct Extension {
  std::string_view extension;
  Named_format format;
  std::string_view description;  // what a file of this name holds, for messages
};

constexpr std::array<Extension, 16> extensions = {{
    {".dwpt", Named_format::binary_points, "binary points (dewall's .dwpt)"},
    {".dwsx", Named_format::binary_simplices, "binary simplices (dewall's .dwsx)"},
    {".node", Named_format::tetgen_node, "TetGen points (.node)"},
    {".ele", Named_format::tetgen_ele, "TetGen simplices (.ele)"},
    {".vtk", Named_format::vtk, "legacy VTK"},
    {".ply", Named_format::ply, "a PLY mesh"},
    {".off", Named_format::off, "an OFF mesh"},
    {".obj", Named_format::obj, "a Wavefront OBJ mesh"},
    {".stl", Named_format::foreign, "an STL mesh"},
    {".msh", Named_format::gmsh, "a gmsh mesh"},
    {".pcd", Named_format::pcd, "a PCL point cloud"},
    {".cgal", Named_format::cgal, "a CGAL triangulation (operator<<)"},
    {".vtu", Named_format::foreign, "an XML VTK grid"},
    {".vtp", Named_format::foreign, "an XML VTK polydata"},
    {".svg", Named_format::foreign, "an SVG picture"},
    {".csv", Named_format::foreign, "comma-separated values"},
}};

const Extension* extension_of(std::string_view path) {
  const auto e = std::find_if(extensions.begin(), extensions.end(),
                              [&](const Extension& x) { return has_extension(path, x.extension); });
  return e == extensions.end() ? nullptr : &*e;
}

/// True for the formats dewall reads but never writes.
bool read_only(Named_format f) {
  return f == Named_format::ply || f == Named_format::off || f == Named_format::obj || f == Named_format::pcd ||
         f == Named_format::cgal || f == Named_format::foreign;
}

/// The refusal of `path` (whose extension is `e`) for writing `what`; `use` lists the names that work.
Write_error wrong_name(const std::string& path, const Extension& e, const char* what, const char* use) {
  return Write_error(file_name(path) + ": the name says " + std::string(e.description) + ", but " + what +
                     (read_only(e.format) ? " (dewall does not write that format)" : "") + ": name it " + use);
}

/// The device and inode `path` names ("-": the descriptor `standard`), when it exists.
std::optional<std::pair<dev_t, ino_t>> identity(const std::string& path, int standard) {
  struct stat st {};
  const int r = path == "-" ? ::fstat(standard, &st) : ::stat(path.c_str(), &st);
  if (r != 0) return std::nullopt;
  // A pipe or terminal behind "-" is never the other file; a regular file or device may be.
  if (path == "-" && !S_ISREG(st.st_mode)) return std::nullopt;
  return std::pair{st.st_dev, st.st_ino};
}

}  // namespace

bool has_extension(std::string_view path, std::string_view extension) {
  if (path.size() <= extension.size()) return false;
  return std::equal(extension.begin(), extension.end(), path.end() - static_cast<std::ptrdiff_t>(extension.size()),
                    [](char a, char b) {
                      return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
                    });
}

Named_format format_named_by(std::string_view path) {
  const Extension* e = extension_of(path);
  return e ? e->format : Named_format::unnamed;
}

void check_points_output_name(const std::string& path) {
  const Extension* e = extension_of(path);
  if (!e) return;
  if (e->format == Named_format::binary_simplices || e->format == Named_format::tetgen_ele ||
      e->format == Named_format::gmsh || read_only(e->format))
    throw wrong_name(path, *e, "points are written here",
                     ".dwpt (binary), .node (TetGen), .vtk (VTK) or anything else for plain text (e.g. .txt)");
}

void check_simplices_output_name(const std::string& path) {
  const Extension* e = extension_of(path);
  if (!e) return;
  if (e->format == Named_format::binary_points || e->format == Named_format::tetgen_node || read_only(e->format))
    throw wrong_name(path, *e, "simplices are written here",
                     ".dwsx (binary), .ele (TetGen), .vtk (VTK), .msh (gmsh) or anything else for the plain list "
                     "(e.g. .txt)");
}

void check_output_is_not_input(const std::string& output, const std::string& input) {
  const auto out = identity(output, STDOUT_FILENO);
  if (!out || out != identity(input, STDIN_FILENO)) return;
  const std::string shown = output == "-" ? "<stdout>" : file_name(output);
  const std::string in = input == "-" ? "<stdin>" : file_name(input);
  throw Write_error(shown + ": the output is the input" + (in == shown ? std::string() : " " + in + " (the same file)") +
                    ": writing it would replace the input; choose another output");
}

}  // namespace dewall::io
