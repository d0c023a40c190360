// File formats: the binary .dwpt and .dwsx formats (bit-exact round trip,
// clean errors on truncated or foreign files), legacy VTK (written triangulations read back),
// text points, the progress line, and the commands generate / triangulate /
// draw through the real executable (exit codes, messages, no partial files).
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <map>
#include <string>
#include <thread>

#include "dewall/dewall.hpp"
#include "dewall/io/binary_points.hpp"
#include "dewall/io/binary_simplices.hpp"
#include "dewall/io/mesh_formats.hpp"
#include "dewall/io/output_file.hpp"
#include "dewall/io/point_generators.hpp"
#include "dewall/io/point_reader.hpp"
#include "dewall/io/progress.hpp"
#include "dewall/io/simplex_reader.hpp"
#include "dewall/io/simplex_writer.hpp"
#include "dewall/io/vtk.hpp"
#include "support/cli_runner.hpp"

using namespace dewall::io;

namespace {

bool same_bits(const Point_table& a, const Point_table& b) {
  return a.dimension == b.dimension && a.coordinates.size() == b.coordinates.size() &&
         std::memcmp(a.coordinates.data(), b.coordinates.data(), a.coordinates.size() * sizeof(double)) == 0;
}

/// Awkward doubles: signed zero, subnormals, extremes, NaN with a payload.
Point_table awkward_points() {
  Point_table t;
  t.dimension = 3;
  const double nan_payload = std::bit_cast<double>(std::uint64_t{0x7ff8000000012345});
  t.coordinates = {0.0, -0.0, 1.0, std::numeric_limits<double>::denorm_min(), -5e-324, 0.1,
                   std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), 1.0 / 3,
                   std::numeric_limits<double>::infinity(), nan_payload, 123456789.123456789};
  return t;
}

std::string binary_bytes(const Point_table& t) {
  std::ostringstream out(std::ios::binary);
  write_binary_points(out, t);
  return out.str();
}

Point_table read_binary_string(const std::string& bytes) {
  std::istringstream in(bytes, std::ios::binary);
  return read_binary_points(in, "test.dwpt");
}

using dewall::test::slurp;

}  // namespace

TEST_CASE("binary points: bit-exact round trip and the documented layout", "[formats]") {
  const auto t = awkward_points();
  const auto bytes = binary_bytes(t);
  REQUIRE(bytes.size() == binary_points_file_size(4, 3));
  CHECK(bytes.substr(0, 4) == "DWPT");
  CHECK(bytes[4] == 1);   // version, little-endian
  CHECK(bytes[8] == 3);   // dimension
  CHECK(bytes[16] == 4);  // count
  double first;
  std::memcpy(&first, bytes.data() + 24 + 16, 8);  // the third coordinate, little-endian on this host
  CHECK(first == 1.0);
  CHECK(same_bits(read_binary_string(bytes), t));

  // Larger than one read chunk (2^20 doubles), through a file and the dispatch
  // on the magic bytes whatever the extension.
  const auto big = generate_points(Point_kind::uniform, 400000, 3, 8);
  std::filesystem::create_directories("formats_test_binary");
  write_points_file("formats_test_binary/big.txt.dwpt", big);
  std::filesystem::rename("formats_test_binary/big.txt.dwpt", "formats_test_binary/big_binary.txt");
  CHECK(same_bits(read_points_file("formats_test_binary/big_binary.txt"), big));
}

TEST_CASE("binary points: truncated and foreign files are clean errors", "[formats]") {
  const auto bytes = binary_bytes(awkward_points());
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    INFO("first " << size << " bytes");
    CHECK_THROWS_AS(read_binary_string(bytes.substr(0, size)), Parse_error);
  }
  CHECK_THROWS_WITH(read_binary_string(bytes.substr(0, 50)), Catch::Contains("truncated") && Catch::Contains("test.dwpt"));
  CHECK_THROWS_WITH(read_binary_string(bytes + "x"), Catch::Contains("after the last point"));
  auto patched = [&](std::size_t offset, char value) {
    auto b = bytes;
    b[offset] = value;
    return b;
  };
  CHECK_THROWS_WITH(read_binary_string(patched(0, 'X')), Catch::Contains("not a binary point file"));
  CHECK_THROWS_WITH(read_binary_string(patched(4, 2)), Catch::Contains("version 2"));
  CHECK_THROWS_WITH(read_binary_string(patched(8, 7)), Catch::Contains("dimension 7"));
  CHECK_THROWS_WITH(read_binary_string(patched(12, 1)), Catch::Contains("flags"));
  CHECK_THROWS_WITH(read_binary_string(patched(23, 0x7f)), Catch::Contains("impossible point count"));
  auto zero = bytes.substr(0, 24);
  zero[16] = 0;
  CHECK_THROWS_WITH(read_binary_string(zero), Catch::Contains("no points"));
}

namespace {

std::string binary_simplex_bytes(const Simplex_table& t) {
  std::ostringstream out(std::ios::binary);
  write_binary_simplices(out, t);
  return out.str();
}

Simplex_list read_binary_simplex_string(const std::string& bytes, int dimension) {
  std::istringstream in(bytes, std::ios::binary);
  return read_binary_simplices(in, "t.dwsx", dimension);
}

/// A header in the documented layout, written by hand (not by the writer).
std::string dwsx_header(std::uint32_t dimension, std::uint32_t width, std::uint64_t count) {
  std::string h = "DWSX";
  for (std::uint64_t v : {std::uint64_t{1}, std::uint64_t{dimension}, std::uint64_t{width}})
    for (int i = 0; i < 4; ++i) h += static_cast<char>((v >> (8 * i)) & 0xff);
  for (int i = 0; i < 8; ++i) h += static_cast<char>((count >> (8 * i)) & 0xff);
  return h;
}

std::string le_bytes(std::uint64_t v, int width) {
  std::string b;
  for (int i = 0; i < width; ++i) b += static_cast<char>((v >> (8 * i)) & 0xff);
  return b;
}

}  // namespace

TEST_CASE("binary simplices: round trip, the documented layout, 8-byte and unknown-count files", "[formats]") {
  const Simplex_table t{3, {0, 1, 2, 2, 1, 3, 4000000000u, 7, 0}};
  const auto bytes = binary_simplex_bytes(t);
  // The writer's bytes are the layout of docs/formats.md, byte for byte.
  std::string expected = dwsx_header(2, 4, 3);
  for (auto v : t.indices) expected += le_bytes(v, 4);
  CHECK(bytes == expected);
  const auto back = read_binary_simplex_string(bytes, 2);
  CHECK(back.table.vertices_per_simplex == 3);
  CHECK(back.table.indices == t.indices);
  CHECK(back.format == "binary");
  CHECK(back.lines.empty());
  CHECK(back.where("t.dwsx", 1) == "t.dwsx");

  // 8-byte indices, and a count the writer did not know (rows to the end).
  std::string wide = dwsx_header(2, 8, 3), open = dwsx_header(2, 4, binary_simplices_unknown_count);
  for (auto v : t.indices) wide += le_bytes(v, 8), open += le_bytes(v, 4);
  CHECK(read_binary_simplex_string(wide, 2).table.indices == t.indices);
  CHECK(read_binary_simplex_string(open, 2).table.indices == t.indices);
  CHECK(read_binary_simplex_string(dwsx_header(2, 4, binary_simplices_unknown_count), 2).table.size() == 0);

  // Larger than one read chunk (2^19 simplices), through a file, recognised by
  // its magic bytes whatever its name.
  Simplex_table big{4, {}};
  for (std::uint32_t i = 0; i < 4 * 600000; ++i) big.indices.push_back(i * 2654435761u);
  std::filesystem::create_directories("formats_test_binary");
  write_simplices_file("formats_test_binary/s.dwsx", big, 0);
  std::filesystem::rename("formats_test_binary/s.dwsx", "formats_test_binary/s.txt");
  CHECK(read_simplices_file("formats_test_binary/s.txt", 3, 0).table.indices == big.indices);
}

TEST_CASE("binary simplices: truncated and foreign files are clean errors", "[formats]") {
  const Simplex_table t{4, {0, 1, 2, 3, 1, 2, 3, 4}};
  const auto bytes = binary_simplex_bytes(t);
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    INFO("first " << size << " bytes");
    CHECK_THROWS_AS(read_binary_simplex_string(bytes.substr(0, size), 3), Parse_error);
  }
  CHECK_THROWS_WITH(read_binary_simplex_string(bytes.substr(0, 30), 3), Catch::Contains("t.dwsx: truncated"));
  CHECK_THROWS_WITH(read_binary_simplex_string(bytes + "x", 3), Catch::Contains("after the last simplex"));
  CHECK_THROWS_WITH(read_binary_simplex_string(bytes, 2), Catch::Contains("simplices of dimension 3"));
  CHECK_THROWS_WITH(read_binary_simplex_string(dwsx_header(3, 2, 0), 3), Catch::Contains("2 bytes per index"));
  CHECK_THROWS_WITH(read_binary_simplex_string(dwsx_header(3, 4, std::uint64_t{1} << 60), 3),
                    Catch::Contains("impossible simplex count"));
  auto other = bytes;
  other[4] = 2;
  CHECK_THROWS_WITH(read_binary_simplex_string(other, 3), Catch::Contains("version 2"));
  other = bytes;
  other[3] = 'T';
  CHECK_THROWS_WITH(read_binary_simplex_string(other, 3), Catch::Contains("not a binary simplex file"));
  // An index that does not fit the 32 bits simplices are kept in.
  std::string wide = dwsx_header(2, 8, 1) + le_bytes(0, 8) + le_bytes(1, 8) + le_bytes(std::uint64_t{1} << 32, 8);
  CHECK_THROWS_WITH(read_binary_simplex_string(wide, 2), Catch::Contains("too large"));
  // Unknown count: the file must end on a whole simplex.
  std::string open = dwsx_header(2, 4, binary_simplices_unknown_count) + le_bytes(0, 4) + le_bytes(1, 4);
  CHECK_THROWS_WITH(read_binary_simplex_string(open, 2), Catch::Contains("ends inside simplex 0"));
}

TEST_CASE("binary files read by name: their size is known before they are read", "[formats]") {
  // Files are read through a stream that cannot seek (io/src/input_file.cpp):
  // the size comes from the file itself, so that a reader allocates once and
  // the certifier can reserve its rows.
  std::filesystem::create_directories("formats_test_sized");
  const Simplex_table t{4, {0, 1, 2, 3, 1, 2, 3, 4, 2, 3, 4, 5}};
  write_simplices_file("formats_test_sized/s.dwsx", t, 0);
  Simplex_file_reader reader("formats_test_sized/s.dwsx", 3, 0);
  CHECK(reader.remaining() == 3);
  std::vector<std::uint32_t> rows(8);
  CHECK(reader.read(rows) == 2);
  CHECK(reader.remaining() == 1);
  // A truncated file or one with bytes after its last row: refused before the
  // rows are read, naming the sizes.
  const auto bytes = binary_simplex_bytes(t);
  for (const auto& [contents, message] :
       {std::pair{bytes.substr(0, bytes.size() - 3), std::string("the file has " + std::to_string(bytes.size() - 3) + " bytes")},
        std::pair{bytes + "xy", std::string("2 bytes after the last simplex")}}) {
    std::ofstream("formats_test_sized/bad.dwsx", std::ios::binary) << contents;
    CHECK_THROWS_WITH(Simplex_file_reader("formats_test_sized/bad.dwsx", 3, 0), Catch::Contains(message));
  }
  const auto points = generate_points(Point_kind::uniform, 100, 3, 8);
  write_points_file("formats_test_sized/p.dwpt", points);
  std::string point_bytes;
  {
    std::ifstream in("formats_test_sized/p.dwpt", std::ios::binary);
    point_bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream("formats_test_sized/short.dwpt", std::ios::binary) << point_bytes.substr(0, point_bytes.size() - 8);
  CHECK_THROWS_WITH(read_points_file("formats_test_sized/short.dwpt"),
                    Catch::Contains("truncated") && Catch::Contains("the file has " + std::to_string(point_bytes.size() - 8) + " bytes"));
  std::filesystem::remove_all("formats_test_sized");
}

TEST_CASE("text points: shortest round-trip form reads back exactly", "[formats]") {
  const auto t = generate_points(Point_kind::bubbles, 500, 4, 21);
  std::ostringstream out;
  write_points_text(out, t);
  std::istringstream in(out.str());
  CHECK(same_bits(read_points(in, "text"), t));
}

TEST_CASE("VTK: written triangulations read back, positively oriented", "[formats]") {
  for (int d : {2, 3}) {
    INFO("dimension " << d);
    const auto points = generate_points(Point_kind::ball, 200, d, 31);
    Simplex_table simplices;
    simplices.vertices_per_simplex = d + 1;
    std::vector<dewall::kernel::Point_d<3>> p3(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      for (int j = 0; j < d; ++j) p3[i][j] = points.coordinates[i * std::size_t(d) + std::size_t(j)];
    if (d == 2) {
      std::vector<dewall::kernel::Point_d<2>> p2(points.size());
      for (std::size_t i = 0; i < points.size(); ++i) p2[i] = {{p3[i][0], p3[i][1]}};
      for (const auto& s : dewall::triangulate<2>(p2).simplices) simplices.indices.insert(simplices.indices.end(), s.begin(), s.end());
    } else {
      for (const auto& s : dewall::triangulate<3>(p3).simplices) simplices.indices.insert(simplices.indices.end(), s.begin(), s.end());
    }
    for (const Vtk_encoding encoding : {Vtk_encoding::binary, Vtk_encoding::ascii}) {
      const bool binary = encoding == Vtk_encoding::binary;
      INFO((binary ? "BINARY" : "ASCII"));
      std::ostringstream out;
      write_vtk_triangulation(out, points, simplices, nullptr, encoding);
      const std::string text = out.str();
      CHECK(text.find(binary ? "\nBINARY\n" : "\nASCII\n") != std::string::npos);
      std::istringstream in(text);
      CHECK(same_bits(read_vtk_points(in, "t.vtk"), points));

      // The cells: count, sizes, types, and VTK's orientation (the fourth point
      // of a tetrahedron on the positive side of the first three;
      // counterclockwise triangles). Binary sections are big-endian 32-bit ints.
      std::istringstream cells(text.substr(text.find("CELLS ")));
      std::string keyword;
      std::size_t count = 0, size = 0;
      cells >> keyword >> count >> size;
      cells.get();  // the newline before the data
      const auto next_int = [&]() -> std::size_t {
        if (!binary) {
          std::size_t v = 0;
          cells >> v;
          return v;
        }
        unsigned char b[4] = {};
        cells.read(reinterpret_cast<char*>(b), 4);
        return (std::size_t{b[0]} << 24) | (std::size_t{b[1]} << 16) | (std::size_t{b[2]} << 8) | b[3];
      };
      REQUIRE(count == simplices.size());
      REQUIRE(size == count * std::size_t(d + 2));
      for (std::size_t s = 0; s < count; ++s) {
        std::array<std::size_t, 4> v{};
        REQUIRE(next_int() == std::size_t(d + 1));
        for (int i = 0; i <= d; ++i) v[std::size_t(i)] = next_int();
        for (int i = 0; i <= d; ++i) REQUIRE(v[std::size_t(i)] == simplices.indices[s * std::size_t(d + 1) + std::size_t(i)]);
        auto e = [&](int a, int j) { return p3[v[std::size_t(a)]][j] - p3[v[0]][j]; };
        const double det = d == 2 ? e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0)
                                  : e(1, 0) * (e(2, 1) * e(3, 2) - e(2, 2) * e(3, 1)) -
                                        e(1, 1) * (e(2, 0) * e(3, 2) - e(2, 2) * e(3, 0)) +
                                        e(1, 2) * (e(2, 0) * e(3, 1) - e(2, 1) * e(3, 0));
        REQUIRE(det > 0);
      }
      cells >> keyword >> count;
      CHECK(keyword == "CELL_TYPES");
      CHECK(count == simplices.size());
      cells.get();
      for (std::size_t s = 0; s < count; ++s) REQUIRE(next_int() == std::size_t(d == 2 ? 5 : 10));
    }
  }
}

TEST_CASE("VTK: points, binary legacy files, errors", "[formats]") {
  SECTION("4D is refused") {
    const auto p = generate_points(Point_kind::uniform, 10, 4, 1);
    std::ostringstream out;
    CHECK_THROWS_AS(write_vtk_points(out, p), Vtk_unsupported);
  }
  SECTION("a 3D point file round-trips, binary and ASCII") {
    const auto p = generate_points(Point_kind::sphere, 100, 3, 1);
    for (const Vtk_encoding encoding : {Vtk_encoding::binary, Vtk_encoding::ascii}) {
      std::ostringstream out;
      write_vtk_points(out, p, nullptr, encoding);
      std::istringstream in(out.str());
      CHECK(same_bits(read_vtk_points(in, "p.vtk"), p));
    }
  }
  SECTION("BINARY legacy POINTS (big-endian float), as ParaView may save them") {
    std::string file = "# vtk DataFile Version 4.2\nsaved\nBINARY\nDATASET POLYDATA\nPOINTS 3 float\n";
    for (float v : {1.0f, 2.0f, 3.0f, 4.5f, 5.0f, 6.0f, -1.0f, 0.0f, 0.25f}) {
      const auto bits = std::bit_cast<std::uint32_t>(v);
      for (int shift = 24; shift >= 0; shift -= 8) file += static_cast<char>((bits >> shift) & 0xff);
    }
    file += "\nVERTICES 0 0\n";
    std::istringstream in(file);
    const auto t = read_vtk_points(in, "b.vtk");
    CHECK(t.dimension == 3);
    CHECK(t.coordinates == std::vector<double>{1, 2, 3, 4.5, 5, 6, -1, 0, 0.25});
  }
  SECTION("errors name the file and line") {
    std::istringstream no_header("POINTS 1 double\n0 0 0\n");
    CHECK_THROWS_WITH(read_vtk_points(no_header, "a.vtk"), Catch::Contains("a.vtk:1") && Catch::Contains("not a legacy VTK"));
    std::istringstream no_points("# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n");
    CHECK_THROWS_WITH(read_vtk_points(no_points, "b.vtk"), Catch::Contains("no POINTS"));
    std::istringstream bad("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 2 double\n0 0 0\n1 x 0\n");
    CHECK_THROWS_WITH(read_vtk_points(bad, "c.vtk"), Catch::Contains("c.vtk:7: 'x' is not a number"));
    std::istringstream short_section("# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 double\n0 0 0\n");
    CHECK_THROWS_WITH(read_vtk_points(short_section, "d.vtk"), Catch::Contains("truncated"));
  }
  SECTION("a POINTS count that does not match the data: truncated or count mismatch, never read on") {
    // Four 3D points, binary, then a cell section; the header announces `announced`.
    const auto binary_file = [](int announced) {
      std::string file = "# vtk DataFile Version 3.0\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS " +
                         std::to_string(announced) + " double\n";
      for (double v : {0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0}) {
        const auto bits = std::bit_cast<std::uint64_t>(v);
        for (int shift = 56; shift >= 0; shift -= 8) file += static_cast<char>((bits >> shift) & 0xff);
      }
      file += "\nCELLS 1 5\n";
      for (std::uint32_t v : {4u, 0u, 1u, 2u, 3u, 10u, 10u, 10u, 10u, 10u, 10u, 10u})  // and padding
        for (int shift = 24; shift >= 0; shift -= 8) file += static_cast<char>((v >> shift) & 0xff);
      return file;
    };
    std::istringstream exact(binary_file(4));
    CHECK(read_vtk_points(exact, "e.vtk").size() == 4);
    std::istringstream fewer(binary_file(3));  // the fourth point is not a section
    CHECK_THROWS_WITH(read_vtk_points(fewer, "f.vtk"), Catch::Contains("f.vtk:5: count mismatch") &&
                                                           Catch::Contains("announces 3 points"));
    std::istringstream more(binary_file(5));  // would read a "point" out of CELLS
    CHECK_THROWS_WITH(read_vtk_points(more, "g.vtk"), Catch::Contains("g.vtk:5: count mismatch"));
    std::istringstream far_more(binary_file(9));  // runs past the end
    CHECK_THROWS_WITH(read_vtk_points(far_more, "h.vtk"), Catch::Contains("truncated"));
    std::istringstream ascii("# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n"
                             "0 0 0 1 0 0\n0 1 0 1 1 0\nCELLS 1 5\n4 0 1 2 3\n");
    CHECK_THROWS_WITH(read_vtk_points(ascii, "i.vtk"),
                      Catch::Contains("i.vtk:5: truncated") && Catch::Contains("the file has 12 before 'CELLS' on line 8"));
  }
}

TEST_CASE("atomic writes leave nothing behind on failure", "[formats]") {
  std::filesystem::create_directories("formats_test_atomic");
  const std::string path = "formats_test_atomic/never.out";
  std::filesystem::remove(path);
  CHECK_THROWS(write_output_file(path, [](std::ostream& out) {
    out << "partial";
    throw std::runtime_error("stop");
  }));
  CHECK(!std::filesystem::exists(path));
  CHECK(std::filesystem::is_empty("formats_test_atomic"));
}

TEST_CASE("progress: silent when disabled, a line per phase when shown", "[formats]") {
  std::FILE* sink = std::tmpfile();
  REQUIRE(sink);
  {
    Progress off(false, sink, 0);
    off.phase("reading", 10);
    off.advance_to(5);
    off.finish();
  }
  CHECK(std::ftell(sink) == 0);
  {
    Progress on(true, sink, 0);  // no delay: shown at the first redraw
    on.phase("writing things", 100);
    on.advance_to(50);
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    on.finish();
  }
  std::rewind(sink);
  std::string text(4096, '\0');
  text.resize(std::fread(text.data(), 1, text.size(), sink));
  std::fclose(sink);
  CHECK(text.find("writing things") != std::string::npos);
  CHECK(text.find("100%") != std::string::npos);  // the final line
  CHECK(text.back() == '\n');
}

using dewall::test::Cli_in_directory;

TEST_CASE("command line: generate", "[cli][formats]") {
  const Cli_in_directory cli("formats_test_generate");
  SECTION("seeded runs are identical, and the seed is printed") {
    const auto a = cli("generate bubbles 100 --dim 2 --seed 77");
    const auto b = cli("generate bubbles 100 --dim 2 --seed 77");
    CHECK(a.status == 0);
    CHECK(a.out == b.out);
    CHECK(std::count(a.out.begin(), a.out.end(), '\n') == 100);
    CHECK(a.err.find("seed 77") != std::string::npos);
    const auto random = cli("generate uniform 10");
    CHECK(random.status == 0);
    CHECK(random.err.find("seed ") != std::string::npos);
  }
  SECTION("binary output, read back by triangulate, equal to text") {
    CHECK(cli("generate lattice-sphere 200 --dim 3 -o ls.dwpt").status == 0);
    CHECK(cli("generate lattice-sphere 200 --dim 3 -o ls.txt").status == 0);
    const auto from_binary = cli("triangulate ls.dwpt");
    const auto from_text = cli("triangulate ls.txt");
    CHECK(from_binary.status == 0);
    CHECK(!from_binary.out.empty());
    CHECK(from_binary.out == from_text.out);
    // A pipe (not seekable) goes through the streaming reader.
    CHECK(cli("triangulate -", "cat ls.dwpt | ").out == from_text.out);
  }
  SECTION("usage errors exit 2") {
    CHECK(cli("generate cube 100").status == 2);
    CHECK(cli("generate cube 100").err.find("lattice-sphere") != std::string::npos);
    CHECK(cli("generate uniform lots").status == 2);
    CHECK(cli("generate uniform 100 --dim 7").status == 2);
    CHECK(cli("generate uniform 2 --dim 3").status == 2);
    CHECK(cli("generate uniform 100 --seed -4").status == 2);
    CHECK(cli("generate uniform").status == 2);
    CHECK(cli("generate uniform 100 --dim 4 -o p.vtk").status == 2);
    CHECK(cli("generate uniform 1e3 --dim 2 -q").status == 0);
  }
}

TEST_CASE("command line: triangulate with binary and VTK files", "[cli][formats]") {
  const Cli_in_directory cli("formats_test_triangulate");
  REQUIRE(cli("generate ball 300 --dim 3 --seed 5 -o b3.dwpt").status == 0);
  SECTION("VTK out, VTK in: the same triangulation") {
    CHECK(cli("triangulate b3.dwpt -o b3.vtk").status == 0);
    CHECK(slurp(cli.path("b3.vtk")).find("CELL_TYPES") != std::string::npos);
    CHECK(cli("triangulate b3.vtk").out == cli("triangulate b3.dwpt").out);
  }
  SECTION("VTK in 4D: a clear error and no file") {
    REQUIRE(cli("generate uniform 50 --dim 4 --seed 5 -o u4.dwpt").status == 0);
    std::filesystem::remove(cli.path("u4.vtk"));
    const auto r = cli("triangulate u4.dwpt -o u4.vtk");
    CHECK(r.status == 2);
    CHECK(r.err.find("2D and 3D only") != std::string::npos);
    CHECK(!std::filesystem::exists(cli.path("u4.vtk")));
  }
  SECTION("truncated binary file: exit 2, file named") {
    const auto bytes = slurp(cli.path("b3.dwpt"));
    std::ofstream(cli.path("cut.dwpt"), std::ios::binary) << bytes.substr(0, 1000);
    const auto r = cli("triangulate cut.dwpt");
    CHECK(r.status == 2);
    CHECK(r.err.find("cut.dwpt: truncated") != std::string::npos);
    CHECK(cli("triangulate -", "cat cut.dwpt | ").status == 2);
  }
  SECTION("binary simplices out: certified, the same simplices as the text list") {
    CHECK(cli("triangulate b3.dwpt -o b3.dwsx").status == 0);
    CHECK(slurp(cli.path("b3.dwsx")).substr(0, 4) == "DWSX");
    CHECK(cli("triangulate b3.dwpt -o b3.txt").status == 0);
    CHECK(read_simplices_file(cli.path("b3.dwsx"), 3, 0).table.indices ==
          read_simplices_file(cli.path("b3.txt"), 3, 0).table.indices);
    CHECK(cli("certify b3.dwpt b3.dwsx --canonical").status == 0);
    CHECK(cli("certify b3.dwpt -", "cat b3.dwsx | ").status == 0);
    // A corrupted index: certify names the simplex, exit 1; cut short: exit 2.
    auto bytes = slurp(cli.path("b3.dwsx"));
    bytes[24] = bytes[28];
    std::ofstream(cli.path("bad.dwsx"), std::ios::binary) << bytes;
    const auto bad = cli("certify b3.dwpt bad.dwsx");
    CHECK(bad.status == 1);
    CHECK(bad.out.find("simplex 0 (bad.dwsx)") != std::string::npos);
    std::ofstream(cli.path("cut.dwsx"), std::ios::binary) << bytes.substr(0, 100);
    CHECK(cli("certify b3.dwpt cut.dwsx").status == 2);
  }
  SECTION("--quiet and a non-terminal stderr print nothing") {
    CHECK(cli("triangulate b3.dwpt -o b3.txt --quiet").err.empty());
    CHECK(cli("triangulate b3.dwpt -o b3.txt").err.empty());
  }
}

TEST_CASE("command line: draw", "[cli][formats]") {
  const Cli_in_directory cli("formats_test_draw");
  REQUIRE(cli("generate bubbles 200 --dim 2 --seed 3 -o p2.txt").status == 0);
  REQUIRE(cli("triangulate p2.txt -o s2.txt").status == 0);
  const auto list = slurp(cli.path("s2.txt"));
  const auto triangles = static_cast<std::size_t>(std::count(list.begin(), list.end(), '\n'));
  auto polygons = [](const std::string& svg) {
    std::size_t n = 0;
    for (auto at = svg.find("<polygon"); at != std::string::npos; at = svg.find("<polygon", at + 1)) ++n;
    return n;
  };
  SECTION("the triangulation") {
    CHECK(cli("draw p2.txt s2.txt -o t.svg").status == 0);
    const auto svg = slurp(cli.path("t.svg"));
    CHECK(svg.rfind("<svg", 0) == 0);
    CHECK(polygons(svg) == triangles);
  }
  SECTION("--walls: every triangle coloured by a level, level 0 present") {
    CHECK(cli("draw p2.txt --walls -o w.svg").status == 0);
    const auto svg = slurp(cli.path("w.svg"));
    CHECK(polygons(svg) == triangles);
    CHECK(svg.find("wall level") != std::string::npos);
    CHECK(svg.find("#e15759") != std::string::npos);  // level 0's colour
    CHECK(svg.find("#dddddd") == std::string::npos);  // nothing unmatched
    // The given triangles (in the list's order) get the levels the walls gave the same triangles.
    CHECK(cli("draw p2.txt s2.txt --walls -o w2.svg").status == 0);
    const auto fills = [](const std::string& picture) {
      std::map<std::string, std::size_t> count;
      for (auto at = picture.find("<polygon"); at != std::string::npos; at = picture.find("<polygon", at + 1)) {
        const auto fill = picture.find("fill=\"", at) + 6;
        ++count[picture.substr(fill, picture.find('"', fill) - fill)];
      }
      return count;
    };
    CHECK(fills(slurp(cli.path("w2.svg"))) == fills(svg));
    CHECK(fills(svg).size() >= 3);
  }
  SECTION("errors") {
    std::ofstream(cli.path("bad.txt")) << "0 1 2\n0 1 999\n";
    const auto r = cli("draw p2.txt bad.txt -o x.svg");
    CHECK(r.status == 2);
    CHECK(r.err.find("bad.txt:2") != std::string::npos);
    CHECK(cli("draw p2.txt -o x.svg").status == 2);  // no SIMPLICES, no --walls
    REQUIRE(cli("generate uniform 20 --dim 3 -o p3.txt").status == 0);
    CHECK(cli("draw p3.txt --walls -o x.svg").status == 2);
  }
}

TEST_CASE("CGAL triangulation files: the three layouts, and clean errors", "[formats]") {
  const auto read = [](const std::string& text) {
    std::istringstream in(text);
    return read_cgal_triangulation(in, "t.cgal");
  };
  // Triangulation_2: "n m 2" (n with the infinite vertex 0), faces, neighbours.
  const std::string two = "4 4 2\n0 0\n1 0\n0 1\n\n1 2 3\n0 3 2\n0 1 3\n0 2 1\n\n1 2 3\n0 3 2\n0 1 3\n0 2 1\n";
  const auto t2 = read(two);
  CHECK(t2.points.dimension == 2);
  CHECK(t2.points.coordinates == std::vector<double>{0, 0, 1, 0, 0, 1});
  CHECK(t2.cells.indices == std::vector<std::uint32_t>{0, 1, 2});
  // Triangulation_3: dimension, finite count, points, cells with vertex 0 infinite.
  const std::string three =
      "3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n5\n1 2 3 4\n0 2 3 4\n0 1 3 4\n0 1 2 4\n0 1 2 3\n"
      "1 2 3 4\n0 2 3 4\n0 1 3 4\n0 1 2 4\n0 1 2 3\n";
  const auto t3 = read(three);
  CHECK(t3.points.dimension == 3);
  CHECK(t3.points.size() == 4);
  CHECK(t3.cells.indices == std::vector<std::uint32_t>{0, 1, 2, 3});
  // dD: the infinite vertex first ("0" or "D 0 … 0"), each point after its dimension.
  for (const std::string infinite : {"0", "3 0 0 0"}) {
    const std::string dd = "3\n4\n" + infinite + "\n3 0 0 0\n3 1 0 0\n3 0 1 0\n3 0 0 1\n\n2\n1 2 3 4\n0 2 3 4\n1 1 1 1\n0 0 0 0\n";
    const auto t = read(dd);
    CHECK(t.points.dimension == 3);
    CHECK(t.points.coordinates == std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
    CHECK(t.cells.indices == std::vector<std::uint32_t>{0, 1, 2, 3});
  }
  CHECK_THROWS_WITH(read("2\n3\n0 0 0\n1 0 0\n0 1 0\n1\n1 2 3\n0 0 0\n"), Catch::Contains("not full-dimensional"));
  CHECK_THROWS_WITH(read("4 1 1\n0\n1\n2\n"), Catch::Contains("not full-dimensional"));
  CHECK_THROWS_WITH(read("3\n4\n0 0 0\n1 0 0\n"), Catch::Contains("truncated"));
  CHECK_THROWS_WITH(read(three.substr(0, three.rfind("1 2 3 4"))), Catch::Contains("truncated"));
  CHECK_THROWS_WITH(read("3\n4\n0 0 0 7\n1 0 0 7\n0 1 0 7\n0 0 1 7\n1\n"), Catch::Contains("not supported"));
  CHECK_THROWS_WITH(read("3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1\n1 2 3 9\n0 0 0 0\n"), Catch::Contains("vertex 9"));
  CHECK_THROWS_WITH(read(three + "1 2 3 4\n"), Catch::Contains("more lines"));
  CHECK_THROWS_WITH(read("3\n4\n0 0 0\n1 x 0\n"), Catch::Contains("not a number"));
  CHECK_THROWS_WITH(read("1 2\n"), Catch::Contains("not a CGAL triangulation"));
}
