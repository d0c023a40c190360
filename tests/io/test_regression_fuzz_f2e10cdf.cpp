// Regression, fuzz_parse finding crash-f2e10cdf (ASan out-of-memory): a legacy
// VTK file of about 100 bytes whose POINTS line announces 1505453338 points.
// read_vtk_points reserved 3 · count doubles (36 GB) for ASCII data, and
// allocated 3 · count · sizeof(type) bytes before reading BINARY data, so a tiny
// file ended in std::bad_alloc (an abort under ASan) instead of the reader's
// "truncated" Parse_error. Expected: Parse_error, with no allocation beyond
// what the file holds.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>

#include "dewall/io/point_reader.hpp"
#include "dewall/io/vtk.hpp"

namespace {

void require_parse_error(const std::string& text) {
  std::istringstream in(text, std::ios::binary);
  REQUIRE_THROWS_AS(dewall::io::read_vtk_points(in, "fuzz.vtk"), dewall::io::Parse_error);
}

const std::string header = "# vtk DataFile Version 3.0\ndewall\n";

}  // namespace

TEST_CASE("fuzz f2e10cdf: a huge VTK point count in a tiny file is a parse error", "[io][regression][fuzz]") {
  require_parse_error(header + "ASCII\nDATASET POLYDATA\nPOINTS 1505453338 float\n0 0 0\n");
  require_parse_error(header + "BINARY\nDATASET POLYDATA\nPOINTS 1505453338 float\n0000");
  require_parse_error(header + "BINARY\nDATASET POLYDATA\nPOINTS 1099511627776 double\n");  // 2^40: the largest count accepted
}
