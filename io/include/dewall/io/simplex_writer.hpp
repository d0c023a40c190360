// Writing simplices: the plain list (one simplex per line, zero-based input
// indices separated by single spaces) or TetGen .ele (chosen by extension).
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace dewall::io {

/// Simplices as rows of `vertices_per_simplex` indices, stored row after row.
struct Simplex_table {
  int vertices_per_simplex = 0;
  std::vector<std::uint32_t> indices;
  std::size_t size() const {
    return vertices_per_simplex ? indices.size() / static_cast<std::size_t>(vertices_per_simplex) : 0;
  }
};

void write_plain(std::ostream& out, const Simplex_table& t);
/// TetGen .ele: "<count> <vertices per simplex> 0", then "<i> <v0> … <vD>", with
/// vertex numbers shifted by `first_index` (the numbering of the .node file).
void write_ele(std::ostream& out, const Simplex_table& t, std::size_t first_index);

/// Writes to `path` ("-" = standard output) atomically: to a temporary file in
/// the same directory, renamed over `path` only when complete.
/// \throws std::runtime_error when the file cannot be written.
void write_simplices_file(const std::string& path, const Simplex_table& t, std::size_t first_index);

}  // namespace dewall::io
