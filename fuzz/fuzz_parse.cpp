// fuzz_parse: every input reader on arbitrary bytes → a value or a clean
// io::Parse_error; never a crash, a hang, a leak or another exception (an
// uncaught exception aborts, which libFuzzer records as a finding).
//
// Input: [reader] [dimension, for simplex lists] then the file's bytes.
// Readers: plain text / rbox (io::read_points), TetGen .node (io::read_node),
// binary .dwpt (io::read_binary_points), legacy VTK (io::read_vtk_points and,
// on the same bytes, io::read_vtk_simplices), and every input through the
// mesh readers (PLY, OFF, OBJ vertices; PCD points; gmsh nodes and elements),
// simplex lists: plain or Qhull (io::read_simplices) and TetGen .ele
// (io::read_ele). The readers added after this harness are compiled in when
// their headers exist.
//
// Properties of a successful read:
//  * points: the dimension is 2 … 6, there is at least one point, and the
//    coordinates are whole points; simplices: D + 1 indices per row, one source
//    line per row;
//  * round trips: a plain-text table written back with %.17g (NaN and ±inf as
//    strtod spells them) reads back to the same values; a binary table written
//    back reads back bit for bit.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include "dewall/io/point_reader.hpp"
#include "fuzz_common.hpp"

#if __has_include("dewall/io/binary_points.hpp")
#define DEWALL_FUZZ_BINARY 1
#include "dewall/io/binary_points.hpp"
#endif
#if __has_include("dewall/io/vtk.hpp")
#define DEWALL_FUZZ_VTK 1
#include "dewall/io/vtk.hpp"
#endif
#if __has_include("dewall/io/mesh_formats.hpp")
#define DEWALL_FUZZ_MESH 1
#include "dewall/io/mesh_formats.hpp"
#endif
#if __has_include("dewall/io/simplex_reader.hpp")
#define DEWALL_FUZZ_SIMPLICES 1
#include "dewall/io/simplex_reader.hpp"
#endif

namespace {

using dewall::io::Parse_error;
using dewall::io::Point_table;

void check_table(const Point_table& t) {
  DEWALL_FUZZ_CHECK(t.dimension >= 2 && t.dimension <= 6);
  DEWALL_FUZZ_CHECK(t.coordinates.size() % static_cast<std::size_t>(t.dimension) == 0);
  DEWALL_FUZZ_CHECK(t.size() >= 1);
}

bool same_value(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

void check_round_trip(const Point_table& t) {
  std::string text;
  char buffer[40];
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (int j = 0; j < t.dimension; ++j) {
      std::snprintf(buffer, sizeof buffer, j ? " %.17g" : "%.17g",
                    t.coordinates[i * static_cast<std::size_t>(t.dimension) + static_cast<std::size_t>(j)]);
      text += buffer;
    }
    text += '\n';
  }
  std::istringstream in(text);
  const Point_table back = dewall::io::read_points(in, "round trip");
  DEWALL_FUZZ_CHECK(back.dimension == t.dimension);
  // Never mistaken for rbox: rbox needs a count alone on the second line, and
  // every written line holds D ≥ 2 values.
  DEWALL_FUZZ_CHECK(back.coordinates.size() == t.coordinates.size());
  for (std::size_t k = 0; k < t.coordinates.size(); ++k)
    DEWALL_FUZZ_CHECK(same_value(back.coordinates[k], t.coordinates[k]));
}

#ifdef DEWALL_FUZZ_BINARY
void check_binary_round_trip(const Point_table& t) {
  std::ostringstream out(std::ios::binary);
  dewall::io::write_binary_points(out, t);
  std::istringstream in(out.str(), std::ios::binary);
  const Point_table back = dewall::io::read_binary_points(in, "round trip");
  DEWALL_FUZZ_CHECK(back.dimension == t.dimension);
  DEWALL_FUZZ_CHECK(back.coordinates.size() == t.coordinates.size());
  DEWALL_FUZZ_CHECK(std::memcmp(back.coordinates.data(), t.coordinates.data(),
                                t.coordinates.size() * sizeof(double)) == 0);
}
#endif

#ifdef DEWALL_FUZZ_SIMPLICES
void check_simplices(const dewall::io::Simplex_list& s, int dimension) {
  DEWALL_FUZZ_CHECK(s.table.vertices_per_simplex == dimension + 1);
  DEWALL_FUZZ_CHECK(s.table.indices.size() % static_cast<std::size_t>(dimension + 1) == 0);
  DEWALL_FUZZ_CHECK(s.lines.size() == s.table.size());
}
#endif

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  enum Reader { text, node, binary, vtk, simplices, ele, reader_count };
  const int reader = data[0] % reader_count;
  const int dimension = 2 + (data[0] / reader_count) % 5;  // for the simplex readers
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  std::istringstream in(bytes, std::ios::binary);
  try {
    switch (reader) {
      case text: {
        const Point_table t = dewall::io::read_points(in, "fuzz");
        check_table(t);
        check_round_trip(t);
        break;
      }
      case node:
        check_table(dewall::io::read_node(in, "fuzz.node"));
        break;
#ifdef DEWALL_FUZZ_BINARY
      case binary: {
        const Point_table t = dewall::io::read_binary_points(in, "fuzz.dwpt");
        check_table(t);
        check_binary_round_trip(t);
        break;
      }
#endif
#ifdef DEWALL_FUZZ_VTK
      case vtk: {
        // The same bytes also as a triangulation: its CELLS as simplices of `dimension`.
        std::istringstream cells(bytes, std::ios::binary);
        try {
          const auto t = dewall::io::read_vtk_simplices(cells, "fuzz.vtk", dimension);
          DEWALL_FUZZ_CHECK(t.vertices_per_simplex == dimension + 1);
          DEWALL_FUZZ_CHECK(t.indices.size() == t.size() * static_cast<std::size_t>(dimension + 1));
        } catch (const Parse_error&) {
        }
        check_table(dewall::io::read_vtk_points(in, "fuzz.vtk"));
        break;
      }
#endif
#ifdef DEWALL_FUZZ_SIMPLICES
      case simplices:
        check_simplices(dewall::io::read_simplices(in, "fuzz", dimension), dimension);
        break;
      case ele:
        check_simplices(dewall::io::read_ele(in, "fuzz.ele", dimension, data[0] & 1), dimension);
        break;
#endif
      default:
        break;
    }
  } catch (const Parse_error&) {
    // The one allowed failure.
  }
#ifdef DEWALL_FUZZ_MESH
  // Every input also through the mesh readers (their key words are short, so
  // the corpus reaches them), each on its own copy of the bytes.
  const auto each_mesh_reader = [&](auto read) {
    std::istringstream copy(bytes, std::ios::binary);
    try {
      read(copy);
    } catch (const Parse_error&) {
    }
  };
  each_mesh_reader([](std::istream& s) { check_table(dewall::io::read_ply_points(s, "fuzz.ply")); });
  each_mesh_reader([](std::istream& s) { check_table(dewall::io::read_off_points(s, "fuzz.off")); });
  each_mesh_reader([](std::istream& s) { check_table(dewall::io::read_obj_points(s, "fuzz.obj")); });
  each_mesh_reader([](std::istream& s) { check_table(dewall::io::read_msh_points(s, "fuzz.msh")); });
  each_mesh_reader([](std::istream& s) { check_table(dewall::io::read_pcd_points(s, "fuzz.pcd")); });
  each_mesh_reader([&](std::istream& s) {
    if (dimension > 3) return;
    const auto t = dewall::io::read_msh_simplices(s, "fuzz.msh", dimension);
    DEWALL_FUZZ_CHECK(t.indices.size() == t.size() * static_cast<std::size_t>(dimension + 1));
  });
#endif
  return 0;
}
