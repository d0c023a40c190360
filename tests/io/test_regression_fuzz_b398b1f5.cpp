// Regression, fuzz_parse finding crash-b398b1f5 (UBSan): a TetGen .node header
// whose dimension (or attribute/marker count) does not fit the integer it is
// converted to. read_node cast the double 262265555526 to int before checking
// the range: undefined behaviour ("outside the range of representable values
// of type 'int'"), silently some dimension in an ordinary build. Expected: a
// clean Parse_error for every such header.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>

#include "dewall/io/point_reader.hpp"

namespace {

void require_parse_error(const std::string& text) {
  INFO("input: " << text);
  std::istringstream in(text);
  REQUIRE_THROWS_AS(dewall::io::read_node(in, "fuzz.node"), dewall::io::Parse_error);
}

}  // namespace

TEST_CASE("fuzz b398b1f5: .node header values out of range are parse errors", "[io][regression][fuzz]") {
  // The fuzzer's input, minus its reader-selection byte.
  require_parse_error("2\v262265555526\v5526\v55555555555555");
  require_parse_error("1 262265555526\n0 1 2\n");
  require_parse_error("1 4294967298\n0 1 2\n");   // 2 modulo 2^32: must not read as 2D
  require_parse_error("1 2 -1\n0 1 2\n");          // negative attribute count
  require_parse_error("1 2 0 1e300\n0 1 2 0\n");    // marker count beyond size_t
}
