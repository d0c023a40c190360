// PCD, the Point Cloud Library's format (issue 57): ASCII and binary files
// read as points with the values they store (floats widened exactly, doubles
// and integers as they are), the other fields skipped; binary_compressed,
// malformed, truncated and overlong files refused with the file, the line and
// the value; recognised by content and by name, through the real executable.
#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "dewall/io/format_names.hpp"
#include "dewall/io/mesh_formats.hpp"
#include "dewall/io/point_reader.hpp"
#include "support/cli_runner.hpp"

using namespace dewall::io;

namespace {

Point_table read(const std::string& bytes, const std::string& name = "cloud.pcd") {
  std::istringstream in(bytes, std::ios::binary);
  return read_pcd_points(in, name);
}

std::string error_of(const std::string& bytes) {
  try {
    read(bytes);
  } catch (const Parse_error& e) {
    return e.what();
  }
  return "no error";
}

template <class T>
void append(std::string& bytes, T v) {
  static_assert(std::endian::native == std::endian::little);  // PCD's binary data is little-endian
  bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
}

const std::string pcl_header =
    "# .PCD v0.7 - Point Cloud Data file format\n"
    "VERSION 0.7\n";

}  // namespace

TEST_CASE("PCD: ASCII points keep the float or double each field stores", "[formats][pcd]") {
  const auto floats = read(pcl_header +
                           "FIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\n"
                           "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n"
                           "0.1 0.2 0.3 4278190080\n1 0 0.5 0\n0 1 -2.5e-3 16777215\n");
  REQUIRE(floats.dimension == 3);
  REQUIRE(floats.size() == 3);
  CHECK(floats.coordinates[0] == static_cast<double>(0.1f));  // the float the file stores, not the double 0.1
  CHECK(floats.coordinates[2] == static_cast<double>(0.3f));
  CHECK(floats.coordinates[8] == static_cast<double>(-2.5e-3f));

  const auto doubles = read("VERSION .7\nFIELDS intensity x y z\nSIZE 4 8 8 8\nTYPE F F F F\nWIDTH 2\nHEIGHT 1\n"
                            "DATA ascii\n7 0.1 0.2 0.3\n8 1e-300 2 3\n");  // no COUNT, no POINTS: PCD 0.7 allows both
  REQUIRE(doubles.size() == 2);
  CHECK(doubles.coordinates[0] == 0.1);
  CHECK(doubles.coordinates[3] == 1e-300);

  const auto flat = read(pcl_header + "FIELDS x y\nSIZE 4 4\nTYPE I I\nCOUNT 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\n"
                                      "DATA ascii\n0 0\n5 0\n0 -7\n");
  CHECK(flat.dimension == 2);  // no z: a 2D set, as PLY's
  CHECK(flat.coordinates == std::vector<double>{0, 0, 5, 0, 0, -7});
}

TEST_CASE("PCD: binary rows, fields of every type and count, padding skipped", "[formats][pcd]") {
  std::string bytes = pcl_header +
                      "FIELDS label x _ y z normal\nSIZE 2 8 1 4 8 4\nTYPE U F U F I F\nCOUNT 1 1 3 1 1 3\n"
                      "WIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA binary\n";
  const double xs[4] = {0.1, -1e300, 3, 5e-324};
  const float ys[4] = {0.25f, 1.0f / 3, -0.0f, 7};
  const std::int64_t zs[4] = {-(std::int64_t{1} << 53), 0, 1, 42};
  for (int r = 0; r < 4; ++r) {
    append(bytes, std::uint16_t{9});
    append(bytes, xs[r]);
    bytes.append(3, '\xff');
    append(bytes, ys[r]);
    append(bytes, zs[r]);
    for (int k = 0; k < 3; ++k) append(bytes, 0.5f);
  }
  const auto t = read(bytes);
  REQUIRE(t.dimension == 3);
  REQUIRE(t.size() == 4);
  for (std::size_t r = 0; r < 4; ++r) {
    CHECK(std::bit_cast<std::uint64_t>(t.coordinates[3 * r]) == std::bit_cast<std::uint64_t>(xs[r]));
    CHECK(std::bit_cast<std::uint64_t>(t.coordinates[3 * r + 1]) ==
          std::bit_cast<std::uint64_t>(static_cast<double>(ys[r])));
    CHECK(t.coordinates[3 * r + 2] == static_cast<double>(zs[r]));
  }

  // Cut anywhere in the data: truncated; a byte more: refused.
  const std::size_t data = bytes.find("DATA binary\n") + 12;
  for (const std::size_t cut : {data, data + 1, bytes.size() - 1}) {
    CAPTURE(cut);
    CHECK_THAT(error_of(bytes.substr(0, cut)), Catch::Contains("truncated: the PCD header announces 4 points"));
  }
  CHECK_THAT(error_of(bytes + "x"), Catch::Contains("more data than the PCD header announces"));
}

TEST_CASE("PCD: malformed files are refused naming the file, the line and the value", "[formats][pcd]") {
  const std::string fields = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n";
  CHECK_THAT(error_of(pcl_header + fields + "DATA binary_compressed\n"),
             Catch::Contains("cloud.pcd:10:") && Catch::Contains("binary_compressed) is not read: convert"));
  CHECK_THAT(error_of(pcl_header + fields + "DATA ascii\n0 0 0\n1 zero 0\n"),
             Catch::Contains("cloud.pcd:12:") && Catch::Contains("'zero' is not a number"));
  CHECK_THAT(error_of(pcl_header + fields + "DATA ascii\n0 0 0\n"),
             Catch::Contains("truncated: the PCD header announces 2 points, the file has 1"));
  CHECK_THAT(error_of(pcl_header + fields + "DATA ascii\n0 0 0\n1 1 1\n2 2 2\n"),
             Catch::Contains("cloud.pcd:13:") && Catch::Contains("more rows than the header announces (2 points)"));
  CHECK_THAT(error_of(pcl_header + fields + "DATA ascii\n0 0 0\n1 1\n"), Catch::Contains("expected 3 values"));
  CHECK_THAT(error_of(pcl_header + fields), Catch::Contains("truncated PCD header (no DATA line)"));
  CHECK_THAT(error_of(pcl_header + "FIELDS x z\nSIZE 4 4\nTYPE F F\nPOINTS 1\nDATA ascii\n0 0\n"),
             Catch::Contains("the PCD fields have no x and y"));
  CHECK_THAT(error_of(pcl_header + "FIELDS x y\nSIZE 4 4\nTYPE F D\nPOINTS 1\nDATA ascii\n0 0\n"),
             Catch::Contains("cloud.pcd:5:") && Catch::Contains("field type 'D' is not F, I or U"));
  CHECK_THAT(error_of(pcl_header + "FIELDS x y\nSIZE 4 4 4\nTYPE F F\nPOINTS 1\nDATA ascii\n0 0\n"),
             Catch::Contains("SIZE has 3 values for 2 fields"));
  CHECK_THAT(error_of(pcl_header + "FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 3\nHEIGHT 2\nPOINTS 5\nDATA ascii\n"),
             Catch::Contains("POINTS 5 but WIDTH x HEIGHT = 3 x 2"));
  CHECK_THAT(error_of(pcl_header + "FIELDS x y\nSIZE 8 8\nTYPE I I\nPOINTS 1\nDATA ascii\n9007199254740993 0\n"),
             Catch::Contains("'9007199254740993' is not exactly a double"));
  CHECK_THAT(error_of(pcl_header + "FIELDS x y\nSIZE 4 4\nTYPE F F\nPOINTS 0\nDATA ascii\n"), Catch::Contains("no points"));
  CHECK_THAT(error_of(pcl_header + "FIELDS x y\nSIZE 4 4\nTYPE F F\nPOINTS 1\nDATA ascii\n1e39 0\n"),
             Catch::Contains("'1e39' is out of the range of float"));
}

TEST_CASE("PCD: recognised by its header or its name", "[formats][pcd]") {
  CHECK(is_pcd_header("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"));
  CHECK(is_pcd_header("VERSION 0.7\nFIELDS x y z\n"));
  CHECK(is_pcd_header("# made by hand\n\nVERSION .7\n"));
  CHECK_FALSE(is_pcd_header("0.5 0.25 1\n"));
  CHECK_FALSE(is_pcd_header("ply\nformat ascii 1.0\n"));
  CHECK(format_named_by("scan.PCD") == Named_format::pcd);
}

TEST_CASE("command line: triangulate reads PCD files, by content and by name", "[cli][formats][pcd]") {
  std::filesystem::remove_all("pcd_test_cli");
  const dewall::test::Cli_in_directory cli("pcd_test_cli");
  REQUIRE(cli("generate uniform 150 --dim 3 --seed 57 -q -o p.txt").status == 0);
  const auto expected = cli("triangulate p.txt");
  REQUIRE(expected.status == 0);
  const std::string points = dewall::test::slurp(cli.path("p.txt"));
  std::string ascii = pcl_header + "FIELDS x y z rgb\nSIZE 8 8 8 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 150\nHEIGHT 1\n"
                                   "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 150\nDATA ascii\n";
  std::string binary = pcl_header + "FIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 150\nHEIGHT 1\n"
                                    "POINTS 150\nDATA binary\n";
  for (std::size_t at = 0; at < points.size();) {
    const std::size_t end = points.find('\n', at);
    const std::string row = points.substr(at, end - at);
    at = end + 1;
    ascii += row + " 4.2108e+06\n";
    std::istringstream values(row);
    for (double v; values >> v;) append(binary, v);
  }
  cli.write("a.pcd", ascii), cli.write("b.PCD", binary), cli.write("scan.data", binary);
  CHECK(cli("triangulate a.pcd").out == expected.out);
  CHECK(cli("triangulate b.PCD").out == expected.out);
  CHECK(cli("triangulate scan.data").out == expected.out);           // by its header
  CHECK(cli("triangulate -", "cat a.pcd | ").out == expected.out);  // through a pipe
  const auto cut = cli("triangulate -", "head -c 1000 b.PCD | ");
  CHECK(cut.status == 2);
  CHECK(cut.err.find("truncated: the PCD header announces 150 points") != std::string::npos);
  cli.write("c.pcd", pcl_header + "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nDATA binary_compressed\n");
  const auto compressed = cli("triangulate c.pcd");
  CHECK(compressed.status == 2);
  CHECK(compressed.err.find("c.pcd:8: compressed PCD data") != std::string::npos);
  CHECK(cli("triangulate p.txt -o out.pcd").status == 2);  // read, never written
}
