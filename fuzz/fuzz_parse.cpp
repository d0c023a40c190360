// fuzz_parse: every input reader on arbitrary bytes → a value or a clean
// io::Parse_error; never a crash, a hang, a leak or another exception (an
// uncaught exception aborts, which libFuzzer records as a finding).
//
// Input: [reader] then the file's bytes. Readers: plain text / rbox
// (io::read_points) and TetGen .node (io::read_node).
//
// Properties of a successful read:
//  * the dimension is 2 … 6, there is at least one point, and the coordinates
//    are whole points;
//  * plain text round trip: the table written back with %.17g (every finite
//    double, NaN and ±inf as strtod spells them) reads back to the same values.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include "dewall/io/point_reader.hpp"
#include "fuzz_common.hpp"

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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int reader = data[0] % 2;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  std::istringstream in(bytes);
  try {
    if (reader == 0) {
      const Point_table t = dewall::io::read_points(in, "fuzz");
      check_table(t);
      check_round_trip(t);
    } else {
      check_table(dewall::io::read_node(in, "fuzz.node"));
    }
  } catch (const Parse_error&) {
    // The one allowed failure.
  }
  return 0;
}
